//! A pair of colliders as one key, in the crate's one pair order.

use super::super::rapier::prelude::{ColliderHandle, ColliderSet, RigidBodySet};

use super::shapes::made_of_parts;
use super::super::model::BodyKinds;

/// A pair of colliders in a fixed order, so that `(a, b)` and `(b, a)` are
/// one key. The order (by slot, then generation) is the one pair order of
/// the crate.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct PairKey(ColliderHandle, ColliderHandle);

impl PairKey {
    #[inline]
    pub(crate) fn new(a: ColliderHandle, b: ColliderHandle) -> PairKey {
        if a.into_raw_parts() <= b.into_raw_parts() {
            PairKey(a, b)
        } else {
            PairKey(b, a)
        }
    }

    #[inline]
    pub(crate) fn colliders(self) -> (ColliderHandle, ColliderHandle) {
        (self.0, self.1)
    }

    /// Whether each collider's body is dynamic, in key order.
    #[inline]
    pub(crate) fn kinds(self, bodies: &RigidBodySet, colliders: &ColliderSet) -> BodyKinds {
        BodyKinds::of(bodies, colliders, self.0, self.1)
    }

    /// Whether a collider of the pair is made of parts (see [`made_of_parts`]).
    #[inline]
    pub(crate) fn made_of_parts(self, colliders: &ColliderSet) -> bool {
        made_of_parts(colliders, self.0, self.1)
    }
}

impl PairKey {
    /// The key as one number that sorts in the pair order: slot, then
    /// generation, of the first collider, then of the second. Sorting a
    /// step's pairs (`hooks/recalculate.rs`) compares one number, not two
    /// pairs of pairs.
    #[inline]
    fn order_word(self) -> u128 {
        let word = |h: ColliderHandle| {
            let (index, generation) = h.into_raw_parts();
            u64::from(index) << 32 | u64::from(generation)
        };
        u128::from(word(self.0)) << 64 | u128::from(word(self.1))
    }
}

impl Ord for PairKey {
    #[inline]
    fn cmp(&self, other: &PairKey) -> std::cmp::Ordering {
        self.order_word().cmp(&other.order_word())
    }
}

impl PartialOrd for PairKey {
    fn partial_cmp(&self, other: &PairKey) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_sort_by_slot_then_generation_of_each_collider() {
        let handles: Vec<ColliderHandle> = [(0, 0), (0, 1), (1, 0), (2, 5), (u32::MAX, 0), (3, u32::MAX)]
            .into_iter()
            .map(|(i, g)| ColliderHandle::from_raw_parts(i, g))
            .collect();
        let keys: Vec<PairKey> = handles
            .iter()
            .flat_map(|&a| handles.iter().map(move |&b| PairKey::new(a, b)))
            .collect();
        let raw = |k: PairKey| (k.0.into_raw_parts(), k.1.into_raw_parts());
        for &x in &keys {
            for &y in &keys {
                assert_eq!(x.cmp(&y), raw(x).cmp(&raw(y)), "{:?} against {:?}", raw(x), raw(y));
            }
        }
    }
}
