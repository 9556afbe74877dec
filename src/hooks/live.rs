//! The live-pair API (`docs/semantics.md`, "Live pairs"): each pair's
//! rule, overrides, manifold settings and forced recalculation.
//!
//! Rapier holds every pair; the hooks keep state only for the pairs the
//! rules reach, so that a world they do not reach costs nothing. The
//! methods without a world ([`RuleHooks::pair_rule`], [`RuleHooks::pairs`])
//! answer from that state: hooked pairs, and the pairs of the colliders the
//! planner configures (groups, collision types). The `*_in` methods take
//! the world and answer for every pair Rapier holds, on demand.

use std::sync::PoisonError;

use rapier3d::prelude::*;

use super::RuleHooks;
use super::upkeep::{pair_exists, partners_of};
use crate::native::{self, Class};
use crate::pairs::{ManifoldUpdate, PairKey, PairState};
use crate::{CollisionRule, Node};

/// What Rapier holds of a world, for the live-pair queries that answer on
/// demand: its narrow phase and its sets. Made from a `&PhysicsWorld`, or
/// with [`WorldRef::new`] for a bare pipeline.
#[derive(Clone, Copy)]
pub struct WorldRef<'a> {
    narrow_phase: &'a NarrowPhase,
    bodies: &'a RigidBodySet,
    colliders: &'a ColliderSet,
}

impl<'a> WorldRef<'a> {
    /// The parts of a world stepped with a bare `PhysicsPipeline`.
    pub fn new(
        narrow_phase: &'a NarrowPhase,
        bodies: &'a RigidBodySet,
        colliders: &'a ColliderSet,
    ) -> WorldRef<'a> {
        WorldRef {
            narrow_phase,
            bodies,
            colliders,
        }
    }
}

impl<'a> From<&'a PhysicsWorld> for WorldRef<'a> {
    fn from(world: &'a PhysicsWorld) -> WorldRef<'a> {
        WorldRef::new(&world.narrow_phase, &world.bodies, &world.colliders)
    }
}

/// The pairs of one native collider the plan configures, as of the last
/// step in which it was looked at: each partner and whether its body was
/// dynamic (an unreached partner's class).
#[derive(Debug, Default)]
pub(crate) struct Partners {
    step: u64,
    /// Whether this collider's body was dynamic.
    dynamic: bool,
    list: Vec<(ColliderHandle, bool)>,
}

/// Live pairs.
impl RuleHooks {
    /// The rule of the live pair of `a` and `b`, in either order, as of the
    /// last step; `None` if the hooks know of no live pair (a `NoPair` pair
    /// is not live). The hooks know every pair of a collider the rules reach
    /// (it or a node of its chain carries rules, is named by one, or is in
    /// the parent map). For a pair of two colliders no rule reaches, ask
    /// [`pair_rule_in`](Self::pair_rule_in).
    #[must_use]
    pub fn pair_rule(&self, a: ColliderHandle, b: ColliderHandle) -> Option<CollisionRule> {
        let key = PairKey::new(a, b);
        match self.pairs.get(key) {
            Some(state) => (!state.absent).then(|| state.rule()),
            None => self.noted_rule(a, b),
        }
        .filter(|&rule| rule != CollisionRule::NoPair)
    }

    /// The rule of the pair of `a` and `b` if Rapier holds it now, for any
    /// pair: answered on demand from Rapier's narrow phase (the cost of a
    /// look-up in Rapier's graph, nothing per step).
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, RuleHooks};
    ///
    /// let mut world = PhysicsWorld::new();
    /// let ground = world.insert_body(RigidBodyBuilder::fixed());
    /// let floor = world.insert_collider(ColliderBuilder::cuboid(10.0, 0.5, 10.0), Some(ground));
    /// let body = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 1.0, 0.0)));
    /// let cube = world.insert_collider(ColliderBuilder::cuboid(0.5, 0.5, 0.5), Some(body));
    /// let mut hooks = RuleHooks::default();
    /// hooks.step(&mut world);
    /// // No rule reaches the cube or the floor: Rapier decides them alone.
    /// assert_eq!(hooks.pair_rule_in(&world, cube, floor), Some(CollisionRule::Normal));
    /// ```
    #[must_use]
    pub fn pair_rule_in<'w>(
        &self,
        world: impl Into<WorldRef<'w>>,
        a: ColliderHandle,
        b: ColliderHandle,
    ) -> Option<CollisionRule> {
        let world = world.into();
        let key = PairKey::new(a, b);
        match self.pairs.get(key) {
            Some(state) if state.absent && !pair_exists(world.narrow_phase, a, b) => None,
            Some(state) => Some(state.rule()),
            None => self.rapier_rule(world, a, b),
        }
        .filter(|&rule| rule != CollisionRule::NoPair)
    }

    /// Every live pair the hooks know (see [`pair_rule`](Self::pair_rule)),
    /// with its rule, in no particular order.
    pub fn pairs(
        &self,
    ) -> impl Iterator<Item = (ColliderHandle, ColliderHandle, CollisionRule)> + '_ {
        let hooked = self
            .pairs
            .iter()
            .filter(|(_, state)| !state.absent)
            .map(|(key, state)| (key.colliders(), state.rule()));
        let noted = self.roster.colliders().iter().flat_map(move |&c| {
            let list = self.partners.get(c).map_or(&[][..], |p| &p.list[..]);
            list.iter().filter_map(move |&(other, _)| {
                // Each pair once: from the fresher side when both are noted.
                let theirs = self.partners.get(other).map(|p| p.step);
                let mine = self.partners.get(c).map(|p| p.step);
                let from_here = match theirs {
                    None => true,
                    Some(step) => {
                        mine > Some(step)
                            || (mine == Some(step) && c.into_raw_parts() < other.into_raw_parts())
                    }
                };
                if !from_here || self.pairs.get(PairKey::new(c, other)).is_some() {
                    return None;
                }
                self.noted_rule(c, other).map(|rule| ((c, other), rule))
            })
        });
        hooked
            .chain(noted)
            .filter(|&(_, rule)| rule != CollisionRule::NoPair)
            .map(|((a, b), rule)| (a, b, rule))
    }

    /// Every pair Rapier holds now, with its rule, in no particular order:
    /// on demand, a walk of Rapier's pair lists.
    pub fn pairs_in<'a, W: Into<WorldRef<'a>>>(
        &'a self,
        world: W,
    ) -> impl Iterator<Item = (ColliderHandle, ColliderHandle, CollisionRule)> + use<'a, W> {
        let world = world.into();
        let contacts = world
            .narrow_phase
            .contact_pairs()
            .map(|p| (p.collider1, p.collider2));
        let sensors = world
            .narrow_phase
            .intersection_pairs()
            .map(|(a, b, _)| (a, b));
        contacts.chain(sensors).filter_map(move |(a, b)| {
            let rule = match self.pairs.get(PairKey::new(a, b)) {
                // Rapier holds it: a pair kept through regrouping is back.
                Some(state) => state.rule(),
                None => self.rules.resolve(world.bodies, world.colliders, a, b),
            };
            (rule != CollisionRule::NoPair).then_some((a, b, rule))
        })
    }

    /// Replaces the rule of the live pair of `a` and `b` for the rest of the
    /// pair's life (automatic recalculation leaves it alone;
    /// [`force_recalculation`](Self::force_recalculation) drops it). `Defer`
    /// drops the override. `NoPair` ends the pair for the crate. Returns
    /// `false`, changing nothing, if the hooks know of no live pair of `a`
    /// and `b` (see [`pair_rule`](Self::pair_rule);
    /// [`set_pair_rule_in`](Self::set_pair_rule_in) reaches every pair).
    pub fn set_pair_rule(
        &mut self,
        a: ColliderHandle,
        b: ColliderHandle,
        rule: CollisionRule,
    ) -> bool {
        let known = self.noted_rule(a, b);
        self.override_pair(a, b, known, rule)
    }

    /// [`set_pair_rule`](Self::set_pair_rule) for any pair Rapier holds now.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, RuleHooks};
    ///
    /// let mut world = PhysicsWorld::new();
    /// let ground = world.insert_body(RigidBodyBuilder::fixed());
    /// let floor = world.insert_collider(ColliderBuilder::cuboid(10.0, 0.5, 10.0), Some(ground));
    /// let body = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.5, 0.0)));
    /// let cube = world.insert_collider(ColliderBuilder::cuboid(0.5, 0.5, 0.5), Some(body));
    /// let mut hooks = RuleHooks::default();
    /// hooks.step(&mut world);
    /// assert!(hooks.set_pair_rule_in(&world, cube, floor, CollisionRule::NoResponse));
    /// for _ in 0..60 {
    ///     hooks.step(&mut world);
    /// }
    /// assert!(world.bodies[body].translation().y < -1.0, "the cube fell through");
    /// ```
    pub fn set_pair_rule_in<'w>(
        &mut self,
        world: impl Into<WorldRef<'w>>,
        a: ColliderHandle,
        b: ColliderHandle,
        rule: CollisionRule,
    ) -> bool {
        let known = self.rapier_rule(world.into(), a, b);
        self.override_pair(a, b, known, rule)
    }

    fn override_pair(
        &mut self,
        a: ColliderHandle,
        b: ColliderHandle,
        native: Option<CollisionRule>,
        rule: CollisionRule,
    ) -> bool {
        let Some(state) = self.live_state(a, b, native) else {
            return false;
        };
        state.overridden = rule.is_decided().then_some(rule);
        self.replan = true;
        self.wake_pair(a, b);
        true
    }

    /// Sets how the live pair of `a` and `b` updates its contacts. Returns
    /// `false`, changing nothing, if the hooks know of no live pair of `a`
    /// and `b` (see [`pair_rule`](Self::pair_rule);
    /// [`set_manifold_update_in`](Self::set_manifold_update_in) reaches
    /// every pair).
    pub fn set_manifold_update(
        &mut self,
        a: ColliderHandle,
        b: ColliderHandle,
        update: ManifoldUpdate,
    ) -> bool {
        let known = self.noted_rule(a, b);
        self.manifold_pair(a, b, known, update)
    }

    /// [`set_manifold_update`](Self::set_manifold_update) for any pair
    /// Rapier holds now.
    pub fn set_manifold_update_in<'w>(
        &mut self,
        world: impl Into<WorldRef<'w>>,
        a: ColliderHandle,
        b: ColliderHandle,
        update: ManifoldUpdate,
    ) -> bool {
        let known = self.rapier_rule(world.into(), a, b);
        self.manifold_pair(a, b, known, update)
    }

    fn manifold_pair(
        &mut self,
        a: ColliderHandle,
        b: ColliderHandle,
        native: Option<CollisionRule>,
        update: ManifoldUpdate,
    ) -> bool {
        let Some(state) = self.live_state(a, b, native) else {
            return false;
        };
        state.manifold = update;
        *state
            .frozen
            .get_mut()
            .unwrap_or_else(PoisonError::into_inner) = None;
        self.replan = true;
        self.wake_pair(a, b);
        true
    }

    /// The manifold setting of the live pair of `a` and `b`, if the hooks
    /// know of it (see [`pair_rule`](Self::pair_rule)).
    #[must_use]
    pub fn manifold_update(&self, a: ColliderHandle, b: ColliderHandle) -> Option<ManifoldUpdate> {
        match self.pairs.get(PairKey::new(a, b)) {
            Some(state) => {
                (state.rule() != CollisionRule::NoPair && !state.absent).then_some(state.manifold)
            }
            None => self.pair_rule(a, b).map(|_| ManifoldUpdate::ByRule),
        }
    }

    /// Recalculates, before the next step, every live pair of `node` and of
    /// its descendants (the design's `ForceCollisionRuleRecalculation`),
    /// dropping their overrides. A pair that becomes `NoPair` stops being live.
    pub fn force_recalculation(&mut self, node: impl Into<Node>) {
        self.forced.push(node.into());
    }

    /// The rule of a pair the hooks noted after the last step between a
    /// native collider the rules reach and its partner; `None` if no such
    /// pair was noted.
    fn noted_rule(&self, a: ColliderHandle, b: ColliderHandle) -> Option<CollisionRule> {
        // The fresher of the two sides' notes tells whether the pair exists.
        let (pa, pb) = (self.partners.get(a), self.partners.get(b));
        let (from, other, notes) = match (pa, pb) {
            (Some(x), Some(y)) if y.step > x.step => (b, a, y),
            (Some(x), _) => (a, b, x),
            (None, Some(y)) => (b, a, y),
            (None, None) => return None,
        };
        let &(_, other_dynamic) = notes.list.iter().find(|(c, _)| *c == other)?;
        // A pair with a hooked collider is the hook's, in the table.
        let hooked = |c| self.plan.colliders.get(c).is_some_and(|p| p.hooked());
        if hooked(a) || hooked(b) {
            return None;
        }
        let class = |c: ColliderHandle, dynamic: bool| {
            self.plan
                .colliders
                .get(c)
                .map_or(Some(Class::unreached(dynamic)), |p| p.class)
        };
        let from_class = class(from, notes.dynamic)?;
        let other_class = class(other, other_dynamic)?;
        Some(native::class_rule(&self.rules, from_class, other_class))
    }

    /// The rule of a pair Rapier holds now, decided natively (not hooked);
    /// `None` if Rapier holds no such pair.
    fn rapier_rule(
        &self,
        world: WorldRef<'_>,
        a: ColliderHandle,
        b: ColliderHandle,
    ) -> Option<CollisionRule> {
        let held = world.colliders.contains(a)
            && world.colliders.contains(b)
            && pair_exists(world.narrow_phase, a, b);
        held.then(|| self.rules.resolve(world.bodies, world.colliders, a, b))
    }

    /// The table entry of a live pair; a pair the hooks do not track yet
    /// (its rule `native`) gets one, and is hooked from the next step on.
    fn live_state(
        &mut self,
        a: ColliderHandle,
        b: ColliderHandle,
        native: Option<CollisionRule>,
    ) -> Option<&mut PairState> {
        let key = PairKey::new(a, b);
        if self.pairs.get(key).is_none() {
            let rule = native.filter(|&r| r != CollisionRule::NoPair)?;
            self.pairs.insert(key, PairState::new(rule, self.step));
        }
        self.pairs
            .get_mut(key)
            .filter(|state| state.rule() != CollisionRule::NoPair && !state.absent)
    }

    /// Wakes, before the next step, the bodies of `a` and `b`.
    pub(super) fn wake_pair(&mut self, a: ColliderHandle, b: ColliderHandle) {
        self.wake_colliders.extend([a, b]);
    }

    /// Notes the pairs of every native collider the rules reach, after
    /// each step: a resting collider's pairs change when an awake partner
    /// the rules do not reach moves, which nothing else tells. The cost is
    /// a walk of these colliders' pairs in Rapier's graph.
    pub(super) fn note_partners(
        &mut self,
        narrow_phase: &NarrowPhase,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
    ) {
        let step = self.step;
        for &c in self.roster.colliders() {
            // A hooked collider's pairs are in the table.
            let noted =
                colliders.contains(c) && !self.plan.colliders.get(c).is_some_and(|p| p.hooked());
            if !noted {
                self.partners.remove(c);
                continue;
            }
            let dynamic_of = |other: ColliderHandle| {
                colliders
                    .get(other)
                    .and_then(|o| o.parent())
                    .and_then(|b| bodies.get(b))
                    .is_some_and(|b| b.is_dynamic())
            };
            if self.partners.get(c).is_none() {
                self.partners.insert(c, Partners::default());
            }
            let partners = self.partners.get_mut(c).expect("inserted above");
            partners.step = step;
            partners.dynamic = dynamic_of(c);
            partners.list.clear();
            partners
                .list
                .extend(partners_of(narrow_phase, c).map(|other| (other, dynamic_of(other))));
        }
    }
}
