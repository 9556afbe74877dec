//! A side table keyed by nodes that looks a node up by its slot, as
//! [`HandleMap`] does for one kind of handle: the planner reads its records
//! of the nodes of every object that comes or goes, several times each,
//! and a hash look-up there cost more than the rest of the work
//! (`docs/performance.md`, "Run 47").

use hashbrown::HashMap;

use super::super::rapier::prelude::{ColliderHandle, RigidBodyHandle};

use super::node::{HandleMap, Node};

/// Values by node: in the slot of the node's handle, or, for a node whose
/// slot holds another generation's value at the same time (an object Rapier
/// removed whose records the planner has yet to forget, next to the new
/// object in its slot), in a hash map that is empty in the common case.
#[derive(Clone, Debug)]
pub(crate) struct NodeMap<V> {
    colliders: HandleMap<ColliderHandle, V>,
    bodies: HandleMap<RigidBodyHandle, V>,
    others: HashMap<Node, V>,
}

impl<V> Default for NodeMap<V> {
    fn default() -> Self {
        NodeMap {
            colliders: HandleMap::default(),
            bodies: HandleMap::default(),
            others: HashMap::new(),
        }
    }
}

/// Where a node's value lives.
enum Place {
    Slot,
    Other,
}

impl<V> NodeMap<V> {
    /// Where `node`'s value is, or would be put.
    #[inline]
    fn place(&self, node: Node) -> Place {
        let other = match node {
            Node::Collider(c) => self.colliders.holds_other(c),
            Node::Body(b) => self.bodies.holds_other(b),
        };
        if other { Place::Other } else { Place::Slot }
    }

    /// `node`'s value: one look at its slot, where it is unless the slot
    /// holds another generation's (then `others`, empty in the common case,
    /// has it).
    #[inline]
    pub(crate) fn get(&self, node: Node) -> Option<&V> {
        let in_slot = match node {
            Node::Collider(c) => self.colliders.get(c),
            Node::Body(b) => self.bodies.get(b),
        };
        in_slot.or_else(|| if self.others.is_empty() { None } else { self.others.get(&node) })
    }

    #[inline]
    pub(crate) fn get_mut(&mut self, node: Node) -> Option<&mut V> {
        // Without other generations every value is in its slot: one look.
        if self.others.is_empty() {
            return match node {
                Node::Collider(c) => self.colliders.get_mut(c),
                Node::Body(b) => self.bodies.get_mut(b),
            };
        }
        match self.place(node) {
            Place::Slot => match node {
                Node::Collider(c) => self.colliders.get_mut(c),
                Node::Body(b) => self.bodies.get_mut(b),
            },
            Place::Other => self.others.get_mut(&node),
        }
    }

    /// `node`'s value, made by `make` if it has none.
    pub(crate) fn get_or_insert_with(&mut self, node: Node, make: impl FnOnce() -> V) -> &mut V {
        match self.place(node) {
            Place::Slot => match node {
                Node::Collider(c) => self.colliders.get_or_insert_with(c, make),
                Node::Body(b) => self.bodies.get_or_insert_with(b, make),
            },
            Place::Other => self.others.entry(node).or_insert_with(make),
        }
    }

    pub(crate) fn remove(&mut self, node: Node) -> Option<V> {
        match self.place(node) {
            Place::Slot => {
                let removed = match node {
                    Node::Collider(c) => self.colliders.remove(c),
                    Node::Body(b) => self.bodies.remove(b),
                };
                if removed.is_some() && !self.others.is_empty() {
                    self.promote(node.slot());
                }
                removed
            }
            Place::Other => self.others.remove(&node),
        }
    }

    /// Moves the value of another generation of a freed slot into it, so
    /// that a node's value is in its slot whenever the slot is free.
    fn promote(&mut self, slot: (bool, u32)) {
        let Some(node) = self.others.keys().copied().find(|n| n.slot() == slot) else {
            return;
        };
        let value = self.others.remove(&node).expect("a key just found");
        match node {
            Node::Collider(c) => self.colliders.get_or_insert_with(c, || value),
            Node::Body(b) => self.bodies.get_or_insert_with(b, || value),
        };
    }

    /// Every value, in no order. Walks every slot up to the highest one
    /// used: for whole plans, never per object.
    pub(crate) fn values(&self) -> impl Iterator<Item = &V> + '_ {
        self.colliders
            .iter()
            .map(|(_, v)| v)
            .chain(self.bodies.iter().map(|(_, v)| v))
            .chain(self.others.values())
    }
}

impl<V: Default> NodeMap<V> {
    /// `node`'s value, a default one if it has none.
    #[inline]
    pub(crate) fn or_default(&mut self, node: Node) -> &mut V {
        self.get_or_insert_with(node, V::default)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use super::super::node::Handle;

    fn collider(index: u32, generation: u32) -> Node {
        Node::Collider(ColliderHandle::from_raw(index, generation))
    }

    #[test]
    fn two_generations_of_a_slot_keep_their_own_values() {
        let mut map = NodeMap::<u8>::default();
        let (old, new) = (collider(3, 0), collider(3, 1));
        *map.or_default(old) = 7;
        *map.or_default(new) = 9;
        assert_eq!((map.get(old), map.get(new), map.values().count()), (Some(&7), Some(&9), 2));
        assert_eq!(map.remove(old), Some(7));
        assert_eq!((map.get(old), map.get(new), map.values().count()), (None, Some(&9), 1));
        assert_eq!(map.remove(new), Some(9));
        assert_eq!(map.values().count(), 0);
        // The slot is free again for either generation.
        *map.or_default(old) = 1;
        assert_eq!((map.get(old), map.get(new)), (Some(&1), None));
        // Three generations at once, removed oldest first.
        *map.or_default(new) = 2;
        *map.or_default(collider(3, 2)) = 3;
        assert_eq!(map.remove(old), Some(1));
        *map.or_default(new) += 10;
        assert_eq!(map.remove(collider(3, 2)), Some(3));
        assert_eq!((map.get(new), map.values().count()), (Some(&12), 1));
    }

    /// Random inserts, edits and removals over a few slots, generations
    /// and both kinds, against a hash map keyed by node.
    #[test]
    fn it_answers_as_a_hash_map_keyed_by_node() {
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = |n: u64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state % n
        };
        for _ in 0..200 {
            let mut map = NodeMap::<u32>::default();
            let mut reference = HashMap::<Node, u32>::new();
            for step in 0..500 {
                let (index, generation) = (next(4) as u32, next(4) as u32);
                let node = if next(2) == 0 {
                    collider(index, generation)
                } else {
                    Node::Body(RigidBodyHandle::from_raw(index, generation))
                };
                match next(3) {
                    0 => {
                        *map.or_default(node) += step;
                        *reference.entry(node).or_default() += step;
                    }
                    1 => assert_eq!(map.remove(node), reference.remove(&node), "remove {node:?}"),
                    _ => {
                        if let (Some(v), Some(r)) = (map.get_mut(node), reference.get_mut(&node)) {
                            *v += 1;
                            *r += 1;
                        }
                    }
                }
                assert_eq!(map.get(node), reference.get(&node), "{node:?} after step {step}");
                let mut values: Vec<u32> = map.values().copied().collect();
                let mut expected: Vec<u32> = reference.values().copied().collect();
                values.sort_unstable();
                expected.sort_unstable();
                assert_eq!(values, expected, "the values after step {step}");
            }
        }
    }

    #[test]
    fn a_collider_and_a_body_of_one_slot_are_two_nodes() {
        let mut map = NodeMap::<u8>::default();
        let body = Node::Body(RigidBodyHandle::from_raw(3, 0));
        *map.or_default(collider(3, 0)) = 1;
        *map.or_default(body) = 2;
        assert_eq!((map.get(collider(3, 0)), map.get(body)), (Some(&1), Some(&2)));
        let mut values: Vec<u8> = map.values().copied().collect();
        values.sort_unstable();
        assert_eq!(values, [1, 2]);
    }
}
