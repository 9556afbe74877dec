//! The group table: unordered pairs of groups to rules, with its set
//! helpers.

use hashbrown::HashMap;

use super::group::CollisionGroup;
use super::super::CollisionRule;

/// The group table: unordered pairs of groups to rules (stage 3 of the
/// calculation), and the groups it made. A missing entry means `Defer`, and
/// an explicit `Defer` is stored as a missing entry. It starts with the two
/// built-in groups and the built-in entry `(DEFAULT_KINEMATIC,
/// DEFAULT_KINEMATIC) -> NoPair`.
///
/// Every [`CollisionRuleSet`](super::super::CollisionRuleSet) holds one
/// ([`group_table`](super::super::CollisionRuleSet::group_table)); a table
/// of its own is for sharing one set of groups between several worlds
/// ([`copy_group_table`](super::super::CollisionRuleSet::copy_group_table)),
/// as the Bevy adapter's `RuleTable` does.
///
/// ```
/// use rapier_collision_rules::{CollisionGroup, CollisionRule, CollisionRuleSet, GroupTable};
///
/// let mut table = GroupTable::default();
/// let (player, debris) = (table.create_group(), table.create_group());
/// table.set_group_rule(player, debris, CollisionRule::NoPair);
/// assert_eq!(table.group_rule(debris, player), CollisionRule::NoPair);
/// let k = CollisionGroup::DEFAULT_KINEMATIC;
/// assert_eq!(table.group_rule(k, k), CollisionRule::NoPair, "the built-in entry");
///
/// let mut world_rules = CollisionRuleSet::default();
/// world_rules.copy_group_table(&table, CollisionRule::Normal);
/// assert_eq!(world_rules.group_rule(player, debris), CollisionRule::NoPair);
/// ```
#[doc(alias = "layer")]
#[doc(alias = "collision matrix")]
#[derive(Clone, Debug, PartialEq)]
pub struct GroupTable {
    entries: HashMap<(CollisionGroup, CollisionGroup), CollisionRule>,
    next_id: u32,
}

impl Default for GroupTable {
    fn default() -> Self {
        let mut table = GroupTable {
            entries: HashMap::new(),
            next_id: 2,
        };
        // The built-in entry: kinematic objects do not collide with each other by default.
        table.set(
            CollisionGroup::DEFAULT_KINEMATIC,
            CollisionGroup::DEFAULT_KINEMATIC,
            CollisionRule::NoPair,
        );
        table
    }
}

/// The table's key: the pair in a fixed order, so `(a, b)` and `(b, a)` are one entry.
fn key(a: CollisionGroup, b: CollisionGroup) -> (CollisionGroup, CollisionGroup) {
    if a <= b { (a, b) } else { (b, a) }
}

impl GroupTable {
    pub(crate) fn create(&mut self) -> CollisionGroup {
        let group = CollisionGroup(self.next_id);
        self.next_id += 1;
        group
    }

    /// Replaces the table with saved entries and a saved group count.
    #[cfg(feature = "serde")]
    pub(crate) fn restore(
        &mut self,
        group_count: u32,
        entries: Vec<(CollisionGroup, CollisionGroup, CollisionRule)>,
    ) {
        self.entries.clear();
        self.next_id = group_count.max(2);
        for (a, b, rule) in entries {
            self.set(a, b, rule);
        }
    }

    /// `other`'s entries, with at least `count` groups (groups created
    /// beyond `other`'s stay valid). Returns whether an entry changed.
    pub(crate) fn copy_from(&mut self, other: &GroupTable, count: u32) -> bool {
        let changed = self.entries != other.entries;
        if changed {
            self.entries.clone_from(&other.entries);
        }
        self.next_id = count.max(other.next_id);
        changed
    }

    pub(crate) fn get(&self, a: CollisionGroup, b: CollisionGroup) -> CollisionRule {
        if self.entries.is_empty() {
            return CollisionRule::Defer;
        }
        self.entries
            .get(&key(a, b))
            .copied()
            .unwrap_or(CollisionRule::Defer)
    }

    pub(crate) fn set(&mut self, a: CollisionGroup, b: CollisionGroup, rule: CollisionRule) {
        if rule == CollisionRule::Defer {
            self.entries.remove(&key(a, b));
        } else {
            self.entries.insert(key(a, b), rule);
        }
    }

    pub(crate) fn remove(&mut self, a: CollisionGroup, b: CollisionGroup) {
        self.entries.remove(&key(a, b));
    }

    /// Every entry, each unordered pair once.
    pub(crate) fn iter(
        &self,
    ) -> impl Iterator<Item = (CollisionGroup, CollisionGroup, CollisionRule)> + '_ {
        self.entries.iter().map(|(&(a, b), &rule)| (a, b, rule))
    }

    /// Each group of `set` with itself gets `self_rule`; each two distinct
    /// groups of `set` get `other_rule`.
    pub(crate) fn set_in_set(
        &mut self,
        set: &[CollisionGroup],
        self_rule: CollisionRule,
        other_rule: CollisionRule,
    ) {
        for (n, &a) in set.iter().enumerate() {
            self.set(a, a, self_rule);
            for &b in &set[n + 1..] {
                if a != b {
                    self.set(a, b, other_rule);
                }
            }
        }
    }

    pub(crate) fn remove_in_set(&mut self, set: &[CollisionGroup]) {
        for (n, &a) in set.iter().enumerate() {
            for &b in &set[n..] {
                self.remove(a, b);
            }
        }
    }

    /// `group` with every member of `set` (itself too, if it is a member).
    pub(crate) fn set_with_set(
        &mut self,
        group: CollisionGroup,
        set: &[CollisionGroup],
        rule: CollisionRule,
    ) {
        for &other in set {
            self.set(group, other, rule);
        }
    }

    pub(crate) fn remove_with_set(&mut self, group: CollisionGroup, set: &[CollisionGroup]) {
        for &other in set {
            self.remove(group, other);
        }
    }

    /// Every member of `a` with every member of `b`.
    pub(crate) fn set_between_sets(
        &mut self,
        a: &[CollisionGroup],
        b: &[CollisionGroup],
        rule: CollisionRule,
    ) {
        for &group in a {
            self.set_with_set(group, b, rule);
        }
    }

    pub(crate) fn remove_between_sets(&mut self, a: &[CollisionGroup], b: &[CollisionGroup]) {
        for &group in a {
            self.remove_with_set(group, b);
        }
    }
}

/// The table's verbs, as [`CollisionRuleSet`](super::super::CollisionRuleSet)
/// has them.
///
/// # Panics
///
/// Each verb that takes a group panics if the group was not created by this
/// table (nor is built in): a group of another table means nothing here.
impl GroupTable {
    /// A new group, distinct from every other group of this table.
    pub fn create_group(&mut self) -> CollisionGroup {
        self.create()
    }

    /// How many groups exist: the two built-in groups plus every created one.
    #[must_use]
    pub fn group_count(&self) -> u32 {
        self.next_id
    }

    /// Sets the rule between two groups, in either order; `Defer` removes
    /// the entry.
    pub fn set_group_rule(&mut self, a: CollisionGroup, b: CollisionGroup, rule: CollisionRule) {
        self.check(&[a, b]);
        self.set(a, b, rule);
    }

    /// The rule between two groups, in either order (`Defer` if none).
    #[must_use]
    pub fn group_rule(&self, a: CollisionGroup, b: CollisionGroup) -> CollisionRule {
        self.get(a, b)
    }

    /// Removes the entry between two groups.
    pub fn remove_group_rule(&mut self, a: CollisionGroup, b: CollisionGroup) {
        self.check(&[a, b]);
        self.remove(a, b);
    }

    /// Each group of `set` with itself gets `self_rule`; each two distinct
    /// groups of `set` get `other_rule`.
    pub fn set_group_rules_in_set(
        &mut self,
        set: &[CollisionGroup],
        self_rule: CollisionRule,
        other_rule: CollisionRule,
    ) {
        self.check(set);
        self.set_in_set(set, self_rule, other_rule);
    }

    /// Removes every entry between two groups of `set`, and of each with itself.
    pub fn remove_group_rules_in_set(&mut self, set: &[CollisionGroup]) {
        self.check(set);
        self.remove_in_set(set);
    }

    /// `group` with every member of `set` gets `rule`.
    pub fn set_group_rules_with_set(
        &mut self,
        group: CollisionGroup,
        set: &[CollisionGroup],
        rule: CollisionRule,
    ) {
        self.check(&[group]);
        self.check(set);
        self.set_with_set(group, set, rule);
    }

    /// Removes the entries of `group` with every member of `set`.
    pub fn remove_group_rules_with_set(&mut self, group: CollisionGroup, set: &[CollisionGroup]) {
        self.check(&[group]);
        self.check(set);
        self.remove_with_set(group, set);
    }

    /// Every member of `a` with every member of `b` gets `rule`.
    pub fn set_group_rules_between_sets(
        &mut self,
        a: &[CollisionGroup],
        b: &[CollisionGroup],
        rule: CollisionRule,
    ) {
        self.check(a);
        self.check(b);
        self.set_between_sets(a, b, rule);
    }

    /// Removes the entries of every member of `a` with every member of `b`.
    pub fn remove_group_rules_between_sets(&mut self, a: &[CollisionGroup], b: &[CollisionGroup]) {
        self.check(a);
        self.check(b);
        self.remove_between_sets(a, b);
    }

    /// Every entry, each unordered pair once, in no particular order.
    pub fn group_rules(
        &self,
    ) -> impl Iterator<Item = (CollisionGroup, CollisionGroup, CollisionRule)> + '_ {
        self.iter()
    }

    /// Refuses groups this table did not create: a caller bug.
    fn check(&self, groups: &[CollisionGroup]) {
        for g in groups {
            assert!(
                g.id() < self.next_id,
                "{g:?} was not created by this group table ({} groups exist)",
                self.next_id
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use CollisionRule::*;

    #[test]
    fn keys_are_unordered_and_defer_is_a_missing_entry() {
        let mut table = GroupTable::default();
        let (a, b) = (table.create(), table.create());
        table.set(a, b, NoResponse);
        assert_eq!(table.get(b, a), NoResponse);
        table.set(b, a, Defer);
        assert_eq!(table.get(a, b), Defer);
        assert_eq!(table.iter().count(), 1, "only the built-in entry is left");
    }

    #[test]
    fn a_copy_takes_the_entries_and_keeps_the_larger_count() {
        let mut from = GroupTable::default();
        let (a, b) = (from.create(), from.create());
        from.set(a, b, NoPair);
        let mut to = GroupTable::default();
        for _ in 0..5 {
            to.create();
        }
        assert!(to.copy_from(&from, to.group_count()), "an entry was added");
        assert_eq!(to.get(b, a), NoPair);
        assert_eq!(to.group_count(), 7, "groups created in the copy stay valid");
        assert!(!to.copy_from(&from, to.group_count()), "the same entries again");
        let mut fewer = GroupTable::default();
        fewer.copy_from(&from, fewer.group_count());
        assert_eq!(fewer.group_count(), from.group_count());
    }

    #[test]
    fn built_in_kinematic_entry() {
        let table = GroupTable::default();
        let k = CollisionGroup::DEFAULT_KINEMATIC;
        assert_eq!(table.get(k, k), NoPair);
        assert_eq!(table.get(k, CollisionGroup::DEFAULT_DYNAMIC), Defer);
    }

    #[test]
    fn created_groups_are_distinct_from_the_built_ins() {
        let mut table = GroupTable::default();
        let g = table.create();
        assert_eq!(g.id(), 2);
        assert_eq!(table.create().id(), 3);
        assert_eq!(table.group_count(), 4);
    }

    #[test]
    fn in_set_gives_self_and_other_rules_and_remove_clears_both() {
        let mut table = GroupTable::default();
        let set = [table.create(), table.create(), table.create()];
        table.set_in_set(&set, NoResponse, NoPair);
        for &a in &set {
            for &b in &set {
                let expected = if a == b { NoResponse } else { NoPair };
                assert_eq!(table.get(a, b), expected, "{a:?} {b:?}");
            }
        }
        table.remove_in_set(&set);
        assert_eq!(table.iter().count(), 1);
    }

    #[test]
    fn with_set_includes_the_group_itself_only_when_listed() {
        let mut table = GroupTable::default();
        let (g, x, y) = (table.create(), table.create(), table.create());
        table.set_with_set(g, &[x, y], NoContacts);
        assert_eq!(table.get(x, g), NoContacts);
        assert_eq!(table.get(g, g), Defer);
        assert_eq!(table.get(x, y), Defer);
        table.remove_with_set(g, &[y]);
        assert_eq!(table.get(g, y), Defer);
        assert_eq!(table.get(g, x), NoContacts);
    }

    #[test]
    fn between_sets_is_every_cross_pair_and_nothing_inside_a_set() {
        let mut table = GroupTable::default();
        let (a, b, c, d) = (
            table.create(),
            table.create(),
            table.create(),
            table.create(),
        );
        table.set_between_sets(&[a, b], &[c, d], NoResponse);
        for (x, y) in [(a, c), (a, d), (b, c), (b, d)] {
            assert_eq!(table.get(y, x), NoResponse);
        }
        assert_eq!(table.get(a, b), Defer);
        assert_eq!(table.get(c, d), Defer);
        table.remove_between_sets(&[b], &[c, d]);
        assert_eq!(table.get(b, c), Defer);
        assert_eq!(table.get(a, c), NoResponse);
    }
}
