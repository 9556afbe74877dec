//! Around bevy_rapier's step: each context's rules prepare its world
//! before the step and take in the pairs after it, however many Rapier
//! steps bevy_rapier runs in between (substeps, catch-up steps)
//! (`docs/bevy.md`).

use bevy::prelude::*;
use bevy_rapier::plugin::context::{
    RapierContextColliders, RapierContextJoints, RapierContextSimulation, RapierRigidBodySet,
    SimulationToRenderTime,
};
use bevy_rapier::plugin::{RapierConfiguration, TimestepMode};

use std::sync::Arc;

use bevy_rapier::rapier::prelude::{
    ColliderSet, CollisionEvent, ContactPair, EventHandler, Real, RigidBodySet, SoftBodySet,
    SoftBodyTearEvent,
};

use super::CollisionRules;
use super::collision_rules::TearListener;
use super::ledger::Ledger;

/// Before the rule components are applied: the pieces of tears take their
/// source's rules in the rule set, so that the ledger can follow the tear
/// (`docs/bevy.md`, "Soft bodies"). `prepare_contexts` follows again, for
/// the soft bodies the components just gave rules.
pub(crate) fn follow_soft_bodies(mut contexts: Query<(&mut CollisionRules, &RapierRigidBodySet)>) {
    for (mut rules, set) in &mut contexts {
        rules
            .hooks_mut()
            .follow_soft_bodies(&set.soft_bodies, &set.bodies);
    }
}

/// The simulated time bevy_rapier's steps will take in this frame, as its
/// `step_simulation` computes it from the timestep mode: zero when it takes
/// no step (the pipeline is off, a zero time scale, the first frame of a
/// variable step, an interpolated simulation ahead of the clock). Rules
/// with an end count it (`docs/bevy.md`, "Rules with an end").
fn frame_time(
    mode: TimestepMode,
    delta: f32,
    active: bool,
    ahead: Option<&SimulationToRenderTime>,
) -> f32 {
    if !active {
        return 0.0;
    }
    let (time, substeps) = match mode {
        TimestepMode::Fixed { dt, substeps } => (dt, substeps),
        TimestepMode::Variable {
            max_dt,
            time_scale,
            substeps,
        } => ((delta * time_scale).min(max_dt), substeps),
        TimestepMode::Interpolated {
            dt,
            time_scale,
            substeps,
        } => {
            if dt <= 0.0 {
                return 0.0;
            }
            // bevy_rapier's loop: a step of `dt` while the simulation is
            // behind the clock.
            let mut diff = ahead.map_or(0.0, |a| a.diff) + delta;
            let mut steps = 0u32;
            while diff > 0.0 {
                steps += 1;
                diff -= dt;
            }
            (steps as f32 * dt * time_scale, substeps)
        }
    };
    if substeps == 0 || time / (substeps as f32) <= 0.0 {
        0.0
    } else {
        time
    }
}

/// What `prepare_contexts` reads and writes of a context.
type Prepared = (
    &'static mut CollisionRules,
    &'static mut RapierContextSimulation,
    &'static mut RapierContextColliders,
    &'static mut RapierRigidBodySet,
    &'static RapierConfiguration,
    Option<&'static SimulationToRenderTime>,
);

/// Before the step: plans the colliders' flags and groups, recalculates
/// the live pairs the edits reach, and wakes their bodies.
pub(crate) fn prepare_contexts(
    mut contexts: Query<Prepared>,
    mode: Res<TimestepMode>,
    time: Res<Time>,
    mut ledger: ResMut<Ledger>,
) {
    let mut reach = false;
    for (mut rules, mut simulation, mut colliders, mut bodies, config, ahead) in &mut contexts {
        let rules = &mut *rules;
        let frame = frame_time(
            *mode,
            time.delta_secs(),
            config.physics_pipeline_active,
            ahead,
        );
        let simulation = simulation.bypass_change_detection();
        let colliders = &mut colliders.bypass_change_detection().colliders;
        let set = bodies.bypass_change_detection();
        rules.colliders_at = std::ptr::from_ref(colliders) as usize;
        listen_for_tears(rules, simulation);
        let hooks = rules.hooks_mut();
        hooks.set_timestep(frame);
        // Pieces of tears take their source's rules, cluster proxies their
        // soft body's root as parent (`docs/semantics.md`, "Soft bodies").
        hooks.follow_soft_bodies(&set.soft_bodies, &set.bodies);
        let bodies = &mut set.bodies;
        hooks.prepare_with_graph(bodies, colliders, &simulation.narrow_phase);
        hooks.freeze_manifolds(&simulation.narrow_phase);
        hooks.wake_edited(&mut simulation.islands, bodies);
        let last = hooks.stats();
        reach |= last.watched_colliders > 0
            || last.watched_bodies > 0
            || last.tracked_pairs > 0
            || last.hooked_colliders > 0
            || last.full_pass.is_some()
            || last.shares_project_bits;
    }
    // Read through `Mut` only when it changes: the book's change tick is
    // not the edits' business.
    if ledger.hooks_reach != reach {
        ledger.hooks_reach = reach;
    }
}

/// Makes the hooks' [`TearListener`] the context's event handler, passing
/// every event on to the project's own handler, unless it already is: a
/// strain tear in one of the frame's Rapier steps (substeps, catch-up
/// steps) then gives the pieces their source's rules in the next ones
/// (`docs/bevy.md`, "Soft bodies"). The plugin keeps a share of the
/// listener it installed: while the context holds the other, at the same
/// place, it is still installed (a box of the project's at the address of
/// a dropped listener cannot pass for it).
fn listen_for_tears(rules: &mut CollisionRules, simulation: &mut RapierContextSimulation) {
    let at = |simulation: &RapierContextSimulation| {
        simulation.event_handler().map_or(0, |handler| {
            std::ptr::from_ref(handler).cast::<()>() as usize
        })
    };
    if let Some((listener, place)) = &rules.listener
        && Arc::strong_count(listener) == 2
        && at(simulation) == *place
    {
        return;
    }
    let mut listener = rules.hooks.tear_listener();
    if let Some(project) = simulation.remove_event_handler() {
        listener = listener.forwarding_to(project);
    }
    let listener = Arc::new(listener);
    simulation.set_event_handler(Installed(Arc::clone(&listener)));
    rules.listener = Some((listener, at(simulation)));
}

/// The listener as a context's event handler: the plugin holds another
/// share of it.
struct Installed(Arc<TearListener>);

impl EventHandler for Installed {
    fn handle_collision_event(
        &self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        event: CollisionEvent,
        contact_pair: Option<&ContactPair>,
    ) {
        self.0
            .handle_collision_event(bodies, colliders, event, contact_pair);
    }

    fn handle_contact_force_event(
        &self,
        dt: Real,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        contact_pair: &ContactPair,
        total_force_magnitude: Real,
    ) {
        self.0.handle_contact_force_event(
            dt,
            bodies,
            colliders,
            contact_pair,
            total_force_magnitude,
        );
    }

    fn handle_soft_body_tear_event(&self, soft_bodies: &SoftBodySet, event: &SoftBodyTearEvent) {
        self.0.handle_soft_body_tear_event(soft_bodies, event);
    }
}

/// After the step: admits the pairs the hook met and forgets those Rapier
/// no longer has.
pub(crate) fn finish_contexts(
    mut contexts: Query<(
        &mut CollisionRules,
        &RapierContextSimulation,
        &RapierContextColliders,
        &RapierRigidBodySet,
        &RapierContextJoints,
    )>,
) {
    for (mut rules, simulation, colliders, bodies, joints) in &mut contexts {
        rules.hooks_mut().after_step_with_joints(
            &simulation.narrow_phase,
            &bodies.bodies,
            &colliders.colliders,
            &joints.impulse_joints,
            &joints.multibody_joints,
        );
    }
}
