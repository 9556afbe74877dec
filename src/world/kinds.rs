//! Rapier's body types of a pair, as its filters read them.

use super::super::rapier::prelude::*;

/// The body types of the pair `a`, `b` (fixed for a collider without a body,
/// as Rapier reads it).
pub(crate) fn body_types(
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    a: ColliderHandle,
    b: ColliderHandle,
) -> (RigidBodyType, RigidBodyType) {
    let of = |c: ColliderHandle| {
        colliders
            .get(c)
            .and_then(|c| c.parent())
            .and_then(|b| bodies.get(b))
            .map_or(RigidBodyType::Fixed, |b| b.body_type())
    };
    (of(a), of(b))
}
