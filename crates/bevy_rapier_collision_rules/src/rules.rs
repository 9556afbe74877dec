//! The rules of one physics context: a component on the context entity,
//! beside bevy_rapier's own (`docs/bevy.md`).

use std::sync::Arc;

use crate::collision_rules::{CollisionRuleSet, RuleHooks, TearListener};
use crate::rule_events::EventEntities;
use bevy::prelude::*;
use bevy_rapier::rapier::prelude::ColliderSet;

/// The rules of one physics context (one Rapier world): every entity's
/// rules, the live pairs and their overrides. The plugin adds it to every
/// entity with bevy_rapier's `RapierContextSimulation`, keeps it in step
/// with the components, and steps the context's world with it.
///
/// Live-pair overrides, policies, a custom calculator or a pair-created
/// callback go through [`hooks_mut`](Self::hooks_mut), with bevy_rapier's
/// handles (`RapierColliderHandle`, `RapierRigidBodyHandle`).
#[derive(Component)]
pub struct CollisionRules {
    pub(crate) hooks: RuleHooks,
    /// Where the context's `ColliderSet` was when it was last prepared:
    /// the hook finds its context by the set Rapier hands it.
    pub(crate) colliders_at: usize,
    /// The hooks' tear listener installed as the context's event handler,
    /// and where its box is (see `step::listen_for_tears`).
    pub(crate) listener: Option<(Arc<TearListener>, usize)>,
    /// The entities the rule events named (see `rule_events`).
    pub(crate) event_entities: EventEntities,
}

impl Default for CollisionRules {
    fn default() -> Self {
        let mut hooks = RuleHooks::default();
        // Each piece of a torn soft body is an entity with its own copies of
        // the rule components: its rules are its own (`docs/bevy.md`, "Soft
        // bodies").
        hooks.set_pieces_copy_rules(true);
        CollisionRules {
            hooks,
            colliders_at: 0,
            listener: None,
            event_entities: EventEntities::default(),
        }
    }
}

impl CollisionRules {
    /// The hooks that hold this context's rules and live pairs.
    #[must_use]
    pub fn hooks(&self) -> &RuleHooks {
        &self.hooks
    }

    /// The hooks, to set a policy, a calculator, a pair-created callback,
    /// pair overrides or manifold settings. Rules that the components give
    /// are theirs: an edit made here to the same nodes is replaced when the
    /// component changes.
    pub fn hooks_mut(&mut self) -> &mut RuleHooks {
        &mut self.hooks
    }

    /// The context's rule set.
    #[must_use]
    pub fn rules(&self) -> &CollisionRuleSet {
        self.hooks.rules()
    }

    pub(crate) fn rules_mut(&mut self) -> &mut CollisionRuleSet {
        self.hooks.rules_mut()
    }

    /// Starts the context's hooks over on a Rapier world put in place of
    /// the one they stepped: a save restored into the context's
    /// components. They keep the rules and what code set, and read the
    /// restored world at the next step as fresh hooks would
    /// ([`RuleHooks::world_replaced`]). The plugin calls it when
    /// bevy_rapier's `RapierContextColliders` is inserted again on a
    /// context it has stepped; a restore that moves the saved sets into
    /// the live components calls it itself (`docs/bevy.md`, "Saving a
    /// context").
    pub fn world_replaced(&mut self) {
        self.hooks.world_replaced();
    }

    /// Whether the hooks have prepared a step of this context.
    pub(crate) fn prepared(&self) -> bool {
        self.colliders_at != 0
    }

    /// Whether `colliders` is this context's collider set as last prepared.
    pub(crate) fn owns(&self, colliders: &ColliderSet) -> bool {
        self.colliders_at == std::ptr::from_ref(colliders) as usize
    }
}
