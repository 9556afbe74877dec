//! The group table: unordered pairs of groups to rules, with its set
//! helpers.

use hashbrown::HashMap;

use super::group::CollisionGroup;
use super::super::CollisionRule;

/// The group table: unordered pairs of groups to rules. A missing entry
/// means `Defer`, and an explicit `Defer` is stored as a missing entry.
#[derive(Clone, Debug)]
pub(crate) struct GroupTable {
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

    /// How many groups exist: the built-in two plus every created one.
    pub(crate) fn group_count(&self) -> u32 {
        self.next_id
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
