//! Step cost of `RuleHooks` against plain Rapier on worlds shaped like real
//! games, where most of the world is idle: what the rules cost must follow
//! what they reach, not the size of the world.
//!
//! - `level`: a static level of `n` fixed tiles (one fixed body), 4,000
//!   boxes resting on it (asleep), 200 balls that never sleep. Variants:
//!   `none` (no rules) and `rules` (10 balls with a personal rule, 10 with
//!   a specific rule about a ball they never meet: per-object rules that
//!   leave the physics as it is);
//! - `field`: `n` boxes on one ground slab, all asleep, no rules;
//! - `floor`: 2,000 boxes that never sleep on one floor, and one ball with
//!   the README's quick-start rule `set_specific(ghost, floor, NoResponse)`,
//!   against the same ghost excluded from the floor by hand-written Rapier
//!   solver groups;
//! - `soft`: 1,000 awake boxes on a floor with a soft cube among them and a
//!   pinned cloth above, with no rules and with a few rules on the soft
//!   bodies that leave the physics as it is;
//! - `pile`: the 1,000-box pile of `benches/step.rs` allowed to fall
//!   asleep, with no rules and with specific rules on 5% of the bodies;
//! - `churn`: worlds that change every step (shooters, a streamed level, a
//!   car driven through a pickup field), and `rate`: balls fired and
//!   removed at 0 to 200 a step over levels of two sizes
//!   (`docs/performance.md`, "Worlds that change");
//! - `ends`: 200 projectiles a second fired from inside ten turrets over
//!   the level, each ignoring its turret until apart
//!   (`Until::apart`), against the same world where the project removes
//!   each rule itself once its own test says apart: both twins step
//!   through `RuleHooks`, and each twin's time includes its own test
//!   (`docs/performance.md`, "Rules with an end").
//!
//! Each variant steps two identical worlds in lockstep, one plain, one with
//! the rules, and times them back to back (the paired ratio: median, min
//! and max of five runs). `control` variants step both worlds plainly: the
//! noise floor of the method, which for steps of a microsecond is several
//! percent (the second world of a pair meets other cache contents).
//! `WORLDS_OUT=docs` writes `upkeep.csv` and `upkeep.svg` there (step time
//! against world size, level and field) when the level runs, and
//! `churn_rate.csv` and `churn_rate.svg` (extra time against the changes
//! per step) when the `rate` variants run.
//!
//! `cargo bench --bench worlds` (criterion, then the paired ratios);
//! `WORLDS_PAIRED_ONLY=1` skips criterion. `WORLDS_VARIANTS=level,churn/stream`
//! runs the scenes whose names start so, `WORLDS_VARIANTS==churn/stream` the
//! one scene of that name. `WORLDS_PAIRS=50` makes each paired run exactly
//! 50 step pairs (for profiles that compare two builds).

use rapier_collision_rules::dim3 as rules;
use rapier3d as rapier;

#[path = "common/chart.rs"]
mod chart;
mod common;
#[path = "common/space3.rs"]
mod space;

use std::collections::VecDeque;
use std::fmt::Write as _;
use std::time::Duration;

use common::{Churn, Twins, pile, specific_rules};
use criterion::{BenchmarkId, Criterion, criterion_group};
use plotters::prelude::*;
use rapier_collision_rules::{CollisionGroup, CollisionRule, CollisionRuleSet, RuleHooks, Until};
use rapier3d::prelude::*;

const SIZES: [usize; 4] = [1_000, 4_000, 16_000, 64_000];

/// A world, the rules for its twin, and what its plain twin needs by hand.
struct Scene {
    world: PhysicsWorld,
    rules: CollisionRuleSet,
}

/// Steps until no more than `awake` bodies are awake (those that never
/// sleep), or `limit` steps.
fn settle(world: &mut PhysicsWorld, awake: usize, limit: usize) {
    for _ in 0..limit {
        world.step();
        if world.islands.num_active_bodies() <= awake {
            break;
        }
    }
}

/// The level: `tiles` fixed tiles, 4,000 resting boxes, 200 awake balls.
fn level(tiles: usize, with_rules: bool) -> Scene {
    let mut world = PhysicsWorld::new();
    let side = (tiles as f32).sqrt().ceil() as usize;
    let ground = world.insert_body(RigidBodyBuilder::fixed());
    for i in 0..tiles {
        let (x, z) = ((i % side) as f32 * 2.0, (i / side) as f32 * 2.0);
        world.insert_collider(
            ColliderBuilder::cuboid(1.0, 0.5, 1.0).translation(Vector::new(x, -0.5, z)),
            Some(ground),
        );
    }
    let extent = side as f32 * 2.0 - 2.0;
    let grid = |count: usize, offset: f32| {
        let per_row = (count as f32).sqrt().ceil() as usize;
        let spacing = extent / per_row as f32;
        (0..count).map(move |i| {
            let (x, z) = ((i % per_row) as f32, (i / per_row) as f32);
            (
                x * spacing + offset * spacing,
                z * spacing + offset * spacing,
            )
        })
    };
    for (x, z) in grid(4_000, 0.25) {
        let body =
            world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(x, 0.2, z)));
        world.insert_collider(ColliderBuilder::cuboid(0.2, 0.2, 0.2), Some(body));
    }
    let mut balls = Vec::new();
    for (x, z) in grid(200, 0.75) {
        let body = world.insert_body(
            RigidBodyBuilder::dynamic()
                .translation(Vector::new(x, 0.15, z))
                .can_sleep(false),
        );
        world.insert_collider(ColliderBuilder::ball(0.15), Some(body));
        balls.push(body);
    }
    settle(&mut world, 200, 2_000);
    let mut rules = CollisionRuleSet::default();
    if with_rules {
        for (i, &ball) in balls.iter().take(20).enumerate() {
            if i % 2 == 0 {
                rules.set_personal(ball, CollisionRule::Normal);
            } else {
                // A ball half the level away: they never meet.
                rules.set_specific(ball, balls[i + 100], CollisionRule::NoPair);
            }
        }
    }
    Scene { world, rules }
}

/// `n` boxes on one ground slab, all asleep.
fn field(n: usize) -> Scene {
    let mut world = PhysicsWorld::new();
    let side = (n as f32).sqrt().ceil() as usize;
    let half = side as f32;
    let ground = world.insert_body(RigidBodyBuilder::fixed());
    world.insert_collider(
        ColliderBuilder::cuboid(half + 1.0, 0.5, half + 1.0)
            .translation(Vector::new(half, -0.5, half)),
        Some(ground),
    );
    for i in 0..n {
        let (x, z) = ((i % side) as f32 * 2.0, (i / side) as f32 * 2.0);
        let body =
            world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(x, 0.5, z)));
        world.insert_collider(ColliderBuilder::cuboid(0.5, 0.5, 0.5), Some(body));
    }
    settle(&mut world, 0, 2_000);
    Scene {
        world,
        rules: CollisionRuleSet::default(),
    }
}

/// `n` boxes that never sleep, on the floor in rows of `row`, 2 m apart.
fn awake_boxes(world: &mut PhysicsWorld, n: usize, row: usize) -> Vec<RigidBodyHandle> {
    let half = row as f32;
    (0..n)
        .map(|i| {
            let (x, z) = ((i % row) as f32 * 2.0 - half, (i / row) as f32 * 2.0 - half);
            let body = world.insert_body(
                RigidBodyBuilder::dynamic()
                    .translation(Vector::new(x, 0.5, z))
                    .can_sleep(false),
            );
            world.insert_collider(ColliderBuilder::cuboid(0.5, 0.5, 0.5), Some(body));
            body
        })
        .collect()
}

/// 2,000 awake boxes and a ghost ball on one floor. With `by_hand`, the
/// ghost passes the floor through Rapier solver groups; else through the
/// quick-start rule.
fn floor(by_hand: bool) -> Scene {
    let mut world = PhysicsWorld::new();
    let ground = world.insert_body(RigidBodyBuilder::fixed());
    let floor = world.insert_collider(
        ColliderBuilder::cuboid(50.0, 0.5, 50.0).translation(Vector::new(0.0, -0.5, 0.0)),
        Some(ground),
    );
    awake_boxes(&mut world, 2_000, 45);
    let ghost = world.insert_body(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, 5.0, 46.0))
            .can_sleep(false),
    );
    let g = world.insert_collider(ColliderBuilder::ball(0.4), Some(ghost));
    let mut rules = CollisionRuleSet::default();
    if by_hand {
        let solver = |member: u32, excluded: u32| {
            InteractionGroups::new(
                Group::from_bits_retain(member),
                Group::ALL - Group::from_bits_retain(excluded),
                InteractionTestMode::And,
            )
        };
        world.colliders[g].set_solver_groups(solver(1, 2));
        world.colliders[floor].set_solver_groups(solver(2, 1));
    } else {
        rules.set_specific(ghost, floor, CollisionRule::NoResponse);
    }
    for _ in 0..30 {
        world.step();
    }
    Scene { world, rules }
}

/// 1,000 boxes on a floor (awake), a soft cube resting among them and a
/// cloth pinned at its corners above them. With `ruled`, a few rules reach
/// the soft bodies: `NoResponse` between the cube and a box it never meets,
/// `NoPair` between the cloth and another, and the cube in a group of its
/// own whose rule with the default group is `Normal`; the physics is the
/// plain twin's.
fn soft(ruled: bool) -> Scene {
    let mut world = PhysicsWorld::new();
    let ground = world.insert_body(RigidBodyBuilder::fixed());
    world.insert_collider(
        ColliderBuilder::cuboid(40.0, 0.5, 40.0).translation(Vector::new(0.0, -0.5, 0.0)),
        Some(ground),
    );
    let boxes = awake_boxes(&mut world, 1_000, 32);
    let cube = SoftBodyBuilder::cuboid(Vector::new(1.0, 0.6, 1.0), Vector::splat(0.5), 4, 4, 4)
        .cell_model(SoftBodyCellModel::Corotational)
        .softness(SpringCoefficients::new(30.0, 1.0));
    let cube = world.insert_soft_body(cube);
    let (n, step) = (12usize, 0.25);
    let corners = [0, n - 1, n * (n - 1), n * n - 1].map(|i| i as u32);
    let cloth = SoftBodyBuilder::cloth(
        Vector::new(-5.0, 2.5, -5.0),
        Vector::new(step, 0.0, 0.0),
        Vector::new(0.0, 0.0, step),
        n,
        n,
    )
    .pinned_particles(corners);
    let cloth = world.insert_soft_body(cloth);
    let mut rules = CollisionRuleSet::default();
    if ruled {
        let (cube_root, cloth_root) = (
            world.soft_bodies[cube].root_body(),
            world.soft_bodies[cloth].root_body(),
        );
        rules.set_specific(cube_root, boxes[999], CollisionRule::NoResponse);
        rules.set_specific(cloth_root, boxes[998], CollisionRule::NoPair);
        let own = rules.create_group();
        rules.set_group(cube_root, Some(own));
        rules.set_group_rule(own, CollisionGroup::DEFAULT_DYNAMIC, CollisionRule::Normal);
    }
    for _ in 0..30 {
        world.step();
    }
    Scene { world, rules }
}

/// The pile of `benches/step.rs` (1,000 boxes in columns of ten), allowed
/// to sleep and settled until it does; `specific` puts rules on 5% of it.
fn sleeping_pile(specific: bool) -> Scene {
    let n = 1_000;
    let (mut world, boxes) = pile(n, true);
    settle(&mut world, 0, 3_000);
    let rules = if specific {
        specific_rules(&boxes)
    } else {
        CollisionRuleSet::default()
    };
    Scene { world, rules }
}

/// Shooters: ten fixed turrets on a floor, each firing a CCD ball from
/// inside itself every step; a ball goes after 60 steps (600 alive). In the
/// rules world each ball ignores its turret as [`Shot`] says; in the plain
/// twin (and in the control's), hand-written collision groups keep balls
/// and turrets apart.
struct Shooters {
    turrets: Vec<RigidBodyHandle>,
    fired: VecDeque<RigidBodyHandle>,
    step: u32,
    shot: Shot,
}

/// How a shooters scene's ball ignores its turret.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Shot {
    /// `set_specific(ball, turret, NoPair)`.
    BallNames,
    /// The turret's `set_specific(turret, ball, NoPair)`, in a level whose
    /// 1,000 far props (in the air, touching nothing) each carry a group
    /// with no rule.
    TurretNames,
    /// `set_specific_until(ball, turret, NoPair, Until::steps(120))`: a
    /// rule with an end, which each ball carries for its whole life.
    BallUntil,
}

/// The collision groups of a turret (`true`) or a ball set apart by hand.
fn apart(turret: bool) -> InteractionGroups {
    let (member, other) = if turret {
        (Group::GROUP_1, Group::GROUP_2)
    } else {
        (Group::GROUP_2, Group::GROUP_1)
    };
    InteractionGroups::new(member, Group::ALL - other, InteractionTestMode::And)
}

/// The floor and the turrets, set apart by hand from the balls in the plain
/// twin (`by_hand`), and the props and their rules where the turrets name
/// the balls.
fn shooters(by_hand: bool, shot: Shot) -> (PhysicsWorld, CollisionRuleSet, Shooters) {
    let mut world = PhysicsWorld::new();
    let mut rules = CollisionRuleSet::default();
    let props = rules.create_group();
    for i in (0..1_000).filter(|_| shot == Shot::TurretNames) {
        let prop = world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(
            (i % 40) as f32 * 3.0 - 60.0,
            5.0,
            (i / 40) as f32 * 3.0 + 100.0,
        )));
        world.insert_collider(ColliderBuilder::cuboid(0.5, 0.5, 0.5), Some(prop));
        if !by_hand {
            rules.set_group(prop, Some(props));
        }
    }
    let ground = world.insert_body(RigidBodyBuilder::fixed());
    world.insert_collider(
        ColliderBuilder::cuboid(200.0, 0.5, 200.0).translation(Vector::new(0.0, -0.5, 0.0)),
        Some(ground),
    );
    let turrets = (0..10)
        .map(|i| {
            let turret = world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(
                i as f32 * 6.0 - 27.0,
                1.0,
                0.0,
            )));
            let mut collider = ColliderBuilder::cuboid(0.5, 1.0, 0.5);
            if by_hand {
                collider = collider.collision_groups(apart(true));
            }
            world.insert_collider(collider, Some(turret));
            turret
        })
        .collect();
    let fired = VecDeque::new();
    (
        world,
        rules,
        Shooters {
            turrets,
            fired,
            step: 0,
            shot,
        },
    )
}

impl Churn for Shooters {
    fn apply(&mut self, world: &mut PhysicsWorld, mut rules: Option<&mut CollisionRuleSet>) {
        self.step += 1;
        for (i, &turret) in self.turrets.iter().enumerate() {
            let from = world.bodies[turret].translation() + Vector::new(0.0, 0.5, 0.0);
            let angle = self.step as f32 * 0.7 + i as f32;
            let aim = Vector::new(angle.cos(), 0.3, angle.sin()) * 30.0;
            let ball = world.insert_body(
                RigidBodyBuilder::dynamic()
                    .translation(from)
                    .linvel(aim)
                    .ccd_enabled(true),
            );
            let mut collider = ColliderBuilder::ball(0.1);
            match (rules.as_deref_mut(), self.shot) {
                (Some(rules), Shot::BallNames) => {
                    rules.set_specific(ball, turret, CollisionRule::NoPair)
                }
                (Some(rules), Shot::TurretNames) => {
                    rules.set_specific(turret, ball, CollisionRule::NoPair)
                }
                (Some(rules), Shot::BallUntil) => {
                    rules.set_specific_until(ball, turret, CollisionRule::NoPair, Until::steps(120))
                }
                (None, _) => collider = collider.collision_groups(apart(false)),
            }
            world.insert_collider(collider, Some(ball));
            self.fired.push_back(ball);
        }
        while self.fired.len() > 600 {
            let old = self.fired.pop_front().expect("a ball");
            world.remove_body(old);
        }
    }
}

/// A streamed level: every step a chunk comes in (40 fixed tiles, each its
/// own body, and 10 dynamic boxes over them) in the slot of the oldest
/// chunk, which goes; 10 chunks (500 bodies) alive. In the rules world the
/// chunk gets rules that leave the physics as it is: its tiles a group that
/// ignores the group of a far marker, half its boxes a personal `Normal`,
/// with `specific` two boxes a specific `NoResponse` about the marker, and
/// with `defaults` the marker's group also ignores `DEFAULT_DYNAMIC`: a rule
/// that reaches the default groups, whose plan then covers every collider
/// (a `FullPass::DefaultGroups`).
struct Stream {
    step: u32,
    chunks: VecDeque<Vec<RigidBodyHandle>>,
    marker: RigidBodyHandle,
    chunk_group: CollisionGroup,
    specific: bool,
}

/// The stream's world, with its marker far away, and the rules: the chunk
/// group, whose tiles ignore each other, and the marker in a group it
/// ignores (and, with `defaults`, the default dynamic group too).
fn stream(specific: bool, defaults: bool) -> (PhysicsWorld, CollisionRuleSet, Stream) {
    let mut world = PhysicsWorld::new();
    let marker =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(1e4, 0.0, 0.0)));
    world.insert_collider(ColliderBuilder::ball(0.5), Some(marker));
    let mut rules = CollisionRuleSet::default();
    let (chunk_group, far) = (rules.create_group(), rules.create_group());
    rules.set_group(marker, Some(far));
    rules.set_group_rule(chunk_group, far, CollisionRule::NoPair);
    if defaults {
        rules.set_group_rule(far, CollisionGroup::DEFAULT_DYNAMIC, CollisionRule::NoPair);
    }
    // The tiles are fixed: without this rule their pairs with each other
    // are `Normal`, which two non-dynamic bodies get as `NoResponse`
    // (contacts, no response), and Rapier would compute contacts between
    // every two neighbouring tiles (`docs/performance.md`, "Why is my
    // world slow").
    rules.set_group_rule(chunk_group, chunk_group, CollisionRule::NoPair);
    let stream = Stream {
        step: 0,
        chunks: VecDeque::new(),
        marker,
        chunk_group,
        specific,
    };
    (world, rules, stream)
}

/// Removes the oldest batch of bodies (a chunk, a volley) once `alive`
/// batches are in the world, to make room for this step's.
fn retire(world: &mut PhysicsWorld, batches: &mut VecDeque<Vec<RigidBodyHandle>>, alive: usize) {
    if batches.len() == alive {
        for body in batches.pop_front().into_iter().flatten() {
            world.remove_body(body);
        }
    }
}

impl Churn for Stream {
    fn apply(&mut self, world: &mut PhysicsWorld, mut rules: Option<&mut CollisionRuleSet>) {
        retire(world, &mut self.chunks, 10);
        let slot = (self.step % 10) as f32 * 12.0;
        self.step += 1;
        let mut chunk = Vec::with_capacity(50);
        for i in 0..40 {
            let (x, z) = ((i % 8) as f32 * 1.0 + slot, (i / 8) as f32 * 1.0);
            let tile =
                world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(x, 0.0, z)));
            world.insert_collider(ColliderBuilder::cuboid(0.5, 0.25, 0.5), Some(tile));
            if let Some(rules) = rules.as_deref_mut() {
                rules.set_group(tile, Some(self.chunk_group));
            }
            chunk.push(tile);
        }
        for i in 0..10 {
            let (x, z) = (
                (i % 5) as f32 * 1.5 + slot + 0.5,
                (i / 5) as f32 * 2.0 + 1.0,
            );
            let body =
                world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(x, 1.0, z)));
            world.insert_collider(ColliderBuilder::cuboid(0.3, 0.3, 0.3), Some(body));
            if let Some(rules) = rules.as_deref_mut() {
                if i % 2 == 0 {
                    rules.set_personal(body, CollisionRule::Normal);
                }
                if self.specific && i < 2 {
                    rules.set_specific(body, self.marker, CollisionRule::NoResponse);
                }
            }
            chunk.push(body);
        }
        self.chunks.push_back(chunk);
    }
}

/// A pickup field: a car (one body: a chassis and four wheels, five
/// colliders) driven round a ring of 100 fixed pickups on a floor, its
/// velocity set every step as a game's controller would. In the rules world
/// each pickup says `set_specific(car, pickup, NoResponse)`: the car passes
/// through, the pair keeps its contacts (to count the pickup); in the plain
/// twin, hand-written solver groups set the car apart from the pickups.
struct Pickups {
    car: RigidBodyHandle,
}

/// The ring's radius (m) and the car's speed (m/s): a lap every 940 steps.
const RING: f32 = 20.0;
const SPEED: f32 = 8.0;

fn pickups(by_hand: bool) -> (PhysicsWorld, CollisionRuleSet, Pickups) {
    let mut world = PhysicsWorld::new();
    let ground = world.insert_body(RigidBodyBuilder::fixed());
    world.insert_collider(
        ColliderBuilder::cuboid(40.0, 0.5, 40.0).translation(Vector::new(0.0, -0.5, 0.0)),
        Some(ground),
    );
    let car = world.insert_body(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(RING, 0.0, 0.0))
            .lock_rotations()
            .can_sleep(false),
    );
    let solver = |member: Group, excluded: Group| {
        InteractionGroups::new(member, Group::ALL - excluded, InteractionTestMode::And)
    };
    let mut parts =
        vec![ColliderBuilder::cuboid(1.0, 0.25, 0.6).translation(Vector::new(0.0, 0.8, 0.0))];
    for (x, z) in [(-0.7, -0.5), (-0.7, 0.5), (0.7, -0.5), (0.7, 0.5)] {
        parts.push(
            ColliderBuilder::ball(0.3)
                .translation(Vector::new(x, 0.3, z))
                .friction(0.0),
        );
    }
    for part in parts {
        let part = if by_hand {
            part.solver_groups(solver(Group::GROUP_2, Group::GROUP_3))
        } else {
            part
        };
        world.insert_collider(part, Some(car));
    }
    let mut rules = CollisionRuleSet::default();
    for i in 0..100 {
        let angle = i as f32 / 100.0 * std::f32::consts::TAU;
        let pickup = world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(
            RING * angle.cos(),
            0.8,
            RING * angle.sin(),
        )));
        let mut coin = ColliderBuilder::ball(0.4);
        if by_hand {
            coin = coin.solver_groups(solver(Group::GROUP_3, Group::GROUP_2));
        } else {
            rules.set_specific(car, pickup, CollisionRule::NoResponse);
        }
        world.insert_collider(coin, Some(pickup));
    }
    (world, rules, Pickups { car })
}

impl Churn for Pickups {
    fn apply(&mut self, world: &mut PhysicsWorld, _: Option<&mut CollisionRuleSet>) {
        let car = &mut world.bodies[self.car];
        let at = car.translation();
        let angle = at.z.atan2(at.x);
        let fall = car.linvel().y;
        car.set_linvel(
            Vector::new(-angle.sin() * SPEED, fall, angle.cos() * SPEED),
            true,
        );
    }
}

/// Balls in and out at a rate: one fixed turret (a 3 m cube) in the middle
/// of a level of fixed tiles (each its own body, no rules), firing
/// `per_step` balls a step from points inside itself, each ball removed 20
/// steps after it was fired. The balls ignore the turret: in the rules
/// world through `set_specific(ball, turret, NoPair)` or, with `group`,
/// through a group rule; in the plain twin through hand-written collision
/// groups.
struct Rate {
    turret: RigidBodyHandle,
    per_step: usize,
    shots: Option<CollisionGroup>,
    fired: VecDeque<Vec<RigidBodyHandle>>,
    step: u32,
}

fn rate(
    tiles: usize,
    per_step: usize,
    group: bool,
    by_hand: bool,
) -> (PhysicsWorld, CollisionRuleSet, Rate) {
    let mut world = PhysicsWorld::new();
    let side = (tiles as f32).sqrt().ceil() as usize;
    let middle = side as f32 / 2.0;
    for i in 0..tiles {
        let (x, z) = ((i % side) as f32 - middle, (i / side) as f32 - middle);
        let tile =
            world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(x, -0.25, z)));
        world.insert_collider(ColliderBuilder::cuboid(0.5, 0.25, 0.5), Some(tile));
    }
    let turret =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, 1.5, 0.0)));
    let mut cube = ColliderBuilder::cuboid(1.5, 1.5, 1.5);
    if by_hand {
        cube = cube.collision_groups(apart(true));
    }
    world.insert_collider(cube, Some(turret));
    let mut rules = CollisionRuleSet::default();
    let shots = (group && !by_hand).then(|| {
        let (guns, shots) = (rules.create_group(), rules.create_group());
        rules.set_group(turret, Some(guns));
        rules.set_group_rule(guns, shots, CollisionRule::NoPair);
        shots
    });
    let churn = Rate {
        turret,
        per_step,
        shots,
        fired: VecDeque::new(),
        step: 0,
    };
    (world, rules, churn)
}

impl Churn for Rate {
    fn apply(&mut self, world: &mut PhysicsWorld, mut rules: Option<&mut CollisionRuleSet>) {
        retire(world, &mut self.fired, 20);
        self.step += 1;
        let from = world.bodies[self.turret].translation();
        let mut volley = Vec::with_capacity(self.per_step);
        for i in 0..self.per_step {
            // A 6 x 6 x 6 lattice inside the turret, 0.5 m apart, turned a
            // little every step; each ball flies out from the middle.
            let slot = (i + self.step as usize * 7) % 216;
            let at = Vector::new(
                (slot % 6) as f32 - 2.5,
                ((slot / 6) % 6) as f32 - 2.5,
                (slot / 36) as f32 - 2.5,
            ) * 0.5;
            let aim = (at + Vector::new(0.0, 1.0, 0.0)).normalize() * 15.0;
            let ball = world.insert_body(
                RigidBodyBuilder::dynamic()
                    .translation(from + at)
                    .linvel(aim),
            );
            let mut collider = ColliderBuilder::ball(0.1);
            match rules.as_deref_mut() {
                Some(rules) => match self.shots {
                    Some(shots) => rules.set_group(ball, Some(shots)),
                    None => rules.set_specific(ball, self.turret, CollisionRule::NoPair),
                },
                None => collider = collider.collision_groups(apart(false)),
            }
            world.insert_collider(collider, Some(ball));
            volley.push(ball);
        }
        self.fired.push_back(volley);
    }
}

/// A world that changes every step (`docs/performance.md`, "Worlds that
/// change").
#[derive(Clone, Copy)]
enum Changing {
    Shooters(Shot),
    Stream {
        specific: bool,
        defaults: bool,
    },
    Pickups,
    /// `per_step` balls in and as many out every step over a level of
    /// `tiles` fixed tiles; `group`: the balls ignore the turret through
    /// groups, else through specific entries.
    Rate {
        tiles: usize,
        per_step: usize,
        group: bool,
    },
}

impl Changing {
    /// The world, its rules and its churn: `by_hand` for the plain twin,
    /// whose physics is made alike by hand-written Rapier settings.
    fn make(self, by_hand: bool) -> (PhysicsWorld, CollisionRuleSet, Box<dyn Churn>) {
        match self {
            Changing::Shooters(shot) => {
                let (world, rules, churn) = shooters(by_hand, shot);
                (world, rules, Box::new(churn))
            }
            Changing::Stream { specific, defaults } => {
                let (world, rules, churn) = stream(specific, defaults);
                (world, rules, Box::new(churn))
            }
            Changing::Pickups => {
                let (world, rules, churn) = pickups(by_hand);
                (world, rules, Box::new(churn))
            }
            Changing::Rate {
                tiles,
                per_step,
                group,
            } => {
                let (world, rules, churn) = rate(tiles, per_step, group, by_hand);
                (world, rules, Box::new(churn))
            }
        }
    }
}

/// The twins of a world that changes every step, warmed up for 120 steps
/// (the balls and chunks at their full count). In the control both twins
/// are the plain world.
fn churn_twins(scene: Changing, control: bool) -> Twins {
    let (plain, _, plain_churn) = scene.make(true);
    let (world, rules, churn) = scene.make(control);
    let rules = if control {
        CollisionRuleSet::default()
    } else {
        rules
    };
    let mut twins = Twins {
        plain,
        world,
        hooks: RuleHooks::new(rules),
        control,
        churn: Some([plain_churn, churn]),
    };
    twins.plan_alike();
    twins.time(60, true);
    twins.time(60, false);
    twins
}

/// A scene's two worlds: plain, and with the scene's rules.
fn twins(make: &dyn Fn(bool) -> Scene, control: bool) -> Twins {
    let plain = make(false).world;
    let Scene { world, rules } = make(true);
    let mut twins = Twins {
        plain,
        world,
        hooks: RuleHooks::new(rules),
        control,
        churn: None,
    };
    twins.plan_alike();
    // What is measured is the steady state.
    twins.time(2, true);
    twins.time(2, false);
    twins
}

trait PairedRuns {
    fn paired(&mut self) -> Paired;
}

impl PairedRuns for Twins {
    /// Five paired runs: each the ratio of the rules world's time to the
    /// plain one's over step pairs timed back to back, and the extra time
    /// per step. Each run lasts at least 0.3 s and 50 pairs; with
    /// `WORLDS_PAIRS=n`, exactly `n` pairs, so that a profile of two builds
    /// counts the same steps (a run of time varies with the machine).
    fn paired(&mut self) -> Paired {
        let exact: Option<u32> = std::env::var("WORLDS_PAIRS")
            .ok()
            .and_then(|n| n.parse().ok());
        let mut runs = Vec::new();
        for _ in 0..5 {
            let (mut plain, mut rules, mut pairs) = (Duration::ZERO, Duration::ZERO, 0u32);
            while match exact {
                Some(n) => pairs < n,
                None => pairs < 50 || plain + rules < Duration::from_millis(300),
            } {
                let pair = self.time_pair(pairs % 2 == 1);
                plain += pair.plain;
                rules += pair.rules;
                pairs += 1;
            }
            runs.push((
                rules.as_secs_f64() / plain.as_secs_f64(),
                plain.as_secs_f64() / f64::from(pairs),
                rules.as_secs_f64() / f64::from(pairs),
            ));
        }
        runs.sort_by(|a, b| a.0.total_cmp(&b.0));
        Paired {
            ratios: runs.iter().map(|r| r.0).collect(),
            plain: runs[2].1,
            rules: runs[2].2,
        }
    }
}

/// What five paired runs gave.
struct Paired {
    /// Sorted.
    ratios: Vec<f64>,
    /// Seconds per step in the median run.
    plain: f64,
    rules: f64,
}

impl Paired {
    /// The CSV fields of every table: us per step plain and with the
    /// rules, then the ratio's median, min and max.
    fn csv(&self) -> String {
        format!(
            "{:.2},{:.2},{:.4},{:.4},{:.4}",
            self.plain * 1e6,
            self.rules * 1e6,
            self.ratios[2],
            self.ratios[0],
            self.ratios[4]
        )
    }
}

type Maker = Box<dyn Fn(bool) -> Scene>;

/// Every variant: a name, a world size, and how to make its twins.
fn variants() -> Vec<(String, usize, Maker)> {
    let mut all: Vec<(String, usize, Maker)> = Vec::new();
    for n in SIZES {
        all.push((
            "level/control".into(),
            n,
            Box::new(move |_| level(n, false)),
        ));
        all.push(("level/none".into(), n, Box::new(move |_| level(n, false))));
        all.push(("level/rules".into(), n, Box::new(move |r| level(n, r))));
        all.push(("field/control".into(), n, Box::new(move |_| field(n))));
        all.push(("field/none".into(), n, Box::new(move |_| field(n))));
    }
    all.push(("soft/control".into(), 1_002, Box::new(|_| soft(false))));
    all.push(("soft/none".into(), 1_002, Box::new(|_| soft(false))));
    all.push(("soft/rules".into(), 1_002, Box::new(soft)));
    all.push(("floor/control".into(), 2_001, Box::new(|_| floor(true))));
    all.push(("floor/one-rule".into(), 2_001, Box::new(|r| floor(!r))));
    all.push((
        "pile-asleep/control".into(),
        1_000,
        Box::new(|_| sleeping_pile(false)),
    ));
    all.push((
        "pile-asleep/none".into(),
        1_000,
        Box::new(|_| sleeping_pile(false)),
    ));
    all.push((
        "pile-asleep/specific".into(),
        1_000,
        Box::new(sleeping_pile),
    ));
    all
}

fn selected(name: &str) -> bool {
    // WORLDS_VARIANTS=level,floor limits the runs to the scenes whose names
    // start so; `=churn/stream` to the scene of that name alone.
    std::env::var("WORLDS_VARIANTS").map_or(true, |v| {
        v.split(',').any(|x| match x.strip_prefix('=') {
            Some(exact) => name == exact,
            None => name.starts_with(x),
        })
    })
}

fn worlds(c: &mut Criterion) {
    let mut group = c.benchmark_group("worlds");
    group
        .sample_size(20)
        .measurement_time(Duration::from_secs(3))
        .warm_up_time(Duration::from_secs(1));
    for (name, n, make) in variants() {
        if !selected(&name) {
            continue;
        }
        let mut twins = twins(&*make, name.ends_with("/control"));
        for (side, rules) in [("plain", false), ("rules", true)] {
            let id = BenchmarkId::new(format!("{name}/{side}"), n);
            group.bench_function(id, |b| b.iter_custom(|iters| twins.time(iters, rules)));
        }
    }
    group.finish();
}

/// The worlds that change every step: a name, a size (the objects alive,
/// or the level's tiles for `rate`), the scene, and whether it is a
/// control (`docs/performance.md`, "Worlds that change").
fn changing() -> Vec<(String, usize, Changing, bool)> {
    let mut all = vec![
        (
            "churn/control".into(),
            600,
            Changing::Shooters(Shot::BallNames),
            true,
        ),
        (
            "churn/shooters".into(),
            600,
            Changing::Shooters(Shot::BallNames),
            false,
        ),
        (
            "churn/shooters-owned".into(),
            600,
            Changing::Shooters(Shot::TurretNames),
            false,
        ),
        (
            "churn/shooters-until".into(),
            600,
            Changing::Shooters(Shot::BallUntil),
            false,
        ),
        (
            "churn/stream-control".into(),
            500,
            Changing::Stream {
                specific: false,
                defaults: false,
            },
            true,
        ),
        (
            "churn/stream-groups".into(),
            500,
            Changing::Stream {
                specific: false,
                defaults: false,
            },
            false,
        ),
        (
            "churn/stream".into(),
            500,
            Changing::Stream {
                specific: true,
                defaults: false,
            },
            false,
        ),
        (
            "churn/stream-defaults".into(),
            500,
            Changing::Stream {
                specific: false,
                defaults: true,
            },
            false,
        ),
        ("churn/pickups-control".into(), 106, Changing::Pickups, true),
        ("churn/pickups".into(), 106, Changing::Pickups, false),
    ];
    for tiles in RATE_SIZES {
        let scene = |per_step, group| Changing::Rate {
            tiles,
            per_step,
            group,
        };
        all.push(("rate/control-50".into(), tiles, scene(50, false), true));
        for per_step in RATES {
            for (kind, group) in [("specific", false), ("group", true)] {
                let name = format!("rate/{kind}-{per_step}");
                all.push((name, tiles, scene(per_step, group), false));
            }
        }
    }
    all
}

/// The chart of extra time against change: balls in (and as many out) per
/// step, and the two level sizes they are fired over.
const RATES: [usize; 5] = [0, 5, 20, 50, 200];
const RATE_SIZES: [usize; 2] = [1_000, 8_000];

fn paired() -> Result<(), Box<dyn std::error::Error>> {
    println!("paired runs (rules / plain: median [min, max] of 5; us per step in the median run):");
    let mut csv = String::from("scene,size,plain_us,rules_us,ratio_median,ratio_min,ratio_max\n");
    let mut rows = Vec::new();
    let churn = changing()
        .into_iter()
        .map(|(name, n, scene, control)| (name, n, None, Some((scene, control))));
    let idle = variants()
        .into_iter()
        .map(|(name, n, make)| (name, n, Some(make), None));
    for (name, n, make, churned) in idle.chain(churn) {
        if !selected(&name) {
            continue;
        }
        let mut twins = match (make, churned) {
            (Some(make), _) => twins(&*make, name.ends_with("/control")),
            (None, Some((scene, control))) => churn_twins(scene, control),
            (None, None) => unreachable!("every variant is idle or changes"),
        };
        let p = twins.paired();
        let stats = twins.hooks.stats();
        println!(
            "  {name:<22} {n:>6}: {:.3} [{:.3}, {:.3}]  plain {:>9.1} us  rules {:>9.1} us  extra {:>7.2} us  (hooked {}, watched {}, planned {}, tracked pairs {}{})",
            p.ratios[2],
            p.ratios[0],
            p.ratios[4],
            p.plain * 1e6,
            p.rules * 1e6,
            (p.rules - p.plain) * 1e6,
            stats.hooked_colliders,
            stats.watched_colliders,
            stats.planned_colliders,
            stats.tracked_pairs,
            if twins.identical() {
                ""
            } else {
                "; the twins differ"
            },
        );
        writeln!(csv, "{name},{n},{}", p.csv())?;
        rows.push((name, n, p));
    }
    let twin_scenes: [TwinScene; 2] = [
        (
            "ends/projectiles",
            ends_paired,
            "by hand",
            "ending",
            "both twins through RuleHooks; ratio to the project ending each rule itself",
        ),
        (
            "events/projectiles",
            events_paired,
            "not recording",
            "recording",
            "the ends scene; ratio to the same world not recording rule events",
        ),
    ];
    for (name, run, second, first, why) in twin_scenes {
        if !selected(name) {
            continue;
        }
        let p = run();
        println!(
            "  {name:<22} {:>6}: {:.3} [{:.3}, {:.3}]  {second} {:>9.1} us  {first} {:>9.1} us  ({why})",
            400,
            p.ratios[2],
            p.ratios[0],
            p.ratios[4],
            p.plain * 1e6,
            p.rules * 1e6,
        );
        writeln!(csv, "{name},400,{}", p.csv())?;
    }
    if let Ok(out) = std::env::var("WORLDS_OUT") {
        let dir = std::path::Path::new(&out);
        if rows.iter().any(|(name, _, _)| name.starts_with("level/")) {
            std::fs::write(dir.join("upkeep.csv"), &csv)?;
            chart(&dir.join("upkeep.svg"), &rows)?;
            println!("wrote upkeep.csv and upkeep.svg in {out}");
        }
        if rows.iter().any(|(name, _, _)| name.starts_with("rate/")) {
            rate_chart(dir, &rows)?;
            println!("wrote churn_rate.csv and churn_rate.svg in {out}");
        }
    }
    Ok(())
}

/// A scene of two `Ends` twins: its name, its run, what the second twin
/// and the first are, and what the ratio compares.
type TwinScene = (
    &'static str,
    fn() -> Paired,
    &'static str,
    &'static str,
    &'static str,
);

/// The `ends` scene's world: the level, and ten fixed turrets on it.
fn turret_level() -> (PhysicsWorld, Vec<RigidBodyHandle>) {
    let Scene { mut world, .. } = level(4_000, false);
    let turrets = (0..10)
        .map(|i| {
            let at = Vector::new(i as f32 * 12.0 + 6.0, 1.0, 60.0);
            let turret = world.insert_body(RigidBodyBuilder::fixed().translation(at));
            world.insert_collider(ColliderBuilder::cuboid(0.5, 1.0, 0.5), Some(turret));
            turret
        })
        .collect();
    (world, turrets)
}

/// One twin of the `ends` scene: its world, its hooks, the turrets, the
/// projectiles alive (with their turret), and whether the project ends
/// each rule itself.
struct Ends {
    world: PhysicsWorld,
    hooks: RuleHooks,
    turrets: Vec<RigidBodyHandle>,
    fired: VecDeque<(RigidBodyHandle, RigidBodyHandle)>,
    step: u32,
    by_hand: bool,
    /// Rule events are recorded and drained after each step.
    drain: bool,
}

impl Ends {
    fn new(by_hand: bool) -> Ends {
        let (world, turrets) = turret_level();
        Ends {
            world,
            hooks: RuleHooks::default(),
            turrets,
            fired: VecDeque::new(),
            step: 0,
            by_hand,
            drain: false,
        }
    }

    /// Fires this step's share of 200 a second (60 steps a second) from
    /// inside the turrets in turn, removes projectiles two seconds old,
    /// and, by hand, removes the rules whose sides are apart; then steps.
    fn step(&mut self) {
        let fire = (self.step + 1) * 200 / 60 - self.step * 200 / 60;
        for k in 0..fire {
            let n = self.step * 4 + k;
            let turret = self.turrets[n as usize % self.turrets.len()];
            let angle = n as f32 * 0.7;
            let ball = self.world.insert_body(
                RigidBodyBuilder::dynamic()
                    .translation(self.world.bodies[turret].translation())
                    .linvel(Vector::new(angle.cos(), 0.4, angle.sin()) * 20.0)
                    .ccd_enabled(true),
            );
            self.world
                .insert_collider(ColliderBuilder::ball(0.1), Some(ball));
            let rules = self.hooks.rules_mut();
            if self.by_hand {
                rules.set_specific(ball, turret, CollisionRule::NoContacts);
            } else {
                rules.set_specific_until(ball, turret, CollisionRule::NoContacts, Until::apart());
            }
            self.fired.push_back((ball, turret));
        }
        while self.fired.len() > 400 {
            let (old, _) = self.fired.pop_front().expect("a projectile");
            self.world.remove_body(old);
        }
        if self.by_hand {
            let mut due: Vec<_> = self
                .fired
                .iter()
                .filter(|&&(ball, turret)| {
                    self.hooks.rules().specific(ball, turret).is_decided()
                        && self.apart(ball, turret)
                })
                .copied()
                .collect();
            due.sort_unstable_by_key(|&(ball, _)| ball.into_raw_parts());
            for (ball, turret) in due {
                self.hooks.rules_mut().remove_specific(ball, turret);
            }
        }
        self.step += 1;
        self.hooks.step(&mut self.world);
        if self.drain {
            std::hint::black_box(self.hooks.drain_rule_events().count());
        }
    }

    /// The project's own test: no box of one overlaps a box of the other.
    fn apart(&self, a: RigidBodyHandle, b: RigidBodyHandle) -> bool {
        use rapier3d::parry::bounding_volume::BoundingVolume;
        let boxes = |body: RigidBodyHandle| {
            self.world.bodies[body]
                .colliders()
                .iter()
                .map(|&c| self.world.colliders[c].compute_aabb())
                .collect::<Vec<_>>()
        };
        let (a, b) = (boxes(a), boxes(b));
        !a.iter().any(|x| b.iter().any(|y| x.intersects(y)))
    }
}

/// The `ends` scene: five paired runs of the twin whose rules end by
/// themselves against the twin whose project ends them, after two seconds
/// of firing (400 projectiles alive).
fn ends_paired() -> Paired {
    twins_paired([Ends::new(false), Ends::new(true)])
}

/// The `events` scene: the `ends` scene recording rule events (drained
/// after each step) against the same scene not recording.
fn events_paired() -> Paired {
    let mut recording = Ends::new(false);
    recording.hooks.record_rule_events(true);
    recording.drain = true;
    twins_paired([recording, Ends::new(false)])
}

/// Five paired runs of the first twin against the second, after two
/// seconds of firing; the two must step alike.
fn twins_paired(mut twins: [Ends; 2]) -> Paired {
    for _ in 0..120 {
        twins.iter_mut().for_each(Ends::step);
    }
    let mut runs = Vec::new();
    for _ in 0..5 {
        let mut took = [Duration::ZERO; 2];
        let mut pairs = 0u32;
        while pairs < 50 || took[0] + took[1] < Duration::from_millis(300) {
            let order = if pairs % 2 == 0 { [0, 1] } else { [1, 0] };
            for i in order {
                let start = std::time::Instant::now();
                twins[i].step();
                took[i] += start.elapsed();
            }
            pairs += 1;
        }
        let [ends, by_hand] = took.map(|t| t.as_secs_f64() / f64::from(pairs));
        runs.push((ends / by_hand, by_hand, ends));
    }
    let same = twins[0]
        .world
        .bodies
        .iter()
        .zip(twins[1].world.bodies.iter())
        .all(|((_, a), (_, b))| a.position() == b.position());
    assert!(
        same,
        "the twins of the ends scene differ: the rules did not end as the project ends them \
         (or recording events changed the physics)"
    );
    runs.sort_by(|a, b| a.0.total_cmp(&b.0));
    Paired {
        ratios: runs.iter().map(|r| r.0).collect(),
        plain: runs[2].1,
        rules: runs[2].2,
    }
}

/// Step time against world size: plain Rapier and `RuleHooks`, on the idle
/// level and the asleep field (log-log).
fn chart(
    path: &std::path::Path,
    rows: &[(String, usize, Paired)],
) -> Result<(), Box<dyn std::error::Error>> {
    let root = chart::canvas(path, (760, 460))?;
    let mut chart = chart::builder(
        &root,
        "Step time against world size: plain Rapier and RuleHooks",
    )
    .build_cartesian_2d(
        (500f64..100_000f64).log_scale(),
        (0.3f64..3_000f64).log_scale(),
    )?;
    chart
        .configure_mesh()
        .x_desc("world size (level tiles, field boxes)")
        .y_desc("time per step (us)")
        .draw()?;
    let series = [
        ("level/none", false, "level, plain Rapier", BLUE),
        ("level/none", true, "level, RuleHooks (no rules)", RED),
        ("level/rules", true, "level, RuleHooks (20 rules)", MAGENTA),
        ("field/none", false, "asleep field, plain Rapier", GREEN),
        ("field/none", true, "asleep field, RuleHooks", BLACK),
    ];
    for (scene, with_rules, label, color) in series {
        let points: Vec<(f64, f64)> = rows
            .iter()
            .filter(|(name, _, _)| name == scene)
            .map(|(_, n, p)| (*n as f64, if with_rules { p.rules } else { p.plain } * 1e6))
            .collect();
        if points.is_empty() {
            continue;
        }
        chart::line(&mut chart, &points, label, color)?;
    }
    chart::finish(chart, &root)
}

/// Extra time per step against the balls fired (and removed) per step, over
/// the two level sizes, for both ways of saying the rule: linear in the
/// changes, flat in the level.
fn rate_chart(
    dir: &std::path::Path,
    rows: &[(String, usize, Paired)],
) -> Result<(), Box<dyn std::error::Error>> {
    let mut csv = String::from(
        "tiles,rule,per_step,plain_us,rules_us,ratio_median,ratio_min,ratio_max,extra_us\n",
    );
    let mut series: Vec<(String, Vec<(f64, f64)>)> = Vec::new();
    for (name, n, p) in rows {
        let Some(rest) = name.strip_prefix("rate/") else {
            continue;
        };
        let Some((kind, per_step)) = rest.rsplit_once('-') else {
            continue;
        };
        let extra = (p.rules - p.plain) * 1e6;
        writeln!(csv, "{n},{kind},{per_step},{},{extra:.2}", p.csv())?;
        if kind == "control" {
            continue;
        }
        let label = format!("{kind} rules, {n} tiles");
        let point = (per_step.parse::<f64>()?, extra);
        match series.iter_mut().find(|(l, _)| *l == label) {
            Some((_, points)) => points.push(point),
            None => series.push((label, vec![point])),
        }
    }
    std::fs::write(dir.join("churn_rate.csv"), &csv)?;
    let top = series
        .iter()
        .flat_map(|(_, points)| points.iter().map(|p| p.1))
        .fold(10.0f64, f64::max)
        * 1.15;
    let path = dir.join("churn_rate.svg");
    let root = chart::canvas(&path, (760, 460))?;
    let mut chart = chart::builder(
        &root,
        "Extra time per step against objects changed per step",
    )
    .build_cartesian_2d(0f64..210f64, (-0.1 * top)..top)?;
    chart
        .configure_mesh()
        .x_desc("balls fired per step (as many removed)")
        .y_desc("RuleHooks - plain Rapier (us per step)")
        .draw()?;
    let colors = [BLUE, RED, GREEN, MAGENTA];
    for ((label, points), color) in series.iter().zip(colors) {
        chart::line(&mut chart, points, label, color)?;
    }
    chart::finish(chart, &root)
}

criterion_group!(benches, worlds);

fn main() -> Result<(), Box<dyn std::error::Error>> {
    if std::env::var_os("WORLDS_PAIRED_ONLY").is_none() {
        benches();
    }
    if std::env::var_os("WORLDS_CRITERION_ONLY").is_none() {
        paired()?;
    }
    Criterion::default().configure_from_args().final_summary();
    Ok(())
}
