//! A native collider's class: the two facts that decide its pairs with
//! every other native collider, its effective group and whether its body
//! is dynamic.

use super::super::rapier::prelude::*;

use super::super::{CollisionGroup, CollisionRuleSet, Node};

/// The facts that decide a native collider's pairs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct Class {
    pub(crate) group: CollisionGroup,
    pub(crate) dynamic: bool,
}

impl Class {
    /// The class of a collider no rule reaches.
    pub(crate) fn unreached(dynamic: bool) -> Class {
        let group = if dynamic {
            CollisionGroup::DEFAULT_DYNAMIC
        } else {
            CollisionGroup::DEFAULT_KINEMATIC
        };
        Class { group, dynamic }
    }
}

/// The class of collider `leaf`, or `None` if its chain carries a personal
/// rule or mixes effective groups.
///
/// A node's effective group is the first explicit group at or above it,
/// else the colliding body's default group (`docs/semantics.md`, "Effective
/// group"), so the chain's groups are its explicit ones, plus that default
/// when the root has none: a chain with no explicit group is one class, the
/// collider's own body's, whatever its ancestors' types.
pub(super) fn native_class(
    rules: &CollisionRuleSet,
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    leaf: ColliderHandle,
    dynamic: bool,
) -> Option<Class> {
    let mut explicit: Option<CollisionGroup> = None;
    let mut root_grouped = false;
    let mut node = Some(Node::Collider(leaf));
    while let Some(current) = node {
        let record = rules.record(current);
        if record.is_some_and(|r| r.personal.is_decided()) {
            return None;
        }
        let own = record.and_then(|r| r.group);
        if let Some(group) = own {
            if explicit.is_some_and(|g| g != group) {
                return None;
            }
            explicit = Some(group);
        }
        root_grouped = own.is_some();
        node = rules.hierarchy.next(bodies, colliders, current);
    }
    let fallback = Class::unreached(dynamic).group;
    let group = match explicit {
        Some(group) if !root_grouped && group != fallback => return None,
        Some(group) => group,
        None => fallback,
    };
    Some(Class { group, dynamic })
}
