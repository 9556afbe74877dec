//! `CollisionRuleSet`: every rule of one world and every verb that edits
//! them, each keeping the set's invariants.

use hashbrown::HashMap;
use super::rapier::prelude::{ColliderHandle, ColliderSet, RigidBodyHandle, RigidBodySet};

use super::group::GroupTable;
use super::hierarchy::Hierarchy;
use super::node::HandleMap;
use super::tombstones::Tombstones;
use super::{CollisionGroup, CollisionRule, Node, RuleError};

/// The rules one node carries. Several nodes may share one record.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Record {
    pub(crate) personal: CollisionRule,
    pub(crate) group: Option<CollisionGroup>,
    /// Never holds a `Defer` value: an explicit `Defer` is stored as no entry.
    pub(crate) specific: HashMap<Node, CollisionRule>,
    /// How many nodes use this record; a record nobody uses is freed at once.
    users: u32,
}

impl Record {
    pub(crate) fn users(&self) -> u32 {
        self.users
    }

    fn is_empty(&self) -> bool {
        self.personal == CollisionRule::Defer && self.group.is_none() && self.specific.is_empty()
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

    fn get_mut(&mut self, id: RecordId) -> &mut Record {
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

    fn live_mut(&mut self) -> impl Iterator<Item = &mut Record> + '_ {
        self.slots.iter_mut().flatten()
    }
}

/// What the edits since the last [`CollisionRuleSet::take_changes`] touched,
/// for the hooks' `OnChange` policy.
#[derive(Clone, Debug, Default)]
pub(crate) struct Changes {
    /// An edit that can affect any pair (the group table, the default rule).
    pub(crate) everything: bool,
    /// A link of the parent map changed: the colliders under a node changed.
    pub(crate) parents: bool,
    records: Vec<RecordId>,
    nodes: Vec<Node>,
}

/// Past this many remembered edits, the log gives up and says "everything".
const CHANGE_LOG_LIMIT: usize = 4096;

impl Changes {
    pub(crate) fn is_empty(&self) -> bool {
        !self.everything && self.records.is_empty() && self.nodes.is_empty()
    }

    fn node(&mut self, node: Node) {
        if !self.everything {
            self.nodes.push(node);
            self.cap();
        }
    }

    fn record(&mut self, id: RecordId) {
        if !self.everything {
            self.records.push(id);
            self.cap();
        }
    }

    pub(crate) fn everything(&mut self) {
        self.everything = true;
        self.records = Vec::new();
        self.nodes = Vec::new();
    }

    fn cap(&mut self) {
        if self.records.len() + self.nodes.len() > CHANGE_LOG_LIMIT {
            self.everything();
        }
    }
}

/// All collision rules of one world: the group table, the default rule, the
/// rules of each collider and rigid body, and the parent map between bodies.
///
/// Rules are decided per pair of colliders by [`resolve`](Self::resolve),
/// from the most specific stage to the most general (see the crate docs).
///
/// A rule set belongs to one world: its rules are keyed by that world's
/// handles. With the `serde` feature it is saved and loaded together with
/// the world's Rapier sets.
///
/// ```
/// use rapier3d::prelude::*;
/// use rapier_collision_rules::{CollisionRule, CollisionRuleSet};
///
/// let mut bodies = RigidBodySet::new();
/// let mut colliders = ColliderSet::new();
/// let ghost = bodies.insert(RigidBodyBuilder::dynamic());
/// let wall = bodies.insert(RigidBodyBuilder::fixed());
/// let g = colliders.insert_with_parent(ColliderBuilder::ball(0.5), ghost, &mut bodies);
/// let w = colliders.insert_with_parent(ColliderBuilder::cuboid(5.0, 5.0, 0.1), wall, &mut bodies);
///
/// let mut rules = CollisionRuleSet::default();
/// rules.set_personal(ghost, CollisionRule::NoResponse);
/// assert_eq!(rules.resolve(&bodies, &colliders, g, w), CollisionRule::NoResponse);
/// ```
#[derive(Clone, Debug)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(
        into = "super::snapshot::Snapshot",
        try_from = "super::snapshot::Snapshot"
    )
)]
pub struct CollisionRuleSet {
    pub(crate) groups: GroupTable,
    pub(crate) default_rule: CollisionRule,
    collider_records: HandleMap<ColliderHandle, RecordId>,
    body_records: HandleMap<RigidBodyHandle, RecordId>,
    pub(crate) records: Records,
    pub(crate) hierarchy: Hierarchy,
    changes: Changes,
    /// How many specific entries name each node (the planner asks).
    named: HashMap<Node, u32>,
    /// The handles forgotten as removed: every editing verb refuses them.
    removed: Tombstones,
}

impl Default for CollisionRuleSet {
    fn default() -> Self {
        CollisionRuleSet {
            groups: GroupTable::default(),
            default_rule: CollisionRule::Normal,
            collider_records: HandleMap::default(),
            body_records: HandleMap::default(),
            records: Records::default(),
            hierarchy: Hierarchy::default(),
            changes: Changes::default(),
            named: HashMap::new(),
            removed: Tombstones::default(),
        }
    }
}

/// Groups.
impl CollisionRuleSet {
    /// A new group, distinct from every other group of this set.
    pub fn create_group(&mut self) -> CollisionGroup {
        self.groups.create()
    }

    /// Sets the rule between two groups; the order of `a` and `b` does not
    /// matter, and `Defer` removes the entry.
    ///
    /// ```
    /// use rapier_collision_rules::{CollisionRule, CollisionRuleSet};
    ///
    /// let mut rules = CollisionRuleSet::default();
    /// let (player, debris) = (rules.create_group(), rules.create_group());
    /// rules.set_group_rule(player, debris, CollisionRule::NoPair);
    /// assert_eq!(rules.group_rule(debris, player), CollisionRule::NoPair);
    /// rules.remove_group_rule(debris, player);
    /// assert_eq!(rules.group_rule(player, debris), CollisionRule::Defer);
    /// ```
    ///
    /// # Panics
    ///
    /// If a group was not created by this rule set (nor is built in): a group
    /// of another rule set means nothing here.
    pub fn set_group_rule(&mut self, a: CollisionGroup, b: CollisionGroup, rule: CollisionRule) {
        self.check_groups(&[a, b]);
        self.groups.set(a, b, rule);
        self.changes.everything();
    }

    /// The rule between two groups, `Defer` where the table has no entry.
    #[must_use]
    pub fn group_rule(&self, a: CollisionGroup, b: CollisionGroup) -> CollisionRule {
        self.groups.get(a, b)
    }

    /// Removes the entry between two groups (the built-in kinematic entry too).
    pub fn remove_group_rule(&mut self, a: CollisionGroup, b: CollisionGroup) {
        self.groups.remove(a, b);
        self.changes.everything();
    }

    /// Each group of `set` gets `self_rule` with itself and `other_rule`
    /// with every other group of `set`.
    ///
    /// ```
    /// use rapier_collision_rules::{CollisionRule::*, CollisionRuleSet};
    ///
    /// let mut rules = CollisionRuleSet::default();
    /// let team = [rules.create_group(), rules.create_group()];
    /// rules.set_group_rules_in_set(&team, NoResponse, NoPair);
    /// assert_eq!(rules.group_rule(team[0], team[0]), NoResponse);
    /// assert_eq!(rules.group_rule(team[1], team[0]), NoPair);
    /// rules.remove_group_rules_in_set(&team);
    /// assert_eq!(rules.group_rule(team[1], team[1]), Defer);
    /// ```
    ///
    /// # Panics
    ///
    /// If a group was not created by this rule set (nor is built in): a group
    /// of another rule set means nothing here.
    pub fn set_group_rules_in_set(
        &mut self,
        set: &[CollisionGroup],
        self_rule: CollisionRule,
        other_rule: CollisionRule,
    ) {
        self.check_groups(set);
        self.groups.set_in_set(set, self_rule, other_rule);
        self.changes.everything();
    }

    /// Removes every entry between two groups of `set`, each with itself included.
    pub fn remove_group_rules_in_set(&mut self, set: &[CollisionGroup]) {
        self.groups.remove_in_set(set);
        self.changes.everything();
    }

    /// `group` gets `rule` with each group of `set` (with itself only if it
    /// is listed in `set`).
    ///
    /// ```
    /// use rapier_collision_rules::{CollisionRule::*, CollisionRuleSet};
    ///
    /// let mut rules = CollisionRuleSet::default();
    /// let ghost = rules.create_group();
    /// let walls = [rules.create_group(), rules.create_group()];
    /// rules.set_group_rules_with_set(ghost, &walls, NoResponse);
    /// assert_eq!(rules.group_rule(walls[1], ghost), NoResponse);
    /// rules.remove_group_rules_with_set(ghost, &walls[..1]);
    /// assert_eq!(rules.group_rule(walls[0], ghost), Defer);
    /// ```
    ///
    /// # Panics
    ///
    /// If a group was not created by this rule set (nor is built in): a group
    /// of another rule set means nothing here.
    pub fn set_group_rules_with_set(
        &mut self,
        group: CollisionGroup,
        set: &[CollisionGroup],
        rule: CollisionRule,
    ) {
        self.check_groups(&[group]);
        self.check_groups(set);
        self.groups.set_with_set(group, set, rule);
        self.changes.everything();
    }

    /// Removes the entries between `group` and each group of `set`.
    pub fn remove_group_rules_with_set(&mut self, group: CollisionGroup, set: &[CollisionGroup]) {
        self.groups.remove_with_set(group, set);
        self.changes.everything();
    }

    /// Every group of `a` gets `rule` with every group of `b`; pairs inside
    /// one set are left alone.
    ///
    /// ```
    /// use rapier_collision_rules::{CollisionRule::*, CollisionRuleSet};
    ///
    /// let mut rules = CollisionRuleSet::default();
    /// let red = [rules.create_group(), rules.create_group()];
    /// let blue = [rules.create_group()];
    /// rules.set_group_rules_between_sets(&red, &blue, NoContacts);
    /// assert_eq!(rules.group_rule(blue[0], red[1]), NoContacts);
    /// assert_eq!(rules.group_rule(red[0], red[1]), Defer);
    /// rules.remove_group_rules_between_sets(&red, &blue);
    /// assert_eq!(rules.group_rule(red[0], blue[0]), Defer);
    /// ```
    ///
    /// # Panics
    ///
    /// If a group was not created by this rule set (nor is built in): a group
    /// of another rule set means nothing here.
    pub fn set_group_rules_between_sets(
        &mut self,
        a: &[CollisionGroup],
        b: &[CollisionGroup],
        rule: CollisionRule,
    ) {
        self.check_groups(a);
        self.check_groups(b);
        self.groups.set_between_sets(a, b, rule);
        self.changes.everything();
    }

    /// Removes every entry between a group of `a` and a group of `b`.
    pub fn remove_group_rules_between_sets(&mut self, a: &[CollisionGroup], b: &[CollisionGroup]) {
        self.groups.remove_between_sets(a, b);
        self.changes.everything();
    }

    /// Every entry of the group table, each unordered pair once, in no
    /// particular order.
    pub fn group_rules(
        &self,
    ) -> impl Iterator<Item = (CollisionGroup, CollisionGroup, CollisionRule)> + '_ {
        self.groups.iter()
    }

    /// How many groups exist: the two built-in groups plus every created one.
    #[must_use]
    pub fn group_count(&self) -> u32 {
        self.groups.group_count()
    }

    /// Makes this set's group table and default rule those of `from`, and
    /// its groups at least `from`'s (a group created here beyond `from`'s
    /// count stays valid, its table entries do not). Nodes, entries and
    /// links are untouched. For one table shared by several worlds, each
    /// with its own rule set: groups created in `from` then mean the same
    /// in every copy. Nothing is logged when the table and the default rule
    /// were already `from`'s, so copying every frame costs no replanning.
    ///
    /// ```
    /// use rapier_collision_rules::{CollisionRule, CollisionRuleSet};
    ///
    /// let mut table = CollisionRuleSet::default();
    /// let (player, debris) = (table.create_group(), table.create_group());
    /// table.set_group_rule(player, debris, CollisionRule::NoPair);
    /// table.set_default_rule(CollisionRule::NoResponse);
    ///
    /// let mut world_rules = CollisionRuleSet::default();
    /// world_rules.copy_group_table(&table);
    /// assert_eq!(world_rules.group_rule(debris, player), CollisionRule::NoPair);
    /// assert_eq!(world_rules.default_rule(), CollisionRule::NoResponse);
    /// assert_eq!(world_rules.group_count(), table.group_count());
    /// ```
    pub fn copy_group_table(&mut self, from: &CollisionRuleSet) {
        let count = self.groups.group_count();
        let entries_changed = self.groups.copy_from(&from.groups, count);
        if entries_changed || self.default_rule != from.default_rule {
            self.default_rule = from.default_rule;
            self.changes.everything();
        }
    }
}

impl CollisionRuleSet {
    /// Refuses groups this rule set did not create: a caller bug.
    fn check_groups(&self, groups: &[CollisionGroup]) {
        let count = self.groups.group_count();
        for g in groups {
            assert!(
                g.id() < count,
                "{g:?} was not created by this rule set ({count} groups exist)"
            );
        }
    }
}

/// The world-wide default (stage 4).
impl CollisionRuleSet {
    /// The rule of a pair that no stage decides. `Defer` is allowed and is
    /// then what [`resolve`](Self::resolve) returns for such pairs.
    pub fn set_default_rule(&mut self, rule: CollisionRule) {
        self.default_rule = rule;
        self.changes.everything();
    }

    /// The rule of a pair that no stage decides; `Normal` unless changed.
    #[must_use]
    pub fn default_rule(&self) -> CollisionRule {
        self.default_rule
    }
}

/// The rules of each node and their sharing.
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
    fn record_mut(&mut self, node: Node) -> Option<&mut Record> {
        if self.is_removed(node) {
            return None;
        }
        let id = match self.record_id(node) {
            Some(id) => id,
            None => {
                let id = self.records.insert(Record {
                    users: 1,
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
    fn attach(&mut self, node: Node, id: RecordId) {
        let previous = match node {
            Node::Collider(handle) => self.collider_records.insert(handle, id),
            Node::Body(handle) => self.body_records.insert(handle, id),
        };
        if let Some(previous) = previous {
            self.release(previous);
        }
    }

    /// Lets one user of record `id` go; a freed record's entries no longer
    /// name anyone. The nodes its entries name lose their entries with that
    /// user (their side of an entry may no longer be the one to hook): they
    /// are logged as edited.
    fn release(&mut self, id: RecordId) {
        let subjects: Vec<Node> = self.records.get(id).specific.keys().copied().collect();
        for subject in subjects {
            self.changes.node(subject);
        }
        if let Some(freed) = self.records.release(id) {
            for other in freed.specific.keys() {
                self.unname(*other);
            }
        }
    }

    fn unname(&mut self, node: Node) {
        if let Some(count) = self.named.get_mut(&node) {
            *count -= 1;
            if *count == 0 {
                self.named.remove(&node);
            }
        }
    }

    /// Whether the rule set holds any specific entry.
    pub(crate) fn has_specific(&self) -> bool {
        !self.named.is_empty()
    }

    /// Whether any specific entry names `node`.
    pub(crate) fn is_named(&self, node: Node) -> bool {
        self.named.contains_key(&node)
    }

    pub(crate) fn named_nodes(&self) -> impl Iterator<Item = &Node> + '_ {
        self.named.keys()
    }

    pub(crate) fn named_count(&self, node: Node) -> u32 {
        self.named.get(&node).copied().unwrap_or(0)
    }

    /// Lets go of `node`'s record.
    fn detach(&mut self, node: Node) {
        let previous = match node {
            Node::Collider(handle) => self.collider_records.remove(handle),
            Node::Body(handle) => self.body_records.remove(handle),
        };
        if let Some(previous) = previous {
            self.release(previous);
        }
    }

    /// Logs an edit of `node`'s rules (and so of every node sharing its record).
    fn touch(&mut self, node: Node) {
        self.changes.node(node);
        // A record shared now: its other users are looked up when the log
        // is read, even if some of them have left it by then.
        if let Some(id) = self.record_id(node) {
            if self.records.get(id).users > 1 {
                self.changes.record(id);
            }
        }
    }

    /// Drops `node`'s record if it holds nothing and nobody else uses it,
    /// so that a node whose rules were all cleared costs nothing.
    fn tidy(&mut self, node: Node) {
        self.touch(node);
        if let Some(id) = self.record_id(node) {
            let record = self.records.get(id);
            if record.users == 1 && record.is_empty() {
                self.detach(node);
            }
        }
    }

    /// Puts `node` in `group` (`None`: no explicit group; the node then takes
    /// the nearest explicit group up its chain, or its body's default group).
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::CollisionRuleSet;
    ///
    /// let mut bodies = RigidBodySet::new();
    /// let body = bodies.insert(RigidBodyBuilder::dynamic());
    /// let mut rules = CollisionRuleSet::default();
    /// let players = rules.create_group();
    /// rules.set_group(body, Some(players));
    /// assert_eq!(rules.group(body), Some(players));
    /// ```
    ///
    /// # Panics
    ///
    /// If a group was not created by this rule set (nor is built in): a group
    /// of another rule set means nothing here.
    pub fn set_group(&mut self, node: impl Into<Node>, group: Option<CollisionGroup>) {
        self.check_groups(group.as_slice());
        let node = node.into();
        if (group.is_none() && self.record_id(node).is_none()) || self.is_removed(node) {
            return;
        }
        if let Some(record) = self.record_mut(node) {
            record.group = group;
        }
        self.tidy(node);
    }

    /// The node's own explicit group (not inherited, not a default).
    #[must_use]
    pub fn group(&self, node: impl Into<Node>) -> Option<CollisionGroup> {
        self.record(node.into()).and_then(|record| record.group)
    }

    /// The node's personal rule (stage 2); `Defer` clears it.
    pub fn set_personal(&mut self, node: impl Into<Node>, rule: CollisionRule) {
        let node = node.into();
        if (rule == CollisionRule::Defer && self.record_id(node).is_none()) || self.is_removed(node)
        {
            return;
        }
        if let Some(record) = self.record_mut(node) {
            record.personal = rule;
        }
        self.tidy(node);
    }

    /// The node's personal rule, `Defer` if it has none.
    #[must_use]
    pub fn personal(&self, node: impl Into<Node>) -> CollisionRule {
        self.record(node.into())
            .map_or(CollisionRule::Defer, |record| record.personal)
    }

    /// What `node` says about `other` (stage 1). `Defer` removes the entry.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, CollisionRuleSet};
    ///
    /// let mut bodies = RigidBodySet::new();
    /// let (a, b) = (bodies.insert(RigidBodyBuilder::dynamic()), bodies.insert(RigidBodyBuilder::dynamic()));
    /// let mut rules = CollisionRuleSet::default();
    /// rules.set_specific(a, b, CollisionRule::NoContacts);
    /// assert_eq!(rules.specific(a, b), CollisionRule::NoContacts);
    /// assert_eq!(rules.specific(b, a), CollisionRule::Defer, "each side has its own entry");
    /// rules.remove_specific(a, b);
    /// assert_eq!(rules.specific(a, b), CollisionRule::Defer);
    /// ```
    pub fn set_specific(
        &mut self,
        node: impl Into<Node>,
        other: impl Into<Node>,
        rule: CollisionRule,
    ) {
        let (node, other) = (node.into(), other.into());
        if rule == CollisionRule::Defer {
            self.remove_specific(node, other);
        } else if !self.is_removed(other) {
            // An entry about a removed object would name nothing.
            self.put_specific(node, other, rule);
        }
    }

    /// Stores an entry of `node` (not a removed object) about `other`. The
    /// loader stores a save's entries this way, whatever `other` is, so
    /// that a loaded rule set is the one saved.
    pub(crate) fn put_specific(&mut self, node: Node, other: Node, rule: CollisionRule) {
        if self.is_removed(node) {
            return;
        }
        if let Some(record) = self.record_mut(node) {
            if record.specific.insert(other, rule).is_none() {
                *self.named.entry(other).or_default() += 1;
            }
            self.touch(node);
            self.changes.node(other);
        }
    }

    /// What `node` says about `other`, `Defer` if nothing.
    #[must_use]
    pub fn specific(&self, node: impl Into<Node>, other: impl Into<Node>) -> CollisionRule {
        let other = other.into();
        self.record(node.into())
            .and_then(|record| record.specific.get(&other).copied())
            .unwrap_or(CollisionRule::Defer)
    }

    /// Removes what `node` says about `other`.
    pub fn remove_specific(&mut self, node: impl Into<Node>, other: impl Into<Node>) {
        let (node, other) = (node.into(), other.into());
        if let Some(id) = self.record_id(node) {
            if self.records.get_mut(id).specific.remove(&other).is_some() {
                self.unname(other);
            }
            self.tidy(node);
            self.changes.node(other);
        }
    }

    /// From now on `to` uses `from`'s rule record: its group, personal rule
    /// and specific entries, and any later edit through either node is seen
    /// by both. `to`'s own rules are dropped.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, CollisionRuleSet};
    ///
    /// let mut bodies = RigidBodySet::new();
    /// let (a, b) = (bodies.insert(RigidBodyBuilder::dynamic()), bodies.insert(RigidBodyBuilder::dynamic()));
    /// let mut rules = CollisionRuleSet::default();
    /// rules.share_rules(a, b);
    /// rules.set_personal(b, CollisionRule::NoResponse);
    /// assert_eq!(rules.personal(a), CollisionRule::NoResponse);
    /// assert!(rules.shares_rules(a, b));
    /// ```
    pub fn share_rules(&mut self, from: impl Into<Node>, to: impl Into<Node>) {
        let (from, to) = (from.into(), to.into());
        // `from` newer than `to` in one slot: storing `from` makes `to` a
        // removed object's handle.
        let older_in_slot = from.slot() == to.slot() && to.generation() < from.generation();
        if from == to || older_in_slot || self.is_removed(to) || self.record_mut(from).is_none() {
            return;
        }
        let id = self.record_id(from).expect("record_mut made one");
        if self.record_id(to) == Some(id) {
            return;
        }
        self.records.get_mut(id).users += 1;
        self.attach(to, id);
        self.changes.node(to);
    }

    /// Whether `a` and `b` use one rule record.
    #[must_use]
    pub fn shares_rules(&self, a: impl Into<Node>, b: impl Into<Node>) -> bool {
        let (a, b) = (a.into(), b.into());
        a == b || matches!((self.record_id(a), self.record_id(b)), (Some(x), Some(y)) if x == y)
    }

    /// Makes every descendant of `node` share `node`'s rule record (the
    /// BEPU design's recursive rule setting): the colliders of a body, and
    /// every body below it in the parent map with their colliders. Later
    /// edits through any of them reach all of them. Bodies or colliders
    /// added later are not included.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, CollisionRuleSet, RuleError};
    ///
    /// let mut bodies = RigidBodySet::new();
    /// let mut colliders = ColliderSet::new();
    /// let chassis = bodies.insert(RigidBodyBuilder::dynamic());
    /// let wheel = bodies.insert(RigidBodyBuilder::dynamic());
    /// let tyre = colliders.insert_with_parent(ColliderBuilder::ball(0.4), wheel, &mut bodies);
    /// let mut rules = CollisionRuleSet::default();
    /// rules.set_parent(wheel, chassis)?;
    /// rules.set_rules_recursive(chassis, &bodies, &colliders);
    /// rules.set_personal(tyre, CollisionRule::NoContacts);
    /// assert_eq!(rules.personal(chassis), CollisionRule::NoContacts);
    /// # Ok::<(), RuleError>(())
    /// ```
    pub fn set_rules_recursive(
        &mut self,
        node: impl Into<Node>,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
    ) {
        let node = node.into();
        if self.is_removed(node) {
            return;
        }
        for descendant in self.descendants(node, bodies, colliders) {
            self.share_rules(node, descendant);
        }
    }

    /// `node` itself if it is a collider in the set, and every collider
    /// below it: the colliders whose chains hold `node`.
    pub(crate) fn colliders_under(
        &self,
        node: Node,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
    ) -> Vec<ColliderHandle> {
        let mut below: Vec<ColliderHandle> = self
            .descendants(node, bodies, colliders)
            .into_iter()
            .filter_map(|n| match n {
                Node::Collider(c) => Some(c),
                Node::Body(_) => None,
            })
            .collect();
        if let Node::Collider(c) = node {
            if colliders.contains(c) {
                below.push(c);
            }
        }
        below
    }

    /// The nodes below `node`: for a body, its colliders and every body below
    /// it in the parent map with their colliders; a collider has none. A
    /// body Rapier has removed is not in the world: neither it nor the
    /// bodies under it are descendants (their chains end below it).
    #[must_use]
    pub fn descendants(
        &self,
        node: impl Into<Node>,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
    ) -> Vec<Node> {
        let Node::Body(root) = node.into() else {
            return Vec::new();
        };
        let mut body_list = self.hierarchy.descendants(root);
        body_list.push(root);
        // Bodies missing from the set are not in the world: not descendants,
        // and a chain ends below one (as `resolve` reads it), so neither are
        // the bodies under it.
        let reaches_root = |mut body: RigidBodyHandle| loop {
            if !bodies.contains(body) {
                return false;
            }
            match self.hierarchy.parent(body) {
                _ if body == root => return true,
                Some(parent) => body = parent,
                None => return false,
            }
        };
        body_list.retain(|&b| reaches_root(b));
        let mut nodes = Vec::new();
        for (body, rigid_body) in body_list.iter().filter_map(|&b| Some((b, bodies.get(b)?))) {
            nodes.extend(
                rigid_body
                    .colliders()
                    .iter()
                    .filter(|&&c| colliders.contains(c))
                    .map(|&c| Node::Collider(c)),
            );
            if body != root {
                nodes.push(Node::Body(body));
            }
        }
        nodes
    }
}

/// The parent map.
impl CollisionRuleSet {
    /// Makes `parent` the parent of `child` in the crate's parent map,
    /// replacing any earlier parent. A handle of a removed object
    /// ([`RuleError::Removed`]), a body as its own parent, or a parent that
    /// already lies below `child` is refused and changes nothing.
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
        self.changes.parents = true;
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
        self.changes.parents = true;
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

/// Forgetting removed objects (`docs/semantics.md`, section 4).
impl CollisionRuleSet {
    /// Forgets a node that left the world: its rules (a shared record lives
    /// on for its other users), every specific entry about it, and for a body
    /// every parent link that names it (its children become roots).
    ///
    /// [`RuleHooks`](crate) does this by itself for objects removed through
    /// Rapier; call it when you use the rule set alone. From then on the
    /// handle is dead to the rule set: `set_parent` refuses it with
    /// [`RuleError::Removed`] and the other editing verbs ignore it
    /// (`docs/semantics.md`, "Handles of removed objects").
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, CollisionRuleSet, RuleError};
    ///
    /// let mut bodies = RigidBodySet::new();
    /// let (a, b) = (bodies.insert(RigidBodyBuilder::dynamic()), bodies.insert(RigidBodyBuilder::dynamic()));
    /// let mut rules = CollisionRuleSet::default();
    /// rules.set_specific(a, b, CollisionRule::NoPair);
    /// rules.set_parent(a, b)?;
    /// rules.remove_node(b);
    /// assert_eq!(rules.specific(a, b), CollisionRule::Defer);
    /// assert_eq!(rules.parent(a), None);
    /// assert_eq!(rules.set_parent(a, b), Err(RuleError::Removed { node: b.into() }));
    /// # Ok::<(), RuleError>(())
    /// ```
    pub fn remove_node(&mut self, node: impl Into<Node>) {
        let node = node.into();
        // Only a node the rules held is remembered as removed: whether an
        // edit through a handle is refused must not depend on which
        // objects the hooks happened to watch.
        let held = self.record(node).is_some_and(|r| !r.is_empty())
            || self.named.contains_key(&node)
            || matches!(node, Node::Body(body) if self.in_hierarchy(body));
        self.detach(node);
        if self.named.remove(&node).is_some() {
            // The nodes holding an entry about it change their pairs: logged,
            // as an edit of theirs would be.
            let holders: Vec<Node> = self
                .nodes()
                .filter(|&n| {
                    self.record(n)
                        .is_some_and(|r| r.specific.contains_key(&node))
                })
                .collect();
            for record in self.records.live_mut() {
                record.specific.remove(&node);
            }
            for holder in holders {
                self.changes.node(holder);
            }
        }
        if let Node::Body(body) = node {
            for (child, parent) in self.hierarchy.links() {
                if parent == body {
                    self.changes.node(Node::Body(child));
                }
            }
            self.hierarchy.forget(body);
        }
        if held {
            self.removed.bury(node);
        }
    }

    /// Forgets every node the rule set knows that is missing from the Rapier
    /// sets: bodies and colliders with rules, bodies in the parent map, and
    /// the subjects of specific entries. Returns how many were forgotten.
    pub fn remove_missing(&mut self, bodies: &RigidBodySet, colliders: &ColliderSet) -> usize {
        let exists = |node: Node| match node {
            Node::Collider(handle) => colliders.contains(handle),
            Node::Body(handle) => bodies.contains(handle),
        };
        let mut missing: Vec<Node> = self.nodes().filter(|&n| !exists(n)).collect();
        for (child, parent) in self.hierarchy.links() {
            missing.extend(
                [Node::Body(child), Node::Body(parent)]
                    .into_iter()
                    .filter(|&n| !exists(n)),
            );
        }
        for record in self.records.live() {
            missing.extend(record.specific.keys().copied().filter(|&n| !exists(n)));
        }
        missing.sort_unstable_by_key(|node| match *node {
            Node::Collider(h) => (0, h.into_raw_parts()),
            Node::Body(h) => (1, h.into_raw_parts()),
        });
        missing.dedup();
        for &node in &missing {
            self.remove_node(node);
        }
        missing.len()
    }

    /// Logs "everything changed": hooks that receive this rule set whole
    /// (a loaded one put in place of another) recalculate and plan all.
    #[cfg(feature = "serde")]
    pub(crate) fn mark_all_changed(&mut self) {
        self.changes.everything();
    }

    /// Whether anything was edited since the last [`take_changes`](Self::take_changes).
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
        nodes.sort_unstable_by_key(|&n| super::native::node_order(n));
        nodes.dedup();
        nodes
    }

    /// Whether `body` is a child or a parent in the parent map.
    pub(crate) fn in_hierarchy(&self, body: RigidBodyHandle) -> bool {
        self.hierarchy.parent(body).is_some() || self.hierarchy.is_parent(body)
    }

    /// Every node that has a rule record, in no particular order.
    pub fn nodes(&self) -> impl Iterator<Item = Node> + '_ {
        self.collider_records
            .iter()
            .map(|(handle, _)| Node::Collider(handle))
            .chain(
                self.body_records
                    .iter()
                    .map(|(handle, _)| Node::Body(handle)),
            )
    }

    /// How many distinct rule records are in use.
    #[must_use]
    pub fn record_count(&self) -> usize {
        self.records.live().count()
    }
}
