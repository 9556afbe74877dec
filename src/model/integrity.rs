//! The integrity check: what `CollisionRuleSet::validate` reports.

use hashbrown::HashMap;
use super::super::rapier::prelude::{ColliderSet, RigidBodyHandle, RigidBodySet};

use super::records::RecordId;
use super::super::{CollisionRuleSet, Node};

/// One thing wrong with a rule set, as [`CollisionRuleSet::validate`] finds it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Problem {
    /// A node carries rules but is not in the Rapier sets.
    DanglingNode(Node),
    /// `node`'s specific entry names `about`, which is not in the Rapier sets.
    DanglingEntry {
        /// The node whose record holds the entry.
        node: Node,
        /// The missing node it names.
        about: Node,
    },
    /// A parent link names a body that is not in the body set.
    DanglingParent {
        /// The child of the link.
        child: RigidBodyHandle,
        /// The parent of the link.
        parent: RigidBodyHandle,
    },
    /// Walking up from this body never reaches a root.
    Cycle(RigidBodyHandle),
    /// A live record no node uses, or whose user count (or the one user it
    /// names) is wrong.
    OrphanedRecord {
        /// The record's index.
        index: u32,
        /// The users the record counts.
        counted: u32,
        /// The nodes that use it.
        actual: u32,
    },
    /// The records the set lists as naming a node disagree with the records.
    NamedCount(Node),
}

impl CollisionRuleSet {
    /// Checks the rule set against the Rapier sets it belongs to: every node
    /// with rules, every subject of a specific entry and every body of the
    /// parent map exists; the parent map has no cycle; every record is used
    /// by exactly the nodes it counts. Returns every problem found.
    ///
    /// A rule set kept by [`RuleHooks`](super::super::RuleHooks) is clean after
    /// every step; one edited by hand while objects are removed from the
    /// world is clean after [`remove_missing`](Self::remove_missing).
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, CollisionRuleSet, Node, Problem};
    ///
    /// let mut bodies = RigidBodySet::new();
    /// let colliders = ColliderSet::new();
    /// let a = bodies.insert(RigidBodyBuilder::dynamic());
    /// let gone = RigidBodyHandle::from_raw_parts(7, 0);
    /// let mut rules = CollisionRuleSet::default();
    /// rules.set_specific(a, gone, CollisionRule::NoPair);
    /// assert_eq!(
    ///     rules.validate(&bodies, &colliders),
    ///     Err(vec![Problem::DanglingEntry { node: Node::Body(a), about: Node::Body(gone) }]),
    /// );
    /// rules.remove_missing(&bodies, &colliders);
    /// assert_eq!(rules.validate(&bodies, &colliders), Ok(()));
    /// ```
    pub fn validate(
        &self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
    ) -> Result<(), Vec<Problem>> {
        let exists = |node: Node| match node {
            Node::Collider(h) => colliders.contains(h),
            Node::Body(h) => bodies.contains(h),
        };
        let mut problems = Vec::new();
        let mut users: HashMap<RecordId, (u32, Node)> = HashMap::new();
        let mut named: HashMap<Node, u32> = HashMap::new();
        for node in self.nodes() {
            if !exists(node) {
                problems.push(Problem::DanglingNode(node));
            }
            let id = self.record_id(node).expect("a listed node has a record");
            users.entry(id).or_insert((0, node)).0 += 1;
        }
        for (id, record) in self.records.iter_with_ids() {
            let (actual, holder) = users
                .get(&id)
                .map_or((0, None), |&(n, node)| (n, Some(node)));
            // The one user a record names is the node using it.
            let one_user = (actual == 1).then_some(holder).flatten();
            if actual != record.users() || record.only_user != one_user {
                problems.push(Problem::OrphanedRecord {
                    index: id.index(),
                    counted: record.users(),
                    actual,
                });
            }
            for &about in record.specific.keys() {
                *named.entry(about).or_default() += 1;
                if !self.named.get(&about).is_some_and(|namers| namers.contains(id)) {
                    problems.push(Problem::NamedCount(about));
                }
                if !exists(about) {
                    if let Some(node) = holder {
                        problems.push(Problem::DanglingEntry { node, about });
                    }
                }
            }
        }
        for node in named.keys().chain(self.named_nodes()) {
            if self.named_count(*node) != named.get(node).copied().unwrap_or(0) {
                problems.push(Problem::NamedCount(*node));
            }
        }
        problems.dedup();
        for (child, parent) in self.parents() {
            if !bodies.contains(child) || !bodies.contains(parent) {
                problems.push(Problem::DanglingParent { child, parent });
            }
            let mut steps = 0;
            let mut up = Some(child);
            while let Some(body) = up {
                steps += 1;
                if steps > self.parents().count() + 1 {
                    problems.push(Problem::Cycle(child));
                    break;
                }
                up = self.parent(body);
            }
        }
        if problems.is_empty() {
            Ok(())
        } else {
            Err(problems)
        }
    }
}
