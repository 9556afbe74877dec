//! The handles of objects the rule set has forgotten as removed, so that
//! every editing verb refuses them alike (`docs/semantics.md`, "Handles of
//! removed objects").

use crate::Node;
use crate::node::Handle;

/// Per Rapier slot, one more than the newest generation forgotten as
/// removed (0: none). Rapier's handles are generational, so every older
/// generation of the slot is dead too, and a newer one is a new object.
/// One number per slot the rules ever named: bounded like Rapier's arenas.
#[derive(Clone, Debug, Default)]
pub(crate) struct Tombstones {
    colliders: Vec<u32>,
    bodies: Vec<u32>,
}

impl Tombstones {
    /// Remembers that `node`'s object, and every older one of its slot, is gone.
    pub(crate) fn bury(&mut self, node: Node) {
        let (slots, (index, generation)) = match node {
            Node::Collider(handle) => (&mut self.colliders, raw(handle)),
            Node::Body(handle) => (&mut self.bodies, raw(handle)),
        };
        let index = index as usize;
        if index >= slots.len() {
            slots.resize(index + 1, 0);
        }
        slots[index] = slots[index].max(generation.saturating_add(1));
    }

    /// Whether `node` was forgotten as removed.
    pub(crate) fn holds(&self, node: Node) -> bool {
        let (slots, (index, generation)) = match node {
            Node::Collider(handle) => (&self.colliders, raw(handle)),
            Node::Body(handle) => (&self.bodies, raw(handle)),
        };
        slots
            .get(index as usize)
            .is_some_and(|&dead| generation < dead)
    }
}

fn raw(handle: impl Handle) -> (u32, u32) {
    handle.raw_parts()
}

#[cfg(test)]
mod tests {
    use super::*;
    use rapier3d::prelude::{ColliderHandle, RigidBodyHandle};

    #[test]
    fn a_buried_handle_and_its_elders_are_dead_a_newer_one_is_not() {
        let mut graves = Tombstones::default();
        let old = Node::Body(RigidBodyHandle::from_raw_parts(3, 1));
        graves.bury(old);
        assert!(graves.holds(old));
        assert!(graves.holds(Node::Body(RigidBodyHandle::from_raw_parts(3, 0))));
        assert!(!graves.holds(Node::Body(RigidBodyHandle::from_raw_parts(3, 2))));
        assert!(!graves.holds(Node::Body(RigidBodyHandle::from_raw_parts(2, 0))));
        assert!(
            !graves.holds(Node::Collider(ColliderHandle::from_raw_parts(3, 1))),
            "bodies and colliders have their own slots"
        );
    }
}
