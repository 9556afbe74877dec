//! Look-ups in Rapier's pair graphs and the filters Rapier applies before
//! the hook: answered on demand, nothing copied per step.

use super::super::rapier::prelude::*;

use super::kinds::body_types;

/// Whether Rapier holds a pair of `a` and `b` (a contact or a sensor pair).
pub(crate) fn pair_exists(
    narrow_phase: &NarrowPhase,
    a: ColliderHandle,
    b: ColliderHandle,
) -> bool {
    narrow_phase.contact_pair(a, b).is_some() || narrow_phase.intersection_pair(a, b).is_some()
}

/// Whether `a` and `b` are on one rigid body: Rapier never lets them
/// interact (its graph may still hold their pair), so they form no pair.
pub(crate) fn same_body(colliders: &ColliderSet, a: ColliderHandle, b: ColliderHandle) -> bool {
    let body = |c: ColliderHandle| colliders.get(c).and_then(|c| c.parent());
    body(a).is_some() && body(a) == body(b)
}

/// A world's joint sets: Rapier asks no hook about the pairs of two bodies
/// that a joint with contacts disabled links.
#[derive(Clone, Copy)]
pub(crate) struct Joints<'a> {
    pub(crate) impulse: &'a ImpulseJointSet,
    pub(crate) multibody: &'a MultibodyJointSet,
}

impl Joints<'_> {
    /// Whether a joint keeps the bodies of `a` and `b` from touching, as
    /// Rapier's narrow phase reads it: an impulse joint with contacts
    /// disabled, or the same multibody without self-contacts or with such
    /// a link between them.
    fn keep_apart(self, colliders: &ColliderSet, a: ColliderHandle, b: ColliderHandle) -> bool {
        let body = |c: ColliderHandle| colliders.get(c).and_then(|c| c.parent());
        let (Some(b1), Some(b2)) = (body(a), body(b)) else {
            return false;
        };
        if self
            .impulse
            .joints_between(b1, b2)
            .any(|(_, joint)| !joint.data.contacts_enabled)
        {
            return true;
        }
        let (Some(l1), Some(l2)) = (
            self.multibody.rigid_body_link(b1),
            self.multibody.rigid_body_link(b2),
        ) else {
            return false;
        };
        l1.multibody == l2.multibody
            && (self
                .multibody
                .get_multibody(l1.multibody)
                .is_some_and(|mb| !mb.self_contacts_enabled())
                || self
                    .multibody
                    .joint_between(b1, b2)
                    .is_some_and(|(_, _, link)| !link.joint.data.contacts_enabled))
    }
}

/// Whether Rapier's own filters before the hook let the pair of `a` and `b`
/// through: two rigid bodies, joints (when the world's joint sets are
/// known), collision types, collision groups (as they are now: the
/// project's combined with the plan). Rapier's graph keeps an edge for a
/// pair they stop, which is no pair.
pub(crate) fn filters_pass(
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    joints: Option<Joints<'_>>,
    a: ColliderHandle,
    b: ColliderHandle,
) -> bool {
    let (Some(ca), Some(cb)) = (colliders.get(a), colliders.get(b)) else {
        return false;
    };
    let types = body_types(bodies, colliders, a, b);
    !same_body(colliders, a, b)
        && !joints.is_some_and(|j| j.keep_apart(colliders, a, b))
        && (ca.active_collision_types().test(types.0, types.1)
            || cb.active_collision_types().test(types.0, types.1))
        && ca.collision_groups().test(cb.collision_groups())
}

/// Every collider Rapier pairs with `collider`.
pub(crate) fn partners_of(
    narrow_phase: &NarrowPhase,
    collider: ColliderHandle,
) -> impl Iterator<Item = ColliderHandle> + '_ {
    let other = move |a: ColliderHandle, b: ColliderHandle| if a == collider { b } else { a };
    narrow_phase
        .contact_pairs_with(collider)
        .map(move |p| other(p.collider1, p.collider2))
        .chain(
            narrow_phase
                .intersection_pairs_with(collider)
                .map(move |(a, b, _)| other(a, b)),
        )
}

/// How many colliders, bodies, contact-graph and intersection-graph nodes
/// and edges the world holds: what changes when the project removes, adds or
/// moves objects through Rapier, which the hooks do not watch unless the
/// rules reach them. A removed collider of a hooked pair leaves Rapier's
/// graphs (its node and its edges), so between two steps in which no body
/// is awake, an unchanged census means no hooked pair can have ended.
pub(crate) fn census(
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    narrow_phase: &NarrowPhase,
) -> Census {
    let (contacts, intersections) = (
        narrow_phase.contact_graph().raw_graph(),
        narrow_phase.intersection_graph().raw_graph(),
    );
    Census {
        colliders: colliders.len(),
        bodies: bodies.len(),
        contact_nodes: contacts.raw_nodes().len(),
        contact_edges: contacts.raw_edges().len(),
        intersection_nodes: intersections.raw_nodes().len(),
        intersection_edges: intersections.raw_edges().len(),
    }
}

/// What [`census`] counts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Census {
    colliders: usize,
    bodies: usize,
    contact_nodes: usize,
    contact_edges: usize,
    intersection_nodes: usize,
    intersection_edges: usize,
}
