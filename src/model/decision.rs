//! How the planner decided a specific entry, kept for the entry's life
//! (`planner/decisions.rs`); a copy travels in the rule set, so that a saved
//! set carries it (`docs/semantics.md`, "Saving and loading").

use super::super::Node;

/// How one specific entry is decided.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) enum Decision {
    /// Rapier's groups decide it: the colliders under `carrying`, all on
    /// dynamic bodies, take `bit` as their membership of `kind` (0:
    /// collision groups, for `NoPair`; 1: solver groups, for `NoResponse`),
    /// and the colliders under `other` leave it out of their filter. Every
    /// entry about `other` of one kind shares one bit.
    Bits {
        carrying: Node,
        other: Node,
        kind: usize,
        bit: u32,
    },
    /// The colliders under `side` are hooked.
    Hooked { side: Node },
}

