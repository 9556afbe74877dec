//! Every refusal of the rule set's editing verbs.

use super::super::rapier::prelude::RigidBodyHandle;

use super::super::Node;

/// Why an edit was refused. A refused edit changes nothing.
///
/// ```
/// use rapier3d::prelude::*;
/// use rapier_collision_rules::{CollisionRuleSet, RuleError};
///
/// let mut bodies = RigidBodySet::new();
/// let pelvis = bodies.insert(RigidBodyBuilder::dynamic());
/// let thigh = bodies.insert(RigidBodyBuilder::dynamic());
/// let mut rules = CollisionRuleSet::default();
/// rules.set_parent(thigh, pelvis)?;
/// assert_eq!(
///     rules.set_parent(pelvis, thigh),
///     Err(RuleError::Cycle { child: pelvis, parent: thigh }),
/// );
/// assert_eq!(rules.parent(pelvis), None, "the refused edit changed nothing");
/// # Ok::<(), RuleError>(())
/// ```
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum RuleError {
    /// A body was given itself as its parent.
    #[error("{} cannot be its own parent", Named(Node::Body(*body)))]
    SelfParent {
        /// The body.
        body: RigidBodyHandle,
    },
    /// The parent is already a descendant of the child.
    #[error(
        "making {parent} the parent of {child} would close a cycle: {parent} is already below \
         {child}; call remove_parent on {parent} (or a body between them) first",
        parent = Named(Node::Body(*parent)),
        child = Named(Node::Body(*child))
    )]
    Cycle {
        /// The body that was to get a parent.
        child: RigidBodyHandle,
        /// The body that was to become its parent, a descendant of `child`.
        parent: RigidBodyHandle,
    },
    /// The handle names an object Rapier has removed: the rule set has
    /// forgotten it (the hooks do so for removed objects the rules reached)
    /// or has seen a newer object in the same slot.
    #[error(
        "{} names an object Rapier has removed (its rules are gone; a new object in \
         its slot has another handle)",
        Named(*node)
    )]
    Removed {
        /// The dead handle.
        node: Node,
    },
}

/// A node as a user names it in a message: "body 3", "collider 5", with the
/// generation of a reused slot ("body 3, generation 2"). `Debug` keeps the
/// handles.
pub(crate) struct Named(pub(crate) Node);

impl std::fmt::Display for Named {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (what, (index, generation)) = match self.0 {
            Node::Body(handle) => ("body", handle.into_raw_parts()),
            Node::Collider(handle) => ("collider", handle.into_raw_parts()),
        };
        write!(f, "{what} {index}")?;
        if generation > 0 {
            write!(f, ", generation {generation}")?;
        }
        Ok(())
    }
}
