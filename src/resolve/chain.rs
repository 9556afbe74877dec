//! A collider's chain as the stages read it: each node with its record and
//! its effective group (`docs/semantics.md`, "Terms", chain and effective group).

use super::super::rapier::prelude::{ColliderHandle, ColliderSet, RigidBodyHandle, RigidBodySet};
use smallvec::SmallVec;

use super::super::model::{Record, is_dynamic};
use super::super::{CollisionGroup, CollisionRuleSet, Node};

/// One node of a chain, with what the stages need of it.
#[derive(Clone, Copy)]
pub(super) struct Link<'a> {
    pub(super) node: Node,
    pub(super) record: Option<&'a Record>,
    /// The node's effective group (`docs/semantics.md`, "Terms").
    pub(super) group: CollisionGroup,
}

/// A body that stands for another in the chains: the new body of a piece
/// torn during a step stands for the body its source's rules are on, until
/// the hooks follow the tear (`hooks/tears.rs`).
pub(crate) type Alias<'a> = &'a dyn Fn(RigidBodyHandle) -> Option<RigidBodyHandle>;

/// Chains of up to this many nodes are resolved without allocating.
const INLINE_CHAIN: usize = 16;

pub(super) struct Chain<'a> {
    pub(super) links: SmallVec<[Link<'a>; INLINE_CHAIN]>,
    /// Whether the leaf collider's body is dynamic.
    pub(super) dynamic: bool,
    pub(super) any_specific: bool,
    pub(super) any_personal: bool,
}

impl CollisionRuleSet {
    /// The chain of collider `leaf` with each node's record and effective group.
    pub(super) fn chain<'a>(
        &'a self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        leaf: ColliderHandle,
        alias: Option<Alias<'_>>,
    ) -> Chain<'a> {
        let present = colliders.contains(leaf);
        // A node with no group at or above it counts as the colliding body's
        // default group, whatever its ancestors' types (`docs/semantics.md`,
        // "Terms", effective group): a parent map alone changes no pair.
        let fallback = default_group(bodies, colliders, Node::Collider(leaf));
        let mut links: SmallVec<[Link<'a>; INLINE_CHAIN]> = SmallVec::new();
        let mut node = Some(Node::Collider(leaf));
        while let Some(current) = node {
            links.push(Link {
                node: current,
                // A stale collider handle is a node with no rules.
                record: if present { self.record(current) } else { None },
                group: fallback,
            });
            node = self.hierarchy.next(bodies, colliders, current);
            if let (Some(alias), Some(Node::Body(body))) = (alias, node) {
                node = alias(body).map(Node::Body).or(node);
            }
        }
        // Effective groups: own group, else the nearest explicit one above,
        // else the fallback already stored. Walk from the root down.
        let mut above: Option<CollisionGroup> = None;
        let (mut any_specific, mut any_personal) = (false, false);
        for link in links.iter_mut().rev() {
            if let Some(record) = link.record {
                above = record.group.or(above);
                any_specific |= !record.specific.is_empty();
                any_personal |= record.personal.is_decided();
            }
            if let Some(group) = above {
                link.group = group;
            }
        }
        Chain {
            dynamic: fallback == CollisionGroup::DEFAULT_DYNAMIC,
            links,
            any_specific,
            any_personal,
        }
    }

    /// The effective group of `node` (`docs/semantics.md`, "Effective
    /// group"): its own group, else the nearest explicit group up its chain,
    /// else the default group of the colliding body, which is `node`'s own
    /// body (a collider's body, or the body itself), whatever the types of
    /// its ancestors. A node further up another collider's chain may count
    /// differently in that collider's pairs:
    /// [`explain`](Self::explain)'s `groups` tells what met in the table.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionGroup, CollisionRuleSet, RuleError};
    ///
    /// let mut bodies = RigidBodySet::new();
    /// let mut colliders = ColliderSet::new();
    /// let pelvis = bodies.insert(RigidBodyBuilder::dynamic());
    /// let thigh = bodies.insert(RigidBodyBuilder::dynamic());
    /// let leg = colliders.insert_with_parent(ColliderBuilder::capsule_y(0.3, 0.1), thigh, &mut bodies);
    /// let mut rules = CollisionRuleSet::default();
    /// assert_eq!(rules.effective_group(&bodies, &colliders, leg), CollisionGroup::DEFAULT_DYNAMIC);
    /// let ragdoll = rules.create_group();
    /// rules.set_group(pelvis, Some(ragdoll));
    /// rules.set_parent(thigh, pelvis)?;
    /// assert_eq!(rules.effective_group(&bodies, &colliders, leg), ragdoll);
    /// # Ok::<(), RuleError>(())
    /// ```
    #[must_use]
    pub fn effective_group(
        &self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        node: impl Into<Node>,
    ) -> CollisionGroup {
        let start = node.into();
        // An object Rapier has removed takes no part in any pair: like
        // `resolve`, read none of its rules (`docs/semantics.md`).
        let present = match start {
            Node::Collider(c) => colliders.contains(c),
            Node::Body(b) => bodies.contains(b),
        };
        let mut node = present.then_some(start);
        while let Some(current) = node {
            if let Some(group) = self.group(current) {
                return group;
            }
            node = self.hierarchy.next(bodies, colliders, current);
        }
        default_group(bodies, colliders, start)
    }
}

/// The default group of the body of `node` (`docs/semantics.md`,
/// "Terms": effective group).
#[inline]
fn default_group(bodies: &RigidBodySet, colliders: &ColliderSet, node: Node) -> CollisionGroup {
    CollisionGroup::default_for(is_dynamic(bodies, colliders, node))
}
