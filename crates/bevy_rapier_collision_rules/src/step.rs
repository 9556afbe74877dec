//! Around bevy_rapier's step: each context's rules prepare its world
//! before the step and take in the pairs after it, however many Rapier
//! steps bevy_rapier runs in between (substeps, catch-up steps)
//! (`docs/bevy.md`).

use bevy::prelude::*;
use bevy_rapier::plugin::context::{
    RapierContextColliders, RapierContextSimulation, RapierRigidBodySet,
};

use super::CollisionRules;

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

/// Before the step: plans the colliders' flags and groups, recalculates
/// the live pairs the edits reach, and wakes their bodies.
pub(crate) fn prepare_contexts(
    mut contexts: Query<(
        &mut CollisionRules,
        &mut RapierContextSimulation,
        &mut RapierContextColliders,
        &mut RapierRigidBodySet,
    )>,
) {
    for (mut rules, mut simulation, mut colliders, mut bodies) in &mut contexts {
        let rules = &mut *rules;
        let simulation = simulation.bypass_change_detection();
        let colliders = &mut colliders.bypass_change_detection().colliders;
        let set = bodies.bypass_change_detection();
        rules.colliders_at = std::ptr::from_ref(colliders) as usize;
        let hooks = rules.hooks_mut();
        // Pieces of tears take their source's rules, cluster proxies their
        // soft body's root as parent (`docs/semantics.md`, "Soft bodies").
        hooks.follow_soft_bodies(&set.soft_bodies, &set.bodies);
        let bodies = &mut set.bodies;
        hooks.prepare_with_graph(bodies, colliders, &simulation.narrow_phase);
        hooks.freeze_manifolds(&simulation.narrow_phase);
        hooks.wake_edited(&mut simulation.islands, bodies);
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
    )>,
) {
    for (mut rules, simulation, colliders, bodies) in &mut contexts {
        rules.hooks_mut().after_step(
            &simulation.narrow_phase,
            &bodies.bodies,
            &colliders.colliders,
        );
    }
}
