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
    // Each side against the other's union first: a body of many colliders
    // waiting for a small one to leave costs a pass over its boxes, not a
    // test of every pair of boxes.
    let reach1 = union(&boxes1);
    let near2: SmallVec<[Aabb; 4]> = boxes2.into_iter().filter(|b| reach1.intersects(b)).collect();
    if near2.is_empty() {
        return true;
    }
    let reach2 = union(&near2);
    let near1 = boxes1.iter().filter(|b| reach2.intersects(b));
    !near1.into_iter().any(|b1| near2.iter().any(|b2| b1.intersects(b2)))
}

/// The box around `boxes` (not empty).
fn union(boxes: &[Aabb]) -> Aabb {
    boxes[1..].iter().fold(boxes[0], |all, b| all.merged(b))
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::super::super::rapier::parry::bounding_volume::BoundingVolume;
    use super::super::super::rapier::prelude::*;
    use super::apart;

    proptest! {
        /// The union tests change nothing: `apart` is the test of every
        /// pair of boxes.
        #[test]
        fn apart_is_every_pair_of_boxes_apart(
            side1 in prop::collection::vec((-4.0f32..4.0, -4.0f32..4.0, 0.1f32..1.5), 1..6),
            side2 in prop::collection::vec((-4.0f32..4.0, -4.0f32..4.0, 0.1f32..1.5), 1..6),
            margin in 0.0f32..0.5,
        ) {
            let mut colliders = ColliderSet::new();
            let mut insert = |side: &[(f32, f32, f32)]| -> Vec<ColliderHandle> {
                side.iter()
                    .map(|&(x, y, r)| {
                        let mut at = Vector::ZERO;
                        at.x = x;
                        at.y = y;
                        colliders.insert(ColliderBuilder::ball(r).translation(at))
                    })
                    .collect()
            };
            let (a, b) = (insert(&side1), insert(&side2));
            let naive = a.iter().all(|&c1| {
                b.iter().all(|&c2| {
                    let box1 = colliders[c1].compute_aabb().loosened(margin);
                    !box1.intersects(&colliders[c2].compute_aabb())
                })
            });
            prop_assert_eq!(apart(&a, &b, &colliders, margin), naive);
        }
    }
}
