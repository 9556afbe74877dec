//! The records of rules that nodes carry, in an arena with a free list,
//! and how nodes attach to them, share them and let them go.

use hashbrown::HashMap;
use hashbrown::hash_map::Entry;

use super::super::{CollisionGroup, CollisionRule, CollisionRuleSet, Node, OneWay};
use super::SmallSet;

/// The rules one node carries. Several nodes may share one record.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Record {
    pub(crate) personal: CollisionRule,
    pub(crate) group: Option<CollisionGroup>,
    /// Never holds a `Defer` value: an explicit `Defer` is stored as no entry.
    pub(crate) specific: HashMap<Node, CollisionRule>,
    /// The node's colliders are a one-way surface.
    pub(crate) one_way: Option<OneWay>,
    /// How many nodes use this record; a record nobody uses is freed at once.
    pub(super) users: u32,
    /// The node using it while it has one user (most records): the holder
    /// of its entries, found without a walk of the records.
    pub(super) only_user: Option<Node>,
}

impl Record {
    pub(crate) fn users(&self) -> u32 {
        self.users
    }

    pub(super) fn is_empty(&self) -> bool {
        self.personal == CollisionRule::Defer
            && self.group.is_none()
            && self.specific.is_empty()
            && self.one_way.is_none()
    }
}

/// The index of a record in [`Records`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct RecordId(u32);

impl RecordId {
    pub(crate) fn index(self) -> u32 {
        self.0
    }
}

/// The records, in an arena with a free list.
#[derive(Clone, Debug, Default)]
pub(crate) struct Records {
    slots: Vec<Option<Record>>,
    free: Vec<u32>,
}

impl Records {
    fn insert(&mut self, record: Record) -> RecordId {
        match self.free.pop() {
            Some(index) => {
                self.slots[index as usize] = Some(record);
                RecordId(index)
            }
            None => {
                self.slots.push(Some(record));
                RecordId(self.slots.len() as u32 - 1)
            }
        }
    }

    #[inline]
    pub(crate) fn get(&self, id: RecordId) -> &Record {
        // OK since a node's RecordId always names a live record: records are
        // freed only when their last user lets go.
        self.slots[id.0 as usize]
            .as_ref()
            .expect("a node names a freed record")
    }

    pub(super) fn get_mut(&mut self, id: RecordId) -> &mut Record {
        self.slots[id.0 as usize]
            .as_mut()
            .expect("a node names a freed record")
    }

    /// Lets one user go; returns the record if that was its last user.
    fn release(&mut self, id: RecordId) -> Option<Record> {
        let record = self.get_mut(id);
        record.users -= 1;
        if record.users > 0 {
            return None;
        }
        self.free.push(id.0);
        self.slots[id.0 as usize].take()
    }

    pub(crate) fn live(&self) -> impl Iterator<Item = &Record> + '_ {
        self.slots.iter().flatten()
    }

    pub(crate) fn iter_with_ids(&self) -> impl Iterator<Item = (RecordId, &Record)> + '_ {
        self.slots
            .iter()
            .enumerate()
            .filter_map(|(i, slot)| slot.as_ref().map(|r| (RecordId(i as u32), r)))
    }
}

/// Records and the nodes that use them.
impl CollisionRuleSet {
    #[inline]
    pub(crate) fn record_id(&self, node: Node) -> Option<RecordId> {
        match node {
            Node::Collider(handle) => self.collider_records.get(handle).copied(),
            Node::Body(handle) => self.body_records.get(handle).copied(),
        }
    }

    #[inline]
    pub(crate) fn record(&self, node: Node) -> Option<&Record> {
        self.record_id(node).map(|id| self.records.get(id))
    }

    /// Whether `node` names an object Rapier has removed, as far as this set
    /// can tell: it forgot the object as removed, or has seen a newer object
    /// in the same slot (`docs/semantics.md`, "Handles of removed objects").
    pub(crate) fn is_removed(&self, node: Node) -> bool {
        self.removed.holds(node)
            || match node {
                Node::Collider(handle) => self.collider_records.is_superseded(handle),
                Node::Body(handle) => {
                    self.body_records.is_superseded(handle) || self.hierarchy.is_superseded(handle)
                }
            }
    }

    /// The record of `node`, created empty if it has none; `None` for a
    /// handle of a removed object (edits through it are ignored).
    pub(super) fn record_mut(&mut self, node: Node) -> Option<&mut Record> {
        if self.is_removed(node) {
            return None;
        }
        let id = match self.record_id(node) {
            Some(id) => id,
            None => {
                let id = self.records.insert(Record {
                    users: 1,
                    only_user: Some(node),
                    ..Record::default()
                });
                self.attach(node, id);
                // A node that starts carrying rules is an edit of its own.
                self.changes.node(node);
                id
            }
        };
        Some(self.records.get_mut(id))
    }

    /// Makes `node` use record `id`, letting go of the record its slot held
    /// before (its own, or a removed object's).
    pub(super) fn attach(&mut self, node: Node, id: RecordId) {
        let previous = match node {
            Node::Collider(handle) => self.collider_records.insert(handle, id),
            Node::Body(handle) => self.body_records.insert(handle, id),
        };
        if let Some(previous) = previous {
            self.endings_leave(node, previous);
            self.release(previous);
        }
    }

    /// Lets one user of record `id` go; a freed record's entries no longer
    /// name anyone. The nodes its entries name lose their entries with that
    /// user: they are logged as subjects, watched (the plan forgets the
    /// decisions of the entries that ended through their owners).
    fn release(&mut self, id: RecordId) {
        let subjects: Vec<Node> = self.records.get(id).specific.keys().copied().collect();
        for subject in subjects {
            self.changes.subject(subject);
        }
        if let Some(freed) = self.records.release(id) {
            for other in freed.specific.keys() {
                self.unname(*other, id);
            }
        } else if self.records.get(id).users == 1 {
            // A shared record down to one user (rare: the one walk of the
            // records left, for a record that was shared).
            let user = self.nodes().find(|&n| self.record_id(n) == Some(id));
            self.records.get_mut(id).only_user = user;
        }
    }

    /// Notes that record `id` holds an entry about `node`.
    pub(super) fn name(&mut self, node: Node, id: RecordId) {
        match self.named.entry(node) {
            Entry::Occupied(mut namers) => namers.get_mut().insert(id),
            Entry::Vacant(place) => {
                place.insert(SmallSet::One(id));
            }
        }
    }

    /// Notes that record `id` no longer holds an entry about `node`.
    pub(super) fn unname(&mut self, node: Node, id: RecordId) {
        if self.named.get_mut(&node).is_some_and(|namers| namers.remove(id)) {
            self.named.remove(&node);
        }
    }

    /// Logs the edit of record `id`'s entry about `other`, which is gone:
    /// as an edit of the entry alone where one node uses the record and it
    /// still holds entries (see `touch_entry`), else as an edit of the
    /// record's users, looked up when the log is read.
    pub(super) fn touch_users(&mut self, id: RecordId, other: Node) {
        let record = self.records.get(id);
        match record.only_user {
            Some(user) if !record.specific.is_empty() => self.changes.entry(user, other),
            Some(user) => self.changes.node(user),
            None => self.changes.record(id),
        }
    }

    /// Whether any specific entry names `node`.
    pub(crate) fn is_named(&self, node: Node) -> bool {
        self.named.contains_key(&node)
    }

    /// Whether a specific entry names `node` or `node` holds one: entries
    /// reach the pairs of the colliders under it.
    pub(crate) fn in_entries(&self, node: Node) -> bool {
        self.is_named(node) || self.record(node).is_some_and(|r| !r.specific.is_empty())
    }

    /// Whether the rules say anything of `node`: a record with rules, an
    /// entry about it, or a link of the parent map.
    pub(crate) fn holds_rules_about(&self, node: Node) -> bool {
        self.record(node).is_some_and(|r| !r.is_empty())
            || self.is_named(node)
            || matches!(node, Node::Body(body) if self.in_hierarchy(body))
    }

    /// The nodes whose records hold an entry about `node`, with its rule
    /// (a walk of the nodes with records: for splits, not per step).
    pub(crate) fn entries_about(&self, node: Node) -> impl Iterator<Item = (Node, CollisionRule)> + '_ {
        let namers = self.named.get(&node);
        self.nodes().filter_map(move |n| {
            let id = self.record_id(n).filter(|&id| namers.is_some_and(|s| s.contains(id)))?;
            Some((n, *self.records.get(id).specific.get(&node)?))
        })
    }

    pub(crate) fn named_nodes(&self) -> impl Iterator<Item = &Node> + '_ {
        self.named.keys()
    }

    pub(crate) fn named_count(&self, node: Node) -> u32 {
        self.named.get(&node).map_or(0, |namers| namers.len() as u32)
    }

    /// Lets go of `node`'s record.
    pub(super) fn detach(&mut self, node: Node) {
        let previous = match node {
            Node::Collider(handle) => self.collider_records.remove(handle),
            Node::Body(handle) => self.body_records.remove(handle),
        };
        if let Some(previous) = previous {
            self.endings_leave(node, previous);
            self.release(previous);
        }
    }

    /// Logs an edit of `node`'s rules (and so of every node sharing its record).
    pub(super) fn touch(&mut self, node: Node) {
        self.changes.node(node);
        // A record shared now: its other users are looked up when the log
        // is read, even if some of them have left it by then.
        if let Some(id) = self.record_id(node) {
            if self.records.get(id).users > 1 {
                self.changes.record(id);
            }
        }
    }

    /// Logs an edit of `node`'s entry about `other` (`held_entries`: its
    /// record held entries before the edit): the entry alone where nothing
    /// else of the node's rules changed, which needs a record of its own
    /// that holds entries before and after (whether entries reach a node's
    /// colliders decides whether a personal rule may); else an edit of the
    /// node's rules, tidied.
    pub(super) fn touch_entry(&mut self, node: Node, other: Node, held_entries: bool) {
        let alone = self.record(node).is_some_and(|r| r.users == 1 && !r.specific.is_empty());
        if held_entries && alone {
            self.changes.entry(node, other);
        } else {
            self.tidy(node);
        }
    }

    /// Logs an edit of `node`'s rules and drops its record if it holds
    /// nothing and nobody else uses it, so that a node whose rules were all
    /// cleared costs nothing.
    pub(super) fn tidy(&mut self, node: Node) {
        self.touch(node);
        if let Some(id) = self.record_id(node) {
            self.free_if_empty(id);
        }
    }

    /// Drops record `id` if it holds nothing and one node alone uses it
    /// (`docs/semantics.md`, "Clearing").
    pub(super) fn free_if_empty(&mut self, id: RecordId) {
        let record = self.records.get(id);
        if let (1, true, Some(user)) = (record.users, record.is_empty(), record.only_user) {
            self.detach(user);
        }
    }

}
