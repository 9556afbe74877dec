//! Shapes made of parts, whose pairs Rapier keeps as one manifold per
//! touching part.

use super::super::rapier::prelude::*;

/// Whether a collider of the pair is made of parts: a triangle mesh,
/// polyline, height field, voxel set or compound. Rapier keeps one
/// manifold per touching part, and parts come and go as the bodies move,
/// so contacts frozen per manifold could not be kept
/// (`docs/architecture.md`, "Manifold settings").
pub(crate) fn made_of_parts(colliders: &ColliderSet, a: ColliderHandle, b: ColliderHandle) -> bool {
    let parts = |c: ColliderHandle| {
        colliders.get(c).is_some_and(|collider| {
            matches!(
                collider.shape().shape_type(),
                ShapeType::TriMesh
                    | ShapeType::Polyline
                    | ShapeType::HeightField
                    | ShapeType::Voxels
                    | ShapeType::Compound
            )
        })
    };
    parts(a) || parts(b)
}
