//! Rules with an end (`docs/semantics.md`, "Rules with an end"): before
//! each step the ends of specific entries and of pair overrides are
//! counted, and a rule whose end came is removed, so that its pairs fall
//! back to the other stages in the step about to be taken. The count costs
//! one look per rule with an end, and the test for apart the colliders of
//! its two sides: nothing else in the world.

use super::super::rapier::prelude::*;

use super::super::model::Due;
use super::super::world::apart;
use super::super::{CollisionRule, Node, Until};
use super::{PairKey, RuleHooks};

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
            self.pair_ends.insert(PairKey::new(a, b), until);
        }
        set
    }

    /// The end of the override of the live pair of `a` and `b`, `None` if
    /// it has none or the pair has no override.
    #[must_use]
    pub fn pair_rule_until(&self, a: ColliderHandle, b: ColliderHandle) -> Option<Until> {
        let key = PairKey::new(a, b);
        self.pairs.get(key).and_then(|state| state.overridden)?;
        self.pair_ends.get(&key).copied()
    }

    /// How long a step is, for rules given for a time
    /// ([`Until::seconds`]), when stepping a bare pipeline with
    /// [`prepare`](Self::prepare): [`step`](Self::step) and
    /// [`step_pipeline`](Self::step_pipeline) read the world's
    /// `IntegrationParameters::dt` themselves. Starts at
    /// `IntegrationParameters::default().dt`.
    ///
    /// # Panics
    ///
    /// If `dt` is not more than zero.
    #[track_caller]
    pub fn set_timestep(&mut self, dt: Real) {
        assert!(dt > 0.0, "RuleHooks::set_timestep({dt}): a step lasts more than zero seconds");
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
        if !self.has_ends() {
            return;
        }
        let dt = self.boundary.dt;
        let rules = &mut self.decide.rules;
        let mut entries: Vec<(Node, Node)> = rules.endings_mut().keys().copied().collect();
        entries.sort_unstable();
        for (node, other) in entries {
            if !rules.specific(node, other).is_decided() {
                // Removed another way (its object went, say): nothing to end.
                rules.endings_mut().remove(&(node, other));
                continue;
            }
            let until = rules.endings_mut().get_mut(&(node, other)).expect("a listed end");
            let ends = match until.count_step(dt) {
                Due::Not => false,
                Due::Now => true,
                Due::IfApart => {
                    let margin = until.margin_of_apart();
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
            let until = self.pair_ends.get_mut(&key).expect("a listed end");
            let (a, b) = key.colliders();
            let ends = match until.count_step(dt) {
                Due::Not => false,
                Due::Now => true,
                Due::IfApart => apart(&[a], &[b], colliders, until.margin_of_apart()),
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
