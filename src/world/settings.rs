//! What the project itself tells Rapier about a collider: its collision
//! groups, solver groups, active collision types and hook bits. The crate
//! combines its plan with these and never writes in their place
//! (`docs/semantics.md`, "The project's own settings"): a pair interacts only as far as both the
//! project's settings and the rules allow.

use super::super::rapier::prelude::*;

pub(crate) use super::super::model::{Settings, Written};

impl Settings {
    /// The settings `collider` has now.
    pub(crate) fn of(collider: &Collider) -> Settings {
        Settings {
            collision: collider.collision_groups(),
            solver: collider.solver_groups(),
            types: collider.active_collision_types(),
            hooks: collider.active_hooks(),
        }
    }

    /// The fields of `now` that differ from `written` (what the crate wrote
    /// last): the project changed them through Rapier since.
    pub(crate) fn changed_since(self, written: Settings, now: Settings) -> Settings {
        fn pick<T: PartialEq>(own: T, written: T, now: T) -> T {
            if now != written { now } else { own }
        }
        Settings {
            collision: pick(self.collision, written.collision, now.collision),
            solver: pick(self.solver, written.solver, now.solver),
            types: pick(self.types, written.types, now.types),
            hooks: pick(self.hooks, written.hooks, now.hooks),
        }
    }

    /// Gives `collider` these settings, touching only what differs (Rapier
    /// marks a collider modified on every `get_mut`, so the caller checks
    /// first).
    pub(crate) fn write(self, collider: &mut Collider) {
        collider.set_active_hooks(self.hooks);
        collider.set_solver_groups(self.solver);
        if collider.active_collision_types() != self.types {
            collider.set_active_collision_types(self.types);
            // Changing the collision types alone sets no change flag:
            // nudging the collision groups makes Rapier look again.
            collider.set_collision_groups(InteractionGroups::none());
        }
        collider.set_collision_groups(self.collision);
    }

    /// Whether these types let Rapier look at a pair of bodies of these types.
    pub(crate) fn types_allow(
        self,
        other: Settings,
        types: (RigidBodyType, RigidBodyType),
    ) -> bool {
        self.types.test(types.0, types.1) || other.types.test(types.0, types.1)
    }

    /// Whether the types let Rapier pair this collider's non-dynamic body
    /// with another non-dynamic one: more than Rapier's defaults.
    pub(crate) fn widened(self) -> bool {
        !(self.types - ActiveCollisionTypes::default()).is_empty()
    }
}

/// A collider's settings as the project set them, without what the rules
/// wrote: what the collider shows once the rules let it go, or after
/// [`RuleHooks::restore_project_settings`](crate::RuleHooks::restore_project_settings).
/// Read them with [`RuleHooks::project_settings`](crate::RuleHooks::project_settings)
/// to change one of them through Rapier on a collider the rules reach
/// (`docs/semantics.md`, "The project's own settings").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ProjectSettings {
    /// The project's `Collider::collision_groups`.
    pub collision_groups: InteractionGroups,
    /// The project's `Collider::solver_groups`.
    pub solver_groups: InteractionGroups,
    /// The project's `Collider::active_collision_types`.
    pub active_collision_types: ActiveCollisionTypes,
    /// The project's `Collider::active_hooks`.
    pub active_hooks: ActiveHooks,
}

impl From<Settings> for ProjectSettings {
    fn from(settings: Settings) -> ProjectSettings {
        ProjectSettings {
            collision_groups: settings.collision,
            solver_groups: settings.solver,
            active_collision_types: settings.types,
            active_hooks: settings.hooks,
        }
    }
}

impl Written {
    /// The project's settings as of `now`: those the project changed since
    /// the crate wrote, the remembered ones otherwise.
    pub(crate) fn own_as_of(&self, now: Settings) -> Settings {
        self.own.changed_since(self.wrote, now)
    }
}
