//! The ends of the specific entries given one, counted against a clock
//! (`docs/architecture.md`, "Cost per step"). Each end keeps the clock's
//! reading when it was given and is listed under the step or the time it
//! comes, so a step counts the ends that come in it, not every end: in a
//! world whose projectiles each carry a rule with an end, a step costs
//! what came, not what is alive. An end that came and waits for its sides
//! to be apart is tested every step until it ends.

use std::cmp::Reverse;
use std::collections::{BTreeMap, BTreeSet, BinaryHeap};

use super::super::Node;
use super::super::rapier::prelude::Real;
use super::ending::{Count, Due, DueEnd, Until};

/// The steps counted and the simulated time they took, since the set was
/// made. `f64`: a day at 60 Hz sums without losing the half step that
/// `Until::seconds` rounds by.
#[derive(Clone, Copy, Debug, Default)]
struct Clock {
    steps: u64,
    time: f64,
}

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

impl End {
    /// The end as [`Until`] reports it at `now`: what is left of its count.
    fn left(&self, now: Clock) -> Until {
        let count = match self.until.count {
            Count::Apart => Count::Apart,
            Count::Steps(steps) => {
                let counted = now.steps - self.given.steps;
                Count::Steps(u64::from(steps).saturating_sub(counted) as u32)
            }
            // A count that came has none left, whatever later steps last.
            Count::Seconds(_) if self.came => Count::Seconds(-1.0),
            Count::Seconds(seconds) => {
                Count::Seconds((f64::from(seconds) - (now.time - self.given.time)) as Real)
            }
        };
        Until {
            count,
            ..self.until
        }
    }
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
        self.ends.get(key).map(|end| end.left(self.clock))
    }

    /// Every end with what is left of its count, in the node order.
    pub(crate) fn iter(&self) -> impl Iterator<Item = ((Node, Node), Until)> + '_ {
        self.ends.iter().map(|(&key, end)| (key, end.left(self.clock)))
    }

    /// Gives `key`'s entry `until`, counted from now, in place of any end
    /// it had.
    pub(crate) fn insert(&mut self, key: (Node, Node), until: Until) {
        self.next_id += 1;
        let id = self.next_id;
        self.ends.insert(
            key,
            End {
                until,
                given: self.clock,
                id,
                came: false,
            },
        );
        self.came.remove(&key);
        match until.count {
            Count::Apart => {
                self.ends.get_mut(&key).expect("just given").came = true;
                self.came.insert(key);
            }
            Count::Steps(steps) => {
                let step = self.clock.steps + u64::from(steps);
                self.by_step.push(Reverse((step, id, key)));
            }
            Count::Seconds(seconds) => {
                // A count may be saved after it came (less than zero left):
                // it comes at once.
                let time = (self.clock.time + f64::from(seconds)).max(0.0);
                self.by_time.push(Reverse((time.to_bits(), id, key)));
            }
        }
        self.tidy_lists();
    }

    /// Takes `key`'s end away, with what is left of its count.
    pub(crate) fn remove(&mut self, key: &(Node, Node)) -> Option<Until> {
        let end = self.ends.remove(key)?;
        if end.came {
            self.came.remove(key);
        }
        Some(end.left(self.clock))
    }

    /// Moves `from`'s end to `to`, unless `to` has one, keeping what is left
    /// of its count.
    pub(crate) fn hand_over(&mut self, from: (Node, Node), to: (Node, Node)) {
        if let Some(until) = self.remove(&from)
            && !self.ends.contains_key(&to)
        {
            self.insert(to, until);
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
        // The nearest whole number of steps: an end with less than half a
        // step left comes now.
        let half_step = f64::from(dt) * 0.5;
        while let Some(&Reverse((time, id, key))) = self.by_time.peek() {
            if f64::from_bits(time) - now.time >= half_step {
                break;
            }
            self.by_time.pop();
            self.come(id, key);
        }
        self.clock.steps += 1;
        self.clock.time += f64::from(dt);

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
                due: if until.wait_apart { Due::IfApart } else { Due::Now },
                margin: until.margin,
            });
            true
        });
        if self.ends.len() > 2 * self.kept.max(32) {
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
        if self.by_step.len() + self.by_time.len() <= 2 * self.ends.len() + 64 {
            return;
        }
        let mut by_step = Vec::new();
        let mut by_time = Vec::new();
        for (&key, end) in self.ends.iter().filter(|(_, end)| !end.came) {
            match end.until.count {
                Count::Apart => {}
                Count::Steps(steps) => {
                    by_step.push(Reverse((end.given.steps + u64::from(steps), end.id, key)));
                }
                Count::Seconds(seconds) => {
                    let time = (end.given.time + f64::from(seconds)).max(0.0);
                    by_time.push(Reverse((time.to_bits(), end.id, key)));
                }
            }
        }
        self.by_step = by_step.into();
        self.by_time = by_time.into();
    }
}

#[cfg(test)]
mod tests {
    use std::cell::Cell;
    use std::collections::{BTreeMap, BTreeSet};

    use proptest::prelude::*;

    use super::super::super::Node;
    use super::super::super::rapier::prelude::{Real, RigidBodyHandle};
    use super::super::ending::{DueEnd, Until};
    use super::Endings;

    fn key(i: u8) -> (Node, Node) {
        let body = |i: u32| Node::Body(RigidBodyHandle::from_raw_parts(i, 0));
        (body(u32::from(i % 3)), body(10 + u32::from(i / 3)))
    }

    /// What an edit or a step does to the ends.
    #[derive(Clone, Debug)]
    enum Op {
        Give(u8, Until),
        TakeAway(u8),
        HandOver(u8, u8),
        /// The entry goes another way (its object left): its end stays
        /// listed until a count drops it.
        EntryGoes(u8),
        Count(Real),
    }

    /// An end of any kind. Times are odd multiples of 1/480 s and steps
    /// last 1/60 or 1/120 s, so no count is ever half a step from coming,
    /// where rounding would decide.
    fn until() -> impl Strategy<Value = Until> {
        let count = prop_oneof![
            Just(Until::apart()),
            (0u32..6).prop_map(Until::steps),
            (0u32..40).prop_map(|m| Until::seconds((2 * m + 1) as Real / 480.0)),
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

    fn op() -> impl Strategy<Value = Op> {
        prop_oneof![
            3 => (0u8..9, until()).prop_map(|(k, u)| Op::Give(k, u)),
            1 => (0u8..9).prop_map(Op::TakeAway),
            1 => (0u8..9, 0u8..9).prop_map(|(a, b)| Op::HandOver(a, b)),
            1 => (0u8..9).prop_map(Op::EntryGoes),
            4 => prop_oneof![Just(1.0 / 60.0), Just(1.0 / 120.0)].prop_map(Op::Count),
        ]
    }

    /// The ends as the hooks counted them before the clock: each end
    /// counted down at every step, every end walked.
    #[derive(Default)]
    struct Naive(BTreeMap<(Node, Node), Until>);

    impl Naive {
        fn count(&mut self, dt: Real, holds: impl Fn(Node, Node) -> bool) -> Vec<DueEnd> {
            let mut due = Vec::new();
            self.0.retain(|&(node, other), until| {
                if !holds(node, other) {
                    return false;
                }
                if let Some(came) = until.count_step(dt) {
                    due.push(DueEnd {
                        node,
                        other,
                        due: came,
                        margin: until.margin(),
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

    proptest! {
        /// Counting against the clock gives what counting every end at
        /// every step gave: the same ends come at the same steps, in the
        /// same order, and each end reports what is left of it.
        #[test]
        fn the_clock_counts_as_every_end_counted_down(ops in prop::collection::vec(op(), 1..120)) {
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
                        naive.0.insert(key(k), until);
                    }
                    Op::TakeAway(k) => {
                        let (a, b) = (clocked.remove(&key(k)), naive.0.remove(&key(k)));
                        // An end whose entry went another way is dropped
                        // by the next count in one, by the next sweep in
                        // the other: either is gone for good.
                        if held.remove(&key(k)) {
                            prop_assert!(same(a, b), "{:?} taken away: {:?} against {:?}", key(k), a, b);
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
                        prop_assert_eq!(&due, &naive.count(dt, holds), "the ends that came");
                    }
                }
                for k in held.iter() {
                    prop_assert!(
                        same(clocked.get(k), naive.0.get(k).copied()),
                        "{:?}: {:?} counted against the clock, {:?} counted down",
                        k, clocked.get(k), naive.0.get(k)
                    );
                }
            }
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
