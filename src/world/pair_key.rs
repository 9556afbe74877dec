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

impl Ord for PairKey {
    fn cmp(&self, other: &PairKey) -> std::cmp::Ordering {
        let raw = |key: &PairKey| (key.0.into_raw_parts(), key.1.into_raw_parts());
        raw(self).cmp(&raw(other))
    }
}

impl PartialOrd for PairKey {
    fn partial_cmp(&self, other: &PairKey) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}
