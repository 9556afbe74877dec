//! **See**: the rules drawn for a person.
//!
//! Everything here reads what the other stages made and changes nothing.
//! One [`palette`] colours the rules everywhere they are drawn (the debug
//! view, the Bevy debug plugin, the pictures under `docs/`). With the
//! feature `debug-render`, the [`view`] draws what Rapier's own debug
//! rendering draws through the project's `DebugRenderBackend`, with the
//! colliders the rules reach [`tint`]ed by how the hooks'
//! [`Reach`](super::Reach) says they are decided, and a line per live pair
//! the rules reach in its rule's colour; the [`filter`] narrows it to one
//! node, one rule or the hooked pairs, and each pair's [`label`] says what
//! [`explain`](super::CollisionRuleSet::explain) says (`docs/semantics.md`,
//! "Seeing the rules").
//!
//! It stands on the [`hooks`](super::hooks), which know the plan and the
//! live pairs, and nothing stands on it.

mod palette;

#[cfg(feature = "debug-render")]
mod filter;
#[cfg(feature = "debug-render")]
mod label;
#[cfg(feature = "debug-render")]
mod tint;
#[cfg(feature = "debug-render")]
mod view;

pub use palette::{RuleColor, RulePalette};

#[cfg(feature = "debug-render")]
pub use filter::RuleDebugFilter;
#[cfg(feature = "debug-render")]
pub use label::RuleLabelBackend;
#[cfg(feature = "debug-render")]
pub use view::{RuleDebugRender, RuleLine, RuleLineKind};
