//! Whether two sets of colliders are apart: the test of a rule with an end
//! (`docs/semantics.md`, "Rules with an end").

use smallvec::SmallVec;

use super::super::rapier::parry::bounding_volume::{Aabb, BoundingVolume};
use super::super::rapier::prelude::{ColliderHandle, ColliderSet, Real};

/// Whether no collider of `side1` overlaps any collider of `side2` by
/// their bounding boxes at their poses now: the boxes are more than
/// `margin` apart (on some axis). A side
/// with no collider in the set is not apart from anything: a rule waiting
/// for its object's colliders holds until they come.
pub(crate) fn apart(
    side1: &[ColliderHandle],
    side2: &[ColliderHandle],
    colliders: &ColliderSet,
    margin: Real,
) -> bool {
    let boxes = |side: &[ColliderHandle], grow: Real| -> SmallVec<[Aabb; 4]> {
        side.iter()
            .filter_map(|&c| colliders.get(c))
            .map(|c| c.compute_aabb().loosened(grow))
            .collect()
    };
    // One side grown by the margin: boxes closer than it overlap.
    let (boxes1, boxes2) = (boxes(side1, margin), boxes(side2, 0.0));
    if boxes1.is_empty() || boxes2.is_empty() {
        return false;
    }
    !boxes1.iter().any(|b1| boxes2.iter().any(|b2| b1.intersects(b2)))
}
