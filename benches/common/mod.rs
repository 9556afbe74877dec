//! What the step benchmarks share: the pile of boxes, and two worlds stepped
//! in lockstep, one plainly and one with the rules, timed back to back.

use std::time::{Duration, Instant};

use crate::rapier::prelude::*;
use crate::rules::{CollisionRule, CollisionRuleSet, RuleHooks};
use crate::space::{at, column, cuboid};

/// A pile of `n` unit boxes standing in columns of ten, the columns side by
/// side (a square of columns in 3D, a row in 2D: `space::column`), on a ground slab, settled for 60 steps; each box's body and column.
/// With `can_sleep` the boxes may fall asleep.
pub fn pile(n: usize, can_sleep: bool) -> (PhysicsWorld, Vec<(RigidBodyHandle, usize)>) {
    let mut world = PhysicsWorld::new();
    let ground = world.insert_body(RigidBodyBuilder::fixed().translation(at(0.0, -0.5, 0.0)));
    world.insert_collider(cuboid(500.0, 0.5, 500.0), Some(ground));
    let mut boxes = Vec::with_capacity(n);
    for i in 0..n {
        let column_index = i / 10;
        let (x, z) = column(column_index, n / 10);
        let y = 0.5 + (i % 10) as f32 * 1.001;
        let body = world.insert_body(
            RigidBodyBuilder::dynamic()
                .translation(at(x, y, z))
                .can_sleep(can_sleep),
        );
        world.insert_collider(cuboid(0.5, 0.5, 0.5), Some(body));
        boxes.push((body, column_index));
    }
    for _ in 0..60 {
        world.step();
    }
    (world, boxes)
}

/// Specific rules on 5% of the pile's bodies: one body in twenty says
/// something (`NoResponse` or `NoContacts`) about a body half the pile away,
/// which it never meets.
pub fn specific_rules(boxes: &[(RigidBodyHandle, usize)]) -> CollisionRuleSet {
    let mut rules = CollisionRuleSet::default();
    let n = boxes.len();
    for i in (0..n).step_by(20) {
        let rule = if i % 40 == 0 {
            CollisionRule::NoResponse
        } else {
            CollisionRule::NoContacts
        };
        rules.set_specific(boxes[i].0, boxes[(i + n / 2) % n].0, rule);
    }
    rules
}

/// What a world that changes every step does before each step: adds and
/// removes objects, and (in the world with the rules, `rules` is `Some`)
/// gives them rules. Applied to both twins in the same order, untimed, so
/// that their handles stay the same.
pub trait Churn {
    fn apply(&mut self, world: &mut PhysicsWorld, rules: Option<&mut CollisionRuleSet>);
}

/// The times of one step of each twin ([`Twins::time_pair`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct TimedPair {
    pub plain: Duration,
    pub rules: Duration,
}

/// Two worlds stepped in lockstep: each measurement times one world's step
/// and steps the other untimed, so that both stand at the same point of
/// their (identical) evolution whenever either is measured.
pub struct Twins {
    pub plain: PhysicsWorld,
    pub world: PhysicsWorld,
    pub hooks: RuleHooks,
    /// The control: both worlds stepped plainly, the noise floor of the method.
    pub control: bool,
    /// For worlds that change every step: the plain twin's churn and the
    /// rules world's, applied before every step of each.
    pub churn: Option<[Box<dyn Churn>; 2]>,
}

impl Twins {
    /// Plans the rules world before its first step and gives each collider
    /// whose Rapier settings the plan changed the same change in the plain
    /// twin (its groups set away and back, its types likewise): Rapier
    /// recomputes a modified collider's contacts, which alone would set the
    /// two worlds apart, and then each would be timed on a different
    /// evolution.
    pub fn plan_alike(&mut self) {
        if self.control {
            return;
        }
        let settings = |c: &Collider| {
            (
                c.collision_groups(),
                c.solver_groups(),
                c.active_collision_types(),
            )
        };
        let before: Vec<_> = self
            .world
            .colliders
            .iter()
            .map(|(h, c)| (h, settings(c)))
            .collect();
        self.hooks
            .follow_soft_bodies(&self.world.soft_bodies, &self.world.bodies);
        self.hooks
            .prepare(&self.world.bodies, &mut self.world.colliders);
        for (handle, was) in before {
            let now = settings(&self.world.colliders[handle]);
            let Some(twin) = self.plain.colliders.get_mut(handle) else {
                continue;
            };
            if (now.0, now.1) != (was.0, was.1) {
                let groups = twin.collision_groups();
                twin.set_collision_groups(InteractionGroups::none());
                twin.set_collision_groups(groups);
            }
            if now.2 != was.2 {
                let types = twin.active_collision_types();
                twin.set_active_collision_types(ActiveCollisionTypes::empty());
                twin.set_active_collision_types(types);
            }
        }
    }

    /// Whether the two worlds' bodies stand exactly alike.
    pub fn identical(&self) -> bool {
        self.plain
            .bodies
            .iter()
            .zip(self.world.bodies.iter())
            .all(|((_, a), (_, b))| a.position() == b.position())
    }

    /// Times `iters` steps of one world (`rules`: the one with the rules),
    /// stepping the other untimed (criterion's benchmarks, one per world).
    pub fn time(&mut self, iters: u64, rules: bool) -> Duration {
        let mut timed = Duration::ZERO;
        for _ in 0..iters {
            for world in [rules, !rules] {
                self.churn_one(world);
                let start = Instant::now();
                self.step_one(world);
                if world == rules {
                    timed += start.elapsed();
                }
            }
        }
        timed
    }

    /// One step of each world, both timed, at the same point of their
    /// evolution: the time of the plain world's step and of the rules
    /// world's. `rules_first` says which goes first; callers alternate it.
    /// Each world's churn comes right before its own step, so each is
    /// timed right after its own changes. Timing the two worlds on
    /// alternate steps instead (one `time(1, ..)` each) measured each on
    /// every other step of the scene, and a scene whose work differs from
    /// one step to the next (a stream's chunk slots, a turret's aim) then
    /// showed as a bias of up to 11% between two plain twins.
    pub fn time_pair(&mut self, rules_first: bool) -> TimedPair {
        let mut pair = TimedPair::default();
        for world in [rules_first, !rules_first] {
            self.churn_one(world);
            let start = Instant::now();
            self.step_one(world);
            let took = start.elapsed();
            if world {
                pair.rules = took;
            } else {
                pair.plain = took;
            }
        }
        pair
    }

    /// Applies one world's changes for its next step (`rules`: the world
    /// with the rules).
    fn churn_one(&mut self, rules: bool) {
        let Some([plain, ruled]) = &mut self.churn else {
            return;
        };
        if rules {
            let set = (!self.control).then(|| self.hooks.rules_mut());
            ruled.apply(&mut self.world, set);
        } else {
            plain.apply(&mut self.plain, None);
        }
    }

    /// Steps one world: the rules world through its hooks (plainly in the
    /// control), the other plainly.
    fn step_one(&mut self, rules: bool) {
        match (rules, self.control) {
            (false, _) => self.plain.step(),
            (true, true) => self.world.step(),
            (true, false) => self.hooks.step(&mut self.world),
        }
    }
}
