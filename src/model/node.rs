//! Nodes (the colliders and rigid bodies that carry rules) and the
//! handle-indexed side tables that hold what the crate knows of them.

use super::super::rapier::prelude::{ColliderHandle, RigidBodyHandle};

/// A collider or a rigid body: anything a rule can be attached to.
///
/// Every method that takes a node takes `impl Into<Node>`, so handles are
/// passed as they are.
///
/// ```
/// use rapier3d::prelude::*;
/// use rapier_collision_rules::Node;
///
/// let mut bodies = RigidBodySet::new();
/// let body = bodies.insert(RigidBodyBuilder::dynamic());
/// assert_eq!(Node::from(body), Node::Body(body));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Node {
    /// A collider: a leaf of every chain.
    Collider(ColliderHandle),
    /// A rigid body: a collider's parent, or a parent in the crate's parent map.
    Body(RigidBodyHandle),
}

impl Node {
    /// The node's kind and Rapier slot index: two nodes of one slot are
    /// generations of it.
    #[inline]
    pub(crate) fn slot(self) -> (bool, u32) {
        match self {
            Node::Collider(handle) => (false, handle.raw_parts().0),
            Node::Body(handle) => (true, handle.raw_parts().0),
        }
    }

    #[inline]
    pub(crate) fn generation(self) -> u32 {
        match self {
            Node::Collider(handle) => handle.raw_parts().1,
            Node::Body(handle) => handle.raw_parts().1,
        }
    }
}

/// The one order on nodes, for deterministic iteration: colliders before
/// bodies, then by slot and generation.
impl Ord for Node {
    fn cmp(&self, other: &Node) -> std::cmp::Ordering {
        let key = |node: &Node| match *node {
            Node::Collider(handle) => (0u8, handle.into_raw_parts()),
            Node::Body(handle) => (1u8, handle.into_raw_parts()),
        };
        key(self).cmp(&key(other))
    }
}

impl PartialOrd for Node {
    fn partial_cmp(&self, other: &Node) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

/// One word per node: the specific stage hashes nodes in its inner loop,
/// and the derived hash (the kind, then the handle's two fields, through a
/// call the compiler stopped inlining) made that stage twice as slow
/// (`docs/performance.md`, `resolve`). Equal nodes give equal words.
impl std::hash::Hash for Node {
    #[inline]
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        let ((body, index), generation) = (self.slot(), self.generation());
        let word = (u64::from(generation) << 32 | u64::from(index)) ^ (u64::from(body) << 63);
        state.write_u64(word);
    }
}

impl From<ColliderHandle> for Node {
    fn from(handle: ColliderHandle) -> Self {
        Node::Collider(handle)
    }
}

impl From<RigidBodyHandle> for Node {
    fn from(handle: RigidBodyHandle) -> Self {
        Node::Body(handle)
    }
}

/// A generational handle of Rapier's: a slot index and the slot's generation.
pub(crate) trait Handle: Copy {
    fn raw_parts(self) -> (u32, u32);
    fn from_raw(index: u32, generation: u32) -> Self;
}

impl Handle for ColliderHandle {
    fn raw_parts(self) -> (u32, u32) {
        self.into_raw_parts()
    }
    fn from_raw(index: u32, generation: u32) -> Self {
        ColliderHandle::from_raw_parts(index, generation)
    }
}

impl Handle for RigidBodyHandle {
    fn raw_parts(self) -> (u32, u32) {
        self.into_raw_parts()
    }
    fn from_raw(index: u32, generation: u32) -> Self {
        RigidBodyHandle::from_raw_parts(index, generation)
    }
}

/// A side table keyed by Rapier handles, stored densely by slot index like
/// Rapier's own `Coarena`. A handle whose generation differs from the stored
/// one (a slot Rapier has reused) finds nothing.
#[derive(Clone, Debug)]
pub(crate) struct HandleMap<H, V> {
    slots: Vec<Option<(u32, V)>>,
    _handle: std::marker::PhantomData<fn(H)>,
}

impl<H, V> Default for HandleMap<H, V> {
    fn default() -> Self {
        HandleMap {
            slots: Vec::new(),
            _handle: std::marker::PhantomData,
        }
    }
}

impl<H: Handle, V> HandleMap<H, V> {
    #[inline]
    pub(crate) fn get(&self, handle: H) -> Option<&V> {
        let (index, generation) = handle.raw_parts();
        match self.slots.get(index as usize) {
            Some(Some((stored, value))) if *stored == generation => Some(value),
            _ => None,
        }
    }

    pub(crate) fn get_mut(&mut self, handle: H) -> Option<&mut V> {
        let (index, generation) = handle.raw_parts();
        match self.slots.get_mut(index as usize) {
            Some(Some((stored, value))) if *stored == generation => Some(value),
            _ => None,
        }
    }

    /// Whether the slot of `handle` holds a newer generation: Rapier has
    /// removed the object and reused its slot, so `handle` names nothing.
    #[inline]
    pub(crate) fn is_superseded(&self, handle: H) -> bool {
        let (index, generation) = handle.raw_parts();
        matches!(self.slots.get(index as usize), Some(Some((stored, _))) if *stored > generation)
    }

    /// Whether the slot of `handle` holds a value of another generation.
    #[inline]
    pub(crate) fn holds_other(&self, handle: H) -> bool {
        let (index, generation) = handle.raw_parts();
        matches!(self.slots.get(index as usize), Some(Some((stored, _))) if *stored != generation)
    }

    /// The value of `handle`, made by `make` if its slot is empty. The
    /// caller checks [`holds_other`](Self::holds_other) first.
    pub(crate) fn get_or_insert_with(&mut self, handle: H, make: impl FnOnce() -> V) -> &mut V {
        debug_assert!(!self.holds_other(handle), "a slot of another generation");
        let (index, generation) = handle.raw_parts();
        let index = index as usize;
        if index >= self.slots.len() {
            self.slots.resize_with(index + 1, || None);
        }
        let (_, value) = self.slots[index].get_or_insert_with(|| (generation, make()));
        value
    }

    /// The handle of a newer generation than `handle` that the slot holds,
    /// if any.
    pub(crate) fn newer_than(&self, handle: H) -> Option<H> {
        let (index, generation) = handle.raw_parts();
        match self.slots.get(index as usize) {
            Some(Some((stored, _))) if *stored > generation => Some(H::from_raw(index, *stored)),
            _ => None,
        }
    }

    /// Stores `value` for `handle`. Returns what the slot held before, of
    /// this generation or an older one (whose object Rapier has removed), so
    /// that the caller can let go of it. The caller checks
    /// [`is_superseded`](Self::is_superseded) first.
    pub(crate) fn insert(&mut self, handle: H, value: V) -> Option<V> {
        debug_assert!(!self.is_superseded(handle), "insert through a dead handle");
        let (index, generation) = handle.raw_parts();
        let index = index as usize;
        if index >= self.slots.len() {
            self.slots.resize_with(index + 1, || None);
        }
        self.slots[index]
            .replace((generation, value))
            .map(|(_, value)| value)
    }

    /// Stores `value` for `handle` and returns the handle and value of an
    /// older generation the slot held, if any.
    pub(crate) fn insert_evicting(&mut self, handle: H, value: V) -> Option<(H, V)> {
        let (index, generation) = handle.raw_parts();
        let index = index as usize;
        if index >= self.slots.len() {
            self.slots.resize_with(index + 1, || None);
        }
        match self.slots[index].replace((generation, value)) {
            Some((old, value)) if old != generation => {
                Some((H::from_raw(index as u32, old), value))
            }
            _ => None,
        }
    }

    pub(crate) fn remove(&mut self, handle: H) -> Option<V> {
        let (index, generation) = handle.raw_parts();
        let slot = self.slots.get_mut(index as usize)?;
        match slot {
            Some((stored, _)) if *stored == generation => slot.take().map(|(_, value)| value),
            _ => None,
        }
    }

    pub(crate) fn iter(&self) -> impl Iterator<Item = (H, &V)> + '_ {
        self.slots.iter().enumerate().filter_map(|(index, slot)| {
            slot.as_ref()
                .map(|(generation, value)| (H::from_raw(index as u32, *generation), value))
        })
    }

    pub(crate) fn retain(&mut self, mut keep: impl FnMut(H, &mut V) -> bool) {
        for (index, slot) in self.slots.iter_mut().enumerate() {
            if let Some((generation, value)) = slot {
                if !keep(H::from_raw(index as u32, *generation), value) {
                    *slot = None;
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_reused_slot_does_not_see_the_old_value() {
        let mut map = HandleMap::<ColliderHandle, u8>::default();
        let old = ColliderHandle::from_raw_parts(3, 0);
        let new = ColliderHandle::from_raw_parts(3, 1);
        map.insert(old, 7);
        assert_eq!(map.get(new), None);
        assert_eq!(map.remove(new), None);
        assert_eq!(
            map.insert(new, 9),
            Some(7),
            "the older generation is evicted"
        );
        assert!(map.is_superseded(old));
        assert!(!map.is_superseded(new));
        assert_eq!(map.get(old), None);
        assert_eq!(map.get(new), Some(&9));
    }

    #[test]
    fn insert_remove_and_retain() {
        let mut map = HandleMap::<RigidBodyHandle, u8>::default();
        for i in 0..5 {
            map.insert(RigidBodyHandle::from_raw_parts(i, 0), i as u8);
        }
        assert_eq!(map.remove(RigidBodyHandle::from_raw_parts(1, 0)), Some(1));
        map.retain(|_, v| *v % 2 == 0);
        let kept: Vec<u8> = map.iter().map(|(_, v)| *v).collect();
        assert_eq!(kept, [0, 2, 4]);
    }
}
