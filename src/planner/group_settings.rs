//! The group-level half of a plan: which groups get a bit, the filters of
//! each, which take every collision type, and which need the hook.

use hashbrown::{HashMap, HashSet};
use super::super::rapier::prelude::*;

use super::class::Class;
use super::collider_plan::ColliderPlan;
use super::plan::Request;
use super::room::Room;
use super::super::{CollisionGroup, CollisionRule, CollisionRuleSet};

/// Whether the default rule refuses a pair or keeps its contacts out: what
/// pairs of non-dynamic bodies get where the project's types let Rapier
/// see them (see `CollisionRuleSet::by_kinematic_entry`), which Rapier's
/// own handling of such pairs (contacts, no response) does not say.
pub(super) fn default_refuses(rules: &CollisionRuleSet) -> bool {
    !matches!(
        rules.default_rule(),
        CollisionRule::Normal | CollisionRule::NoResponse | CollisionRule::Defer
    )
}

/// The group-level half of a plan: which groups get a bit, the filters of
/// each, which take every collision type, and which need the hook.
pub(super) struct GroupSettings {
    /// Whether each group used has dynamic and non-dynamic members.
    pub(super) members: HashMap<CollisionGroup, (bool, bool)>,
    pub(super) bits: HashMap<CollisionGroup, u32>,
    pub(super) involved: HashSet<CollisionGroup>,
    pub(super) needs_hook: HashSet<CollisionGroup>,
    pub(super) static_types: HashSet<CollisionGroup>,
    pub(super) filters: HashMap<CollisionGroup, (Group, Group)>,
    /// A `NoPair` relation is left to Rapier's default collision types.
    pub(super) relies_on_types: bool,
}

impl GroupSettings {
    /// The settings of the groups of `classes`, with the two default
    /// classes always counted as used: every collider no rule reaches is in
    /// one of them. Bits are taken from `room` (what the project's settings
    /// leave), from the highest down, away from the low bits projects
    /// usually name their layers with.
    ///
    /// A group the table relates that has no member yet counts as having a
    /// dynamic one, so that it has its bit, and the groups it relates to
    /// their filters, before its first member comes: Rapier looks again at
    /// every pair of a collider whose groups are rewritten, which wakes the
    /// bodies resting on it, and the first member of a group would otherwise
    /// rewrite every collider of the groups it relates to (the floor under
    /// a sleeping pile). Where the bits would not fit with those groups
    /// counted, only the groups with members are (`docs/architecture.md`,
    /// "The planner").
    pub(super) fn new(
        request: &Request<'_>,
        classes: impl Iterator<Item = Class>,
        room: Room,
    ) -> GroupSettings {
        let rules = request.rules;
        let mut members: HashMap<CollisionGroup, (bool, bool)> = HashMap::new();
        let defaults = [Class::unreached(true), Class::unreached(false)];
        for class in classes.chain(defaults) {
            let entry = members.entry(class.group).or_default();
            if class.dynamic {
                entry.0 = true;
            } else {
                entry.1 = true;
            }
        }
        // Most plans have no memberless group in the table: no copy then.
        let memberless = |g: &CollisionGroup| !members.contains_key(g);
        let waiting = rules
            .groups
            .iter()
            .any(|(a, b, rule)| rule.is_decided() && (memberless(&a) || memberless(&b)));
        if waiting {
            let mut awaiting = members.clone();
            for (a, b, rule) in rules.groups.iter() {
                if rule.is_decided() {
                    for g in [a, b] {
                        awaiting.entry(g).or_insert((true, false));
                    }
                }
            }
            let settings = GroupSettings::of_members(request, awaiting, room);
            if settings.bits.len() == settings.involved.len() {
                return settings;
            }
        }
        GroupSettings::of_members(request, members, room)
    }

    /// The settings of the groups in `members`, with whether each has
    /// dynamic and non-dynamic members.
    fn of_members(
        request: &Request<'_>,
        members: HashMap<CollisionGroup, (bool, bool)>,
        room: Room,
    ) -> GroupSettings {
        let rules = request.rules;
        let mut used: Vec<CollisionGroup> = members.keys().copied().collect();
        used.sort_unstable();
        let group_rule = |a: CollisionGroup, b: CollisionGroup| {
            let rule = rules.group_rule(a, b);
            if rule.is_decided() {
                rule
            } else {
                rules.default_rule()
            }
        };
        let relations: Vec<(CollisionGroup, CollisionGroup, CollisionRule)> = used
            .iter()
            .flat_map(|&a| used.iter().map(move |&b| (a, b)))
            .map(|(a, b)| (a, b, group_rule(a, b)))
            .collect();
        // A group with a NoContacts relation needs the hook: the pair must
        // exist without contacts, which no group test can say; so does a
        // NoResponse that Rapier's groups cannot say (soft bodies).
        let needs_hook: HashSet<CollisionGroup> = relations
            .iter()
            .filter(|&&(_, _, rule)| rule == CollisionRule::NoContacts || !request.native_rule(rule))
            .flat_map(|&(a, b, _)| [a, b])
            .collect();
        let has_dynamic = |g: CollisionGroup| members[&g].0;
        let has_static = |g: CollisionGroup| members[&g].1;
        // Rapier pairs two non-dynamic colliders when either side's collision
        // types allow it. Where two groups' non-dynamic members may pair
        // (their rule is not NoPair), one side takes every type: the side
        // that is not a default group, so that colliders no rule reaches
        // keep Rapier's defaults; both sides between two created groups.
        let default_group = |g: CollisionGroup| {
            g == CollisionGroup::DEFAULT_DYNAMIC || g == CollisionGroup::DEFAULT_KINEMATIC
        };
        let mut static_types = HashSet::new();
        for &(a, b, rule) in &relations {
            if rule == CollisionRule::NoPair || !has_static(a) || !has_static(b) {
                continue;
            }
            match (default_group(a), default_group(b)) {
                (false, true) => static_types.insert(a),
                (true, false) => static_types.insert(b),
                _ => {
                    static_types.insert(a);
                    static_types.insert(b)
                }
            };
        }
        let filtered_by_types = |g: CollisionGroup| !has_dynamic(g) && !static_types.contains(&g);
        // The (DEFAULT_KINEMATIC, DEFAULT_KINEMATIC) entry gives way to a
        // project's wider collision types (`docs/semantics.md`, "The project's own settings"), so
        // Rapier's type test decides those pairs whatever the project set.
        let kinematic_entry = |a: CollisionGroup, b: CollisionGroup| {
            a == CollisionGroup::DEFAULT_KINEMATIC && b == CollisionGroup::DEFAULT_KINEMATIC
        };
        let by_types = |a: CollisionGroup, b: CollisionGroup| {
            filtered_by_types(a) && filtered_by_types(b) && !kinematic_entry(a, b)
        };
        let relies_on_types = relations
            .iter()
            .any(|&(a, b, rule)| rule == CollisionRule::NoPair && by_types(a, b));
        let needs_bits = |a: CollisionGroup, b: CollisionGroup, rule: CollisionRule| match rule {
            // A project type that pairs non-dynamic bodies undoes the test by
            // types: bits then say it.
            CollisionRule::NoPair => {
                !(filtered_by_types(a) && filtered_by_types(b)) || (room.widened && by_types(a, b))
            }
            // Only a dynamic body responds: other pairs need no solver test.
            CollisionRule::NoResponse => has_dynamic(a) || has_dynamic(b),
            _ => false,
        };
        let mut involved: Vec<CollisionGroup> = relations
            .iter()
            .filter(|&&(a, b, _)| !needs_hook.contains(&a) && !needs_hook.contains(&b))
            .filter(|&&(a, b, rule)| needs_bits(a, b, rule))
            .flat_map(|&(a, b, _)| [a, b])
            .collect::<HashSet<_>>()
            .into_iter()
            .collect();
        involved.sort_unstable();
        // One bit per involved group while they fit; the rest fall back to
        // hooks. A group with no relation to test keeps every bit as its
        // membership (a collider's default), which no filter leaves out.
        let free = (0..32u32)
            .rev()
            .filter(|&bit| room.bits().contains(Group::from_bits_retain(1 << bit)));
        let bits: HashMap<CollisionGroup, u32> = involved.iter().copied().zip(free).collect();
        let filter_of = |g: CollisionGroup, excluded: CollisionRule| {
            let mut filter = Group::ALL;
            for (&h, &bit) in &bits {
                if group_rule(g, h) == excluded && needs_bits(g, h, excluded) {
                    filter.remove(Group::from_bits_retain(1 << bit));
                }
            }
            filter
        };
        let filters = used
            .iter()
            .map(|&g| {
                let filters = (
                    filter_of(g, CollisionRule::NoPair),
                    filter_of(g, CollisionRule::NoResponse),
                );
                (g, filters)
            })
            .collect();
        GroupSettings {
            members,
            relies_on_types,
            bits,
            involved: involved.into_iter().collect(),
            needs_hook,
            static_types,
            filters,
        }
    }

    /// The plan of a native collider of `class`; `None` if its group needs
    /// the hook (a `NoContacts` relation, or past the 32 bits).
    pub(super) fn entry(&self, class: Class) -> Option<ColliderPlan> {
        let g = class.group;
        let fits = self.bits.contains_key(&g) || !self.involved.contains(&g);
        if self.needs_hook.contains(&g) || !fits || !self.members.contains_key(&g) {
            return None;
        }
        let membership = self
            .bits
            .get(&g)
            .map_or(Group::ALL, |&bit| Group::from_bits_retain(1 << bit));
        let (collision, solver) = self.filters[&g];
        let types = if class.dynamic || !self.static_types.contains(&g) {
            ActiveCollisionTypes::default()
        } else {
            ActiveCollisionTypes::all()
        };
        // A group's bit narrows only the groups that test it: its collision
        // groups when a NoPair relation leaves a bit out of its filter (the
        // relation is symmetric, so then the other side leaves its bit out
        // too), its solver groups likewise for NoResponse. The other kind
        // stays Rapier's default, which the project's own settings replace.
        let narrowed = |filter: Group| {
            if filter == Group::ALL {
                InteractionGroups::all()
            } else {
                InteractionGroups::new(membership, filter, InteractionTestMode::And)
            }
        };
        Some(ColliderPlan {
            class: Some(class),
            collision: narrowed(collision),
            solver: narrowed(solver),
            types,
        })
    }

    /// Whether the plan shares something with the project's settings (group
    /// bits, or the default collision types as a filter), so that these
    /// must be looked at over the whole world.
    pub(super) fn needs_room(&self) -> bool {
        !self.involved.is_empty() || self.relies_on_types
    }

    /// Whether a rule reaches the default groups: their plan is not
    /// Rapier's defaults, so every collider must be planned.
    pub(super) fn reaches_defaults(&self) -> bool {
        [Class::unreached(true), Class::unreached(false)]
            .into_iter()
            .any(|class| !self.entry(class).is_some_and(|e| e.is_rapier_default()))
    }
}
