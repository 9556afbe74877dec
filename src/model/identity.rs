//! Which rule set is which: hooks whose set was replaced notice it.

use std::sync::atomic::{AtomicU64, Ordering};

/// A number no other rule set of the process has. A new set, a copy and a
/// loaded set each take a new one, so that hooks whose set is put in place
/// of theirs (`*hooks.rules_mut() = other`, or two hooks' sets swapped)
/// follow it whole at the next step, whatever its change log holds
/// (`docs/semantics.md`, "Saving and loading").
#[derive(Debug, PartialEq, Eq)]
pub(crate) struct Identity(u64);

impl Identity {
    /// The number, for the hooks to remember (never 0).
    pub(crate) fn number(&self) -> u64 {
        self.0
    }
}

impl Default for Identity {
    fn default() -> Self {
        static NEXT: AtomicU64 = AtomicU64::new(1);
        Identity(NEXT.fetch_add(1, Ordering::Relaxed))
    }
}

/// A copy is another set: its edits do not reach the original's hooks.
impl Clone for Identity {
    fn clone(&self) -> Self {
        Identity::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_set_and_every_copy_is_another() {
        let a = Identity::default();
        let b = Identity::default();
        let c = a.clone();
        assert_ne!(a, b);
        assert_ne!(a, c);
        assert_ne!(b, c);
        assert_ne!(a.number(), 0);
    }
}
