//! The change log: what the edits since the hooks last looked touched.

use super::super::rapier::prelude::RigidBodyHandle;

use super::records::RecordId;
use super::super::{CollisionRuleSet, Node};

/// What the edits since the last [`CollisionRuleSet::take_changes`] touched,
/// for the hooks' `OnChange` policy.
#[derive(Clone, Debug, Default)]
pub(crate) struct Changes {
    /// An edit that can affect any pair (the group table, the default rule).
    pub(crate) everything: bool,
    /// Bodies whose link in the parent map changed: the chains of the
    /// colliders under them changed, and with them the sides of the entries
    /// that name a node of their old or new chains.
    rechained: Vec<RigidBodyHandle>,
    records: Vec<RecordId>,
    nodes: Vec<Node>,
    /// Nodes an entry edit named as its subject: watched, but their own
    /// colliders' plans do not change (the entry's owner, or the entry
    /// alone, is logged too).
    subjects: Vec<Node>,
    /// Entries edited on a record its owner alone uses, which held entries
    /// before and after the edit: `(owner, subject)`. The owner's other
    /// rules stand, so the entry alone is decided again (a turret's record
    /// names every live ball: its other entries are not read).
    entries: Vec<(Node, Node)>,
}

/// Past this many remembered edits, the log gives up and says "everything".
const CHANGE_LOG_LIMIT: usize = 4096;

impl Changes {
    #[inline]
    pub(crate) fn is_empty(&self) -> bool {
        !self.everything
            && self.records.is_empty()
            && self.nodes.is_empty()
            && self.subjects.is_empty()
            && self.entries.is_empty()
            && self.rechained.is_empty()
    }

    /// The bodies whose link in the parent map changed (see the field).
    pub(crate) fn rechained(&self) -> &[RigidBodyHandle] {
        &self.rechained
    }

    pub(super) fn rechain(&mut self, child: RigidBodyHandle) {
        if !self.everything {
            self.rechained.push(child);
            self.cap();
        }
    }

    /// The subjects of entry edits (see the field).
    pub(crate) fn subjects(&self) -> &[Node] {
        &self.subjects
    }

    /// The entries edited alone (see the field).
    pub(crate) fn entries(&self) -> &[(Node, Node)] {
        &self.entries
    }

    pub(super) fn entry(&mut self, owner: Node, subject: Node) {
        if !self.everything {
            self.entries.push((owner, subject));
            self.cap();
        }
    }

    pub(super) fn subject(&mut self, node: Node) {
        if !self.everything {
            self.subjects.push(node);
            self.cap();
        }
    }

    pub(super) fn node(&mut self, node: Node) {
        if !self.everything {
            self.nodes.push(node);
            self.cap();
        }
    }

    pub(super) fn record(&mut self, id: RecordId) {
        if !self.everything {
            self.records.push(id);
            self.cap();
        }
    }

    pub(crate) fn everything(&mut self) {
        self.everything = true;
        self.records = Vec::new();
        self.nodes = Vec::new();
        self.subjects = Vec::new();
        self.entries = Vec::new();
        self.rechained = Vec::new();
    }

    fn cap(&mut self) {
        let logged = self.records.len() + self.nodes.len() + self.subjects.len();
        if logged + self.entries.len() + self.rechained.len() > CHANGE_LOG_LIMIT {
            self.everything();
        }
    }
}


/// The change log, which the hooks read before each step.
impl CollisionRuleSet {
    /// Logs "everything changed": hooks that receive this rule set whole
    /// (one put in place of another) recalculate and plan all.
    pub(crate) fn mark_all_changed(&mut self) {
        self.changes.everything();
    }

    /// Whether anything was edited since the last [`take_changes`](Self::take_changes).
    #[inline]
    pub(crate) fn has_changes(&self) -> bool {
        !self.changes.is_empty()
    }

    /// The edits logged since the last call, and a fresh log.
    pub(crate) fn take_changes(&mut self) -> Changes {
        std::mem::take(&mut self.changes)
    }

    /// The nodes an edit log touched: logged nodes and every user of a
    /// logged record. `None` when the log says "everything".
    pub(crate) fn touched_nodes(&self, changes: &Changes) -> Option<Vec<Node>> {
        if changes.everything {
            return None;
        }
        let mut nodes = changes.nodes.clone();
        // Only records shared when they were edited are logged (a record
        // with one user is only that user's, which the log holds): they
        // send us looking for their users.
        if !changes.records.is_empty() {
            nodes.extend(self.nodes().filter(|&node| {
                self.record_id(node)
                    .is_some_and(|id| changes.records.contains(&id))
            }));
        }
        Some(nodes)
    }

    /// Every node the rules name: nodes with a record, subjects of specific
    /// entries, and bodies of the parent map; in a fixed order.
    pub(crate) fn ruled_nodes(&self) -> Vec<Node> {
        let mut nodes: Vec<Node> = self.nodes().chain(self.named.keys().copied()).collect();
        for (child, parent) in self.hierarchy.links() {
            nodes.extend([Node::Body(child), Node::Body(parent)]);
        }
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }

}
