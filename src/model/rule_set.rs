//! `CollisionRuleSet`: every rule of one world, its group verbs and its
//! default rule. The verbs on nodes, the parent map and removal are in
//! their own files of this folder.

use hashbrown::HashMap;
use super::super::rapier::prelude::{ColliderHandle, RigidBodyHandle};

use super::changes::Changes;
use super::endings::Endings;
use super::group_table::GroupTable;
use super::hierarchy::Hierarchy;
use super::identity::Identity;
use super::decision::Decision;
use super::written::Written;
use super::node::HandleMap;
use super::records::{RecordId, Records};
use super::small_set::SmallSet;
use super::tombstones::Tombstones;
use super::super::{CollisionGroup, CollisionRule, Node};

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
        into = "super::snapshot::SavedRuleSet",
        try_from = "super::snapshot::SavedRuleSet"
    )
)]
pub struct CollisionRuleSet {
    pub(crate) groups: GroupTable,
    pub(crate) default_rule: CollisionRule,
    pub(super) collider_records: HandleMap<ColliderHandle, RecordId>,
    pub(super) body_records: HandleMap<RigidBodyHandle, RecordId>,
    pub(crate) records: Records,
    pub(crate) hierarchy: Hierarchy,
    pub(super) changes: Changes,
    /// The records holding a specific entry about each node: the planner
    /// asks whether a node is named, and the removal of a named node visits
    /// those records alone.
    pub(super) named: HashMap<Node, SmallSet<RecordId>>,
    /// The handles forgotten as removed: every editing verb refuses them.
    pub(super) removed: Tombstones,
    /// The ends of the specific entries given one (see [`Until`](super::super::Until)).
    pub(super) endings: Endings,
    /// A node was given a one-way setting once (see `set_one_way`).
    pub(super) one_ways_used: bool,
    /// A copy of what the hooks wrote on each collider and the project's
    /// own settings under it, kept by the hooks that hold this set, so that
    /// a saved set carries it: hooks given the set with a world saved with
    /// it tell their own writes from the project's settings
    /// (`docs/semantics.md`, "Saving and loading"). Not an edit: it is no
    /// rule, and nothing logs it.
    pub(crate) writes: HandleMap<ColliderHandle, Written>,
    /// A copy of how the hooks decided each specific entry, kept as
    /// `writes` is, for the same reason.
    pub(crate) decisions: HashMap<(Node, Node), Decision>,
    /// Which set this is: hooks tell a set put in place of theirs.
    pub(crate) identity: Identity,
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
            endings: Endings::default(),
            one_ways_used: false,
            writes: HandleMap::default(),
            decisions: HashMap::new(),
            identity: Identity::default(),
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
    /// If a group was not created by this rule set (nor is built in): its id
    /// is past the groups this set created. A group of another rule set
    /// whose id this set also has cannot be told from this set's own, and
    /// is taken as it: use each set's groups with that set only.
    #[track_caller]
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
    ///
    /// # Panics
    ///
    /// As [`set_group_rule`](Self::set_group_rule).
    #[track_caller]
    pub fn remove_group_rule(&mut self, a: CollisionGroup, b: CollisionGroup) {
        self.check_groups(&[a, b]);
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
    /// As [`set_group_rule`](Self::set_group_rule).
    #[track_caller]
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
    ///
    /// # Panics
    ///
    /// As [`set_group_rule`](Self::set_group_rule).
    #[track_caller]
    pub fn remove_group_rules_in_set(&mut self, set: &[CollisionGroup]) {
        self.check_groups(set);
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
    /// As [`set_group_rule`](Self::set_group_rule).
    #[track_caller]
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
    ///
    /// # Panics
    ///
    /// As [`set_group_rule`](Self::set_group_rule).
    #[track_caller]
    pub fn remove_group_rules_with_set(&mut self, group: CollisionGroup, set: &[CollisionGroup]) {
        self.check_groups(&[group]);
        self.check_groups(set);
        self.groups.remove_with_set(group, set);
        self.changes.everything();
    }

    /// Every group of `a` gets `rule` with every group of `b`; pairs inside
    /// one set are left alone, but a group listed in both sets gets `rule`
    /// with itself (it is a group of `a` and of `b`).
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
    /// As [`set_group_rule`](Self::set_group_rule).
    #[track_caller]
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
    ///
    /// # Panics
    ///
    /// As [`set_group_rule`](Self::set_group_rule).
    #[track_caller]
    pub fn remove_group_rules_between_sets(&mut self, a: &[CollisionGroup], b: &[CollisionGroup]) {
        self.check_groups(a);
        self.check_groups(b);
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

    /// The group table: the groups this set made and the rules between them.
    #[must_use]
    pub fn group_table(&self) -> &GroupTable {
        &self.groups
    }

    /// Makes this set's group table `table` and its default rule
    /// `default_rule`, and its groups at least `table`'s (a group created
    /// here beyond `table`'s count stays valid, its table entries do not).
    /// Nodes, entries and links are untouched. For one table shared by
    /// several worlds, each with its own rule set: groups created in the
    /// shared table then mean the same in every copy. Nothing is logged
    /// when the table and the default rule were already these, so copying
    /// every frame costs no replanning.
    ///
    /// ```
    /// use rapier_collision_rules::{CollisionRule, CollisionRuleSet, GroupTable};
    ///
    /// let mut table = GroupTable::default();
    /// let (player, debris) = (table.create_group(), table.create_group());
    /// table.set_group_rule(player, debris, CollisionRule::NoPair);
    ///
    /// let mut world_rules = CollisionRuleSet::default();
    /// world_rules.copy_group_table(&table, CollisionRule::NoResponse);
    /// assert_eq!(world_rules.group_rule(debris, player), CollisionRule::NoPair);
    /// assert_eq!(world_rules.default_rule(), CollisionRule::NoResponse);
    /// assert_eq!(world_rules.group_count(), table.group_count());
    /// // Another rule set's table serves as well.
    /// let mut other = CollisionRuleSet::default();
    /// other.copy_group_table(world_rules.group_table(), world_rules.default_rule());
    /// assert_eq!(other.group_rule(player, debris), CollisionRule::NoPair);
    /// ```
    pub fn copy_group_table(&mut self, table: &GroupTable, default_rule: CollisionRule) {
        let count = self.groups.group_count();
        let entries_changed = self.groups.copy_from(table, count);
        if entries_changed || self.default_rule != default_rule {
            self.default_rule = default_rule;
            self.changes.everything();
        }
    }

}

impl CollisionRuleSet {
    /// Refuses groups this rule set did not create: a caller bug.
    #[track_caller]
    pub(super) fn check_groups(&self, groups: &[CollisionGroup]) {
        let count = self.groups.group_count();
        for g in groups {
            assert!(
                g.id() < count,
                "{g:?} was not created by this rule set ({count} groups exist): use the groups \
                 `create_group` of this rule set returned (a group of another rule set names \
                 nothing here)"
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


/// What the rule set holds.
impl CollisionRuleSet {
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

/// A rule set whose hooks start over on another world.
impl CollisionRuleSet {
    /// Forgets what belongs to the world these rules were stepped with:
    /// the objects it removed (which the new world may hold again), and,
    /// unless `saved` (a set loaded with the new world, which carries its
    /// hooks' writes and decisions), the copy of what the hooks wrote and
    /// decided there (`docs/semantics.md`, "Saving and loading").
    pub(crate) fn start_over(&mut self, saved: bool) {
        self.removed = Tombstones::default();
        if !saved {
            self.writes = HandleMap::default();
            self.decisions.clear();
        }
    }
}
