//! The project's own bevy_rapier settings: `CollisionGroups`,
//! `SolverGroups`, `ActiveCollisionTypes` and `ActiveHooks` stay the
//! project's. bevy_rapier writes them into Rapier when they change; the
//! rules combine with what it wrote before the next step (`docs/bevy.md`).

use bevy::prelude::*;
use bevy_rapier::prelude::{
    ActiveCollisionTypes, ActiveHooks, CollisionGroups, RapierColliderHandle,
    RapierContextEntityLink, SolverGroups,
};

use super::CollisionRules;
use super::ledger::Ledger;

type Changes<'w, 's, T> = Query<
    'w,
    's,
    (
        Ref<'static, RapierColliderHandle>,
        &'static RapierContextEntityLink,
    ),
    Changed<T>,
>;

/// Tells each context's rules when the project changed one of those
/// components on a collider that already existed (a new collider is
/// noticed by itself), or removed one (bevy_rapier then writes Rapier's
/// default).
#[allow(clippy::too_many_arguments)]
pub(crate) fn notice_project_settings(
    mut ledger: ResMut<Ledger>,
    mut contexts: Query<&mut CollisionRules>,
    links: Query<&RapierContextEntityLink>,
    collision_groups: Changes<CollisionGroups>,
    solver_groups: Changes<SolverGroups>,
    types: Changes<ActiveCollisionTypes>,
    hooks: Changes<ActiveHooks>,
) {
    let changed = collision_groups
        .iter()
        .chain(&solver_groups)
        .chain(&types)
        .chain(&hooks)
        .filter(|(handle, _)| !handle.is_added())
        .map(|(_, link)| link.0);
    let reset = ledger
        .settings_removed
        .drain(..)
        .filter_map(|entity| links.get(entity).ok().map(|link| link.0));
    let mut touched: Vec<Entity> = changed.chain(reset).collect();
    touched.sort_unstable();
    touched.dedup();
    for context in touched {
        if let Ok(mut rules) = contexts.get_mut(context) {
            rules.hooks_mut().project_settings_changed();
        }
    }
}
