//! Personal rules that Rapier's groups decide: colliders of dynamic bodies
//! whose chain's personal rules all say one `Normal`, `NoResponse` or
//! `NoPair`.

use hashbrown::HashMap;
use super::super::rapier::prelude::*;

use super::class::Class;
use super::plan::Request;
use super::super::{CollisionRule, CollisionRuleSet, Node};

/// The first decided personal rule up the chain of `leaf`, and its depth
/// (0 for the collider itself).
pub(super) fn first_personal(
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
pub(super) fn personal_rule(
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
pub(super) fn personal_natives(
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
        let Some((rule, depth)) = personal_rule(rules, bodies, colliders, handle)
            .filter(|&(rule, _)| request.native_rule(rule))
        else {
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

/// Whether `start` or a node above it carries specific entries or is named
/// by one.
fn touches_entries(
    rules: &CollisionRuleSet,
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    start: impl Into<Node>,
) -> bool {
    rules
        .hierarchy
        .chain(bodies, colliders, start.into())
        .any(|node| rules.in_entries(node))
}
