//! What Rapier can test itself. The planner gives each collider the
//! cheapest mechanism that decides all of its pairs exactly: collision
//! groups for group-level `NoPair`, solver groups for group-level
//! `NoResponse`, active collision types for pairs of non-dynamic bodies, and
//! the hook flag only where a pair needs a decision per pair
//! (`docs/architecture.md`, "The planner").
//!
//! A collider is *native* when its pairs with every other native collider
//! are a function of two small facts about each side: its effective group
//! and whether its body is dynamic. That holds when no node of its chain
//! carries a personal rule, every node of its chain has the same effective
//! group, and every specific entry that could reach its pairs is carried by
//! a hooked collider on the other side: then the specific and personal
//! stages defer, every step of the group stage compares the same two groups,
//! and the rule is `table[g1, g2]`, else the default, then the special case
//! of `docs/semantics.md`. A collider of a dynamic body whose chain's
//! personal rules all say one `Normal`, `NoResponse` or `NoPair` is native
//! too, where Rapier's test gives its pairs that rule (see
//! [`native_personal`]). A pair with a hooked collider is decided by the
//! hook, so hooked colliders carry permissive groups and pass every native
//! test.
//!
//! Only the colliders the rules reach are planned. Every other collider is
//! in a default group (`DEFAULT_DYNAMIC` or `DEFAULT_KINEMATIC`) and keeps
//! Rapier's own settings, which already say `Normal`, and no pair between two
//! non-dynamic bodies (the built-in table entry): as long as the default
//! groups' plans are Rapier's defaults, the planner needs nothing of them.
//! When a rule reaches the default groups, every collider is planned (a
//! [`FullPass`]).

use hashbrown::{HashMap, HashSet};
use super::super::rapier::prelude::*;

use super::carriers::pinned_carriers;
use super::class::{Class, native_class};
use super::collider_plan::ColliderPlan;
use super::decisions::{Base, Decisions, Facts};
use super::group_settings::{GroupSettings, default_refuses};
use super::personal::{PersonalDepths, first_personal, native_personal};
use super::room::Room;
use super::super::model::{HandleMap, dynamic_body};
use super::super::world::{PairKey, Settings};
use super::super::{CollisionRule, CollisionRuleSet, FullPass, Node};

/// The plan of the colliders the rules reach (or of every collider, in a
/// full pass). A collider without an entry keeps Rapier's defaults.
#[derive(Debug, Default)]
pub(crate) struct Plan {
    pub(crate) colliders: HandleMap<ColliderHandle, ColliderPlan>,
    /// The settings of each class that has native members: an edit that
    /// moves a collider into one of these classes plans that collider alone.
    pub(super) classes: HashMap<Class, ColliderPlan>,
    /// Why every collider was planned; `None` when only the reached ones were.
    pub(crate) full: Option<FullPass>,
    /// The colliders hooked to carry the specific entries and pinned pairs
    /// of their other side (see [`plan`]).
    pub(crate) carriers: HashSet<ColliderHandle>,
    /// What the project's settings leave to the planner, and the number of
    /// colliders when every collider was looked at for it; `None` when the
    /// plan gives no group a bit and relies on no collision type, so that
    /// no project setting can conflict with it.
    pub(crate) room: Option<(Room, usize)>,
    /// The planned colliders' first personal rules, by depth: whether
    /// Rapier's groups say a collider's personal rule depends on them.
    pub(super) personal_depths: PersonalDepths,
    /// Each planned collider's plan before the entries (see [`Base`]).
    pub(super) base: HashMap<ColliderHandle, Base>,
    /// How each specific entry is decided, kept from plan to plan.
    pub(crate) decisions: Decisions,
    /// The bits the groups took (raw): entries take theirs from the rest of
    /// the room.
    pub(super) group_bits: u32,
    /// How many planned colliders each class has (by their chains): the
    /// groups' settings follow which classes have members.
    pub(super) class_counts: HashMap<Class, usize>,
}

impl Plan {
    /// Whether the plan hooks `collider`: the hook decides its pairs.
    #[inline]
    pub(crate) fn hooks(&self, collider: ColliderHandle) -> bool {
        self.colliders.get(collider).is_some_and(ColliderPlan::hooked)
    }

    /// Forgets `collider` (removed, or no longer reached); `true` if the
    /// whole plan must be made again: the last member of a class left (the
    /// groups' settings follow which classes have members), or its personal
    /// rule changed what the others' read (see [`Plan::personal_moved`]).
    pub(crate) fn forget(&mut self, collider: ColliderHandle) -> bool {
        self.colliders.remove(collider);
        let Some(base) = self.base.remove(&collider) else {
            return false;
        };
        let emptied = base.class.is_some_and(|class| self.count_out(class));
        self.personal_moved(base.first_personal, None) || emptied
    }

    /// A planned collider's first personal rule went from `old` to `new`;
    /// `true` if that changes whether Rapier's groups can say another
    /// collider's personal rule (the least restrictive first personal rule
    /// above some depth), which only a whole plan can follow.
    pub(super) fn personal_moved(
        &mut self,
        old: Option<(CollisionRule, usize)>,
        new: Option<(CollisionRule, usize)>,
    ) -> bool {
        if old == new {
            return false;
        }
        // More colliders of kinds already counted (the common case: a
        // spawner's ghosts) change nothing the others read.
        let depths = &mut self.personal_depths;
        let before = depths.changes_kinds(old, new).then(|| depths.shallower());
        depths.count(old, false);
        depths.count(new, true);
        before.is_some_and(|before| depths.shallower() != before)
    }

    /// One member less of `class`; `true` if that was its last (a default
    /// class always counts as having members).
    pub(super) fn count_out(&mut self, class: Class) -> bool {
        let Some(count) = self.class_counts.get_mut(&class) else {
            return false;
        };
        *count -= 1;
        if *count > 0 {
            return false;
        }
        self.class_counts.remove(&class);
        class != Class::unreached(class.dynamic)
    }

    /// The plan entry of `collider`, or the defaults of an unreached one.
    pub(crate) fn entry(&self, collider: ColliderHandle, dynamic: bool) -> ColliderPlan {
        self.colliders
            .get(collider)
            .copied()
            .unwrap_or_else(|| ColliderPlan::unreached(dynamic))
    }
}

/// What the planner is asked to plan.
pub(crate) struct Request<'a> {
    pub(crate) rules: &'a CollisionRuleSet,
    pub(crate) bodies: &'a RigidBodySet,
    pub(crate) colliders: &'a ColliderSet,
    /// The colliders the rules reach (ignored in a full pass, which plans all).
    pub(crate) reached: &'a [ColliderHandle],
    /// The nodes whose records may hold specific entries.
    pub(crate) ruled: &'a [Node],
    /// Pairs with an override or a manifold setting: one side is hooked.
    pub(crate) pinned: &'a [PairKey],
    /// Set when every collider must pass the hook (a calculator, a callback,
    /// the `Manual` policy, the planner turned off).
    pub(crate) all_hooked: Option<FullPass>,
    /// The project's own settings of a collider.
    pub(crate) own: &'a dyn Fn(ColliderHandle, &Collider) -> Settings,
    /// How many pairs a collider has in Rapier's graph now, where the graph
    /// is at hand: what hooking it costs (see [`side_cost`](super::carriers::side_cost)).
    pub(crate) pairs_of: &'a dyn Fn(ColliderHandle) -> Option<usize>,
    /// The decisions of the plan before, kept (see [`Decisions`]).
    pub(crate) decided: &'a Decisions,
    /// The world holds soft bodies, whose solver reads no solver groups: no
    /// `NoResponse` is then left to Rapier's groups (`docs/semantics.md`,
    /// "Soft bodies").
    pub(crate) soft_bodies: bool,
    /// The world was loaded with the crate's writes but without the
    /// decisions they rest on: entries not yet decided are decided as the
    /// colliders' settings and marks show (`docs/semantics.md`, "Saving
    /// and loading").
    pub(crate) loaded: bool,
}

impl Request<'_> {
    /// Whether Rapier's groups can say `rule` for a pair: not a
    /// `NoResponse` where soft bodies may be on one side.
    #[inline]
    pub(super) fn native_rule(&self, rule: CollisionRule) -> bool {
        !(self.soft_bodies && rule == CollisionRule::NoResponse)
    }
}

impl Request<'_> {
    /// Both colliders of every pinned pair.
    pub(super) fn pinned_colliders(&self) -> HashSet<ColliderHandle> {
        self.pinned
            .iter()
            .flat_map(|k| {
                let (a, b) = k.colliders();
                [a, b]
            })
            .collect()
    }
}

/// Plans the colliders of `request`.
pub(crate) fn plan(request: &Request<'_>) -> Plan {
    let Request {
        rules,
        bodies,
        colliders,
        ..
    } = *request;
    let mut plan = Plan::default();
    if let Some(reason) = request.all_hooked {
        plan.full = Some(reason);
        for (handle, collider) in colliders.iter() {
            let entry = ColliderPlan::hooked_plan(dynamic_body(bodies, collider.parent()));
            plan.colliders.insert(handle, entry);
        }
        return plan;
    }

    // Each reached collider's class, or None where its chain needs the hook.
    let class_of = |handle: ColliderHandle| {
        let collider = colliders.get(handle)?;
        let dynamic = dynamic_body(bodies, collider.parent());
        Some((
            handle,
            native_class(rules, bodies, colliders, handle, dynamic),
            dynamic,
        ))
    };
    let mut classes: Vec<(ColliderHandle, Option<Class>, bool)> = request
        .reached
        .iter()
        .filter_map(|&h| class_of(h))
        .collect();
    let mut settings = GroupSettings::new(request, classes.iter().filter_map(|c| c.1), Room::ALL);
    if settings.needs_room() {
        // Group bits and collision types are shared with the project's
        // settings of every collider: look at them all.
        let room = Room::of_world(colliders, request.own);
        plan.room = Some((room, colliders.len()));
        settings = GroupSettings::new(request, classes.iter().filter_map(|c| c.1), room);
    }
    // A collider no rule names may carry project types that pair
    // non-dynamic bodies, where the kinematic entry gives way to a default
    // rule Rapier's type test cannot say: every collider is looked at.
    plan.full =
        (settings.reaches_defaults() || default_refuses(rules)).then_some(FullPass::DefaultGroups);
    if plan.full.is_some() {
        classes = colliders.iter().filter_map(|(h, _)| class_of(h)).collect();
    }

    // Dynamic colliders whose chains say one personal rule (see
    // `personal_rule`) are native where Rapier's test gives each of their
    // pairs the rule the personal stage gives it, which depends on every
    // collider's first personal rule: counted once, kept with the plan.
    let mut firsts: HashMap<ColliderHandle, (CollisionRule, usize)> = HashMap::new();
    for &(handle, class, _) in &classes {
        if class.is_none() {
            if let Some(first) = first_personal(rules, bodies, colliders, handle) {
                plan.personal_depths.count(Some(first), true);
                firsts.insert(handle, first);
            }
        }
    }
    let shallower = plan.personal_depths.shallower();
    let pinned = request.pinned_colliders();
    let personal: HashMap<ColliderHandle, CollisionRule> = classes
        .iter()
        .filter(|&&(handle, class, _)| class.is_none() && firsts.contains_key(&handle))
        .filter_map(|&(handle, _, dynamic)| {
            native_personal(request, &shallower, &pinned, handle, dynamic).map(|r| (handle, r))
        })
        .collect();

    // Hooked by their own chains or groups.
    let mut hooked: HashSet<ColliderHandle> = classes
        .iter()
        .filter(|(h, class, _)| {
            class.is_none_or(|c| settings.entry(c).is_none()) && !personal.contains_key(h)
        })
        .map(|&(h, _, _)| h)
        .collect();
    // A pinned pair hooks its cheaper side.
    plan.carriers = pinned_carriers(request, &mut hooked);
    // A carrier the rules did not otherwise reach (one side of a pinned
    // pair) is planned too.
    let known: HashSet<ColliderHandle> = classes.iter().map(|c| c.0).collect();
    let mut extra: Vec<ColliderHandle> = plan
        .carriers
        .iter()
        .copied()
        .filter(|c| !known.contains(c))
        .collect();
    extra.sort_unstable_by_key(|c| c.into_raw_parts());
    classes.extend(extra.into_iter().filter_map(class_of));

    // Each collider's plan before the entries.
    for &(handle, class, dynamic) in &classes {
        let entry = match class.filter(|_| !hooked.contains(&handle)) {
            None if !hooked.contains(&handle) => personal
                .get(&handle)
                .map_or(ColliderPlan::hooked_plan(dynamic), |&rule| {
                    ColliderPlan::personal(rule)
                }),
            None => ColliderPlan::hooked_plan(dynamic),
            Some(class) => match settings.entry(class) {
                Some(entry) => {
                    plan.classes.insert(class, entry);
                    entry
                }
                None => ColliderPlan::hooked_plan(dynamic),
            },
        };
        let personal = personal.contains_key(&handle) && !entry.hooked();
        let body = colliders.get(handle).and_then(|c| c.parent());
        let first_personal = firsts.get(&handle).copied();
        if let Some(class) = class {
            *plan.class_counts.entry(class).or_default() += 1;
        }
        plan.base.insert(
            handle,
            Base {
                plan: entry,
                personal,
                first_personal,
                class,
                dynamic,
                body,
            },
        );
    }

    // Specific entries: Rapier's groups with bits of their own where that
    // is exact, else a hooked side; decisions already made are kept.
    plan.group_bits = settings.bits.values().fold(0, |g, &bit| g | 1 << bit);
    let entries = ruled_entries(request);
    let mut decisions = request.decided.clone();
    decisions.keep_only(&entries);
    let mut looked_up = plan.room.map(|(room, _)| room);
    {
        let group_bits = plan.group_bits;
        let mut free = || {
            let room = *looked_up.get_or_insert_with(|| Room::of_world(colliders, request.own));
            room.bits() - Group::from_bits_retain(group_bits)
        };
        let base = |c: ColliderHandle| plan.base.get(&c).copied();
        let pinned = request.pinned_colliders();
        let is_pinned = |c: ColliderHandle| pinned.contains(&c);
        let mut facts = Facts {
            base: &base,
            pinned: &is_pinned,
            free: &mut free,
        };
        decisions.decide(request, &mut facts, &entries);
    }
    if plan.room.is_none() {
        plan.room = looked_up.map(|room| (room, colliders.len()));
    }

    for (handle, _, dynamic) in classes {
        let base = plan.base[&handle];
        let entry = decisions.apply(request, handle, base);
        let own = colliders.get(handle).map(|c| (request.own)(handle, c));
        let entry = own.map_or(entry, |own| entry.fitted(own, dynamic, rules));
        plan.colliders.insert(handle, entry);
    }
    plan.decisions = decisions;
    plan
}

/// A specific entry between `a` and `b`, its nodes in the node order.
pub(super) fn ordered(a: Node, b: Node) -> (Node, Node) {
    if a <= b { (a, b) } else { (b, a) }
}

/// Every specific entry of the ruled nodes, each once, in the node order.
pub(super) fn ruled_entries(request: &Request<'_>) -> Vec<(Node, Node)> {
    let rules = request.rules;
    let mut entries: Vec<(Node, Node)> = request
        .ruled
        .iter()
        .filter_map(|&node| rules.record(node).map(|r| (node, r)))
        .flat_map(|(node, record)| record.specific.keys().map(move |&o| ordered(node, o)))
        .collect();
    entries.sort_unstable();
    entries.dedup();
    entries
}
