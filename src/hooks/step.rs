//! The step boundary: stepping a world with the rules, and the parts a
//! bare pipeline calls around `PhysicsPipeline::step`, each of which
//! panics naming the part left out (`docs/architecture.md`, "The step
//! boundary").

use std::sync::PoisonError;

use super::super::rapier::prelude::*;

use super::expiry::counts;
use super::{ManifoldUpdate, RuleHooks, WorldRef};
use super::super::StepStats;
use super::super::world::{Joints, census};

/// Names the call a bare-pipeline user left out; the physics would
/// otherwise change silently (`docs/architecture.md`, "The step boundary").
#[cold]
#[track_caller]
pub(super) fn missing(call: &str, when: &str) -> ! {
    panic!(
        "RuleHooks::{call} was not called {when}: without it the rules do not \
         hold. Step with RuleHooks::step, RuleHooks::step_pipeline, or call \
         follow_soft_bodies (where there are or were soft bodies), prepare, \
         freeze_manifolds and wake_edited before PhysicsPipeline::step and \
         after_step after it"
    )
}

/// Stepping.
impl RuleHooks {
    /// Steps `world` with the rules: [`prepare`](Self::prepare), waking what
    /// the edits need awake, Rapier's step, and [`after_step`](Self::after_step).
    ///
    /// A [`prepare`](Self::prepare) the project called since the last step
    /// (to read [`stats`](Self::stats) or [`pair_rule`](Self::pair_rule)
    /// before it) is part of this step: the rules with an end count it once.
    ///
    /// # Panics
    ///
    /// If the world's `integration_parameters.dt` is negative, infinite or
    /// not a number. The same holds for
    /// [`step_with_events`](Self::step_with_events) and
    /// [`step_pipeline`](Self::step_pipeline).
    #[track_caller]
    pub fn step(&mut self, world: &mut PhysicsWorld) {
        self.step_with_events(world, &());
    }

    /// [`step`](Self::step), with Rapier's events sent to `events`.
    #[track_caller]
    pub fn step_with_events(&mut self, world: &mut PhysicsWorld, events: &dyn EventHandler) {
        self.check_own_step(world.integration_parameters.dt);
        self.seed_rule_events((&*world).into());
        self.follow_soft_bodies(&world.soft_bodies, &world.bodies);
        if self.idle(&world.colliders) {
            // The same call as `world.step_with_events`, so that a world the
            // rules do not reach steps as plainly as it can
            // (`docs/performance.md`, "What the remaining cost is").
            self.count_idle_step();
            self.boundary.own_step = false;
            world.step_with_events(&*self, events);
            self.boundary.own_step = true;
            self.record_step((&*world).into());
            return;
        }
        self.step_pipeline(
            &mut world.physics_pipeline,
            world.gravity,
            &world.integration_parameters,
            &mut world.islands,
            &mut world.broad_phase,
            &mut world.narrow_phase,
            &mut world.bodies,
            &mut world.colliders,
            &mut world.impulse_joints,
            &mut world.multibody_joints,
            &mut world.soft_bodies,
            &mut world.ccd_solver,
            events,
        );
    }

    /// Steps a bare `PhysicsPipeline` with the rules: everything
    /// [`step_with_events`](Self::step_with_events) does around Rapier's
    /// step. Takes `PhysicsPipeline::step`'s arguments in its order, but
    /// the hooks.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, RuleHooks};
    ///
    /// let (mut bodies, mut colliders) = (RigidBodySet::new(), ColliderSet::new());
    /// let floor = bodies.insert(RigidBodyBuilder::fixed());
    /// colliders.insert_with_parent(ColliderBuilder::cuboid(5.0, 0.5, 5.0), floor, &mut bodies);
    /// let ghost = bodies.insert(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 1.5, 0.0)));
    /// colliders.insert_with_parent(ColliderBuilder::ball(0.5), ghost, &mut bodies);
    /// let mut hooks = RuleHooks::default();
    /// hooks.rules_mut().set_specific(ghost, floor, CollisionRule::NoResponse);
    ///
    /// let (mut pipeline, mut islands) = (PhysicsPipeline::new(), IslandManager::new());
    /// let (mut broad_phase, mut narrow_phase) = (BroadPhaseBvh::new(), NarrowPhase::new());
    /// let (mut impulse_joints, mut multibody_joints) = (ImpulseJointSet::new(), MultibodyJointSet::new());
    /// let (mut soft_bodies, mut ccd) = (SoftBodySet::new(), CCDSolver::new());
    /// let params = IntegrationParameters::default();
    /// for _ in 0..60 {
    ///     hooks.step_pipeline(
    ///         &mut pipeline, Vector::Y * -9.81, &params, &mut islands,
    ///         &mut broad_phase, &mut narrow_phase, &mut bodies, &mut colliders,
    ///         &mut impulse_joints, &mut multibody_joints, &mut soft_bodies, &mut ccd, &(),
    ///     );
    /// }
    /// assert!(bodies[ghost].translation().y < 0.0, "the ghost fell through the floor");
    /// ```
    #[allow(clippy::too_many_arguments)]
    #[track_caller]
    pub fn step_pipeline(
        &mut self,
        pipeline: &mut PhysicsPipeline,
        gravity: Vector,
        integration_parameters: &IntegrationParameters,
        islands: &mut IslandManager,
        broad_phase: &mut BroadPhaseBvh,
        narrow_phase: &mut NarrowPhase,
        bodies: &mut RigidBodySet,
        colliders: &mut ColliderSet,
        impulse_joints: &mut ImpulseJointSet,
        multibody_joints: &mut MultibodyJointSet,
        soft_bodies: &mut SoftBodySet,
        ccd_solver: &mut CCDSolver,
        events: &dyn EventHandler,
    ) {
        self.check_own_step(integration_parameters.dt);
        self.seed_rule_events(WorldRef::new(narrow_phase, bodies, colliders));
        self.follow_soft_bodies(soft_bodies, bodies);
        self.boundary.dt = integration_parameters.dt;
        self.boundary.own_step = false;
        let idle = self.idle(colliders);
        if idle {
            self.count_idle_step();
        } else {
            // `freeze_manifolds`' witness check, made before the look so
            // that the look reads everything after a step without the hooks.
            let unhooked = self.witness_overridden(narrow_phase);
            if unhooked {
                self.planned.roster.read_all_next();
            }
            self.prepare_with_graph(bodies, colliders, narrow_phase);
            if unhooked {
                self.check_witness(narrow_phase);
            }
            self.settle_manifolds(narrow_phase);
            self.wake_edited(islands, bodies);
        }
        let resting = islands.num_active_bodies() == 0;
        pipeline.step(
            gravity,
            integration_parameters,
            islands,
            broad_phase,
            narrow_phase,
            bodies,
            colliders,
            impulse_joints,
            multibody_joints,
            soft_bodies,
            ccd_solver,
            &*self,
            events,
        );
        if idle {
            self.boundary.own_step = true;
            self.record_step(WorldRef::new(narrow_phase, bodies, colliders).with_joints(impulse_joints, multibody_joints));
            return;
        }
        // Rapier applies removals to its graphs during the step.
        let census = census(bodies, colliders, narrow_phase);
        let unchanged = std::mem::replace(&mut self.boundary.census, census) == census;
        let quiet = resting && unchanged && islands.num_active_bodies() == 0;
        let joints = Joints {
            impulse: impulse_joints,
            multibody: multibody_joints,
        };
        self.finish_step(narrow_phase, bodies, colliders, Some(joints), quiet);
        self.boundary.own_step = true;
        // Nothing came between `prepare` and Rapier's step, which cleared
        // the change flags; Rapier's soft bodies change colliders without
        // them (`docs/architecture.md`, "Rapier's change flags").
        if !self.soft.seen(bodies) {
            self.planned.roster.stepped(bodies, colliders);
        }
        self.record_step(WorldRef::new(narrow_phase, bodies, colliders).with_joints(impulse_joints, multibody_joints));
    }

    /// A step of a world the rules do not reach: no collider carries the
    /// hook flag, so Rapier never calls the hook.
    #[inline]
    /// What a step of the hooks' own is given: a timestep the ends can
    /// count.
    #[track_caller]
    fn check_own_step(&self, dt: Real) {
        assert!(
            counts(dt),
            "IntegrationParameters::dt is {dt}: the rules with an end count the world's \
             timestep, a finite number of seconds, zero or more"
        );
    }

    fn count_idle_step(&mut self) {
        self.boundary.step += 1;
        // The step's follow served this step, which closes here.
        self.boundary.followed = false;
        self.stats = StepStats {
            shares_project_bits: self.planned.plan.room.is_some(),
            ..StepStats::default()
        };
    }

    /// Settles `ManifoldUpdate::Never` settings made since the last step
    /// for pairs that have no contacts now: they are frozen empty. (Pairs
    /// with contacts are frozen in their next contact update, in each body's
    /// frame.) Part of [`step`](Self::step); call it after
    /// [`prepare`](Self::prepare) when stepping a bare pipeline.
    pub fn freeze_manifolds(&mut self, narrow_phase: &NarrowPhase) {
        self.check_witness(narrow_phase);
        self.settle_manifolds(narrow_phase);
    }

    /// [`freeze_manifolds`](Self::freeze_manifolds) but the witness check.
    fn settle_manifolds(&mut self, narrow_phase: &NarrowPhase) {
        self.boundary.owe_freeze = false;
        if !std::mem::take(&mut self.boundary.unsettled) {
            return;
        }
        for (key, state) in self.pairs.iter() {
            if state.manifold != ManifoldUpdate::Never {
                continue;
            }
            let mut frozen = state.frozen.lock().unwrap_or_else(PoisonError::into_inner);
            if frozen.is_some() {
                continue;
            }
            let (a, b) = key.colliders();
            let touching = narrow_phase
                .contact_pair(a, b)
                .is_some_and(|pair| pair.has_any_active_contact());
            if !touching {
                // Step 0 never comes again: no manifold is frozen later.
                *frozen = Some((0, Vec::new()));
            }
        }
    }

    /// Wakes the bodies of pairs whose rule an edit changed, so that the
    /// change takes effect on sleeping bodies too. Part of
    /// [`step`](Self::step); call it after [`prepare`](Self::prepare) when
    /// stepping a bare pipeline.
    pub fn wake_edited(&mut self, islands: &mut IslandManager, bodies: &mut RigidBodySet) {
        // In the node order, whichever way the plan came to them: the order
        // of Rapier's wake-ups is the order of its islands, and so of its
        // solver.
        self.queued.to_wake.sort_unstable_by_key(|b| b.into_raw_parts());
        self.queued.to_wake.dedup();
        for body in self.queued.to_wake.drain(..) {
            if bodies.contains(body) {
                islands.wake_up(bodies, body, true);
            }
        }
    }

    /// After a bare `PhysicsPipeline::step`: admits the pairs the hook met
    /// during the step, forgets hooked pairs Rapier no longer has, and gives
    /// a rule to pairs of newly hooked colliders that Rapier made without
    /// asking the hook (pairs of resting bodies).
    ///
    /// Rapier may step several times between [`prepare`](Self::prepare)
    /// and `after_step` (substeps, catch-up steps): the rules hold in each.
    ///
    /// # Panics
    ///
    /// If [`prepare`](Self::prepare) was not called before the step, or if
    /// [`wake_edited`](Self::wake_edited) or
    /// [`freeze_manifolds`](Self::freeze_manifolds) was left out when the
    /// edits before it needed them.
    ///
    /// Without the joint sets, rule events (if recorded) count a pair of
    /// bodies that a joint with contacts disabled links as live; a world
    /// with such joints calls
    /// [`after_step_with_joints`](Self::after_step_with_joints).
    pub fn after_step(
        &mut self,
        narrow_phase: &NarrowPhase,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
    ) {
        self.finish_step(narrow_phase, bodies, colliders, None, false);
        self.record_step(WorldRef::new(narrow_phase, bodies, colliders));
    }

    /// [`after_step`](Self::after_step), reading the joint sets as Rapier
    /// does: a pair of bodies that a joint with contacts disabled links is
    /// not live, for the pair table and for rule events alike.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, RuleEvent, RuleHooks};
    ///
    /// let mut w = PhysicsWorld::new();
    /// let floor = w.insert_body(RigidBodyBuilder::fixed());
    /// w.insert_collider(ColliderBuilder::cuboid(5.0, 0.5, 5.0), Some(floor));
    /// let arm = w.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.9, 0.0)));
    /// w.insert_collider(ColliderBuilder::ball(0.5), Some(arm));
    /// // A hinge with contacts off holds the arm in the floor.
    /// let hinge = RevoluteJointBuilder::new(Vector::Z).contacts_enabled(false);
    /// w.impulse_joints.insert(floor, arm, hinge, true);
    /// let mut hooks = RuleHooks::default();
    /// hooks.rules_mut().set_specific(arm, floor, CollisionRule::NoResponse);
    /// hooks.record_rule_events(true);
    /// for _ in 0..10 {
    ///     hooks.prepare(&w.bodies, &mut w.colliders);
    ///     hooks.freeze_manifolds(&w.narrow_phase);
    ///     hooks.wake_edited(&mut w.islands, &mut w.bodies);
    ///     w.step_with_events(&hooks, &());
    ///     hooks.after_step_with_joints(
    ///         &w.narrow_phase, &w.bodies, &w.colliders, &w.impulse_joints, &w.multibody_joints,
    ///     );
    /// }
    /// // The joint keeps the pair from being live: no event names it.
    /// assert!(hooks.drain_rule_events().next().is_none());
    /// ```
    pub fn after_step_with_joints(
        &mut self,
        narrow_phase: &NarrowPhase,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        impulse_joints: &ImpulseJointSet,
        multibody_joints: &MultibodyJointSet,
    ) {
        let joints = Joints {
            impulse: impulse_joints,
            multibody: multibody_joints,
        };
        self.finish_step(narrow_phase, bodies, colliders, Some(joints), false);
        self.record_step(
            WorldRef::new(narrow_phase, bodies, colliders).with_joints(impulse_joints, multibody_joints),
        );
    }
}
