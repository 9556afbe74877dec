//! Rules with an end (`docs/semantics.md`, "Rules with an end"): before
//! each step the ends of specific entries and of pair overrides are
//! counted, and a rule whose end came is removed, so that its pairs fall
//! back to the other stages in the step about to be taken. The count of
//! the entries' ends costs the ends that come (`model/endings.rs`), that of
//! the overrides' ends a look at each, and the test for apart the colliders
//! of its two sides: nothing else in the world.

use super::super::rapier::prelude::*;

use super::super::model::{Countdown, Due, DueEnd};
use super::super::world::apart;
use super::super::{CollisionRule, Until};
use super::{PairKey, RuleHooks};

/// Whether the rules with an end can count a step of `dt` seconds: a
/// finite time, zero (a paused world) or more.
pub(super) fn counts(dt: Real) -> bool {
    dt >= 0.0 && dt.is_finite()
}

impl RuleHooks {
    /// Replaces the rule of the live pair of `a` and `b` as
    /// [`set_pair_rule`](Self::set_pair_rule) does, until `until` comes:
    /// then the override is dropped before the next step and the pair takes
    /// the rule the rules give it. The sides tested for apart are the two
    /// colliders. Returns `false`, changing nothing, if they form no live
    /// pair.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, RuleHooks, Until};
    ///
    /// let mut world = PhysicsWorld::new();
    /// let ground = world.insert_body(RigidBodyBuilder::fixed());
    /// let floor = world.insert_collider(ColliderBuilder::cuboid(10.0, 0.5, 10.0), Some(ground));
    /// let body = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 1.0, 0.0)));
    /// let cube = world.insert_collider(ColliderBuilder::cuboid(0.5, 0.5, 0.5), Some(body));
    /// let mut hooks = RuleHooks::default();
    /// hooks.step(&mut world);
    /// // Ten steps of falling through, then the floor holds again: the cube
    /// // is still inside it, so the override lasts until they are apart.
    /// assert!(hooks.set_pair_rule_until(&world, cube, floor, CollisionRule::NoResponse, Until::steps(10)));
    /// for _ in 0..120 {
    ///     hooks.step(&mut world);
    /// }
    /// assert!(world.bodies[body].translation().y < -1.0, "the cube fell through");
    /// assert_eq!(hooks.pair_rule(&world, cube, floor), None, "apart: the pair and its override are gone");
    /// ```
    pub fn set_pair_rule_until<'w>(
        &mut self,
        world: impl Into<super::WorldRef<'w>>,
        a: ColliderHandle,
        b: ColliderHandle,
        rule: CollisionRule,
        until: Until,
    ) -> bool {
        let set = self.set_pair_rule(world, a, b, rule);
        if set && rule.is_decided() {
            self.pair_ends.insert(PairKey::new(a, b), Countdown::new(until));
        }
        set
    }

    /// The end of the override of the live pair of `a` and `b`, `None` if
    /// it has none or the pair has no override.
    #[must_use]
    pub fn pair_rule_until(&self, a: ColliderHandle, b: ColliderHandle) -> Option<Until> {
        let key = PairKey::new(a, b);
        self.pairs.get(key).and_then(|state| state.overridden)?;
        self.pair_ends.get(&key).map(Countdown::until)
    }

    /// How much simulated time the steps between the next
    /// [`prepare`](Self::prepare) and [`after_step`](Self::after_step)
    /// take, for rules given for a time ([`Until::seconds`]), when
    /// stepping a bare pipeline: [`step`](Self::step) and
    /// [`step_pipeline`](Self::step_pipeline) read the world's
    /// `IntegrationParameters::dt` themselves. Zero says that no step is
    /// taken (a paused game): then no end is counted, neither steps nor
    /// time nor apart. Starts at `IntegrationParameters::default().dt`, and
    /// holds until set again.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, RuleHooks, Until};
    ///
    /// let (mut bodies, mut colliders) = (RigidBodySet::new(), ColliderSet::new());
    /// let a = bodies.insert(RigidBodyBuilder::dynamic());
    /// colliders.insert_with_parent(ColliderBuilder::ball(0.5), a, &mut bodies);
    /// let b = bodies.insert(RigidBodyBuilder::dynamic());
    /// colliders.insert_with_parent(ColliderBuilder::ball(0.5), b, &mut bodies);
    /// let mut hooks = RuleHooks::default();
    /// hooks.rules_mut().set_specific_until(a, b, CollisionRule::NoContacts, Until::steps(2));
    /// hooks.set_timestep(0.0);
    /// for _ in 0..5 {
    ///     hooks.prepare(&bodies, &mut colliders); // paused: nothing counts
    /// }
    /// assert_eq!(hooks.rules().specific_until(a, b).and_then(|u| u.steps_left()), Some(2));
    /// hooks.set_timestep(1.0 / 60.0);
    /// hooks.prepare(&bodies, &mut colliders);
    /// assert_eq!(hooks.rules().specific_until(a, b).and_then(|u| u.steps_left()), Some(1));
    /// ```
    ///
    /// # Panics
    ///
    /// If `dt` is negative, infinite or not a number.
    #[track_caller]
    pub fn set_timestep(&mut self, dt: Real) {
        assert!(
            counts(dt),
            "RuleHooks::set_timestep({dt}): the time the coming steps take, a finite number of \
             seconds, zero or more"
        );
        self.boundary.dt = dt;
    }

    /// Whether any rule has an end to count.
    pub(super) fn has_ends(&self) -> bool {
        self.decide.rules.has_endings() || !self.pair_ends.is_empty()
    }

    /// Counts the step about to be taken against every rule with an end,
    /// and removes those whose end came. In the node order, then the pair
    /// order: the edits reach the plan and Rapier in the same order in
    /// every run.
    pub(super) fn end_rules(&mut self, bodies: &RigidBodySet, colliders: &ColliderSet) {
        let dt = self.boundary.dt;
        if !self.has_ends() || dt == 0.0 || self.boundary.counted {
            // No step is taken (nothing moves, and no count runs), or this
            // step was counted by an earlier `prepare` of its bracket.
            return;
        }
        self.boundary.counted = true;
        let rules = &mut self.decide.rules;
        for DueEnd {
            node,
            other,
            due,
            margin,
        } in rules.count_ends(dt)
        {
            let ends = match due {
                Due::Now => true,
                Due::IfApart => {
                    let side1 = rules.colliders_under(node, bodies, colliders);
                    let side2 = rules.colliders_under(other, bodies, colliders);
                    apart(&side1, &side2, colliders, margin)
                }
            };
            if ends {
                rules.remove_specific(node, other);
                if let Some(recording) = &mut self.recording {
                    recording.expired.push((node, other));
                }
            }
        }
        let mut pairs: Vec<PairKey> = self.pair_ends.keys().copied().collect();
        pairs.sort_unstable();
        for key in pairs {
            if self.pairs.get(key).is_none_or(|state| state.overridden.is_none()) {
                // The pair ended, or its override was dropped another way.
                self.pair_ends.remove(&key);
                continue;
            }
            let end = self.pair_ends.get_mut(&key).expect("a listed end");
            let (a, b) = key.colliders();
            let ends = match end.count_step(dt) {
                None => false,
                Some(Due::Now) => true,
                Some(Due::IfApart) => apart(&[a], &[b], colliders, end.until().margin()),
            };
            if ends {
                self.pair_ends.remove(&key);
                if let Some(recording) = &mut self.recording {
                    recording.expired_pairs.insert(key);
                }
                // Straight to the state: a `NoPair` override is no live
                // pair to `set_pair_rule`, but Rapier still holds the pair.
                // The rule the rules give the pair now: its bodies may have
                // changed type while the override held it.
                let computed = self.calculate(bodies, colliders, a, b);
                if let Some(state) = self.pairs.get_mut(key) {
                    state.overridden = None;
                    state.computed = computed;
                    state.kinds = key.kinds(bodies, colliders);
                }
                self.queued.replan = Some(super::PlanCause::PinnedPair);
                self.wake_pair(a, b);
            }
        }
    }
}
