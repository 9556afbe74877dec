//! The ends of the specific entries given one, counted against a clock
//! (`docs/architecture.md`, "Cost per step"). Each end keeps the clock's
//! reading when it was given and is listed under the step or the time it
//! comes, so a step counts the ends that come in it, not every end: in a
//! world whose projectiles each carry a rule with an end, a step costs
//! what came, not what is alive. An end that came and waits for its sides
//! to be apart is tested every step until it ends.

use std::cmp::Reverse;
use std::collections::btree_map::Entry;
use std::collections::{BTreeMap, BTreeSet, BinaryHeap};

use super::super::Node;
use super::super::rapier::prelude::Real;
#[cfg(feature = "serde")]
use super::ending::MOST_STEPS;
use super::ending::{Clock, Count, DueEnd, Until, seconds_come};

/// The fewest ends a sweep waits for: ends whose entry went another way
/// are dropped once the ends are twice as many as the last sweep kept, or
/// as this. Small in the unit tests, so that their few ends are swept.
const SWEEP_FLOOR: usize = if cfg!(test) { 2 } else { 32 };

/// How many stale listings the lists hold before they are made again from
/// the ends, besides two for each end. Small in the unit tests, so that
/// their short ends, handed over and given again, make the lists again.
const LIST_SLACK: usize = if cfg!(test) { 4 } else { 64 };

/// An entry's end: as given, with the clock's reading then.
#[derive(Clone, Copy, Debug)]
struct End {
    until: Until,
    given: Clock,
    /// Told apart from an end given again to the same entry, whose earlier
    /// listing under its step or time is then stale.
    id: u64,
    /// Its count came: it ends now, or once its sides are apart.
    came: bool,
}

/// An end as a save holds it (feature `serde`): as given, with the reading
/// of the ends' clock then, and whether its count came. A save of what is
/// left of a time would round it to a `Real`, and a time a few of its last
/// bits short of a half step could then end a step apart from the set
/// never saved (`docs/semantics.md`, "Saving and loading").
#[cfg(feature = "serde")]
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SavedEnd {
    pub(crate) until: Until,
    pub(crate) given: Clock,
    pub(crate) came: bool,
}

#[cfg(feature = "serde")]
impl SavedEnd {
    /// What the constructors and the clock let through: a valid `until`
    /// (see [`Until::is_valid`]), come if it counts to apart, given at a
    /// reading of `clock` at or before `clock`'s own (see
    /// [`clock_is_valid`]).
    pub(crate) fn is_valid(&self, clock: Clock) -> bool {
        // An end at apart comes when given.
        let came_if_apart = self.came || !matches!(self.until.count, Count::Apart);
        self.until.is_valid()
            && came_if_apart
            && clock_is_valid(self.given)
            && self.given.steps <= clock.steps
            && self.given.time <= clock.time
    }
}

/// What counting lets a clock reach: steps short of [`MOST_STEPS`], and a
/// finite time of zero or more (not `-0.0`, whose bits would list an end
/// after every other).
#[cfg(feature = "serde")]
pub(crate) fn clock_is_valid(clock: Clock) -> bool {
    clock.steps < MOST_STEPS && clock.time.is_finite() && clock.time.is_sign_positive()
}

/// A place in a list of ends by when they come: the step (or the time's
/// bits: a time is never negative, and the bits of non-negative floats
/// order as the floats do), the end's id, and its entry.
type Listing = Reverse<(u64, u64, (Node, Node))>;

/// The ends of the specific entries, by entry, with the lists by when they
/// come.
#[derive(Clone, Debug, Default)]
pub(crate) struct Endings {
    ends: BTreeMap<(Node, Node), End>,
    clock: Clock,
    by_step: BinaryHeap<Listing>,
    by_time: BinaryHeap<Listing>,
    /// The ends whose count came (an end at apart comes at once), tested
    /// every step in the node order.
    came: BTreeSet<(Node, Node)>,
    next_id: u64,
    /// How many ends the last sweep kept: ends whose entry went another
    /// way are dropped when the set has grown to twice that.
    kept: usize,
}

impl Endings {
    pub(crate) fn is_empty(&self) -> bool {
        self.ends.is_empty()
    }

    pub(crate) fn contains_key(&self, key: &(Node, Node)) -> bool {
        self.ends.contains_key(key)
    }

    /// The end of `key`'s entry, with what is left of its count.
    pub(crate) fn get(&self, key: &(Node, Node)) -> Option<Until> {
        self.ends.get(key).map(|end| end.until.left(self.clock.since(end.given), end.came))
    }

    /// Every end with what is left of its count, in the node order.
    pub(crate) fn iter(&self) -> impl Iterator<Item = ((Node, Node), Until)> + '_ {
        self.ends
            .iter()
            .map(|(&key, end)| (key, end.until.left(self.clock.since(end.given), end.came)))
    }

    /// The clock the ends count by, as a save holds it.
    #[cfg(feature = "serde")]
    pub(crate) fn clock(&self) -> Clock {
        self.clock
    }

    /// Every end as a save holds it, in the node order.
    #[cfg(feature = "serde")]
    pub(crate) fn saved(&self) -> impl Iterator<Item = ((Node, Node), SavedEnd)> + '_ {
        self.ends.iter().map(|(&key, end)| {
            let End { until, given, came, .. } = *end;
            (key, SavedEnd { until, given, came })
        })
    }

    /// The ends a save holds, counting on from `clock` (each checked by
    /// [`SavedEnd::is_valid`]): every end comes at the step the set that
    /// was saved would have counted it at.
    #[cfg(feature = "serde")]
    pub(crate) fn restored(clock: Clock, saved: impl IntoIterator<Item = ((Node, Node), SavedEnd)>) -> Endings {
        let mut endings = Endings {
            clock,
            ..Endings::default()
        };
        for (key, SavedEnd { until, given, came }) in saved {
            debug_assert!(SavedEnd { until, given, came }.is_valid(clock), "checked by the load");
            endings.put(key, until, given, came);
        }
        endings.kept = endings.ends.len();
        endings
    }

    /// Gives `key`'s entry `until`, counted from now, in place of any end
    /// it had.
    pub(crate) fn insert(&mut self, key: (Node, Node), until: Until) {
        // An end at apart comes at once.
        self.put(key, until, self.clock, matches!(until.count, Count::Apart));
    }

    /// Gives `key`'s entry the end `until`, given at the reading `given`
    /// of the clock, in place of any end it had, and lists it.
    fn put(&mut self, key: (Node, Node), until: Until, given: Clock, came: bool) {
        self.next_id += 1;
        let end = End {
            until,
            given,
            id: self.next_id,
            came,
        };
        if let Some(was) = self.ends.insert(key, end)
            && was.came
        {
            self.came.remove(&key);
        }
        self.list(key, end);
        self.tidy_lists();
    }

    /// Lists `key`'s `end` under the step or the time it comes, or among
    /// those that came.
    fn list(&mut self, key: (Node, Node), end: End) {
        if end.came {
            self.came.insert(key);
            return;
        }
        match end.until.count {
            Count::Apart => unreachable!("an end at apart comes at once"),
            Count::Steps(steps) => {
                let step = end.given.steps + u64::from(steps);
                self.by_step.push(Reverse((step, end.id, key)));
            }
            Count::Seconds(seconds) => {
                // A count saved after it came (less than zero left) comes
                // at once: listed at zero.
                let time = (end.given.time + f64::from(seconds)).max(0.0);
                self.by_time.push(Reverse((time.to_bits(), end.id, key)));
            }
        }
    }

    /// Takes `key`'s end away, with what is left of its count.
    pub(crate) fn remove(&mut self, key: &(Node, Node)) -> Option<Until> {
        let end = self.ends.remove(key)?;
        if end.came {
            self.came.remove(key);
        }
        Some(end.until.left(self.clock.since(end.given), end.came))
    }

    /// Gives `to` a copy of `from`'s end, in place of any end it had: the
    /// same count from the same reading of the clock, which comes at the
    /// step `from`'s does.
    pub(crate) fn copy(&mut self, from: (Node, Node), to: (Node, Node)) {
        if let Some(&End { until, given, came, .. }) = self.ends.get(&from) {
            self.put(to, until, given, came);
        }
    }

    /// Moves `from`'s end to `to`, unless `to` has one: the same end, which
    /// comes at the step it would have.
    pub(crate) fn hand_over(&mut self, from: (Node, Node), to: (Node, Node)) {
        let Some(end) = self.ends.remove(&from) else {
            return;
        };
        if end.came {
            self.came.remove(&from);
        }
        if let Entry::Vacant(slot) = self.ends.entry(to) {
            slot.insert(end);
            self.list(to, end);
        }
    }

    /// Counts a step of `dt`: the ends whose count comes in it join those
    /// that came before; returns them all, in the node order, after
    /// dropping those whose entry went another way (`holds` says which
    /// entries are still held).
    pub(crate) fn count(&mut self, dt: Real, holds: impl Fn(Node, Node) -> bool) -> Vec<DueEnd> {
        let now = self.clock;
        while let Some(&Reverse((step, id, key))) = self.by_step.peek() {
            if step > now.steps {
                break;
            }
            self.by_step.pop();
            self.come(id, key);
        }
        while let Some(&Reverse((time, id, key))) = self.by_time.peek() {
            if !seconds_come(f64::from_bits(time) - now.time, dt) {
                break;
            }
            self.by_time.pop();
            self.come(id, key);
        }
        self.clock.tick(dt);

        let mut due = Vec::with_capacity(self.came.len());
        let ends = &mut self.ends;
        self.came.retain(|&(node, other)| {
            if !holds(node, other) {
                ends.remove(&(node, other));
                return false;
            }
            let until = ends[&(node, other)].until;
            due.push(DueEnd {
                node,
                other,
                due: until.due(),
                margin: until.margin(),
            });
            true
        });
        if self.ends.len() > 2 * self.kept.max(SWEEP_FLOOR) {
            self.ends.retain(|&(node, other), _| holds(node, other));
            self.kept = self.ends.len();
            let ends = &self.ends;
            self.came.retain(|key| ends.contains_key(key));
        }
        due
    }

    /// The listed end `id` of `key` comes, if it is still the entry's end.
    fn come(&mut self, id: u64, key: (Node, Node)) {
        if let Some(end) = self.ends.get_mut(&key).filter(|end| end.id == id && !end.came) {
            end.came = true;
            self.came.insert(key);
        }
    }

    /// Lists again, from the ends alone, once most listings are stale (ends
    /// taken away or given again before they came): the lists stay within
    /// a constant factor of the ends.
    fn tidy_lists(&mut self) {
        if self.by_step.len() + self.by_time.len() <= 2 * self.ends.len() + LIST_SLACK {
            return;
        }
        self.by_step.clear();
        self.by_time.clear();
        let waiting: Vec<((Node, Node), End)> =
            self.ends.iter().filter(|(_, end)| !end.came).map(|(&key, &end)| (key, end)).collect();
        for (key, end) in waiting {
            self.list(key, end);
        }
    }
}

#[cfg(test)]
mod tests {
    use std::cell::Cell;
    use std::collections::{BTreeMap, BTreeSet};

    use proptest::prelude::*;

    use super::super::super::Node;
    use super::super::super::rapier::prelude::{Real, RigidBodyHandle};
    use super::super::ending::{Countdown, DueEnd, Until};
    use super::Endings;

    fn key(i: u16) -> (Node, Node) {
        let body = |i: u32| Node::Body(RigidBodyHandle::from_raw_parts(i, 0));
        (body(u32::from(i % 3)), body(1_000 + u32::from(i / 3)))
    }

    /// What an edit or a step does to the ends.
    #[derive(Clone, Debug)]
    enum Op {
        Give(u16, Until),
        TakeAway(u16),
        HandOver(u16, u16),
        /// The entry goes another way (its object left): its end stays
        /// listed until a count drops it.
        EntryGoes(u16),
        Count(Real),
    }

    /// An end of any kind, of up to `steps` steps or `steps` steps of
    /// 1/60 s. Times are multiples of 1/480 s and steps last 1/60 or 1/120
    /// s: many fall on a half step.
    fn until(steps: u32) -> impl Strategy<Value = Until> {
        let count = prop_oneof![
            Just(Until::apart()),
            (0..steps).prop_map(Until::steps),
            (0..steps * 8).prop_map(|m| Until::seconds(m as Real / 480.0)),
        ];
        (count, any::<bool>(), 0u8..3).prop_map(|(until, overlapping, margin)| {
            let until = until.with_margin(Real::from(margin) * 0.1);
            if overlapping && until.steps_left().or(until.seconds_left().map(|_| 0)).is_some() {
                until.even_if_overlapping()
            } else {
                until
            }
        })
    }

    /// An edit of the ends of `keys` entries, of up to `steps` steps, or a
    /// step.
    fn op(keys: u16, steps: u32) -> impl Strategy<Value = Op> {
        prop_oneof![
            3 => (0..keys, until(steps)).prop_map(|(k, u)| Op::Give(k, u)),
            1 => (0..keys).prop_map(Op::TakeAway),
            1 => (0..keys, 0..keys).prop_map(|(a, b)| Op::HandOver(a, b)),
            1 => (0..keys).prop_map(Op::EntryGoes),
            4 => prop_oneof![Just(1.0 / 60.0), Just(1.0 / 120.0)].prop_map(Op::Count),
        ]
    }

    /// Every end counted down at every step with a [`Countdown`], every end
    /// walked: what the clock's listings, sweeps and lists made again must
    /// give. Both read the same rounding rule (`Until::comes`), which the
    /// unit tests of `ending.rs` pin by number.
    #[derive(Default)]
    struct Naive(BTreeMap<(Node, Node), Countdown>);

    impl Naive {
        fn count(&mut self, dt: Real, holds: impl Fn(Node, Node) -> bool) -> Vec<DueEnd> {
            let mut due = Vec::new();
            self.0.retain(|&(node, other), end| {
                if !holds(node, other) {
                    return false;
                }
                if let Some(came) = end.count_step(dt) {
                    due.push(DueEnd {
                        node,
                        other,
                        due: came,
                        margin: end.until().margin(),
                    });
                }
                true
            });
            due
        }
    }

    fn same(clocked: Option<Until>, naive: Option<Until>) -> bool {
        match (clocked, naive) {
            (Some(a), Some(b)) => {
                a.steps_left() == b.steps_left()
                    && a.margin() == b.margin()
                    && a.ends_even_if_overlapping() == b.ends_even_if_overlapping()
                    && match (a.seconds_left(), b.seconds_left()) {
                        (Some(x), Some(y)) => (x - y).abs() < 1e-4,
                        (x, y) => x == y,
                    }
            }
            (a, b) => a.is_none() && b.is_none(),
        }
    }

    /// Runs `ops` on the clocked ends and on every end counted down at
    /// every step: the same ends come at the same steps, in the same
    /// order, and each end reports what is left of it.
    fn compare(ops: Vec<Op>) {
        let mut clocked = Endings::default();
        let mut naive = Naive::default();
        let mut held: BTreeSet<(Node, Node)> = BTreeSet::new();
        // An entry goes another way only with one of its objects, whose
        // handle is dead from then on: nothing gives it an end again.
        let mut dead: BTreeSet<(Node, Node)> = BTreeSet::new();
        for op in ops {
            match op {
                Op::Give(k, _) | Op::HandOver(_, k) if dead.contains(&key(k)) => {}
                Op::Give(k, until) => {
                    held.insert(key(k));
                    clocked.insert(key(k), until);
                    naive.0.insert(key(k), Countdown::new(until));
                }
                Op::TakeAway(k) => {
                    let (a, b) = (clocked.remove(&key(k)), naive.0.remove(&key(k)).map(|c| c.until()));
                    // An end whose entry went another way is dropped
                    // by the next count in one, by the next sweep in
                    // the other: either is gone for good.
                    if held.remove(&key(k)) {
                        assert!(same(a, b), "{:?} taken away: {:?} against {:?}", key(k), a, b);
                    }
                }
                // An entry's end is handed over with the entry, which
                // is still held, to another node (`endings_leave`).
                Op::HandOver(from, to) if from != to && held.contains(&key(from)) => {
                    if let Some(until) = naive.0.remove(&key(from)) {
                        naive.0.entry(key(to)).or_insert(until);
                        held.insert(key(to));
                    }
                    held.remove(&key(from));
                    clocked.hand_over(key(from), key(to));
                }
                Op::HandOver(..) => {}
                Op::EntryGoes(k) => {
                    held.remove(&key(k));
                    dead.insert(key(k));
                }
                Op::Count(dt) => {
                    let holds = |n, o| held.contains(&(n, o));
                    let due = clocked.count(dt, holds);
                    assert_eq!(&due, &naive.count(dt, holds), "the ends that came");
                }
            }
            // After every edit as after every count: each held entry reports
            // what is left of its end.
            for k in held.iter() {
                assert!(
                    same(clocked.get(k), naive.0.get(k).map(Countdown::until)),
                    "{:?}: {:?} counted against the clock, {:?} counted down",
                    k, clocked.get(k), naive.0.get(k).map(Countdown::until)
                );
            }
        }
    }

    proptest! {
        /// Counting against the clock gives what counting every end at
        /// every step gave, with a few entries.
        #[test]
        fn the_clock_counts_as_every_end_counted_down(ops in prop::collection::vec(op(9, 8), 1..120)) {
            compare(ops);
        }

    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]
        /// The same with more entries and longer ends, given again and
        /// handed over before they come: ends whose entry went are swept,
        /// and the lists, stale listings of steps and times, made again
        /// from the ends.
        #[test]
        fn the_sweeps_keep_every_live_end(ops in prop::collection::vec(op(30, 300), 300..900)) {
            compare(ops);
        }
    }

    /// Ends given again and again leave stale listings behind; once they
    /// outnumber the ends, the lists are made again from the ends, and
    /// every end still comes at its step.
    #[test]
    fn lists_made_again_keep_every_end_at_its_step() {
        let mut endings = Endings::default();
        let body = |i: u32| Node::Body(RigidBodyHandle::from_raw_parts(i, 0));
        let keys: Vec<(Node, Node)> = (0..100).map(|i| (body(i), body(5_000))).collect();
        for round in 0..4 {
            for (i, &key) in keys.iter().enumerate() {
                endings.insert(key, Until::steps((i % 10) as u32 + 3 - round).even_if_overlapping());
            }
        }
        // One end given again until the lists are made again: then each
        // end is listed once.
        let last = keys[99];
        let mut given = 0;
        while endings.by_step.len() > keys.len() {
            endings.insert(last, Until::steps(9).even_if_overlapping());
            given += 1;
            assert!(given < 1_000, "{} listings for {} ends: never made again", endings.by_step.len(), keys.len());
        }
        assert_eq!(endings.by_step.len(), keys.len(), "one listing an end");
        let mut came = vec![None; keys.len()];
        for step in 0..20 {
            for end in endings.count(1.0 / 60.0, |_, _| true) {
                let i = keys.iter().position(|&k| k == (end.node, end.other)).expect("a key");
                came[i].get_or_insert(step);
            }
        }
        for (i, came) in came.iter().enumerate() {
            assert_eq!(*came, Some(i % 10), "the end of entry {i}, Until::steps({})", i % 10);
        }
    }

    /// A step looks at the ends that come in it, and at those whose entry
    /// went another way only in a sweep once they are as many as the ends
    /// kept: a thousand long ends cost nothing a step.
    #[test]
    fn a_step_looks_at_the_ends_that_come_not_at_every_end() {
        let mut endings = Endings::default();
        let body = |i: u32| Node::Body(RigidBodyHandle::from_raw_parts(i, 0));
        for i in 0..1_000 {
            let until = if i % 2 == 0 { Until::steps(10_000) } else { Until::seconds(600.0) };
            endings.insert((body(i), body(5_000)), until);
        }
        let asked = Cell::new(0usize);
        for _ in 0..1_000 {
            let due = endings.count(1.0 / 60.0, |_, _| {
                asked.set(asked.get() + 1);
                true
            });
            assert!(due.is_empty());
        }
        assert!(asked.get() <= 1_000, "the entries were asked about {} times in 1,000 steps", asked.get());
        // One end comes: it alone is asked about.
        endings.insert((body(7_000), body(5_000)), Until::steps(0).even_if_overlapping());
        asked.set(0);
        let due = endings.count(1.0 / 60.0, |_, _| {
            asked.set(asked.get() + 1);
            true
        });
        assert_eq!((due.len(), asked.get()), (1, 1), "the end that came, alone");
    }
}
