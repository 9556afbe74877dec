//! Carriers: which side of each specific entry and pinned pair is hooked,
//! chosen by cost (`docs/architecture.md`, "The planner").

use hashbrown::HashSet;
use super::super::rapier::prelude::*;

use super::plan::Request;
use super::super::Node;
use super::super::model::dynamic_body;

/// Chooses, for every specific entry and every pinned pair, the side that
/// carries the hook flag, adds its colliders to `hooked` and returns those
/// it added. A specific entry `x -> y` reaches only pairs whose chains hold
/// `x` on one side and `y` on the other, so hooking every collider under
/// either node decides all of them; the cheaper side is taken (colliders
/// already hooked cost nothing, dynamic ones little, a fixed or kinematic
/// hub much), the entry's owner on a tie.
pub(super) fn carriers(
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
        subjects.sort_unstable();
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
                    Some(collider) if dynamic_body(bodies, collider.parent()) => 1,
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
