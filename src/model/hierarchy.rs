//! The parent map between rigid bodies, chains, and the cycle check.

use super::super::rapier::prelude::{ColliderSet, RigidBodyHandle, RigidBodySet};

use hashbrown::HashMap;

use super::node::HandleMap;
use super::super::{Node, RuleError};

/// The crate's own parent map between rigid bodies. Invariant: it has no
/// cycle (every `set` checks), so walking up always ends.
#[derive(Clone, Debug, Default)]
pub(crate) struct Hierarchy {
    parents: HandleMap<RigidBodyHandle, RigidBodyHandle>,
    /// How many children each parent has.
    children: HashMap<RigidBodyHandle, u32>,
}

impl Hierarchy {
    #[inline]
    pub(crate) fn parent(&self, child: RigidBodyHandle) -> Option<RigidBodyHandle> {
        self.parents.get(child).copied()
    }

    /// Whether the map has seen a newer body in `body`'s slot.
    pub(crate) fn is_superseded(&self, body: RigidBodyHandle) -> bool {
        self.parents.is_superseded(body)
    }

    /// The newer body the map holds in `body`'s slot, if any.
    pub(crate) fn newer_than(&self, body: RigidBodyHandle) -> Option<RigidBodyHandle> {
        self.parents.newer_than(body)
    }

    pub(crate) fn set_parent(
        &mut self,
        child: RigidBodyHandle,
        parent: RigidBodyHandle,
    ) -> Result<(), RuleError> {
        if child == parent {
            return Err(RuleError::SelfParent { body: child });
        }
        if self.parents.is_superseded(child) {
            return Err(RuleError::Removed {
                node: Node::Body(child),
            });
        }
        if self.is_ancestor_or_self(child, parent) {
            return Err(RuleError::Cycle { child, parent });
        }
        if let Some(former) = self.parents.insert(child, parent) {
            self.unlink(former);
        }
        *self.children.entry(parent).or_default() += 1;
        Ok(())
    }

    pub(crate) fn remove_parent(&mut self, child: RigidBodyHandle) -> Option<RigidBodyHandle> {
        let parent = self.parents.remove(child)?;
        self.unlink(parent);
        Some(parent)
    }

    fn unlink(&mut self, parent: RigidBodyHandle) {
        if let Some(count) = self.children.get_mut(&parent) {
            *count -= 1;
            if *count == 0 {
                self.children.remove(&parent);
            }
        }
    }

    /// Whether `body` is the parent of some body.
    pub(crate) fn is_parent(&self, body: RigidBodyHandle) -> bool {
        self.children.contains_key(&body)
    }

    /// Removes every link that names `body`: its own, and its children's
    /// (they become roots).
    pub(crate) fn forget(&mut self, body: RigidBodyHandle) {
        self.remove_parent(body);
        if self.children.remove(&body).is_some() {
            self.parents.retain(|_, parent| *parent != body);
        }
    }

    /// Whether `ancestor` is `body` or lies above it.
    pub(crate) fn is_ancestor_or_self(
        &self,
        ancestor: RigidBodyHandle,
        body: RigidBodyHandle,
    ) -> bool {
        let mut current = Some(body);
        while let Some(b) = current {
            if b == ancestor {
                return true;
            }
            current = self.parent(b);
        }
        false
    }

    /// Every link, child first.
    pub(crate) fn links(&self) -> impl Iterator<Item = (RigidBodyHandle, RigidBodyHandle)> + '_ {
        self.parents.iter().map(|(child, parent)| (child, *parent))
    }

    /// The bodies below `root` in the parent map (not `root` itself).
    pub(crate) fn descendants(&self, root: RigidBodyHandle) -> Vec<RigidBodyHandle> {
        self.parents
            .iter()
            .map(|(child, _)| child)
            .filter(|&child| child != root && self.is_ancestor_or_self(root, child))
            .collect()
    }

    /// The node above `node` in its chain: a collider's body, or a body's
    /// parent. Handles missing from the Rapier sets end the chain.
    #[inline]
    pub(crate) fn next(
        &self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        node: Node,
    ) -> Option<Node> {
        let body = match node {
            Node::Collider(handle) => colliders.get(handle)?.parent()?,
            Node::Body(handle) => self.parent(handle)?,
        };
        bodies.contains(body).then_some(Node::Body(body))
    }

    /// `start` and every node above it, leaf first.
    pub(crate) fn chain<'a>(
        &'a self,
        bodies: &'a RigidBodySet,
        colliders: &'a ColliderSet,
        start: Node,
    ) -> impl Iterator<Item = Node> + 'a {
        std::iter::successors(Some(start), move |&node| self.next(bodies, colliders, node))
    }
}
