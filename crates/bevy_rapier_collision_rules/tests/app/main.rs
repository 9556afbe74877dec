//! Headless apps (`MinimalPlugins`, bevy_rapier's plugin and ours) stepped
//! by hand: every rule's outcome, edits through components, the hierarchy,
//! despawns, the project's own settings and hooks, bevy_rapier's stepping
//! modes, several contexts, and rule events as messages.

// One test source for both crates (the 2D one links this folder): each
// names its dimension's bevy_rapier and crate under one name.
#[cfg(feature = "dim2")]
extern crate bevy_rapier2d as bevy_rapier;
#[cfg(feature = "dim3")]
extern crate bevy_rapier3d as bevy_rapier;
#[cfg(feature = "dim2")]
extern crate bevy_rapier_collision_rules2d as bevy_rapier_collision_rules;

#[path = "../dimension/mod.rs"]
mod dimension;

mod contexts;
#[cfg(feature = "debug-render")]
mod debug_view;
mod edits;
mod elevator;
mod endings;
mod hierarchy;
mod one_way;
mod outcomes;
mod project;
mod queries;
mod rule_events;
#[cfg(feature = "serde")]
mod saving;
mod scene;
mod soft;
mod stepping;
