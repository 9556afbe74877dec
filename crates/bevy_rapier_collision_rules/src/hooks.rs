//! The rules as bevy_rapier's hooks: Rapier asks them about the pairs of
//! hooked colliders during the step, and a project's own hooks can ask
//! them too (`docs/bevy.md`).

use crate::collision_rules::RuleHooks;
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy_rapier::pipeline::{
    BevyPhysicsHooks, ContactModificationContextView, PairFilterContextView,
};
use bevy_rapier::prelude::RapierContextEntityLink;
use bevy_rapier::rapier::prelude::{
    ActiveHooks, ColliderHandle, ColliderSet, PhysicsHooks, SolverFlags,
};

use super::CollisionRules;
use super::misuse::HooksProbe;

/// The rules of every context as bevy_rapier's hooks: give it to
/// `RapierPhysicsPlugin::<CollisionRulesHooks>`. A project with hooks of
/// its own puts this parameter in its hooks and asks it first (see
/// [`filter_contact_pair`](Self::filter_contact_pair)). Without
/// [`CollisionRulesPlugin`](super::CollisionRulesPlugin) it has no rules to
/// answer with, and warns once when bevy_rapier sets up its step.
#[derive(SystemParam)]
pub struct CollisionRulesHooks<'w, 's> {
    contexts: Query<'w, 's, &'static CollisionRules>,
    links: Query<'w, 's, &'static RapierContextEntityLink>,
    /// Never read: made when bevy_rapier sets up its step with these
    /// hooks, it tells the plugin that they are in use, and warns when the
    /// plugin is missing (`misuse.rs`).
    _probe: Local<'s, HooksProbe>,
}

/// A pair that Rapier asks bevy_rapier's hooks about: the view that
/// `filter_contact_pair` and `filter_intersection_pair` get, or the one
/// that `modify_solver_contacts` gets. [`CollisionRulesHooks::project_asks`]
/// takes either.
pub trait HookedPair: sealed::Sealed {
    /// The collider set Rapier is stepping and the pair's two colliders.
    fn colliders(&self) -> (&ColliderSet, ColliderHandle, ColliderHandle);
}

impl HookedPair for PairFilterContextView<'_> {
    fn colliders(&self) -> (&ColliderSet, ColliderHandle, ColliderHandle) {
        (self.raw.colliders, self.raw.collider1, self.raw.collider2)
    }
}

impl HookedPair for ContactModificationContextView<'_, '_> {
    fn colliders(&self) -> (&ColliderSet, ColliderHandle, ColliderHandle) {
        (self.raw.colliders, self.raw.collider1, self.raw.collider2)
    }
}

/// Only bevy_rapier's two views are pairs the hooks are asked about.
mod sealed {
    pub trait Sealed {}
    impl Sealed for bevy_rapier::pipeline::PairFilterContextView<'_> {}
    impl Sealed for bevy_rapier::pipeline::ContactModificationContextView<'_, '_> {}
}

impl CollisionRulesHooks<'_, '_> {
    /// The rules of the context whose collider set Rapier is stepping.
    fn rules_of(&self, colliders: &ColliderSet, collider: ColliderHandle) -> Option<&RuleHooks> {
        if let Some(rules) = self.contexts.iter().find(|rules| rules.owns(colliders)) {
            return Some(rules.hooks());
        }
        // Not where it was prepared (a context that moved in memory, or
        // one stepped without being prepared): found through the entity.
        let entity = Entity::try_from_bits(colliders.get(collider)?.user_data as u64)?;
        let context = self.links.get(entity).ok()?.0;
        self.contexts.get(context).ok().map(CollisionRules::hooks)
    }

    /// The rules' answer for a contact pair: `None` for `NoPair` and
    /// `NoContacts` pairs, no impulses for `NoResponse`, Rapier's default
    /// otherwise (and in contexts without rules). A project's own hooks
    /// call it first and may only restrict its answer:
    ///
    /// ```
    /// use bevy::ecs::system::SystemParam;
    /// use bevy::prelude::*;
    /// use bevy_rapier3d::prelude::*;
    /// use bevy_rapier3d::rapier::prelude::ActiveHooks;
    /// use bevy_rapier_collision_rules::CollisionRulesHooks;
    ///
    /// #[derive(Component)]
    /// struct Intangible;
    ///
    /// #[derive(SystemParam)]
    /// struct GameHooks<'w, 's> {
    ///     rules: CollisionRulesHooks<'w, 's>,
    ///     intangible: Query<'w, 's, &'static Intangible>,
    /// }
    ///
    /// impl BevyPhysicsHooks for GameHooks<'_, '_> {
    ///     fn filter_contact_pair(&self, context: PairFilterContextView) -> Option<SolverFlags> {
    ///         let flags = self.rules.filter_contact_pair(&context)?;
    ///         // The game's own rule, where its own ActiveHooks ask for it.
    ///         let asked = self.rules.project_asks(&context, ActiveHooks::FILTER_CONTACT_PAIRS);
    ///         let intangible = |e| self.intangible.contains(e);
    ///         if asked && (intangible(context.collider1()) || intangible(context.collider2())) {
    ///             return None;
    ///         }
    ///         Some(flags)
    ///     }
    ///     fn filter_intersection_pair(&self, context: PairFilterContextView) -> bool {
    ///         self.rules.filter_intersection_pair(&context)
    ///     }
    ///     fn modify_solver_contacts(&self, mut context: ContactModificationContextView) {
    ///         self.rules.modify_solver_contacts(&mut context);
    ///     }
    /// }
    ///
    /// let mut app = App::new();
    /// app.add_plugins((
    ///     MinimalPlugins,
    ///     TransformPlugin,
    ///     RapierPhysicsPlugin::<GameHooks>::default(),
    ///     bevy_rapier_collision_rules::CollisionRulesPlugin::default(),
    /// ));
    /// app.update();
    /// ```
    pub fn filter_contact_pair(&self, context: &PairFilterContextView) -> Option<SolverFlags> {
        let raw = context.raw;
        match self.rules_of(raw.colliders, raw.collider1) {
            Some(rules) => PhysicsHooks::filter_contact_pair(rules, raw),
            None => Some(SolverFlags::COMPUTE_RIGID_IMPULSES),
        }
    }

    /// The rules' answer for a sensor pair: `false` for `NoPair` and
    /// `NoContacts` pairs.
    pub fn filter_intersection_pair(&self, context: &PairFilterContextView) -> bool {
        let raw = context.raw;
        self.rules_of(raw.colliders, raw.collider1)
            .is_none_or(|rules| PhysicsHooks::filter_intersection_pair(rules, raw))
    }

    /// Replays the contacts of pairs set to `ManifoldUpdate::Never`; a
    /// project's own contact modification runs after it.
    pub fn modify_solver_contacts(&self, context: &mut ContactModificationContextView) {
        let (colliders, collider) = (context.raw.colliders, context.raw.collider1);
        if let Some(rules) = self.rules_of(colliders, collider) {
            PhysicsHooks::modify_solver_contacts(rules, context.raw);
        }
    }

    /// Whether the project's own `ActiveHooks` on either collider ask for
    /// `bit`: whether Rapier would have called the project's hooks for this
    /// pair without the rules. The rules hook colliders of their own, so a
    /// project's hooks are called for more pairs than they asked for.
    /// `context` is the view any of the three hooks gets:
    ///
    /// ```
    /// use bevy::ecs::system::SystemParam;
    /// use bevy::prelude::*;
    /// use bevy_rapier3d::prelude::*;
    /// use bevy_rapier3d::rapier::prelude::{ActiveHooks, ModifiableContacts};
    /// use bevy_rapier_collision_rules::prelude::*;
    ///
    /// #[derive(SystemParam)]
    /// struct SlipperyHooks<'w, 's> {
    ///     rules: CollisionRulesHooks<'w, 's>,
    /// }
    ///
    /// impl BevyPhysicsHooks for SlipperyHooks<'_, '_> {
    ///     fn filter_contact_pair(&self, context: PairFilterContextView) -> Option<SolverFlags> {
    ///         self.rules.filter_contact_pair(&context)
    ///     }
    ///     fn filter_intersection_pair(&self, context: PairFilterContextView) -> bool {
    ///         self.rules.filter_intersection_pair(&context)
    ///     }
    ///     fn modify_solver_contacts(&self, mut context: ContactModificationContextView) {
    ///         self.rules.modify_solver_contacts(&mut context);
    ///         // The game's own contact change, only where its ActiveHooks ask.
    ///         if self.rules.project_asks(&context, ActiveHooks::MODIFY_SOLVER_CONTACTS)
    ///             && let ModifiableContacts::Rigid(manifold) = &mut context.raw.contacts
    ///         {
    ///             *manifold.friction = 0.0;
    ///         }
    ///     }
    /// }
    ///
    /// let mut app = App::new();
    /// app.add_plugins((
    ///     MinimalPlugins,
    ///     TransformPlugin,
    ///     RapierPhysicsPlugin::<SlipperyHooks>::default(),
    ///     CollisionRulesPlugin::default(),
    /// ));
    /// app.update();
    /// ```
    pub fn project_asks(&self, context: &impl HookedPair, bit: ActiveHooks) -> bool {
        let (colliders, a, b) = context.colliders();
        match self.rules_of(colliders, a) {
            Some(rules) => rules.project_asks(colliders, a, b, bit),
            None => [a, b].into_iter().any(|c| {
                colliders
                    .get(c)
                    .is_some_and(|c| c.active_hooks().contains(bit))
            }),
        }
    }
}

impl BevyPhysicsHooks for CollisionRulesHooks<'_, '_> {
    fn filter_contact_pair(&self, context: PairFilterContextView) -> Option<SolverFlags> {
        CollisionRulesHooks::filter_contact_pair(self, &context)
    }

    fn filter_intersection_pair(&self, context: PairFilterContextView) -> bool {
        CollisionRulesHooks::filter_intersection_pair(self, &context)
    }

    fn modify_solver_contacts(&self, mut context: ContactModificationContextView) {
        CollisionRulesHooks::modify_solver_contacts(self, &mut context);
    }
}
