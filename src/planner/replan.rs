//! Planning a few colliders against the rest of the plan, and when that
//! is not enough.

use hashbrown::{HashMap, HashSet};
use super::super::rapier::prelude::*;

use super::class::{Class, native_class};
use super::collider_plan::ColliderPlan;
use super::decisions::{Base, Facts, Footprint};
use super::personal::{Shallower, first_personal, native_personal};
use super::plan::{Plan, Request, ordered};
use super::room::Room;
use super::super::model::dynamic_body;
use super::super::Node;

/// Plans `handles` alone, against the rest of `plan`, at the cost of their
/// own colliders, the specific entries that reach them and, where an
/// entry's decision changes, the colliders under its two nodes
/// (`docs/architecture.md`, "Cost per step"). Each collider's plan before
/// the entries is its class's (a class the plan already has), a personal
/// `Normal`, or hooked by its own chain; the entries that reach it are
/// decided as a whole plan decides them (see [`Decisions`](super::decisions::Decisions)), and their
/// decisions applied. `rechained` are the colliders whose chains a
/// parent-map edit changed: every entry that names a node of their new
/// chains is checked again, since they may now be on its sides (those of
/// their old chains only lost them, which leaves a decision exact). Updates the plan's decisions and bases, and returns
/// the colliders' plans to write. `None` (plan everything again) when a
/// collider needs what only a whole plan gives: a class no native collider
/// has, a class losing its last member, a personal rule that changes
/// whether the groups can say others' (see [`Plan::personal_moved`]),
/// settings outside the room the plan took, or a pinned pair.
pub(crate) fn replan_some(
    plan: &mut Plan,
    request: &Request<'_>,
    handles: &[ColliderHandle],
    edited: &[(Node, Node)],
    rechained: &HashSet<ColliderHandle>,
) -> Option<Vec<(ColliderHandle, ColliderPlan)>> {
    let Request {
        rules,
        bodies,
        colliders,
        ..
    } = *request;
    if request.all_hooked.is_some() {
        return None;
    }
    let pinned = request.pinned_colliders();
    // What decides whether the groups say a personal rule: any change of it
    // is planned whole (see `put_base`), so it holds for every collider here.
    let shallower = plan.personal_depths.shallower();
    let mut asked: Vec<ColliderHandle> = Vec::with_capacity(handles.len());
    // Sized once: growing a set rehashes it each time it doubles.
    let mut seen: HashSet<ColliderHandle> = HashSet::with_capacity(2 * handles.len());
    // Asked colliders new to the plan, or whose plan before the entries or
    // body changed.
    let mut moved: HashSet<ColliderHandle> = HashSet::with_capacity(handles.len());
    for &handle in handles {
        if pinned.contains(&handle) {
            return None;
        }
        if let Some(base) = base_of(plan, request, &shallower, &pinned, handle)? {
            let (old, whole) = put_base(plan, handle, base);
            if whole {
                return None;
            }
            if old != Some(base) {
                moved.insert(handle);
            }
            if rechained.contains(&handle) {
                moved.insert(handle);
            }
            if seen.insert(handle) {
                asked.push(handle);
            }
        }
    }

    // The entries edited alone, and those that reach an asked collider:
    // those of the nodes of its chain (an edit of a node's rules may have
    // changed them), and, for a collider that moved, those the decisions
    // list under them (where it is the subject of an entry). The entries
    // listed under a collider that did not move are as exact as they were:
    // a hub named by many entries costs nothing when an edit or a removal
    // touches it.
    let mut entries: Vec<(Node, Node)> = edited.iter().map(|&(x, y)| ordered(x, y)).collect();
    for &handle in &asked {
        let moved = moved.contains(&handle);
        for node in rules.hierarchy.chain(bodies, colliders, Node::Collider(handle)) {
            if let Some(record) = rules.record(node) {
                entries.extend(record.specific.keys().map(|&other| ordered(node, other)));
            }
            if moved {
                entries.extend(plan.decisions.listed(node));
            }
        }
    }
    entries.sort_unstable();
    entries.dedup();
    // A new entry may link the sides of an entry that Rapier's groups
    // decide with a bit, which must then be checked again.
    let linked: Vec<(Node, Node)> = entries
        .iter()
        .filter(|&&e| !plan.decisions.made(e))
        .flat_map(|&e| plan.decisions.linked_by(request, e))
        .collect();
    if !linked.is_empty() {
        entries.extend(linked);
        entries.sort_unstable();
        entries.dedup();
    }
    // What the decisions say of each node of the entries, before: a node
    // whose say the new decisions leave as it was keeps its colliders' plans.
    let mut before: HashMap<Node, Footprint> = HashMap::with_capacity(2 * entries.len());
    before.extend(
        entries
            .iter()
            .flat_map(|&(x, y)| [x, y])
            .map(|node| (node, plan.decisions.footprint(node))),
    );
    let changed = {
        let Plan {
            base,
            decisions,
            room,
            group_bits,
            ..
        } = plan;
        let group_bits = *group_bits;
        let mut free = || {
            let (found, _) = *room.get_or_insert_with(|| {
                (Room::of_world(colliders, request.own), colliders.len())
            });
            found.bits() - Group::from_bits_retain(group_bits)
        };
        let known = |c: ColliderHandle| base.get(&c).copied();
        let is_pinned = |c: ColliderHandle| pinned.contains(&c);
        let mut facts = Facts {
            base: &known,
            pinned: &is_pinned,
            free: &mut free,
        };
        decisions.decide(request, &mut facts, &entries)
    };
    // An entry decided anew changes the colliders under its nodes whose say
    // changed (a ball that shares its turret's bit leaves the turret's
    // colliders as they were), those no entry reaches through any more
    // (see `Decisions::forget_ended`), and those not planned yet.
    let mut nodes: Vec<Node> = changed.into_iter().flat_map(|(x, y)| [x, y]).collect();
    nodes.sort_unstable();
    nodes.dedup();
    for node in nodes {
        let under = rules.colliders_under(node, bodies, colliders);
        let kept = before.get(&node) == Some(&plan.decisions.footprint(node))
            && rules.in_entries(node)
            && under.iter().all(|c| plan.base.contains_key(c));
        if kept {
            continue;
        }
        for c in under {
            if seen.insert(c) {
                if plan.base.get(&c).is_none() {
                    let base = base_of(plan, request, &shallower, &pinned, c)??;
                    if put_base(plan, c, base).1 {
                        return None;
                    }
                }
                asked.push(c);
            }
        }
    }
    let planned = asked
        .into_iter()
        .filter_map(|handle| {
            let base = plan.base[&handle];
            let own = (request.own)(handle, colliders.get(handle)?);
            let entry = plan.decisions.apply(request, handle, base);
            Some((handle, entry.fitted(own, base.dynamic, rules)))
        })
        .collect();
    Some(planned)
}

/// Gives `handle` its plan before the entries, counted in its class and by
/// its first personal rule; returns the old one, and whether only a whole
/// plan can follow the change: the last member of its old class left (the
/// groups' settings follow which classes have members), or its personal
/// rule changed what the others read (see [`Plan::personal_moved`]).
fn put_base(plan: &mut Plan, handle: ColliderHandle, base: Base) -> (Option<Base>, bool) {
    let old = plan.base.insert(handle, base);
    if old == Some(base) {
        return (old, false);
    }
    if let Some(class) = base.class {
        *plan.class_counts.entry(class).or_default() += 1;
    }
    let emptied = old.and_then(|o| o.class).is_some_and(|c| plan.count_out(c));
    let personal = plan.personal_moved(old.and_then(|o| o.first_personal), base.first_personal);
    (old, emptied || personal)
}

/// The plan of `handle` before the entries, against the rest of `plan`:
/// `Some(None)` for a collider no longer in the world, `None` where only a
/// whole plan can say (see [`replan_some`]).
fn base_of(
    plan: &Plan,
    request: &Request<'_>,
    shallower: &Shallower,
    pinned: &HashSet<ColliderHandle>,
    handle: ColliderHandle,
) -> Option<Option<Base>> {
    let Request {
        rules,
        bodies,
        colliders,
        ..
    } = *request;
    let Some(collider) = colliders.get(handle) else {
        return Some(None);
    };
    let own = (request.own)(handle, collider);
    if plan.room.is_some_and(|(room, _)| !room.holds(own)) {
        // Its settings take bits or types the plan gave away: look again.
        return None;
    }
    let dynamic = dynamic_body(bodies, collider.parent());
    let first_personal = first_personal(rules, bodies, colliders, handle);
    let mut personal = false;
    let class = native_class(rules, bodies, colliders, handle, dynamic);
    let entry = match class {
        None => match native_personal(request, shallower, pinned, handle, dynamic) {
            Some(rule) => {
                personal = true;
                ColliderPlan::personal(rule)
            }
            None => ColliderPlan::hooked_plan(dynamic),
        },
        Some(class) if class == Class::unreached(dynamic) => {
            match plan.classes.get(&class) {
                Some(entry) => *entry,
                // Checked when the plan was made: a default class is planned
                // as Rapier's defaults unless the plan is a full pass.
                None if plan.full.is_none() => ColliderPlan::unreached(dynamic),
                // A full pass classed every collider: a default class with
                // members and no entry is one its groups' settings hook (a
                // `NoResponse` where soft bodies are); one without members
                // is new to the plan, whose settings did not see it.
                None if plan.class_counts.contains_key(&class) => {
                    ColliderPlan::hooked_plan(dynamic)
                }
                None => return None,
            }
        }
        Some(class) => *plan.classes.get(&class)?,
    };
    Some(Some(Base {
        plan: entry,
        personal,
        first_personal,
        class,
        dynamic,
        body: collider.parent(),
    }))
}
