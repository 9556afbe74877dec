//! Every refusal of the rule set's editing verbs.

use super::rapier::prelude::RigidBodyHandle;

use super::Node;

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
    #[error("body {body:?} cannot be its own parent")]
    SelfParent {
        /// The body.
        body: RigidBodyHandle,
    },
    /// The parent is already a descendant of the child.
    #[error("making {parent:?} the parent of {child:?} would close a cycle")]
    Cycle {
        /// The body that was to get a parent.
        child: RigidBodyHandle,
        /// The body that was to become its parent, a descendant of `child`.
        parent: RigidBodyHandle,
    },
    /// The handle names an object Rapier has removed: the rule set has
    /// forgotten it (the hooks do so for removed objects the rules reached)
    /// or has seen a newer object in the same slot.
    #[error("{node:?} names a removed object")]
    Removed {
        /// The dead handle.
        node: Node,
    },
}
