//! Planning a few colliders against the rest of the plan, and when that
//! is not enough.

use super::super::rapier::prelude::*;

use super::class::{Class, native_class};
use super::collider_plan::ColliderPlan;
use super::personal::{first_personal, personal_rule};
use super::plan::{Plan, Request};
use super::super::model::dynamic_body;
use super::super::{CollisionRule, CollisionRuleSet, Node};

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
        let dynamic = dynamic_body(bodies, collider.parent());
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
