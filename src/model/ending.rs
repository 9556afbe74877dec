//! Rules with an end (`docs/semantics.md`, "Rules with an end"): a
//! specific entry given [`Until`] the two sides are apart, for a number of
//! steps, or for a simulated time. The rule set keeps each entry's end
//! beside the entry, against its clock ([`endings`](super::endings)); the
//! hooks count the steps and remove the entry when its end comes (they can
//! see the world, the rule set cannot).

use smallvec::SmallVec;

use super::super::rapier::prelude::Real;

use super::super::{CollisionRule, CollisionRuleSet, Node};

/// When a rule with an end ends: given to
/// [`CollisionRuleSet::set_specific_until`] or
/// [`RuleHooks::set_pair_rule_until`](super::super::RuleHooks::set_pair_rule_until).
///
/// Two sides are *apart* when no collider of one overlaps any collider of
/// the other by their bounding boxes, nor comes closer than the margin (0
/// unless [`margin`](Self::margin) says otherwise), before a step. A rule given for a number of
/// steps or a time that comes due while the two still overlap holds until
/// they are apart, so that a pair never starts responding deep inside
/// itself ([`even_if_overlapping`](Self::even_if_overlapping) ends it at
/// once instead).
///
/// ```
/// use rapier3d::prelude::*;
/// use rapier_collision_rules::{CollisionRule, CollisionRuleSet, Until};
///
/// let mut bodies = RigidBodySet::new();
/// let shooter = bodies.insert(RigidBodyBuilder::dynamic());
/// let bullet = bodies.insert(RigidBodyBuilder::dynamic());
/// let mut rules = CollisionRuleSet::default();
/// rules.set_specific_until(bullet, shooter, CollisionRule::NoContacts, Until::apart().with_margin(0.05));
/// assert_eq!(rules.specific(bullet, shooter), CollisionRule::NoContacts);
/// assert_eq!(rules.specific_until(bullet, shooter), Some(Until::apart().with_margin(0.05)));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Until {
    pub(super) count: Count,
    pub(super) margin: Real,
    /// A due count waits for the sides to be apart.
    pub(super) wait_apart: bool,
}

/// What an end counts, and what is left of it.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(super) enum Count {
    Apart,
    Steps(u32),
    Seconds(Real),
}

/// An end that came with one more step counted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Due {
    /// The rule ends now if the sides are apart, and holds otherwise.
    IfApart,
    /// The rule ends now.
    Now,
}

impl Until {
    /// Until the two sides are apart.
    #[must_use]
    pub fn apart() -> Until {
        Until {
            count: Count::Apart,
            margin: 0.0,
            wait_apart: true,
        }
    }

    /// For `steps` steps of the hooks (`steps(1)`: the next step only),
    /// then until the sides are apart.
    #[must_use]
    pub fn steps(steps: u32) -> Until {
        Until {
            count: Count::Steps(steps),
            ..Until::apart()
        }
    }

    /// For `seconds` of simulated time (counted in whole steps, the nearest
    /// number of the world's `dt`), then until the sides are apart.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, RuleHooks, Until};
    ///
    /// let mut world = PhysicsWorld::new(); // 60 Hz
    /// let ball = world.insert_body(RigidBodyBuilder::dynamic());
    /// world.insert_collider(ColliderBuilder::ball(0.5), Some(ball));
    /// let ground = world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -5.0, 0.0)));
    /// world.insert_collider(ColliderBuilder::cuboid(5.0, 0.5, 5.0), Some(ground));
    /// let mut hooks = RuleHooks::default();
    /// // 0.125 s is 7.5 steps of 1/60 s: a time on a half step holds that step.
    /// hooks.rules_mut().set_specific_until(ball, ground, CollisionRule::NoPair, Until::seconds(0.125));
    /// for _ in 0..8 {
    ///     hooks.step(&mut world);
    /// }
    /// assert!(hooks.rules().specific(ball, ground).is_decided(), "it held the 8 steps");
    /// hooks.step(&mut world);
    /// assert_eq!(hooks.rules().specific(ball, ground), CollisionRule::Defer, "gone before the 9th");
    /// ```
    ///
    /// # Panics
    ///
    /// If `seconds` is negative, infinite or not a number (a rule without
    /// an end is given with `set_specific`).
    #[must_use]
    #[track_caller]
    pub fn seconds(seconds: Real) -> Until {
        assert!(
            seconds >= 0.0 && seconds.is_finite(),
            "Until::seconds({seconds}): a time to hold a rule must be a finite number of seconds, \
             zero or more; a rule without an end is given with set_specific"
        );
        Until {
            count: Count::Seconds(seconds),
            ..Until::apart()
        }
    }

    /// How far apart the sides' bounding boxes must be for the sides to
    /// be apart.
    ///
    /// # Panics
    ///
    /// If `margin` is negative, infinite or not a number.
    #[must_use]
    #[track_caller]
    pub fn with_margin(self, margin: Real) -> Until {
        assert!(
            margin >= 0.0 && margin.is_finite(),
            "Until::with_margin({margin}): the margin must be a finite distance, zero or more"
        );
        Until { margin, ..self }
    }

    /// A rule given for steps or a time ends when they run out, even if the
    /// sides still overlap then (they are pushed apart as Rapier pushes any
    /// overlap, at up to its `max_corrective_velocity`: `docs/stability.md`).
    ///
    /// # Panics
    ///
    /// On [`Until::apart`], which has no count to run out.
    #[must_use]
    #[track_caller]
    pub fn even_if_overlapping(self) -> Until {
        assert!(
            self.count != Count::Apart,
            "Until::apart().even_if_overlapping(): an end at apart has nothing else to wait for; \
             use Until::steps or Until::seconds"
        );
        Until {
            wait_apart: false,
            ..self
        }
    }

    /// The margin of the test for apart ([`with_margin`](Self::with_margin)).
    #[must_use]
    pub fn margin(&self) -> Real {
        self.margin
    }

    /// Whether a count that runs out while the sides overlap ends the rule
    /// anyway ([`even_if_overlapping`](Self::even_if_overlapping)).
    #[must_use]
    pub fn ends_even_if_overlapping(&self) -> bool {
        !self.wait_apart
    }

    /// The steps left, for a rule given for a number of steps. `Some(0)`
    /// once the count has run out: the rule ends before the next step, or,
    /// unless it ends [even if overlapping](Self::even_if_overlapping),
    /// once its sides are apart.
    #[must_use]
    pub fn steps_left(&self) -> Option<u32> {
        match self.count {
            Count::Steps(left) => Some(left),
            _ => None,
        }
    }

    /// The simulated time left, for a rule given for a time. `Some(0.0)`
    /// once less than half a step is left: the rule ends before the next
    /// step, or, unless it ends [even if overlapping](Self::even_if_overlapping),
    /// once its sides are apart.
    #[must_use]
    pub fn seconds_left(&self) -> Option<Real> {
        match self.count {
            Count::Seconds(left) => Some(left.max(0.0)),
            _ => None,
        }
    }

    /// What the constructors and the count let through: a finite margin of
    /// zero or more, a finite time (below zero in what is left of a count
    /// that came, which a project may give again). A save may hold
    /// anything.
    #[cfg(feature = "serde")]
    pub(crate) fn is_valid(&self) -> bool {
        let time = match self.count {
            Count::Seconds(left) => left.is_finite(),
            _ => true,
        };
        self.margin >= 0.0 && self.margin.is_finite() && time
    }

    /// Whether the count has come before a step of `dt`, `counted` after
    /// the end was given. A time rounds to the nearest whole number of
    /// steps, and a time within [`HALF_STEP_SLACK`] of a step of a half
    /// holds the step: the `f32` rounding of a time as given or of the
    /// steps does not decide, for counts up to about 8,000 steps
    /// (`docs/semantics.md`, "Rules with an end").
    pub(crate) fn comes(&self, counted: Clock, dt: Real) -> bool {
        match self.count {
            Count::Apart => true,
            Count::Steps(steps) => counted.steps >= u64::from(steps),
            Count::Seconds(seconds) => seconds_come(f64::from(seconds) - counted.time, dt),
        }
    }

    /// What is left of the count, `counted` after the end was given (`came`:
    /// it has come, and none is left whatever later steps last).
    pub(crate) fn left(&self, counted: Clock, came: bool) -> Until {
        let count = match self.count {
            Count::Apart => Count::Apart,
            Count::Steps(steps) => {
                Count::Steps(u64::from(steps).saturating_sub(counted.steps) as u32)
            }
            Count::Seconds(_) if came => Count::Seconds(-1.0),
            Count::Seconds(seconds) => Count::Seconds((f64::from(seconds) - counted.time) as Real),
        };
        Until { count, ..*self }
    }

    /// How the rule ends once its count came.
    pub(crate) fn due(&self) -> Due {
        if self.wait_apart { Due::IfApart } else { Due::Now }
    }
}

/// Whether a time with `left` seconds left has come before a step of `dt`
/// (see [`Until::comes`]).
pub(crate) fn seconds_come(left: f64, dt: Real) -> bool {
    left < (0.5 - HALF_STEP_SLACK) * f64::from(dt)
}

/// How near a half step, in steps, a time holds that step: above the
/// `f32` rounding of a time and a timestep for counts up to about 8,000
/// steps (each rounds by up to 6e-8 of itself), and far below anything a
/// project would mean.
pub(crate) const HALF_STEP_SLACK: f64 = 1e-3;

/// Steps counted and the simulated time they took. `f64`: a day at 60 Hz
/// sums without losing the half step a time rounds by. Saved as it is, the
/// time as its bits (`time_bits`): a text format may read a decimal back
/// one bit off (`serde_json` without its `float_roundtrip` feature does,
/// for about one time in nine), and a loaded set counts on from the same
/// bits.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub(crate) struct Clock {
    pub(crate) steps: u64,
    #[cfg_attr(feature = "serde", serde(rename = "time_bits", with = "bits"))]
    pub(crate) time: f64,
}

/// An `f64` saved as its bits.
#[cfg(feature = "serde")]
mod bits {
    use serde::{Deserialize, Deserializer, Serializer};

    pub(super) fn serialize<S: Serializer>(time: &f64, to: S) -> Result<S::Ok, S::Error> {
        to.serialize_u64(time.to_bits())
    }

    pub(super) fn deserialize<'de, D: Deserializer<'de>>(from: D) -> Result<f64, D::Error> {
        u64::deserialize(from).map(f64::from_bits)
    }
}

/// More steps than any run counts (about 285,000 years at a thousand
/// steps a second): a saved clock or end at or past it is refused, so that
/// counting on from it cannot overflow.
#[cfg(feature = "serde")]
pub(crate) const MOST_STEPS: u64 = 1 << 53;

impl Clock {
    /// Counts a step of `dt`.
    pub(crate) fn tick(&mut self, dt: Real) {
        self.steps += 1;
        self.time += f64::from(dt);
    }

    /// What was counted since `earlier`.
    pub(crate) fn since(self, earlier: Clock) -> Clock {
        Clock {
            steps: self.steps - earlier.steps,
            time: self.time - earlier.time,
        }
    }
}

/// One end counted at every step: a pair override's, which lasts while
/// its pair lives.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Countdown {
    until: Until,
    counted: Clock,
    came: bool,
}

impl Countdown {
    pub(crate) fn new(until: Until) -> Countdown {
        Countdown {
            until,
            counted: Clock::default(),
            came: false,
        }
    }

    /// What is left of it.
    pub(crate) fn until(&self) -> Until {
        self.until.left(self.counted, self.came)
    }

    /// Counts the step about to be taken, `dt` long: whether the rule ends
    /// before it (`None` while the count runs). A count that came stays
    /// come.
    pub(crate) fn count_step(&mut self, dt: Real) -> Option<Due> {
        self.came = self.came || self.until.comes(self.counted, dt);
        self.counted.tick(dt);
        self.came.then(|| self.until.due())
    }
}

/// A specific entry whose end came in [`CollisionRuleSet::count_ends`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct DueEnd {
    /// The entry's holder, as given.
    pub(crate) node: Node,
    /// The entry's subject.
    pub(crate) other: Node,
    /// Whether it ends now or once its sides are apart.
    pub(crate) due: Due,
    /// How far apart the sides must be.
    pub(crate) margin: Real,
}

/// Rules with an end.
impl CollisionRuleSet {
    /// What `node` says about `other` (as
    /// [`set_specific`](Self::set_specific)) until `until` comes: then the
    /// entry is removed by the hooks before the next step, and the pair
    /// falls back to the other stages. `Defer` removes the entry. A later
    /// `set_specific` of the same entry makes it timeless again.
    ///
    /// The sides tested for apart are `node` and `other` with every
    /// collider under them (if `node` leaves a record others share, the
    /// first of them takes its place). Under [`RecalculationPolicy::Manual`](super::super::RecalculationPolicy::Manual),
    /// a live pair keeps its rule after the end until it ends or is
    /// recalculated, as after any edit.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, RuleHooks, Until};
    ///
    /// let mut world = PhysicsWorld::new();
    /// let shooter = world.insert_body(RigidBodyBuilder::dynamic().gravity_scale(0.0));
    /// world.insert_collider(ColliderBuilder::cuboid(0.5, 1.0, 0.5), Some(shooter));
    /// // Spawned inside its shooter, flying out to the right.
    /// let bullet = world.insert_body(
    ///     RigidBodyBuilder::dynamic().gravity_scale(0.0).linvel(Vector::new(5.0, 0.0, 0.0)),
    /// );
    /// world.insert_collider(ColliderBuilder::ball(0.1), Some(bullet));
    /// let mut hooks = RuleHooks::default();
    /// hooks.rules_mut().set_specific_until(bullet, shooter, CollisionRule::NoContacts, Until::apart());
    /// hooks.step(&mut world);
    /// assert_eq!(hooks.rules().specific(bullet, shooter), CollisionRule::NoContacts, "still inside");
    /// for _ in 0..30 {
    ///     hooks.step(&mut world);
    /// }
    /// assert_eq!(hooks.rules().specific(bullet, shooter), CollisionRule::Defer, "out: the rule ended");
    /// assert!(world.bodies[shooter].linvel().length() < 1e-6, "the shooter was never pushed");
    /// ```
    pub fn set_specific_until(
        &mut self,
        node: impl Into<Node>,
        other: impl Into<Node>,
        rule: CollisionRule,
        until: Until,
    ) {
        let (node, other) = (node.into(), other.into());
        self.set_specific(node, other, rule);
        if self.specific(node, other) != CollisionRule::Defer {
            self.endings.insert((node, other), until);
        }
    }

    /// The end of what `node` says about `other`, `None` if the entry is
    /// timeless or there is none. Counts down as the hooks step.
    #[must_use]
    pub fn specific_until(&self, node: impl Into<Node>, other: impl Into<Node>) -> Option<Until> {
        let key = self.end_key(node.into(), other.into())?;
        self.endings.get(&key)
    }

    /// Where the end of what `node` says about `other` is kept: under the
    /// entry, or under the node sharing `node`'s record it was given
    /// through; `None` if the entry is timeless or there is none.
    pub(super) fn end_key(&self, node: Node, other: Node) -> Option<(Node, Node)> {
        if self.specific(node, other) == CollisionRule::Defer {
            return None;
        }
        if self.endings.contains_key(&(node, other)) {
            return Some((node, other));
        }
        // A record with one user keeps its ends under it (see
        // `endings_leave`): nothing to look for.
        let record = self.record_id(node)?;
        if self.records.get(record).users < 2 {
            return None;
        }
        self.endings
            .iter()
            .find(|((n, o), _)| *o == other && self.record_id(*n) == Some(record))
            .map(|(key, _)| key)
    }

    /// Forgets the end of the entry of `node`'s record about `other`, given
    /// through `node` or any node sharing its record: the entry changed.
    pub(super) fn forget_ending(&mut self, node: Node, other: Node) {
        if self.endings.is_empty() {
            return;
        }
        match self.record_id(node) {
            // A record shared: the end may have been given through another
            // of its users. A record with one user keeps its ends under it
            // (see `endings_leave`).
            Some(record) if self.records.get(record).users > 1 => {
                let ids: Vec<(Node, Node)> = self
                    .endings
                    .iter()
                    .map(|(key, _)| key)
                    .filter(|(n, o)| *o == other && (*n == node || self.record_id(*n) == Some(record)))
                    .collect();
                for key in ids {
                    self.endings.remove(&key);
                }
            }
            _ => {
                self.endings.remove(&(node, other));
            }
        }
    }

    /// `node` left record `id` (it shares another's now, or carries none),
    /// which it still counts among its users: the ends given through it go
    /// to the record's first other user, whose sides are tested from now
    /// on, or with the record if nobody is left. The ends are looked up by
    /// the record's entries, not among every end (an end whose entry went
    /// another way is dropped by the hooks' count).
    pub(super) fn endings_leave(&mut self, node: Node, id: super::records::RecordId) {
        if self.endings.is_empty() || self.record_id(node) == Some(id) {
            return;
        }
        let record = self.records.get(id);
        // A ball's record holds one entry: no allocation for a handful.
        let keys: SmallVec<[(Node, Node); 4]> = record
            .specific
            .keys()
            .map(|&other| (node, other))
            .filter(|key| self.endings.contains_key(key))
            .collect();
        if keys.is_empty() {
            return;
        }
        let heir = if record.users > 1 {
            self.nodes().filter(|&n| self.record_id(n) == Some(id)).min()
        } else {
            None
        };
        for key in keys {
            match heir {
                Some(heir) => self.endings.hand_over(key, (heir, key.1)),
                None => {
                    self.endings.remove(&key);
                }
            }
        }
    }

    /// Counts a step of `dt`: returns the entries whose end has come or
    /// comes once their sides are apart, with the end's margin, in the
    /// node order, and forgets on the way the ends whose entry went another
    /// way (its object left, say). Costs the ends that came, not every end
    /// (`docs/architecture.md`, "Cost per step").
    pub(crate) fn count_ends(&mut self, dt: Real) -> Vec<DueEnd> {
        let mut endings = std::mem::take(&mut self.endings);
        let due = endings.count(dt, |node, other| self.end_holds((node, other)));
        self.endings = endings;
        due
    }

    /// Whether the entry of an end is still held: the end of an entry that
    /// went another way (with a removed object, say) ends nothing, and is
    /// neither counted, nor saved, nor loaded.
    pub(super) fn end_holds(&self, (node, other): (Node, Node)) -> bool {
        self.specific(node, other).is_decided()
    }

    /// Whether any entry has an end.
    pub(crate) fn has_endings(&self) -> bool {
        !self.endings.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::{Countdown, Due, Real, Until};

    #[test]
    fn steps_hold_for_exactly_their_count() {
        let mut until = Countdown::new(Until::steps(2));
        assert_eq!(until.count_step(0.1), None);
        assert_eq!(until.count_step(0.1), None);
        assert_eq!(until.count_step(0.1), Some(Due::IfApart));
        assert_eq!(until.count_step(0.1), Some(Due::IfApart), "a due count stays due");
        assert_eq!(until.until().steps_left(), Some(0));
    }

    /// How many steps of `dt` a time holds, counted from `Until::seconds`.
    fn held(seconds: f32, dt: f32) -> usize {
        let mut until = Countdown::new(Until::seconds(seconds).even_if_overlapping());
        (0..100_000).take_while(|_| until.count_step(dt).is_none()).count()
    }

    #[test]
    fn seconds_round_to_the_nearest_step() {
        let dt = 1.0 / 60.0;
        for (seconds, steps) in [(0.5, 30), (0.51, 31), (0.505, 30), (0.0, 0), (0.01, 1)] {
            let held = held(seconds, dt);
            assert_eq!(held, steps, "Until::seconds({seconds}) at 60 Hz held {held} steps");
        }
    }

    /// A time that falls on a half step holds that step, whatever the
    /// `f32` rounding of the time and of `dt` (7.5 steps of 1/60 s hold 8).
    #[test]
    fn a_half_step_holds_the_step() {
        for (seconds, hz, steps) in [(0.125, 60.0, 8), (0.075, 60.0, 5), (0.725, 60.0, 44), (0.25, 30.0, 8), (0.13, 50.0, 7)]
        {
            let held = held(seconds, 1.0 / hz);
            assert_eq!(held, steps, "Until::seconds({seconds}) at {hz} Hz held {held} steps");
        }
        // Far from a half, a long time is counted without drift: 5.441 s
        // at 144 Hz is 783.5 steps and a little more.
        assert_eq!(held(5.441, 1.0 / 144.0), 784);
    }

    /// The half step holds for counts up to 8,000 steps, at any common
    /// rate; past about that, the `f32` rounding of the time and of `dt`
    /// may pass [`HALF_STEP_SLACK`] and decide (`docs/semantics.md`,
    /// "Rules with an end").
    #[test]
    fn a_half_step_holds_for_counts_up_to_8000_steps() {
        for hz in [30.0f32, 50.0, 60.0, 120.0, 144.0, 240.0] {
            for k in (0..8_000u32).step_by(97).chain([7_999]) {
                let seconds = (k as f32 + 0.5) / hz;
                let held = held(seconds, 1.0 / hz);
                assert_eq!(held, k as usize + 1, "Until::seconds({seconds}) at {hz} Hz, {k}.5 steps, held {held}");
            }
        }
        // 10,985.5 steps at 60 Hz: the rounding is 1.3 thousandths of a step.
        assert_eq!(held(10_985.5 / 60.0, 1.0 / 60.0), 10_985);
    }

    /// What is left, given again as a new end (by a project that reads
    /// `specific_until` and gives it to another entry), comes at the step
    /// the end would have come.
    #[test]
    fn what_is_left_comes_when_the_end_would_have() {
        for hz in [30.0f32, 50.0, 60.0, 144.0] {
            let dt = 1.0 / hz;
            for millis in 0..2_000 {
                let seconds = millis as f32 / 1_000.0;
                let whole = held(seconds, dt);
                for counted in [1, 3, whole.saturating_sub(1)] {
                    let mut until = Countdown::new(Until::seconds(seconds).even_if_overlapping());
                    for _ in 0..counted {
                        until.count_step(dt);
                    }
                    let mut again = Countdown::new(until.until());
                    let rest = (0..100_000).take_while(|_| again.count_step(dt).is_none()).count();
                    assert_eq!(
                        counted.min(whole) + rest,
                        whole,
                        "Until::seconds({seconds}) at {hz} Hz, given again after {counted} steps"
                    );
                }
            }
        }
    }

    #[test]
    fn apart_is_due_at_once() {
        assert_eq!(Countdown::new(Until::apart()).count_step(0.1), Some(Due::IfApart));
    }

    #[test]
    #[should_panic(expected = "must be a finite number of seconds")]
    fn a_negative_time_is_refused() {
        let _ = Until::seconds(-1.0);
    }

    /// An infinite time or margin never ends, and a save cannot hold it
    /// (JSON writes it as `null`, which does not load).
    #[test]
    fn an_infinite_time_or_margin_is_refused() {
        let refused = |make: fn() -> Until| std::panic::catch_unwind(make).is_err();
        assert!(refused(|| Until::seconds(Real::INFINITY)), "an infinite time");
        assert!(refused(|| Until::seconds(Real::NAN)), "a time that is no number");
        assert!(refused(|| Until::apart().with_margin(Real::INFINITY)), "an infinite margin");
        assert!(!refused(|| Until::seconds(Real::MAX).with_margin(Real::MAX)), "a finite one");
    }

    #[test]
    #[should_panic(expected = "nothing else to wait for")]
    fn apart_cannot_end_while_overlapping() {
        let _ = Until::apart().even_if_overlapping();
    }
}
