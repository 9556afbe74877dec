//! What Rapier can test itself. The planner gives each collider the
//! cheapest mechanism that decides all of its pairs exactly: collision
//! groups for group-level `NoPair`, solver groups for group-level
//! `NoResponse`, active collision types for pairs of non-dynamic bodies, and
//! the hook flag only where a pair needs a decision per pair.
//!
//! A collider is *native* when its pairs with every other native collider
//! are a function of two small facts about each side: its effective group
//! and whether its body is dynamic. That holds when no node of its chain
//! carries a personal rule or specific entries, no specific entry names a
//! node of its chain, and every node of its chain has the same effective
//! group: then the specific and personal stages defer, every step of the
//! group stage compares the same two groups, and the rule is
//! `table[g1, g2]`, else the default, then the special case of section 5.
//! A pair with a hooked collider is decided by the hook, so hooked colliders
//! carry permissive groups and pass every native test.

use hashbrown::{HashMap, HashSet};
use rapier3d::prelude::*;

use crate::node::HandleMap;
use crate::{CollisionGroup, CollisionRule, CollisionRuleSet, Node};

/// The facts that decide a native collider's pairs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct Class {
    pub(crate) group: CollisionGroup,
    pub(crate) dynamic: bool,
}

/// The Rapier settings the planner gives one collider.
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

    /// A hooked collider keeps a collider's default groups (every bit), which
    /// pass every native test, so the hook decides; a non-dynamic one takes every collision type so that
    /// the hook also sees its pairs with other non-dynamic colliders.
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

/// The rule between two native classes.
pub(crate) fn class_rule(rules: &CollisionRuleSet, a: Class, b: Class) -> CollisionRule {
    let mut rule = rules.group_rule(a.group, b.group);
    if !rule.is_decided() {
        rule = rules.default_rule();
    }
    if rule == CollisionRule::Normal && !a.dynamic && !b.dynamic {
        rule = CollisionRule::NoResponse;
    }
    rule
}

/// The plan of every collider.
#[derive(Debug, Default)]
pub(crate) struct Plan {
    pub(crate) colliders: HandleMap<ColliderHandle, ColliderPlan>,
    /// The settings of each class that has native members: an edit that
    /// moves a collider into one of these classes plans that collider alone.
    classes: HashMap<Class, ColliderPlan>,
}

/// Plans every collider of `colliders`. `pinned` colliders are hooked
/// whatever their rules (pairs with an override or a manifold setting);
/// with `all_hooked`, every collider is.
pub(crate) fn plan(
    rules: &CollisionRuleSet,
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    pinned: &HashSet<ColliderHandle>,
    all_hooked: bool,
) -> Plan {
    let dynamic_of = |collider: &Collider| {
        collider
            .parent()
            .and_then(|b| bodies.get(b))
            .is_some_and(|b| b.is_dynamic())
    };
    let mut plan = Plan::default();
    if all_hooked {
        for (handle, collider) in colliders.iter() {
            plan.colliders
                .insert(handle, ColliderPlan::hooked_plan(dynamic_of(collider)));
        }
        return plan;
    }

    // Each collider's class, or None where its chain needs the hook.
    let mut classes: Vec<(ColliderHandle, Option<Class>, bool)> =
        Vec::with_capacity(colliders.len());
    for (handle, collider) in colliders.iter() {
        let dynamic = dynamic_of(collider);
        let class = (!pinned.contains(&handle))
            .then(|| native_class(rules, bodies, colliders, handle, dynamic))
            .flatten();
        classes.push((handle, class, dynamic));
    }

    // The groups native colliders use, whether each has dynamic and
    // non-dynamic members, and the rules between them.
    let mut members: HashMap<CollisionGroup, (bool, bool)> = HashMap::new();
    for class in classes.iter().filter_map(|(_, class, _)| *class) {
        let entry = members.entry(class.group).or_default();
        if class.dynamic {
            entry.0 = true;
        } else {
            entry.1 = true;
        }
    }
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
    let relations = || {
        used.iter()
            .flat_map(|&a| used.iter().map(move |&b| (a, b, group_rule(a, b))))
    };
    // A group with a NoContacts relation needs the hook: the pair must exist
    // without contacts, which no group test can say.
    let needs_hook: HashSet<CollisionGroup> = relations()
        .filter(|&(_, _, rule)| rule == CollisionRule::NoContacts)
        .flat_map(|(a, b, _)| [a, b])
        .collect();
    let has_dynamic = |g: CollisionGroup| members[&g].0;
    let has_static = |g: CollisionGroup| members[&g].1;
    // Non-dynamic members take every collision type only where they may pair
    // with other non-dynamic colliders; elsewhere Rapier's default types
    // already keep them apart, as NoPair would.
    let static_types: HashSet<CollisionGroup> = relations()
        .filter(|&(a, b, rule)| rule != CollisionRule::NoPair && has_static(a) && has_static(b))
        .flat_map(|(a, b, _)| [a, b])
        .collect();
    let filtered_by_types = |g: CollisionGroup| !has_dynamic(g) && !static_types.contains(&g);
    let needs_bits = |(a, b, rule): (CollisionGroup, CollisionGroup, CollisionRule)| match rule {
        CollisionRule::NoPair => !(filtered_by_types(a) && filtered_by_types(b)),
        // Only a dynamic body responds: other pairs need no solver test.
        CollisionRule::NoResponse => has_dynamic(a) || has_dynamic(b),
        _ => false,
    };
    let mut involved: Vec<CollisionGroup> = relations()
        .filter(|&(a, b, _)| !needs_hook.contains(&a) && !needs_hook.contains(&b))
        .filter(|&relation| needs_bits(relation))
        .flat_map(|(a, b, _)| [a, b])
        .collect::<HashSet<_>>()
        .into_iter()
        .collect();
    involved.sort_unstable();
    // One bit per involved group while they fit; the rest fall back to
    // hooks. A group with no relation to test keeps every bit as its
    // membership (a collider's default), which no filter leaves out.
    let bits: HashMap<CollisionGroup, u32> = involved
        .iter()
        .take(32)
        .enumerate()
        .map(|(i, &g)| (g, i as u32))
        .collect();
    let native_group = |g: CollisionGroup| {
        !needs_hook.contains(&g) && (bits.contains_key(&g) || !involved.contains(&g))
    };
    let bit_of = |g: CollisionGroup| {
        bits.get(&g)
            .map_or(Group::ALL, |&bit| Group::from_bits_retain(1 << bit))
    };
    let filter_of = |g: CollisionGroup, excluded: CollisionRule| {
        let mut filter = Group::ALL;
        for (&h, &bit) in &bits {
            if group_rule(g, h) == excluded && needs_bits((g, h, excluded)) {
                filter.remove(Group::from_bits_retain(1 << bit));
            }
        }
        filter
    };
    let mut filters: HashMap<CollisionGroup, (Group, Group)> = HashMap::new();

    for (handle, class, dynamic) in classes {
        let entry = match class.filter(|c| native_group(c.group)) {
            None => ColliderPlan::hooked_plan(dynamic),
            Some(class) => {
                let g = class.group;
                let (collision, solver) = *filters.entry(g).or_insert_with(|| {
                    (
                        filter_of(g, CollisionRule::NoPair),
                        filter_of(g, CollisionRule::NoResponse),
                    )
                });
                let types = if dynamic || !static_types.contains(&g) {
                    ActiveCollisionTypes::default()
                } else {
                    ActiveCollisionTypes::all()
                };
                ColliderPlan {
                    class: Some(class),
                    collision: InteractionGroups::new(
                        bit_of(g),
                        collision,
                        InteractionTestMode::And,
                    ),
                    solver: InteractionGroups::new(bit_of(g), solver, InteractionTestMode::And),
                    types,
                }
            }
        };
        if let Some(class) = entry.class {
            plan.classes.insert(class, entry);
        }
        plan.colliders.insert(handle, entry);
    }
    plan
}

/// Plans `handles` alone, against the rest of `plan`: possible when each of
/// them ends up hooked or in a class the plan already has (the bits and
/// filters of every group then stay as they are). `None`: plan everything.
pub(crate) fn replan_some(
    plan: &Plan,
    rules: &CollisionRuleSet,
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    handles: &[ColliderHandle],
    pinned: &HashSet<ColliderHandle>,
    all_hooked: bool,
) -> Option<Vec<(ColliderHandle, ColliderPlan)>> {
    let mut planned = Vec::with_capacity(handles.len());
    for &handle in handles {
        let Some(collider) = colliders.get(handle) else {
            continue;
        };
        let dynamic = collider
            .parent()
            .and_then(|b| bodies.get(b))
            .is_some_and(|b| b.is_dynamic());
        let class = (!all_hooked && !pinned.contains(&handle))
            .then(|| native_class(rules, bodies, colliders, handle, dynamic))
            .flatten();
        let entry = match class {
            None => ColliderPlan::hooked_plan(dynamic),
            Some(class) => *plan.classes.get(&class)?,
        };
        planned.push((handle, entry));
    }
    Some(planned)
}

/// The class of collider `leaf`, or `None` if its chain carries per-pair
/// rules or mixes effective groups.
fn native_class(
    rules: &CollisionRuleSet,
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    leaf: ColliderHandle,
    dynamic: bool,
) -> Option<Class> {
    let mut group = None;
    let mut node = Some(Node::Collider(leaf));
    while let Some(current) = node {
        if rules.is_named(current) {
            return None;
        }
        if let Some(record) = rules.record(current) {
            if record.personal.is_decided() || !record.specific.is_empty() {
                return None;
            }
        }
        let effective = rules.effective_group(bodies, colliders, current);
        if group.is_some_and(|g| g != effective) {
            return None;
        }
        group = Some(effective);
        node = rules.hierarchy.next(bodies, colliders, current);
    }
    group.map(|group| Class { group, dynamic })
}
