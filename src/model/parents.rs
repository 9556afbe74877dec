//! The parent map's verbs: `set_parent` refuses cycles and changes nothing
//! when it does.

use super::super::rapier::prelude::RigidBodyHandle;

use super::super::{CollisionRuleSet, Node, RuleError};

/// The parent map.
impl CollisionRuleSet {
    /// Makes `parent` the parent of `child` in the crate's parent map,
    /// replacing any earlier parent. A body as its own parent, a parent
    /// that already lies below `child`, or a handle of an object the rule
    /// set knows to be removed ([`RuleError::Removed`]) is refused and
    /// changes nothing. The rule set learns of a removal when the hooks
    /// step: until then a body just removed through Rapier is taken, and
    /// its link dropped at the next step (`docs/semantics.md`, "Handles of
    /// removed objects"; [`validate`](Self::validate) reports it before).
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
    /// assert_eq!(rules.parent(thigh), Some(pelvis));
    /// assert_eq!(rules.set_parent(thigh, thigh), Err(RuleError::SelfParent { body: thigh }));
    /// rules.remove_parent(thigh);
    /// assert_eq!(rules.parent(thigh), None);
    /// # Ok::<(), RuleError>(())
    /// ```
    pub fn set_parent(
        &mut self,
        child: RigidBodyHandle,
        parent: RigidBodyHandle,
    ) -> Result<(), RuleError> {
        for body in [child, parent] {
            if self.is_removed(Node::Body(body)) {
                return Err(RuleError::Removed {
                    node: Node::Body(body),
                });
            }
        }
        let former = self.hierarchy.parent(child);
        self.hierarchy.set_parent(child, parent)?;
        self.changes.rechain(child);
        self.changes.node(Node::Body(child));
        // The former parent lost the colliders under `child`.
        if let Some(former) = former.filter(|&f| f != parent) {
            self.changes.node(Node::Body(former));
        }
        // Logged too, so that a parent already removed is noticed.
        self.changes.node(Node::Body(parent));
        Ok(())
    }

    /// Makes `child` a root again; returns its former parent.
    pub fn remove_parent(&mut self, child: RigidBodyHandle) -> Option<RigidBodyHandle> {
        let parent = self.hierarchy.remove_parent(child)?;
        self.changes.rechain(child);
        self.changes.node(Node::Body(child));
        self.changes.node(Node::Body(parent));
        Some(parent)
    }

    /// The parent of `child` in the crate's parent map.
    #[must_use]
    pub fn parent(&self, child: RigidBodyHandle) -> Option<RigidBodyHandle> {
        self.hierarchy.parent(child)
    }

    /// Every link of the parent map as `(child, parent)`, in no particular order.
    pub fn parents(&self) -> impl Iterator<Item = (RigidBodyHandle, RigidBodyHandle)> + '_ {
        self.hierarchy.links()
    }
}
