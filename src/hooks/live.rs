//! The live-pair API (`docs/semantics.md`, "Decisions about live pairs"): each pair's
//! rule, overrides, manifold settings and forced recalculation.
//!
//! Rapier holds every pair; the hooks keep state only for the pairs they
//! decide (hooked pairs), so that the parts of a world the rules do not
//! reach cost nothing and nothing copies Rapier's pair list per step. Every
//! method takes the world ([`WorldRef`]) and answers every pair Rapier
//! holds, on demand, however it is decided: the hooked ones from the hooks,
//! the others from Rapier's graph and the rules.

use std::sync::PoisonError;

use super::super::rapier::prelude::*;

use super::{ManifoldUpdate, PairKey, PairState, PlanCause, RuleHooks};
use super::super::model::BodyKinds;
use super::super::world::{Joints, filters_pass, pair_exists};
use super::super::{CollisionRule, Node};

/// A pair Rapier decides alone, as the live-pair edits need it to start
/// keeping state for it.
#[derive(Clone, Copy)]
struct Native {
    /// Its rule, as the default calculation gives it.
    rule: CollisionRule,
    /// Whether each body is dynamic, in key order.
    kinds: BodyKinds,
    /// Whether a collider of the pair is made of parts.
    parts: bool,
}

/// What Rapier holds of a world, for the live-pair queries that answer on
/// demand: its narrow phase and its sets. Made from a `&PhysicsWorld`, or
/// with [`WorldRef::new`] for a bare pipeline.
#[derive(Clone, Copy)]
pub struct WorldRef<'a> {
    pub(crate) narrow_phase: &'a NarrowPhase,
    pub(crate) bodies: &'a RigidBodySet,
    pub(crate) colliders: &'a ColliderSet,
    pub(crate) joints: Option<Joints<'a>>,
    /// Only the debug view reads them (Rapier draws soft bodies).
    pub(crate) soft_bodies: Option<&'a SoftBodySet>,
}

impl<'a> WorldRef<'a> {
    /// The parts of a world stepped with a bare `PhysicsPipeline`. Without
    /// [`with_joints`](Self::with_joints), a pair of bodies that a joint
    /// with contacts disabled links is answered as if the joint allowed
    /// contacts.
    pub fn new(
        narrow_phase: &'a NarrowPhase,
        bodies: &'a RigidBodySet,
        colliders: &'a ColliderSet,
    ) -> WorldRef<'a> {
        WorldRef {
            narrow_phase,
            bodies,
            colliders,
            joints: None,
            soft_bodies: None,
        }
    }

    /// The world's joint sets too: a pair of bodies that a joint with
    /// contacts disabled links forms no pair, as Rapier reads it.
    #[must_use]
    pub fn with_joints(
        mut self,
        impulse: &'a ImpulseJointSet,
        multibody: &'a MultibodyJointSet,
    ) -> WorldRef<'a> {
        self.joints = Some(Joints { impulse, multibody });
        self
    }

    /// The world's soft bodies too, for a debug view that draws them as
    /// Rapier's debug rendering does (feature `debug-render`); the
    /// live-pair questions do not need them.
    #[must_use]
    pub fn with_soft_bodies(mut self, soft_bodies: &'a SoftBodySet) -> WorldRef<'a> {
        self.soft_bodies = Some(soft_bodies);
        self
    }
}

impl<'a> From<&'a PhysicsWorld> for WorldRef<'a> {
    fn from(world: &'a PhysicsWorld) -> WorldRef<'a> {
        WorldRef::new(&world.narrow_phase, &world.bodies, &world.colliders)
            .with_joints(&world.impulse_joints, &world.multibody_joints)
            .with_soft_bodies(&world.soft_bodies)
    }
}

/// Live pairs.
impl RuleHooks {
    /// The rule of the live pair of `a` and `b`, in either order, for any
    /// pair Rapier holds now, however it is decided (Rapier's groups as the
    /// planner wrote them, or the hook); `None` if they form no live pair (a
    /// `NoPair` pair is not live). Answered on demand: a look-up in Rapier's
    /// graph (the pairs of `a`) and, for a pair the hooks do not decide, the
    /// default calculation. Nothing per step.
    ///
    /// `world` is a `&PhysicsWorld`, or a [`WorldRef::new`] over a bare
    /// pipeline's narrow phase and sets.
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
    /// assert_eq!(hooks.pair_rule(&world, cube, floor), Some(CollisionRule::Normal));
    /// ```
    #[must_use]
    pub fn pair_rule<'w>(
        &self,
        world: impl Into<WorldRef<'w>>,
        a: ColliderHandle,
        b: ColliderHandle,
    ) -> Option<CollisionRule> {
        let world = world.into();
        let key = PairKey::new(a, b);
        match self.pairs.get(key) {
            Some(state) if state.absent && !pair_exists(world.narrow_phase, a, b) => None,
            // Rapier's filters stop it now (the project changed a setting).
            Some(_) if !filters_pass(world.bodies, world.colliders, world.joints, a, b) => None,
            Some(state) => Some(self.rule_now(state, world.bodies, world.colliders, a, b)),
            None => self.rapier_rule(world, a, b),
        }
        .filter(|&rule| rule != CollisionRule::NoPair)
    }

    /// The hooked live pairs as of the last step, with their rules: the
    /// hooks' own table, which the crate's tests compare with Rapier's graph.
    /// Not part of the API (feature `test-oracle`): [`pairs`](Self::pairs)
    /// answers every pair.
    #[cfg(feature = "test-oracle")]
    pub fn hooked_pairs(
        &self,
    ) -> impl Iterator<Item = (ColliderHandle, ColliderHandle, CollisionRule)> + '_ {
        self.pairs
            .iter()
            .filter(|(_, state)| !state.absent)
            .map(|(key, state)| (key.colliders(), state.rule()))
            .filter(|&(_, rule)| rule != CollisionRule::NoPair)
            .map(|((a, b), rule)| (a, b, rule))
    }

    /// Every live pair Rapier holds now, with its rule, however it is
    /// decided, in no particular order: on demand, a walk of Rapier's pair
    /// lists.
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
    /// hooks.rules_mut().set_personal(body, CollisionRule::NoResponse);
    /// hooks.step(&mut world);
    /// let pairs: Vec<_> = hooks.pairs(&world).collect();
    /// assert_eq!(pairs.len(), 1);
    /// let (a, b, rule) = pairs[0];
    /// assert!((a, b) == (cube, floor) || (a, b) == (floor, cube));
    /// assert_eq!(rule, CollisionRule::NoResponse);
    /// ```
    pub fn pairs<'a, W: Into<WorldRef<'a>>>(
        &'a self,
        world: W,
    ) -> impl Iterator<Item = (ColliderHandle, ColliderHandle, CollisionRule)> + use<'a, W> {
        let world = world.into();
        self.held_pairs(world).filter_map(move |(a, b)| {
            let rule = self.held_rule(world, a, b, || self.resolve(world.bodies, world.colliders, a, b));
            (rule != CollisionRule::NoPair).then_some((a, b, rule))
        })
    }

    /// The pairs Rapier holds now that its filters let through, in its
    /// graph's order: contact pairs, then sensor pairs.
    pub(super) fn held_pairs<'a>(
        &self,
        world: WorldRef<'a>,
    ) -> impl Iterator<Item = (ColliderHandle, ColliderHandle)> + use<'a> {
        let contacts = world
            .narrow_phase
            .contact_pairs()
            .map(|p| (p.collider1, p.collider2));
        let sensors = world
            .narrow_phase
            .intersection_pairs()
            .map(|(a, b, _)| (a, b));
        contacts
            .chain(sensors)
            .filter(move |&(a, b)| filters_pass(world.bodies, world.colliders, world.joints, a, b))
    }

    /// The rule of a pair Rapier holds: the hooks' for a hooked pair,
    /// `unhooked` for the others (the default calculation, which equals what
    /// Rapier's groups do with them).
    pub(super) fn held_rule(
        &self,
        world: WorldRef<'_>,
        a: ColliderHandle,
        b: ColliderHandle,
        unhooked: impl FnOnce() -> CollisionRule,
    ) -> CollisionRule {
        match self.pairs.get(PairKey::new(a, b)) {
            // Rapier holds it: a pair kept through regrouping is back.
            Some(state) => self.rule_now(state, world.bodies, world.colliders, a, b),
            None => unhooked(),
        }
    }

    /// Replaces the rule of the live pair of `a` and `b` for the rest of the
    /// pair's life (automatic recalculation leaves it alone;
    /// [`force_recalculation`](Self::force_recalculation) drops it). `Defer`
    /// drops the override. `NoPair` ends the pair for the crate. Any live
    /// pair Rapier holds now can be given a rule: a pair Rapier decided
    /// alone is hooked from the next step on. Returns `false`, changing
    /// nothing, if `a` and `b` form no live pair (see
    /// [`pair_rule`](Self::pair_rule)). A pair given `NoPair` is no longer
    /// live, so a later `Defer` here finds nothing to drop: `force_recalculation`
    /// of either side's node drops that override.
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
    /// assert!(hooks.set_pair_rule(&world, cube, floor, CollisionRule::NoResponse));
    /// for _ in 0..60 {
    ///     hooks.step(&mut world);
    /// }
    /// assert!(world.bodies[body].translation().y < -1.0, "the cube fell through");
    /// ```
    pub fn set_pair_rule<'w>(
        &mut self,
        world: impl Into<WorldRef<'w>>,
        a: ColliderHandle,
        b: ColliderHandle,
        rule: CollisionRule,
    ) -> bool {
        let known = self.rapier_state(world.into(), a, b);
        let set = self.override_pair(a, b, known, rule);
        // A pair that takes no override keeps the end it had.
        if set {
            self.pair_ends.remove(&PairKey::new(a, b));
        }
        set
    }

    /// Edits the live pair of `a` and `b` (a pair the hooks do not track
    /// yet, its rule `native`, gets an entry and is hooked from the next step
    /// on), plans again and wakes its bodies; `false`, changing nothing, if
    /// they form no live pair.
    fn edit_pair(
        &mut self,
        a: ColliderHandle,
        b: ColliderHandle,
        native: Option<Native>,
        edit: impl FnOnce(&mut PairState),
    ) -> bool {
        let Some(state) = self.live_state(a, b, native) else {
            return false;
        };
        edit(state);
        self.queued.replan = Some(PlanCause::PinnedPair);
        self.wake_pair(a, b);
        true
    }

    fn override_pair(
        &mut self,
        a: ColliderHandle,
        b: ColliderHandle,
        native: Option<Native>,
        rule: CollisionRule,
    ) -> bool {
        let edited = self.edit_pair(a, b, native, |state| {
            state.overridden = rule.is_decided().then_some(rule);
        });
        if let Some(recording) = self.recording.as_mut().filter(|_| edited) {
            recording.overridden.insert(PairKey::new(a, b));
        }
        edited
    }

    /// Sets how the live pair of `a` and `b` updates its contacts; any
    /// live pair Rapier holds now (a pair Rapier decided alone is hooked from
    /// the next step on). Returns `false`, changing nothing, if they form no
    /// live pair (see [`pair_rule`](Self::pair_rule)).
    ///
    /// `ManifoldUpdate::Never` is refused the same way (`false`, nothing
    /// changed) when a collider of the pair is made of parts: a triangle
    /// mesh, polyline, height field, voxel set or compound. Rapier keeps
    /// one manifold per touching part, and parts come and go as the bodies
    /// move, so frozen contacts could not be kept (`docs/architecture.md`,
    /// "Manifold settings").
    pub fn set_manifold_update<'w>(
        &mut self,
        world: impl Into<WorldRef<'w>>,
        a: ColliderHandle,
        b: ColliderHandle,
        update: ManifoldUpdate,
    ) -> bool {
        let known = self.rapier_state(world.into(), a, b);
        self.manifold_pair(a, b, known, update)
    }

    fn manifold_pair(
        &mut self,
        a: ColliderHandle,
        b: ColliderHandle,
        native: Option<Native>,
        update: ManifoldUpdate,
    ) -> bool {
        let parts = match self.pairs.get(PairKey::new(a, b)) {
            Some(state) => state.parts,
            None => native.is_some_and(|native| native.parts),
        };
        if update == ManifoldUpdate::Never && parts {
            return false;
        }
        self.boundary.unsettled |= update == ManifoldUpdate::Never;
        self.edit_pair(a, b, native, |state| {
            state.manifold = update;
            *state
                .frozen
                .get_mut()
                .unwrap_or_else(PoisonError::into_inner) = None;
        })
    }

    /// The manifold setting of the live pair of `a` and `b` (`ByRule` for a
    /// pair that was never given one); `None` if they form no live pair (see
    /// [`pair_rule`](Self::pair_rule)).
    #[must_use]
    pub fn manifold_update<'w>(
        &self,
        world: impl Into<WorldRef<'w>>,
        a: ColliderHandle,
        b: ColliderHandle,
    ) -> Option<ManifoldUpdate> {
        // A live pair, whatever its rule (`Defer` too, where the default
        // rule or a calculator says it).
        self.pair_rule(world, a, b)?;
        let state = self.pairs.get(PairKey::new(a, b));
        Some(state.map_or(ManifoldUpdate::ByRule, |state| state.manifold))
    }

    /// Recalculates, before the next step, every live pair of `node` and of
    /// its descendants (the design's `ForceCollisionRuleRecalculation`),
    /// dropping their overrides. A pair that becomes `NoPair` stops being live.
    pub fn force_recalculation(&mut self, node: impl Into<Node>) {
        if let Some(recording) = &mut self.recording {
            recording.forced = true;
        }
        self.queued.forced.push(node.into());
    }

    /// [`rapier_rule`](Self::rapier_rule), with what a new entry needs.
    fn rapier_state(
        &self,
        world: WorldRef<'_>,
        a: ColliderHandle,
        b: ColliderHandle,
    ) -> Option<Native> {
        let key = PairKey::new(a, b);
        self.rapier_rule(world, a, b).map(|rule| Native {
            rule,
            kinds: key.kinds(world.bodies, world.colliders),
            parts: key.made_of_parts(world.colliders),
        })
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
            && filters_pass(world.bodies, world.colliders, world.joints, a, b)
            && pair_exists(world.narrow_phase, a, b);
        held.then(|| self.resolve(world.bodies, world.colliders, a, b))
    }

    /// The table entry of a live pair; a pair the hooks do not track yet
    /// (its rule `native`) gets one, and is hooked from the next step on.
    fn live_state(
        &mut self,
        a: ColliderHandle,
        b: ColliderHandle,
        native: Option<Native>,
    ) -> Option<&mut PairState> {
        let key = PairKey::new(a, b);
        if self.pairs.get(key).is_none() {
            let native = native.filter(|native| native.rule != CollisionRule::NoPair)?;
            let state = PairState::new(native.rule, self.boundary.step, native.kinds, native.parts);
            self.pairs.insert(key, state);
        }
        self.pairs
            .get_mut(key)
            .filter(|state| state.rule() != CollisionRule::NoPair && !state.absent)
    }

    /// Wakes, before the next step, the bodies of `a` and `b`.
    pub(super) fn wake_pair(&mut self, a: ColliderHandle, b: ColliderHandle) {
        self.queued.wake_colliders.extend([a, b]);
    }
}
