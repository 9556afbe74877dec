//! The saved form of a rule set (feature `serde`): the group table, the
//! default rule, each record with the nodes that use it, and the parent map.
//! Handles are saved as Rapier saves them, so a rule set is saved and loaded
//! together with the Rapier sets it belongs to.

use super::super::rapier::prelude::{ColliderHandle, RigidBodyHandle};
use serde::{Deserialize, Serialize};

use super::super::{CollisionGroup, CollisionRule, CollisionRuleSet, Node, OneWay, RuleError, Until};
use super::decision::Decision;
use super::ending::Clock;
use super::endings::{Endings, SavedEnd, clock_is_valid};
use super::written::Written;

/// Why a saved rule set was refused: what no rule set of this crate holds,
/// so what only a damaged or hand-edited save can say. A refused load builds
/// nothing.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum LoadError {
    /// The saved group count leaves no group to create.
    #[error("saved group count {count}: no group could be created")]
    GroupCount {
        /// The saved count.
        count: u32,
    },
    /// A group (of a node or of a table entry) past the saved count: a
    /// later `create_group` would hand it out again.
    #[error("saved group {} is past the group count {count}", group.id())]
    GroupPastCount {
        /// The group.
        group: CollisionGroup,
        /// The saved count.
        count: u32,
    },
    /// A node in two records, or twice in one.
    #[error("saved node {node:?} uses more than one record")]
    SharedTwice {
        /// The node.
        node: Node,
    },
    /// A body with two parents.
    #[error("saved body {child:?} has more than one parent")]
    TwoParents {
        /// The body.
        child: RigidBodyHandle,
    },
    /// The end of an entry with a negative or not-a-number margin or a
    /// time that is not finite (`Until` refuses them when built), an end
    /// at apart that has not come (it comes when given), or one given at a
    /// reading of the ends' clock that no count reaches or past the
    /// clock's own.
    #[error(
        "saved end of the entry of {node:?} about {other:?} has a negative or NaN margin or an \
         infinite or NaN time, waits to count to apart, or was given after the saved clock"
    )]
    BadEnd {
        /// The node holding the entry.
        node: Node,
        /// The node the entry is about.
        other: Node,
    },
    /// The ends' clock has a negative or not-a-number time, or more steps
    /// than any run counts: no steps count to it.
    #[error("saved clock of the ends has a negative or NaN time, or more steps than a run counts")]
    BadEndsClock,
    /// A one-way setting whose normal is not of length 1 or whose angle is
    /// not between 0 and pi: `OneWay` refuses them when built.
    #[error("saved one-way setting of {node:?} has a normal not of length 1 or an angle out of 0..=pi")]
    BadOneWay {
        /// A node of the record.
        node: Node,
    },
    /// The parent map refused a saved link (a cycle, a body as its own
    /// parent).
    #[error("saved parent map: {0}")]
    ParentMap(RuleError),
    /// What the saving hooks had written is saved twice for one collider
    /// (its slot): only one can be what the collider holds.
    #[error("saved writes name collider {collider:?} (or its slot) more than once")]
    WrittenTwice {
        /// The collider.
        collider: ColliderHandle,
    },
    /// A saved decision that no hooks make: of an entry decided twice or
    /// whose nodes are out of order, a side that is not one of the entry's
    /// nodes, a kind or bit out of range, or a node on two bits of one
    /// kind. Loaded, it would panic at the first step or change pairs the
    /// rules do not name.
    #[error("saved decision of the entry of {node:?} and {other:?}: {why}")]
    BadDecision {
        /// The entry's first node.
        node: Node,
        /// The entry's other node.
        other: Node,
        /// What is wrong with it.
        why: &'static str,
    },
}

/// The end of the entry of `node` about `other`.
#[derive(Clone, Copy, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct SavedEnding {
    node: Node,
    other: Node,
    /// As given.
    until: Until,
    /// The reading of the ends' clock when it was given.
    given: Clock,
    /// Its count came.
    came: bool,
}

impl SavedEnding {
    fn end(&self) -> SavedEnd {
        let SavedEnding { until, given, came, .. } = *self;
        SavedEnd { until, given, came }
    }
}

/// One rule record and the nodes that share it.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct SavedRecord {
    users: Vec<Node>,
    personal: CollisionRule,
    group: Option<CollisionGroup>,
    specific: Vec<(Node, CollisionRule)>,
    /// Absent from saves made before one-way surfaces.
    #[serde(default)]
    one_way: Option<OneWay>,
}

/// A rule set as saved (feature `serde`): what a rule set serializes into,
/// read back without being checked. Deserializing a [`CollisionRuleSet`]
/// checks it at once and reports a refusal through the format's error as
/// text; deserializing a `SavedRuleSet` and converting it with
/// `CollisionRuleSet::try_from` gives the refusal as a typed [`LoadError`].
///
/// A field this version does not know is refused (`unknown field`): a save
/// made by a later version, whose rules this one would drop in silence, is
/// not loaded. Fields added since the first saves are optional, so earlier
/// saves load.
///
/// ```
/// use rapier_collision_rules::{CollisionRule, CollisionRuleSet, LoadError, SavedRuleSet};
///
/// let mut rules = CollisionRuleSet::default();
/// let group = rules.create_group();
/// rules.set_group_rule(group, group, CollisionRule::NoPair);
/// let mut saved = serde_json::to_value(&rules).expect("saved");
/// saved["group_rules"][0][0] = serde_json::json!(99); // damaged
///
/// let saved: SavedRuleSet = serde_json::from_value(saved).expect("well formed");
/// match CollisionRuleSet::try_from(saved) {
///     Err(LoadError::GroupPastCount { group, count }) => assert_eq!((group.id(), count), (99, 3)),
///     other => panic!("{other:?}"),
/// }
/// ```
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SavedRuleSet {
    default_rule: CollisionRule,
    group_count: u32,
    group_rules: Vec<(CollisionGroup, CollisionGroup, CollisionRule)>,
    records: Vec<SavedRecord>,
    parents: Vec<(RigidBodyHandle, RigidBodyHandle)>,
    /// The ends of entries given one, each as given with the reading of
    /// the ends' clock then (absent from saves made before rules had ends).
    #[serde(default)]
    endings: Vec<SavedEnding>,
    /// The ends' clock: the steps and the simulated time counted since the
    /// set was made, so that a loaded set counts every end on from the same
    /// bits as the set never saved (absent as `endings`).
    #[serde(default)]
    ends_clock: Clock,
    /// What the hooks that held the set had written on each collider, and
    /// the project's own settings under it: hooks given the set with the
    /// world saved beside it tell the crate's writes from the project's
    /// settings (`docs/semantics.md`, "Saving and loading"). Absent from
    /// saves made before it was saved.
    #[serde(default)]
    writes: Vec<(ColliderHandle, Written)>,
    /// How those hooks decided each specific entry (absent as `writes`).
    #[serde(default)]
    decisions: Vec<(Node, Node, Decision)>,
}

impl From<CollisionRuleSet> for SavedRuleSet {
    fn from(rules: CollisionRuleSet) -> SavedRuleSet {
        let mut records: Vec<(super::records::RecordId, SavedRecord)> = Vec::new();
        for node in rules.nodes() {
            let id = rules.record_id(node).expect("a listed node has a record");
            match records.iter_mut().find(|(r, _)| *r == id) {
                Some((_, saved)) => saved.users.push(node),
                None => {
                    let record = rules.records.get(id);
                    let mut specific: Vec<_> =
                        record.specific.iter().map(|(&n, &r)| (n, r)).collect();
                    specific.sort_by_key(|&(n, _)| n);
                    records.push((
                        id,
                        SavedRecord {
                            users: vec![node],
                            personal: record.personal,
                            group: record.group,
                            specific,
                            one_way: record.one_way,
                        },
                    ));
                }
            }
        }
        let mut group_rules: Vec<_> = rules.group_rules().collect();
        group_rules.sort();
        let mut parents: Vec<_> = rules.parents().collect();
        parents.sort_by_key(|(c, _)| c.into_raw_parts());
        // An end whose entry went with a removed object is not saved: the
        // count drops it when it comes, the save at once.
        // In the node order, the endings' own.
        let endings: Vec<_> = rules
            .endings
            .saved()
            .filter(|&(key, _)| rules.end_holds(key))
            .map(|((node, other), SavedEnd { until, given, came })| SavedEnding {
                node,
                other,
                until,
                given,
                came,
            })
            .collect();
        let writes = rules.writes.iter().map(|(h, &w)| (h, w)).collect();
        let mut decisions: Vec<_> = rules.decisions.iter().map(|(&(n, o), &d)| (n, o, d)).collect();
        decisions.sort_by_key(|&(n, o, _)| (n, o));
        SavedRuleSet {
            default_rule: rules.default_rule(),
            group_count: rules.group_count(),
            group_rules,
            records: records.into_iter().map(|(_, r)| r).collect(),
            parents,
            endings,
            ends_clock: rules.endings.clock(),
            writes,
            decisions,
        }
    }
}

impl SavedRuleSet {
    /// What no saved rule set of this crate holds: a group past the saved
    /// count (a later `create_group` would hand it out again), a node in two
    /// records or twice in one, a body with two parents. A parent cycle is
    /// refused by `set_parent` while loading. Checked before anything is
    /// built, so that a refused load is an error naming the problem, never a
    /// panic or a rule set that breaks later.
    fn check(&self) -> Result<(), LoadError> {
        let count = self.group_count.max(2);
        if count == u32::MAX {
            return Err(LoadError::GroupCount { count });
        }
        let known = |g: CollisionGroup| {
            if g.id() < count {
                Ok(())
            } else {
                Err(LoadError::GroupPastCount { group: g, count })
            }
        };
        for &(a, b, _) in &self.group_rules {
            known(a)?;
            known(b)?;
        }
        let mut users = hashbrown::HashSet::new();
        for record in &self.records {
            if let Some(group) = record.group {
                known(group)?;
            }
            if let Some(&user) = record.users.first().filter(|_| record.one_way.is_some_and(|w| !w.is_valid())) {
                return Err(LoadError::BadOneWay { node: user });
            }
            for &user in &record.users {
                if !users.insert(user) {
                    return Err(LoadError::SharedTwice { node: user });
                }
            }
        }
        let clock = self.ends_clock;
        if !clock_is_valid(clock) {
            return Err(LoadError::BadEndsClock);
        }
        if let Some(&SavedEnding { node, other, .. }) = self.endings.iter().find(|e| !e.end().is_valid(clock)) {
            return Err(LoadError::BadEnd { node, other });
        }
        let mut children = hashbrown::HashSet::new();
        for &(child, _) in &self.parents {
            if !children.insert(child) {
                return Err(LoadError::TwoParents { child });
            }
        }
        let mut slots = hashbrown::HashSet::new();
        for &(collider, _) in &self.writes {
            if !slots.insert(collider.into_raw_parts().0) {
                return Err(LoadError::WrittenTwice { collider });
            }
        }
        check_decisions(&self.decisions)
    }
}

/// What the planner's decisions always are (`planner/decisions.rs`): each
/// entry decided once, its nodes in the node order (one node twice for an
/// entry of a node about itself), with its own nodes as sides; a `Bits`
/// decision of kind 0 or 1 on one of the 32 bits, between two nodes; one
/// bit per node for each role and kind. Not which nodes share a bit: the
/// decisions a world saved alone gets from its marks may give a hooked
/// node a bit no entry pairs with every other node on it.
fn check_decisions(decisions: &[(Node, Node, Decision)]) -> Result<(), LoadError> {
    use hashbrown::{HashMap, HashSet};
    let mut entries = HashSet::new();
    // (node, carries, kind) -> bit
    let mut bits: HashMap<(Node, bool, usize), u32> = HashMap::new();
    for &(node, other, decision) in decisions {
        let bad = |why| Err(LoadError::BadDecision { node, other, why });
        // An entry of a node about itself (a robot's root, so that its
        // links ignore each other) is one node twice.
        if node > other {
            return bad("its nodes are not in the node order");
        }
        if !entries.insert((node, other)) {
            return bad("decided more than once");
        }
        match decision {
            Decision::Hooked { side } if side != node && side != other => {
                return bad("its hooked side is not one of its nodes");
            }
            Decision::Hooked { .. } => {}
            Decision::Bits {
                carrying,
                other: sharing,
                kind,
                bit,
            } => {
                if (carrying, sharing) != (node, other) && (carrying, sharing) != (other, node)
                    || node == other
                {
                    return bad("its bit's sides are not its two nodes");
                }
                if kind > 1 || bit > 31 {
                    return bad("a kind past 1 or a bit past 31");
                }
                for (side, carries) in [(carrying, true), (sharing, false)] {
                    if *bits.entry((side, carries, kind)).or_insert(bit) != bit {
                        return bad("a node on two bits of one kind");
                    }
                }
            }
        }
    }
    Ok(())
}

impl TryFrom<SavedRuleSet> for CollisionRuleSet {
    type Error = LoadError;

    fn try_from(saved: SavedRuleSet) -> Result<CollisionRuleSet, LoadError> {
        saved.check()?;
        let mut rules = CollisionRuleSet::default();
        rules.groups.restore(saved.group_count, saved.group_rules);
        rules.set_default_rule(saved.default_rule);
        for record in saved.records {
            let Some(&first) = record.users.first() else {
                continue;
            };
            rules.set_personal(first, record.personal);
            rules.set_group(first, record.group);
            rules.set_one_way(first, record.one_way);
            for (other, rule) in record.specific.into_iter().filter(|(_, r)| r.is_decided()) {
                rules.put_specific(first, other, rule);
            }
            for &user in &record.users[1..] {
                rules.share_rules(first, user);
            }
        }
        for (child, parent) in saved.parents {
            match rules.set_parent(child, parent) {
                // A link naming an object whose slot the save also names at
                // another generation: the link changes no chain (it ends
                // below a body missing from the world), and the hooks
                // would forget it at the next step. Skipped, as entries
                // about such objects are.
                Ok(()) | Err(RuleError::Removed { .. }) => {}
                Err(e) => return Err(LoadError::ParentMap(e)),
            }
        }
        // An end of an entry the save does not hold ends nothing.
        let held: Vec<_> = saved
            .endings
            .into_iter()
            .filter(|e| rules.end_holds((e.node, e.other)))
            .map(|e| ((e.node, e.other), e.end()))
            .collect();
        rules.endings = Endings::restored(saved.ends_clock, held);
        for (collider, written) in saved.writes {
            rules.writes.insert_evicting(collider, written);
        }
        rules.decisions = saved.decisions.into_iter().map(|(n, o, d)| ((n, o), d)).collect();
        // Put in place of a rule set the hooks hold (`*hooks.rules_mut() =
        // loaded`), it is another set (`model/identity.rs`): every pair and
        // plan is looked at again.
        Ok(rules)
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::rapier::prelude::{Real, RigidBodyHandle};
    use super::super::super::{CollisionRule, CollisionRuleSet, Until};

    /// For each step up to `horizon`, whether the end of an entry given
    /// `until` is due, in a set counted in steps of `dt` from `before`
    /// steps before it was given: never saved, or saved through serde and
    /// loaded before step `save_at`.
    fn due_steps(until: Until, dt: Real, before: usize, horizon: usize, save_at: Option<usize>) -> Vec<bool> {
        let (a, b) = (RigidBodyHandle::from_raw_parts(0, 0), RigidBodyHandle::from_raw_parts(1, 0));
        let mut rules = CollisionRuleSet::default();
        for _ in 0..before {
            rules.count_ends(dt);
        }
        rules.set_specific_until(a, b, CollisionRule::NoPair, until);
        (0..horizon)
            .map(|step| {
                if Some(step) == save_at {
                    let saved = serde_json::to_string(&rules).expect("a rule set saves");
                    rules = serde_json::from_str(&saved).expect("a saved rule set loads");
                }
                !rules.count_ends(dt).is_empty()
            })
            .collect()
    }

    /// Found by a sweep of a rollback trial: a save held what was left of a
    /// time, rounded to a `Real`, and a time a few of its last bits from
    /// where a step holds it or not (a half step, less the slack of
    /// `HALF_STEP_SLACK`) ended a step apart from the set never saved at
    /// some save points. A save now holds each end as given, with the
    /// clock it counts by. Saved before its end came and after, ending
    /// even if overlapping or once apart.
    #[test]
    fn an_end_saved_at_any_step_comes_at_the_step_of_the_set_never_saved() {
        let mut checked = 0;
        for dt in [1.0 / 60.0, 1.0 / 144.0] {
            for n in 1..24u16 {
                let edge = (f64::from(n) + 0.499) * f64::from(dt);
                for bits in -12..=12 {
                    let seconds = f32::from_bits((edge as f32).to_bits().wrapping_add_signed(bits));
                    for until in [Until::seconds(seconds), Until::seconds(seconds).even_if_overlapping()] {
                        let horizon = usize::from(n) + 3;
                        let never = due_steps(until, dt, 7, horizon, None);
                        assert!(never.contains(&true), "{until:?} came within {horizon} steps");
                        for save_at in 0..horizon {
                            let saved = due_steps(until, dt, 7, horizon, Some(save_at));
                            assert_eq!(
                                saved, never,
                                "{until:?} in steps of {dt}, saved before step {save_at}: due at \
                                 the steps marked, not as never saved"
                            );
                            checked += 1;
                        }
                    }
                }
            }
        }
        assert!(checked > 30_000, "{checked} save points");
    }

    /// Found by a review: a clock past a few thousand steps has a time
    /// whose decimal `serde_json` (without `float_roundtrip`) reads back
    /// one bit off, and an end near the edge of a step then came a step
    /// early. The clock's time is saved as its bits.
    #[test]
    fn a_clock_saved_after_many_steps_counts_on_from_the_same_bits() {
        let dt = f32::from_bits(0x3d45_3460);
        let until = Until::seconds(f32::from_bits(0x3e5d_ce4d)).even_if_overlapping();
        let never = due_steps(until, dt, 9_994, 8, None);
        assert_eq!(never.iter().position(|&due| due), Some(5), "{never:?}");
        for save_at in 0..8 {
            assert_eq!(due_steps(until, dt, 9_994, 8, Some(save_at)), never, "saved before step {save_at}");
        }
    }
}
