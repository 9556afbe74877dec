//! What the crate wrote on a collider and the project's own settings under
//! it: kept by the hooks, and a copy in the rule set so that a saved rule
//! set carries it (`docs/semantics.md`, "Saving and loading"). Reading and
//! writing them in Rapier is the world's (`world/settings.rs`).

use super::super::rapier::prelude::{ActiveCollisionTypes, ActiveHooks, InteractionGroups};

/// The four per-collider settings Rapier reads before the hook.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Settings {
    pub(crate) collision: InteractionGroups,
    pub(crate) solver: InteractionGroups,
    pub(crate) types: ActiveCollisionTypes,
    pub(crate) hooks: ActiveHooks,
}

/// A collider the crate has written settings to: the project's own
/// settings, and what the crate wrote (a difference later means the project
/// changed a setting through Rapier).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct Written {
    pub(crate) own: Settings,
    pub(crate) wrote: Settings,
}
