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
//! [`personal_natives`]). A pair with a hooked collider is decided by the
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
use super::rapier::prelude::*;

use super::node::HandleMap;
use super::pairs::PairKey;
use super::project::{Room, Settings};
use super::{CollisionGroup, CollisionRule, CollisionRuleSet, FullPass, Node};

/// The facts that decide a native collider's pairs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct Class {
    pub(crate) group: CollisionGroup,
    pub(crate) dynamic: bool,
}

impl Class {
    /// The class of a collider no rule reaches.
    pub(crate) fn unreached(dynamic: bool) -> Class {
        let group = if dynamic {
            CollisionGroup::DEFAULT_DYNAMIC
        } else {
            CollisionGroup::DEFAULT_KINEMATIC
        };
        Class { group, dynamic }
    }
}

/// The hook flags every hooked collider carries.
const HOOKS: ActiveHooks =
    ActiveHooks::FILTER_CONTACT_PAIRS.union(ActiveHooks::FILTER_INTERSECTION_PAIR);

/// The Rapier settings the planner gives one collider, before they are
/// combined with the project's own (see [`ColliderPlan::combined`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct ColliderPlan {
    /// `None`: the collider is hooked.
    pub(crate) class: Option<Class>,
    pub(crate) collision: InteractionGroups,
    pub(crate) solver: InteractionGroups,
    pub(crate) types: ActiveCollisionTypes,
}

impl ColliderPlan {
    pub(crate) fn hooked(&self) -> bool {
        self.class.is_none()
    }

    /// Whether the plan leaves the collider with Rapier's own settings.
    pub(crate) fn is_rapier_default(&self) -> bool {
        !self.hooked()
            && self.collision == InteractionGroups::all()
            && self.solver == InteractionGroups::all()
            && self.types == ActiveCollisionTypes::default()
    }

    /// The settings a collider gets: the plan combined with the project's
    /// own settings `own` (`docs/semantics.md`, section 6). The hook bits are
    /// added to the project's; the project's collision and solver groups are
    /// kept, and narrowed only where the planner gave a group a bit, which it
    /// does only for colliders whose own groups are Rapier's defaults; the
    /// collision types are the project's, widened where a rule lets two
    /// non-dynamic bodies pair (never narrowed). `modifying`: the collider
    /// also modifies contacts (`ManifoldUpdate::Never`).
    pub(crate) fn combined(&self, own: Settings, modifying: bool) -> Settings {
        let mut hooks = own.hooks;
        if self.hooked() {
            hooks |= HOOKS;
        }
        if modifying {
            hooks |= ActiveHooks::MODIFY_SOLVER_CONTACTS;
        }
        let keep = |planned: InteractionGroups, own: InteractionGroups| {
            if planned == InteractionGroups::all() {
                own
            } else {
                planned
            }
        };
        Settings {
            collision: keep(self.collision, own.collision),
            solver: keep(self.solver, own.solver),
            types: own.types | (self.types - ActiveCollisionTypes::default()),
            hooks,
        }
    }

    /// This plan, or the hooked one where it cannot be combined exactly with
    /// the project's settings `own`: a group bit on a collider whose own
    /// groups are narrowed (no single group test says "both allow").
    fn fitted(self, own: Settings, dynamic: bool, rules: &CollisionRuleSet) -> ColliderPlan {
        let narrows = |planned: InteractionGroups, own: InteractionGroups| {
            planned != InteractionGroups::all() && own != InteractionGroups::all()
        };
        // The kinematic entry gives way to wider project types (see
        // `CollisionRuleSet::by_kinematic_entry`), pair by pair, which a bit
        // that keeps DEFAULT_KINEMATIC from itself cannot say.
        // Nor can Rapier's type test, where the pairs it lets through get a
        // default rule that refuses them or keeps their contacts out.
        let default_refuses = default_refuses(rules);
        let kinematic = self.class.is_some_and(|c| {
            c.group == CollisionGroup::DEFAULT_KINEMATIC
                && (default_refuses || !self.collision.filter.contains(self.collision.memberships))
        });
        let typed = !dynamic && own.widened() && kinematic;
        if !self.hooked()
            && (narrows(self.collision, own.collision) || narrows(self.solver, own.solver) || typed)
        {
            ColliderPlan::hooked_plan(dynamic)
        } else {
            self
        }
    }

    /// The plan of a dynamic collider native by its personal `rule` (see
    /// [`personal_natives`]): every pair it has with a native collider gets
    /// `rule`, whatever the groups say. Its memberships are every bit, which
    /// every filter that is not empty holds (as a hooked collider's do);
    /// its filters say `rule`: none for `NoPair` (collision groups), none
    /// for `NoResponse` (solver groups), all for `Normal`, which leaves it
    /// with Rapier's defaults. Nothing in it depends on the rest of the
    /// plan, so a partial plan gives it exactly what a whole plan would.
    fn personal(rule: CollisionRule) -> ColliderPlan {
        let none = InteractionGroups::new(Group::ALL, Group::NONE, InteractionTestMode::And);
        let (collision, solver) = match rule {
            CollisionRule::NoPair => (none, InteractionGroups::all()),
            CollisionRule::NoResponse => (InteractionGroups::all(), none),
            _ => (InteractionGroups::all(), InteractionGroups::all()),
        };
        ColliderPlan {
            // Its group takes no part in its pairs: the class only marks it
            // native.
            class: Some(Class::unreached(true)),
            collision,
            solver,
            types: ActiveCollisionTypes::default(),
        }
    }

    /// The plan of a collider no rule reaches: Rapier's defaults.
    pub(crate) fn unreached(dynamic: bool) -> ColliderPlan {
        ColliderPlan {
            class: Some(Class::unreached(dynamic)),
            collision: InteractionGroups::all(),
            solver: InteractionGroups::all(),
            types: ActiveCollisionTypes::default(),
        }
    }

    /// A hooked collider keeps a collider's default groups (every bit), which
    /// pass every native test, so the hook decides; a non-dynamic one takes
    /// every collision type so that the hook also sees its pairs with other
    /// non-dynamic colliders.
    fn hooked_plan(dynamic: bool) -> ColliderPlan {
        ColliderPlan {
            class: None,
            collision: InteractionGroups::all(),
            solver: InteractionGroups::all(),
            types: if dynamic {
                ActiveCollisionTypes::default()
            } else {
                ActiveCollisionTypes::all()
            },
        }
    }
}

/// The plan of the colliders the rules reach (or of every collider, in a
/// full pass). A collider without an entry keeps Rapier's defaults.
#[derive(Debug, Default)]
pub(crate) struct Plan {
    pub(crate) colliders: HandleMap<ColliderHandle, ColliderPlan>,
    /// The settings of each class that has native members: an edit that
    /// moves a collider into one of these classes plans that collider alone.
    classes: HashMap<Class, ColliderPlan>,
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
    /// Some collider is native by a personal `NoPair` or `NoResponse`,
    /// which a personal rule elsewhere can make inexact: a collider whose
    /// chain has a personal rule is then planned with everything.
    personal_restricts: bool,
}

impl Plan {
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
}

impl Request<'_> {
    /// Both colliders of every pinned pair.
    fn pinned_colliders(&self) -> HashSet<ColliderHandle> {
        self.pinned
            .iter()
            .flat_map(|k| {
                let (a, b) = k.colliders();
                [a, b]
            })
            .collect()
    }
}

fn is_dynamic(bodies: &RigidBodySet, collider: &Collider) -> bool {
    collider
        .parent()
        .and_then(|b| bodies.get(b))
        .is_some_and(|b| b.is_dynamic())
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
            let entry = ColliderPlan::hooked_plan(is_dynamic(bodies, collider));
            plan.colliders.insert(handle, entry);
        }
        return plan;
    }

    // Each reached collider's class, or None where its chain needs the hook.
    let class_of = |handle: ColliderHandle| {
        let collider = colliders.get(handle)?;
        let dynamic = is_dynamic(bodies, collider);
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
    let mut settings = GroupSettings::new(rules, classes.iter().filter_map(|c| c.1), Room::ALL);
    if settings.needs_room() {
        // Group bits and collision types are shared with the project's
        // settings of every collider: look at them all.
        let room = Room::of_world(colliders, request.own);
        plan.room = Some((room, colliders.len()));
        settings = GroupSettings::new(rules, classes.iter().filter_map(|c| c.1), room);
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
    // pairs the rule the personal stage gives it.
    let personal = personal_natives(request, &classes);
    plan.personal_restricts = personal.values().any(|&r| r != CollisionRule::Normal);

    // Hooked by their own chains or groups.
    let mut hooked: HashSet<ColliderHandle> = classes
        .iter()
        .filter(|(h, class, _)| {
            class.is_none_or(|c| settings.entry(c).is_none()) && !personal.contains_key(h)
        })
        .map(|&(h, _, _)| h)
        .collect();
    // Specific entries Rapier's groups can decide take bits of their own;
    // the others are carried by a hooked side.
    let looked_up = plan.room.map(|(room, _)| room);
    let entry_bits = EntryBits::plan(request, &classes, &settings, &personal, &hooked, looked_up);
    if plan.room.is_none() {
        plan.room = entry_bits.room.map(|room| (room, colliders.len()));
    }
    plan.carriers = carriers(request, &mut hooked, &entry_bits.decided);
    // A carrier the rules did not otherwise reach (a named node's collider,
    // one side of a pinned pair) is planned too.
    let known: HashSet<ColliderHandle> = classes.iter().map(|c| c.0).collect();
    let mut extra: Vec<ColliderHandle> = plan
        .carriers
        .iter()
        .copied()
        .filter(|c| !known.contains(c))
        .collect();
    extra.sort_unstable_by_key(|c| c.into_raw_parts());
    classes.extend(extra.into_iter().filter_map(class_of));

    for (handle, class, dynamic) in classes {
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
        let own = colliders.get(handle).map(|c| (request.own)(handle, c));
        let entry = entry_bits.apply(handle, entry);
        let entry = own.map_or(entry, |own| entry.fitted(own, dynamic, rules));
        plan.colliders.insert(handle, entry);
    }
    plan
}

/// Chooses, for every specific entry and every pinned pair, the side that
/// carries the hook flag, adds its colliders to `hooked` and returns those
/// it added. A specific entry `x -> y` reaches only pairs whose chains hold
/// `x` on one side and `y` on the other, so hooking every collider under
/// either node decides all of them; the cheaper side is taken (colliders
/// already hooked cost nothing, dynamic ones little, a fixed or kinematic
/// hub much), the entry's owner on a tie.
fn carriers(
    request: &Request<'_>,
    hooked: &mut HashSet<ColliderHandle>,
    decided: &HashSet<(Node, Node)>,
) -> HashSet<ColliderHandle> {
    let Request {
        rules,
        bodies,
        colliders,
        ..
    } = *request;
    let under = |node: Node| rules.colliders_under(node, bodies, colliders);
    let mut sides: Vec<(Vec<ColliderHandle>, Vec<ColliderHandle>)> = Vec::new();
    for &node in request.ruled {
        let Some(record) = rules.record(node) else {
            continue;
        };
        // Sorted, so that the choice is the same in every run.
        let mut subjects: Vec<Node> = record.specific.keys().copied().collect();
        subjects.sort_unstable_by_key(|n| node_order(*n));
        for subject in subjects {
            if !decided.contains(&(node, subject)) {
                sides.push((under(node), under(subject)));
            }
        }
    }
    for key in request.pinned {
        let (a, b) = key.colliders();
        sides.push((vec![a], vec![b]));
    }

    let mut added = HashSet::new();
    for (owner, other) in sides {
        let cost = |side: &[ColliderHandle], hooked: &HashSet<ColliderHandle>| -> u64 {
            side.iter()
                .filter(|c| !hooked.contains(*c))
                .map(|&c| match colliders.get(c) {
                    Some(collider) if is_dynamic(bodies, collider) => 1,
                    Some(_) => 1_000,
                    None => 0,
                })
                .sum()
        };
        let side = if cost(&other, hooked) < cost(&owner, hooked) {
            other
        } else {
            owner
        };
        for c in side {
            if hooked.insert(c) {
                added.insert(c);
            }
        }
    }
    added
}

/// Specific entries that Rapier's groups decide, without the hook: a
/// `NoPair` entry in collision groups, a `NoResponse` entry in solver
/// groups. The colliders under one side, all on dynamic bodies, take a bit
/// of their own as their membership; the colliders under the other side
/// leave that bit out of their filter. Their pairs keep Rapier's contact
/// recycling, which a hooked pair loses (`docs/architecture.md`, "The
/// planner").
///
/// It is exact where the entry decides every pair between the two sides
/// and nothing else changes: both sides' colliders are native with
/// Rapier's default groups in their class and in the project's settings,
/// none is in a pinned pair, no other specific entry links a node of one
/// side's chains to a node of the other's (so the specific stage finds this
/// entry for each of their pairs), and each collider carries at most one
/// bit of each kind. The bit comes from the room the project's settings
/// leave (as a group's bit does), beside the groups' own bits; a side that
/// carries several entries uses one bit for all of them. Where any of this
/// fails, or the bits run out, the entry is carried by a hooked side.
#[derive(Debug, Default)]
struct EntryBits {
    /// The entries decided by bits, in both orders.
    decided: HashSet<(Node, Node)>,
    /// Each carrying collider's membership bit: collision, solver.
    memberships: HashMap<ColliderHandle, [Option<u32>; 2]>,
    /// The bits each collider leaves out of its filters: collision, solver.
    excluded: HashMap<ColliderHandle, [Group; 2]>,
    /// The room looked up for the bits, if an entry asked for one: the plan
    /// is made again when colliders come or go, which may change it.
    room: Option<Room>,
}

impl EntryBits {
    fn plan(
        request: &Request<'_>,
        classes: &[(ColliderHandle, Option<Class>, bool)],
        settings: &GroupSettings,
        personal: &HashMap<ColliderHandle, CollisionRule>,
        hooked: &HashSet<ColliderHandle>,
        looked_up: Option<Room>,
    ) -> EntryBits {
        let Request {
            rules,
            bodies,
            colliders,
            ..
        } = *request;
        let mut bits = EntryBits::default();
        // Each entry once, in a fixed order; its rule is what the specific
        // stage reads between the two nodes (both directions).
        let ordered = |a: Node, b: Node| {
            if node_order(a) <= node_order(b) {
                (a, b)
            } else {
                (b, a)
            }
        };
        let mut entries: Vec<(Node, Node)> = request
            .ruled
            .iter()
            .filter_map(|&node| rules.record(node).map(|r| (node, r)))
            .flat_map(|(node, record)| record.specific.keys().map(move |&o| ordered(node, o)))
            .collect();
        entries.sort_unstable_by_key(|&(a, b)| (node_order(a), node_order(b)));
        entries.dedup();
        let kind_of = |(x, y): (Node, Node)| match rules.specific(x, y).most_restrictive(rules.specific(y, x)) {
            CollisionRule::NoPair => Some(0),
            CollisionRule::NoResponse => Some(1),
            _ => None,
        };
        let entries: Vec<((Node, Node), usize)> = entries
            .into_iter()
            .filter_map(|e| kind_of(e).map(|kind| (e, kind)))
            .collect();
        if entries.is_empty() {
            return bits;
        }

        // A collider may carry a bit if it is native with Rapier's default
        // groups, in its class's plan and in its project's settings.
        let known: HashMap<ColliderHandle, (Option<Class>, bool)> =
            classes.iter().map(|&(h, c, d)| (h, (c, d))).collect();
        let pinned = request.pinned_colliders();
        let all = InteractionGroups::all();
        let eligible = |c: ColliderHandle| -> Option<bool> {
            let &(class, dynamic) = known.get(&c)?;
            if hooked.contains(&c) || personal.contains_key(&c) || pinned.contains(&c) {
                return None;
            }
            let planned = settings.entry(class?)?;
            let own = (request.own)(c, colliders.get(c)?);
            let defaults = [planned.collision, planned.solver, own.collision, own.solver];
            defaults.iter().all(|&g| g == all).then_some(dynamic)
        };
        let chains = |side: &[ColliderHandle]| -> HashSet<Node> {
            side.iter()
                .flat_map(|&c| rules.hierarchy.chain(bodies, colliders, Node::Collider(c)))
                .collect()
        };
        // Another entry from a node of `from` to a node of `to` than `entry`.
        let other_entry = |from: &HashSet<Node>, to: &HashSet<Node>, entry: (Node, Node)| {
            from.iter().any(|&a| {
                rules.record(a).is_some_and(|r| {
                    r.specific
                        .keys()
                        .any(|&b| to.contains(&b) && ordered(a, b) != entry)
                })
            })
        };

        let taken = settings
            .bits
            .values()
            .fold(Group::empty(), |g, &bit| g | Group::from_bits_retain(1 << bit));
        let mut free: Option<Group> = None;
        let mut node_bits: HashMap<(Node, usize), u32> = HashMap::new();
        for ((x, y), kind) in entries {
            let under = |node: Node| rules.colliders_under(node, bodies, colliders);
            let (cx, cy) = (under(x), under(y));
            if cx.is_empty() || cy.is_empty() {
                continue;
            }
            let side = |cs: &[ColliderHandle]| -> Option<bool> {
                cs.iter()
                    .map(|&c| eligible(c))
                    .try_fold(true, |all_dynamic, d| d.map(|d| all_dynamic && d))
            };
            let (Some(x_dynamic), Some(y_dynamic)) = (side(&cx), side(&cy)) else {
                continue;
            };
            // The carrying side: all dynamic, the smaller, the first node on a tie.
            let (owner, carrying, other) = match (x_dynamic, y_dynamic) {
                (true, true) if cy.len() < cx.len() => (y, cy, cx),
                (true, _) => (x, cx, cy),
                (false, true) => (y, cy, cx),
                (false, false) => continue,
            };
            if carrying.iter().any(|c| other.contains(c)) {
                continue;
            }
            let (s_nodes, t_nodes) = (chains(&carrying), chains(&other));
            if other_entry(&s_nodes, &t_nodes, (x, y)) || other_entry(&t_nodes, &s_nodes, (x, y)) {
                continue;
            }
            let bit = match node_bits.get(&(owner, kind)) {
                Some(&bit) => bit,
                None => {
                    // The groups' bits may have looked the room up already.
                    let room = *bits.room.get_or_insert_with(|| {
                        looked_up.unwrap_or_else(|| Room::of_world(colliders, request.own))
                    });
                    let free = free.get_or_insert(room.bits() - taken);
                    let Some(bit) = (0..32u32).find(|&b| free.contains(Group::from_bits_retain(1 << b)))
                    else {
                        continue;
                    };
                    bit
                }
            };
            let carries_other = carrying.iter().any(|c| {
                bits.memberships
                    .get(c)
                    .and_then(|m| m[kind])
                    .is_some_and(|b| b != bit)
            });
            if carries_other {
                continue;
            }
            if node_bits.insert((owner, kind), bit).is_none() {
                if let Some(free) = free.as_mut() {
                    free.remove(Group::from_bits_retain(1 << bit));
                }
            }
            for c in carrying {
                bits.memberships.entry(c).or_default()[kind] = Some(bit);
            }
            for c in other {
                bits.excluded.entry(c).or_insert([Group::empty(); 2])[kind] |=
                    Group::from_bits_retain(1 << bit);
            }
            bits.decided.insert((x, y));
            bits.decided.insert((y, x));
        }
        bits
    }

    /// `entry` with the bits of `collider`, if it carries or leaves out any.
    fn apply(&self, collider: ColliderHandle, mut entry: ColliderPlan) -> ColliderPlan {
        let membership = self.memberships.get(&collider).copied().unwrap_or_default();
        let excluded = self
            .excluded
            .get(&collider)
            .copied()
            .unwrap_or([Group::empty(); 2]);
        let narrow = |groups: InteractionGroups, bit: Option<u32>, excluded: Group| {
            if bit.is_none() && excluded.is_empty() {
                return groups;
            }
            let memberships = bit.map_or(groups.memberships, |b| Group::from_bits_retain(1 << b));
            InteractionGroups::new(memberships, groups.filter - excluded, InteractionTestMode::And)
        };
        entry.collision = narrow(entry.collision, membership[0], excluded[0]);
        entry.solver = narrow(entry.solver, membership[1], excluded[1]);
        entry
    }
}

/// Whether the default rule refuses a pair or keeps its contacts out: what
/// pairs of non-dynamic bodies get where the project's types let Rapier
/// see them (see `CollisionRuleSet::by_kinematic_entry`), which Rapier's
/// own handling of such pairs (contacts, no response) does not say.
fn default_refuses(rules: &CollisionRuleSet) -> bool {
    !matches!(
        rules.default_rule(),
        CollisionRule::Normal | CollisionRule::NoResponse | CollisionRule::Defer
    )
}

/// A total order on nodes, for deterministic iteration.
pub(crate) fn node_order(node: Node) -> (u8, (u32, u32)) {
    match node {
        Node::Collider(h) => (0, h.into_raw_parts()),
        Node::Body(h) => (1, h.into_raw_parts()),
    }
}

/// Plans `handles` alone, against the rest of `plan`: possible when each of
/// them ends up hooked by its own chain, or in a class the plan already has,
/// and no specific entry or pinned pair could make it a carrier (the bits
/// and filters of every group then stay as they are). `None`: plan again.
pub(crate) fn replan_some(
    plan: &Plan,
    request: &Request<'_>,
    handles: &[ColliderHandle],
) -> Option<Vec<(ColliderHandle, ColliderPlan)>> {
    let Request {
        rules,
        bodies,
        colliders,
        ..
    } = *request;
    if request.all_hooked.is_some() || plan.full.is_some() {
        return None;
    }
    let pinned = request.pinned_colliders();
    let mut planned = Vec::with_capacity(handles.len());
    for &handle in handles {
        let Some(collider) = colliders.get(handle) else {
            continue;
        };
        if pinned.contains(&handle) || touches_entries(rules, bodies, colliders, handle) {
            return None;
        }
        // A personal rule: native by `Normal` as the plan has it; any other
        // native personal rule depends on every collider's personal rules.
        let personal = first_personal(rules, bodies, colliders, handle)
            .map(|_| personal_rule(rules, bodies, colliders, handle).map(|(rule, _)| rule));
        let restricts = personal
            .flatten()
            .is_some_and(|r| r != CollisionRule::Normal);
        if personal.is_some() && (plan.personal_restricts || restricts) {
            return None;
        }
        let own = (request.own)(handle, collider);
        if plan.room.is_some_and(|(room, _)| !room.holds(own)) {
            // Its settings take bits or types the plan gave away: look again.
            return None;
        }
        let dynamic = is_dynamic(bodies, collider);
        let entry = match native_class(rules, bodies, colliders, handle, dynamic) {
            None if dynamic && personal.flatten() == Some(CollisionRule::Normal) => {
                ColliderPlan::personal(CollisionRule::Normal)
            }
            None => ColliderPlan::hooked_plan(dynamic),
            Some(class) if class == Class::unreached(dynamic) => {
                match plan.classes.get(&class) {
                    Some(entry) => *entry,
                    // Checked when the plan was made: a default class is planned
                    // as Rapier's defaults unless the plan is a full pass.
                    None => ColliderPlan::unreached(dynamic),
                }
            }
            Some(class) => *plan.classes.get(&class)?,
        };
        planned.push((handle, entry.fitted(own, dynamic, rules)));
    }
    Some(planned)
}

/// Whether `start` or a node above it carries specific entries or is named
/// by one: the side that carries them is chosen by a whole plan, from the
/// colliders under each side and their bodies' types.
pub(crate) fn touches_entries(
    rules: &CollisionRuleSet,
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    start: impl Into<Node>,
) -> bool {
    rules
        .hierarchy
        .chain(bodies, colliders, start.into())
        .any(|node| {
            rules.is_named(node) || rules.record(node).is_some_and(|r| !r.specific.is_empty())
        })
}

/// The class of collider `leaf`, or `None` if its chain carries a personal
/// rule or mixes effective groups.
///
/// A node's effective group is the first explicit group at or above it,
/// else the colliding body's default group (`docs/semantics.md`, "Effective
/// group"), so the chain's groups are its explicit ones, plus that default
/// when the root has none: a chain with no explicit group is one class, the
/// collider's own body's, whatever its ancestors' types.
fn native_class(
    rules: &CollisionRuleSet,
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    leaf: ColliderHandle,
    dynamic: bool,
) -> Option<Class> {
    let mut explicit: Option<CollisionGroup> = None;
    let mut root_grouped = false;
    let mut node = Some(Node::Collider(leaf));
    while let Some(current) = node {
        let record = rules.record(current);
        if record.is_some_and(|r| r.personal.is_decided()) {
            return None;
        }
        let own = record.and_then(|r| r.group);
        if let Some(group) = own {
            if explicit.is_some_and(|g| g != group) {
                return None;
            }
            explicit = Some(group);
        }
        root_grouped = own.is_some();
        node = rules.hierarchy.next(bodies, colliders, current);
    }
    let fallback = Class::unreached(dynamic).group;
    let group = match explicit {
        Some(group) if !root_grouped && group != fallback => return None,
        Some(group) => group,
        None => fallback,
    };
    Some(Class { group, dynamic })
}

/// The first decided personal rule up the chain of `leaf`, and its depth
/// (0 for the collider itself).
fn first_personal(
    rules: &CollisionRuleSet,
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    leaf: ColliderHandle,
) -> Option<(CollisionRule, usize)> {
    let mut node = Some(Node::Collider(leaf));
    let mut depth = 0;
    while let Some(current) = node {
        let personal = rules.record(current).map(|r| r.personal);
        if let Some(rule) = personal.filter(|r| r.is_decided()) {
            return Some((rule, depth));
        }
        node = rules.hierarchy.next(bodies, colliders, current);
        depth += 1;
    }
    None
}

/// The rule of `leaf`'s chain at the personal stage when every personal
/// rule of the chain says the same `Normal`, `NoResponse` or `NoPair`, with
/// the depth of the first.
fn personal_rule(
    rules: &CollisionRuleSet,
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    leaf: ColliderHandle,
) -> Option<(CollisionRule, usize)> {
    let (rule, depth) = first_personal(rules, bodies, colliders, leaf)?;
    let native = matches!(
        rule,
        CollisionRule::Normal | CollisionRule::NoResponse | CollisionRule::NoPair
    );
    let mut node = Some(Node::Collider(leaf));
    while let Some(current) = node {
        let personal = rules.record(current).map(|r| r.personal);
        if personal.is_some_and(|r| r.is_decided() && r != rule) {
            return None;
        }
        node = rules.hierarchy.next(bodies, colliders, current);
    }
    native.then_some((rule, depth))
}

/// The dynamic colliders of `classes` (hooked by their chains) that can be
/// native by their personal rule, with that rule.
///
/// The personal stage compares the two chains step by step: a collider `c`
/// whose chain says one rule `r` from depth `d` up gets `r` with every
/// collider whose first personal rule is deeper, the more restrictive of the
/// two with one at depth `d`, and the other's rule with one shallower.
/// Rapier's test gives `c` and a native other side the more restrictive of
/// their two encodings, and lets a hooked side restrict further. So `c` is
/// exact unless some collider whose first personal rule is shallower than
/// `d` says a less restrictive rule than `r` (then `c` is hooked), and
/// unless a specific entry or a pinned pair may reach its pairs and `r`
/// keeps the pair from the hook (`NoPair`, `NoResponse`). Every collider
/// with a personal rule is reached, so `classes` holds them all.
fn personal_natives(
    request: &Request<'_>,
    classes: &[(ColliderHandle, Option<Class>, bool)],
) -> HashMap<ColliderHandle, CollisionRule> {
    let Request {
        rules,
        bodies,
        colliders,
        ..
    } = *request;
    // The least restrictive first personal rule at each depth, then above
    // each depth: one pass, whatever the number of personal colliders.
    let mut least: Vec<Option<CollisionRule>> = Vec::new();
    for &(h, class, _) in classes {
        if class.is_some() {
            continue;
        }
        if let Some((rule, depth)) = first_personal(rules, bodies, colliders, h) {
            if least.len() <= depth {
                least.resize(depth + 1, None);
            }
            least[depth] = Some(least[depth].map_or(rule, |r| r.min(rule)));
        }
    }
    // `shallower[d]`: the least restrictive first personal rule at a depth
    // below `d`.
    let mut shallower = vec![None; least.len() + 1];
    for d in 0..least.len() {
        shallower[d + 1] = match (shallower[d], least[d]) {
            (Some(a), Some(b)) => Some(CollisionRule::min(a, b)),
            (a, b) => a.or(b),
        };
    }
    let shallower_than = |depth: usize| shallower[depth.min(least.len())];
    let pinned = request.pinned_colliders();
    let mut natives = HashMap::new();
    for &(handle, class, dynamic) in classes {
        if class.is_some() || !dynamic {
            continue;
        }
        let Some((rule, depth)) = personal_rule(rules, bodies, colliders, handle) else {
            continue;
        };
        if rule != CollisionRule::Normal {
            let overridden = shallower_than(depth).is_some_and(|r| r < rule);
            let reached_by_entries =
                pinned.contains(&handle) || touches_entries(rules, bodies, colliders, handle);
            if overridden || reached_by_entries {
                continue;
            }
        }
        natives.insert(handle, rule);
    }
    natives
}

/// The group-level half of a plan: which groups get a bit, the filters of
/// each, which take every collision type, and which need the hook.
struct GroupSettings {
    /// Whether each group used has dynamic and non-dynamic members.
    members: HashMap<CollisionGroup, (bool, bool)>,
    bits: HashMap<CollisionGroup, u32>,
    involved: HashSet<CollisionGroup>,
    needs_hook: HashSet<CollisionGroup>,
    static_types: HashSet<CollisionGroup>,
    filters: HashMap<CollisionGroup, (Group, Group)>,
    /// A `NoPair` relation is left to Rapier's default collision types.
    relies_on_types: bool,
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
    fn new(
        rules: &CollisionRuleSet,
        classes: impl Iterator<Item = Class>,
        room: Room,
    ) -> GroupSettings {
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
        let mut awaiting = members.clone();
        for (a, b, rule) in rules.groups.iter() {
            if rule.is_decided() {
                for g in [a, b] {
                    awaiting.entry(g).or_insert((true, false));
                }
            }
        }
        if awaiting.len() > members.len() {
            let settings = GroupSettings::of_members(rules, awaiting, room);
            if settings.bits.len() == settings.involved.len() {
                return settings;
            }
        }
        GroupSettings::of_members(rules, members, room)
    }

    /// The settings of the groups in `members`, with whether each has
    /// dynamic and non-dynamic members.
    fn of_members(
        rules: &CollisionRuleSet,
        members: HashMap<CollisionGroup, (bool, bool)>,
        room: Room,
    ) -> GroupSettings {
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
        // exist without contacts, which no group test can say.
        let needs_hook: HashSet<CollisionGroup> = relations
            .iter()
            .filter(|&&(_, _, rule)| rule == CollisionRule::NoContacts)
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
        // project's wider collision types (`docs/semantics.md`, section 6), so
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
    fn entry(&self, class: Class) -> Option<ColliderPlan> {
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
    fn needs_room(&self) -> bool {
        !self.involved.is_empty() || self.relies_on_types
    }

    /// Whether a rule reaches the default groups: their plan is not
    /// Rapier's defaults, so every collider must be planned.
    fn reaches_defaults(&self) -> bool {
        [Class::unreached(true), Class::unreached(false)]
            .into_iter()
            .any(|class| !self.entry(class).is_some_and(|e| e.is_rapier_default()))
    }
}
