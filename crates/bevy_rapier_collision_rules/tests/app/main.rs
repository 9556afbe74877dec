//! Headless apps (`MinimalPlugins`, bevy_rapier's plugin and ours) stepped
//! by hand: every rule's outcome, edits through components, the hierarchy,
//! despawns, the project's own settings and hooks, bevy_rapier's stepping
//! modes and several contexts.

mod contexts;
mod edits;
mod elevator;
mod hierarchy;
mod outcomes;
mod project;
mod scene;
mod soft;
mod stepping;
