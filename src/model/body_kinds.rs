//! Whether a body is dynamic: the one fact about Rapier's body types the
//! rules read (the default groups, the special case), written once; and
//! whether a pair joins a soft body's surface to a rigid collider, the one
//! fact about soft bodies the answers read.

use super::super::rapier::prelude::{
    ColliderHandle, ColliderSet, RigidBody, RigidBodyHandle, RigidBodySet,
};

use super::super::Node;

/// The rigid body `collider` is attached to, if any (and in the set).
#[inline]
pub(crate) fn body_of<'a>(
    bodies: &'a RigidBodySet,
    colliders: &ColliderSet,
    collider: ColliderHandle,
) -> Option<&'a RigidBody> {
    colliders
        .get(collider)
        .and_then(|c| c.parent())
        .and_then(|b| bodies.get(b))
}

/// Whether `body` is a dynamic rigid body of `bodies`; a missing body, or
/// none (a collider without a body), is not.
#[inline]
pub(crate) fn dynamic_body(bodies: &RigidBodySet, body: Option<RigidBodyHandle>) -> bool {
    body.and_then(|handle| bodies.get(handle))
        .is_some_and(|body| body.is_dynamic())
}

/// Whether the rigid body of `node` (a collider's own body, or the body
/// itself) is dynamic.
#[inline]
pub(crate) fn is_dynamic(bodies: &RigidBodySet, colliders: &ColliderSet, node: Node) -> bool {
    let body = match node {
        Node::Collider(handle) => colliders.get(handle).and_then(|c| c.parent()),
        Node::Body(handle) => Some(handle),
    };
    dynamic_body(bodies, body)
}

/// Whether `collider` is a soft body's surface.
#[inline]
pub(crate) fn soft_surface(colliders: &ColliderSet, collider: ColliderHandle) -> bool {
    colliders.get(collider).is_some_and(|c| c.deformable_mesh_ref().is_some())
}

/// Whether one collider of the pair is a soft body's surface and the other
/// is not: Rapier 0.36.1 solves every contact of such a pair, so one without
/// response has none (`docs/semantics.md`, "Soft bodies").
#[inline]
pub(crate) fn soft_rigid(colliders: &ColliderSet, a: ColliderHandle, b: ColliderHandle) -> bool {
    soft_surface(colliders, a) != soft_surface(colliders, b)
}

/// Whether each body of a pair of colliders is dynamic, in the pair's
/// order.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct BodyKinds {
    /// The first collider's body.
    pub(crate) first: bool,
    /// The second collider's body.
    pub(crate) second: bool,
}

impl BodyKinds {
    /// The kinds of the bodies of `a` and `b`.
    #[inline]
    pub(crate) fn of(
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        a: ColliderHandle,
        b: ColliderHandle,
    ) -> BodyKinds {
        BodyKinds {
            first: is_dynamic(bodies, colliders, Node::Collider(a)),
            second: is_dynamic(bodies, colliders, Node::Collider(b)),
        }
    }

    /// Neither body is dynamic: the pair cannot respond.
    #[inline]
    pub(crate) fn neither_dynamic(self) -> bool {
        !self.first && !self.second
    }

    /// The same kinds for the pair in the other order.
    #[inline]
    pub(crate) fn swapped(self) -> BodyKinds {
        BodyKinds {
            first: self.second,
            second: self.first,
        }
    }
}
