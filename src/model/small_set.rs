//! A set that keeps a single member in place: most nodes are named by one
//! entry (a ball about its turret), which then needs no table of its own;
//! a hub is named by hundreds, which come and go one at a time.

use std::hash::Hash;

use hashbrown::HashSet;

/// A set of `T`, never empty: one member in place, or a hash set from the
/// second member on.
#[derive(Clone, Debug)]
pub(crate) enum SmallSet<T> {
    One(T),
    Many(HashSet<T>),
}

impl<T: Copy + Eq + Hash> SmallSet<T> {
    pub(crate) fn insert(&mut self, member: T) {
        match self {
            SmallSet::One(one) if *one == member => {}
            SmallSet::One(one) => *self = SmallSet::Many(HashSet::from_iter([*one, member])),
            SmallSet::Many(set) => {
                set.insert(member);
            }
        }
    }

    /// Takes `member` out; `true` when the set is left empty (the caller
    /// drops it).
    pub(crate) fn remove(&mut self, member: T) -> bool {
        match self {
            SmallSet::One(one) => *one == member,
            SmallSet::Many(set) => {
                set.remove(&member);
                set.is_empty()
            }
        }
    }

    pub(crate) fn contains(&self, member: T) -> bool {
        match self {
            SmallSet::One(one) => *one == member,
            SmallSet::Many(set) => set.contains(&member),
        }
    }

    /// The members, in no order.
    pub(crate) fn iter(&self) -> impl Iterator<Item = T> + '_ {
        let (one, many) = match self {
            SmallSet::One(one) => (Some(*one), None),
            SmallSet::Many(set) => (None, Some(set)),
        };
        one.into_iter().chain(many.into_iter().flatten().copied())
    }

    pub(crate) fn len(&self) -> usize {
        match self {
            SmallSet::One(_) => 1,
            SmallSet::Many(set) => set.len(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_set_holds_its_members_from_one_to_many_and_says_when_it_is_empty() {
        let mut set = SmallSet::One(1);
        set.insert(1);
        assert!(matches!(set, SmallSet::One(1)), "a member twice is one member");
        set.insert(2);
        set.insert(3);
        let mut members: Vec<i32> = set.iter().collect();
        members.sort_unstable();
        assert_eq!((members, set.len()), (vec![1, 2, 3], 3));
        assert!(set.contains(2) && !set.contains(4));
        assert!(!set.remove(4), "a stranger leaves the set as it was");
        assert!(!set.remove(1) && !set.remove(2));
        assert!(set.remove(3), "the last member out empties the set");
        let mut one = SmallSet::One(7);
        assert!(!one.remove(8) && one.contains(7));
        assert!(one.remove(7));
    }
}
