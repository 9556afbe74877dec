//! The handles of objects the rule set has forgotten as removed, so that
//! every editing verb refuses them alike (`docs/semantics.md`, "Handles of
//! removed objects").

use super::super::Node;

/// Per Rapier slot, the generation last forgotten as removed, plus one (0:
/// none). Only that exact handle is dead here: a handle of another
/// generation may be one Rapier has yet to hand out (a corrupt save can
/// name one), and burying it must not kill the live object of its slot.
/// One number per slot the rules ever named: bounded like Rapier's arenas.
#[derive(Clone, Debug, Default)]
pub(crate) struct Tombstones {
    colliders: Vec<u32>,
    bodies: Vec<u32>,
}

impl Tombstones {
    /// Remembers that `node`'s object is gone.
    pub(crate) fn bury(&mut self, node: Node) {
        let ((body, index), generation) = (node.slot(), node.generation());
        let slots = if body {
            &mut self.bodies
        } else {
            &mut self.colliders
        };
        let index = index as usize;
        if index >= slots.len() {
            slots.resize(index + 1, 0);
        }
        slots[index] = generation.wrapping_add(1);
    }

    /// Whether `node` was the last object of its slot forgotten as removed.
    pub(crate) fn holds(&self, node: Node) -> bool {
        let ((body, index), generation) = (node.slot(), node.generation());
        let slots = if body { &self.bodies } else { &self.colliders };
        slots
            .get(index as usize)
            .is_some_and(|&dead| dead == generation.wrapping_add(1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use super::super::super::rapier::prelude::{ColliderHandle, RigidBodyHandle};

    #[test]
    fn a_buried_handle_is_dead_and_no_other_generation_is() {
        let mut graves = Tombstones::default();
        let body =
            |index, generation| Node::Body(RigidBodyHandle::from_raw_parts(index, generation));
        graves.bury(body(3, 1));
        assert!(graves.holds(body(3, 1)));
        assert!(
            !graves.holds(body(3, 2)),
            "a newer object of the slot lives"
        );
        assert!(!graves.holds(body(3, 0)));
        assert!(!graves.holds(body(2, 1)));
        assert!(
            !graves.holds(Node::Collider(ColliderHandle::from_raw_parts(3, 1))),
            "bodies and colliders have their own slots"
        );
        graves.bury(body(3, 7));
        assert!(
            graves.holds(body(3, 7)) && !graves.holds(body(3, 1)),
            "one per slot"
        );
    }
}
