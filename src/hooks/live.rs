//! The live-pair API (`docs/semantics.md`, "Live pairs"): each pair's
//! rule, overrides, manifold settings and forced recalculation.
//!
//! Rapier holds every pair; the hooks keep state only for the pairs the
//! rules reach, so that a world they do not reach costs nothing. The
//! methods without a world ([`RuleHooks::pair_rule`], [`RuleHooks::pairs`])
//! answer from that state: hooked pairs, and the pairs of the colliders the
//! planner configures (groups, collision types). The `*_in` methods take
//! the world and answer for every pair Rapier holds, on demand.

use std::sync::{Mutex, MutexGuard, PoisonError};

use rapier3d::prelude::*;

use super::RuleHooks;
use super::upkeep::{pair_exists, partners_of, same_body};
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

/// Whether the list is sorted, and each noted pair with its colliders' classes.
type Noted = (bool, Vec<(PairKey, Class, Class)>);

/// The pairs of the native colliders the rules reach, noted after each
/// step with the classes of their two colliders: what `pair_rule` and
/// `pairs` answer from for pairs without a hooked collider. Sorted on the
/// first query after a step (queries are rare, steps are not).
#[derive(Debug, Default)]
pub(crate) struct Notes {
    pairs: Mutex<Noted>,
    /// One bit per collider slot: set for the noted colliders.
    bits: Vec<u64>,
}

impl Notes {
    fn sorted(&self) -> MutexGuard<'_, Noted> {
        let mut pairs = self.pairs.lock().unwrap_or_else(PoisonError::into_inner);
        if !pairs.0 {
            pairs.1.sort_unstable_by_key(|(k, _, _)| key_order(*k));
            pairs.0 = true;
        }
        pairs
    }

    fn noted(&self, c: ColliderHandle) -> bool {
        bit(&self.bits, c)
    }
}

/// Whether the bit of `c`'s slot is set.
fn bit(bits: &[u64], c: ColliderHandle) -> bool {
    let index = c.into_raw_parts().0 as usize;
    bits.get(index / 64)
        .is_some_and(|w| w >> (index % 64) & 1 == 1)
}

fn key_order(key: PairKey) -> ((u32, u32), (u32, u32)) {
    let (a, b) = key.colliders();
    (a.into_raw_parts(), b.into_raw_parts())
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
        let noted: Vec<_> = self
            .notes
            .sorted()
            .1
            .iter()
            .map(|&(key, x, y)| (key.colliders(), native::class_rule(&self.rules, x, y)))
            .collect();
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
            if same_body(world.colliders, a, b) {
                return None;
            }
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
        if !self.notes.noted(a) && !self.notes.noted(b) {
            return None;
        }
        let key = PairKey::new(a, b);
        let notes = self.notes.sorted();
        let at = notes
            .1
            .binary_search_by_key(&key_order(key), |(k, _, _)| key_order(*k))
            .ok()?;
        let (_, x, y) = notes.1[at];
        Some(native::class_rule(&self.rules, x, y))
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
            && !same_body(world.colliders, a, b)
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
    /// the rules do not reach moves, which nothing else tells. Walking one
    /// collider's pairs in Rapier's graph costs about as much as reading 64
    /// entries of Rapier's pair list in order, so with many noted colliders
    /// the list is read once instead.
    pub(super) fn note_pairs(
        &mut self,
        narrow_phase: &NarrowPhase,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
    ) {
        let Notes { pairs, bits } = &mut self.notes;
        let pairs = pairs.get_mut().unwrap_or_else(PoisonError::into_inner);
        pairs.0 = false;
        pairs.1.clear();
        bits.iter_mut().for_each(|w| *w = 0);
        let plan = &self.plan;
        // A hooked collider's pairs are in the table.
        let class_of = |c: ColliderHandle| match plan.colliders.get(c) {
            Some(entry) => entry.class,
            None => {
                let dynamic = colliders
                    .get(c)
                    .and_then(|o| o.parent())
                    .and_then(|b| bodies.get(b))
                    .is_some_and(|b| b.is_dynamic());
                Some(Class::unreached(dynamic))
            }
        };
        let mut noted = 0;
        for &c in self.roster.colliders() {
            if colliders.contains(c) && plan.colliders.get(c).is_some_and(|p| !p.hooked()) {
                let index = c.into_raw_parts().0 as usize;
                if index / 64 >= bits.len() {
                    bits.resize(index / 64 + 1, 0);
                }
                bits[index / 64] |= 1 << (index % 64);
                noted += 1;
            }
        }
        if noted == 0 {
            return;
        }
        let bits: &[u64] = bits;
        let mut note = |a: ColliderHandle, b: ColliderHandle| {
            if same_body(colliders, a, b) {
                return;
            }
            if let (Some(x), Some(y)) = (class_of(a), class_of(b)) {
                let key = PairKey::new(a, b);
                let (x, y) = if key.colliders().0 == a {
                    (x, y)
                } else {
                    (y, x)
                };
                pairs.1.push((key, x, y));
            }
        };
        let listed = narrow_phase.contact_pairs().size_hint().0
            + narrow_phase.intersection_pairs().size_hint().0;
        if noted * 64 < listed {
            for &c in self.roster.colliders() {
                if !bit(bits, c) {
                    continue;
                }
                for other in partners_of(narrow_phase, c) {
                    // A pair of two noted colliders is noted from its first side.
                    if !bit(bits, other) || PairKey::new(c, other).colliders().0 == c {
                        note(c, other);
                    }
                }
            }
        } else {
            let contacts = narrow_phase
                .contact_pairs()
                .map(|p| (p.collider1, p.collider2));
            let sensors = narrow_phase.intersection_pairs().map(|(a, b, _)| (a, b));
            for (a, b) in contacts.chain(sensors) {
                if bit(bits, a) || bit(bits, b) {
                    note(a, b);
                }
            }
        }
    }
}
