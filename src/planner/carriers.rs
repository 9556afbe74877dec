//! Carriers: which side of a specific entry or a pinned pair is hooked,
//! chosen by cost (`docs/architecture.md`, "The planner").

use hashbrown::HashSet;
use super::super::rapier::prelude::*;

use super::plan::Request;
use super::super::model::dynamic_body;

/// Hooks the cheaper side of every pinned pair (an override or a manifold
/// setting keeps one side hooked), adds its colliders to `hooked` and
/// returns those it added. The side is chosen by body type alone, which
/// does not change with the pair's neighbours, so every plan of the same
/// world chooses alike.
pub(super) fn pinned_carriers(
    request: &Request<'_>,
    hooked: &mut HashSet<ColliderHandle>,
) -> HashSet<ColliderHandle> {
    let mut added = HashSet::new();
    for key in request.pinned {
        let (a, b) = key.colliders();
        let is_hooked = |c: ColliderHandle| hooked.contains(&c);
        let by_type = |_| None;
        let side = if side_cost(request, &[b], is_hooked, &by_type)
            < side_cost(request, &[a], is_hooked, &by_type)
        {
            b
        } else {
            a
        };
        if hooked.insert(side) {
            added.insert(side);
        }
    }
    added
}

/// What hooking the colliders of `side` not yet `hooked` costs: each loses
/// Rapier's contact recycling on every pair it has. Where Rapier's graph is
/// at hand a collider costs one more than its pairs now, and a fixed or
/// kinematic one one more again (a fixed pickup that touches nothing is
/// cheap, a floor under a pile dear, and at equal pairs the dynamic side is
/// hooked); without it (a bare `prepare`) a dynamic collider costs 1 and a
/// fixed or kinematic one, which may be a hub, 1,000 (`docs/architecture.md`,
/// "The planner").
pub(super) fn side_cost(
    request: &Request<'_>,
    side: &[ColliderHandle],
    hooked: impl Fn(ColliderHandle) -> bool,
    pairs_of: &dyn Fn(ColliderHandle) -> Option<usize>,
) -> u64 {
    side.iter()
        .filter(|&&c| !hooked(c))
        .map(|&c| match request.colliders.get(c) {
            None => 0,
            Some(collider) => {
                let dynamic = dynamic_body(request.bodies, collider.parent());
                match pairs_of(c) {
                    // A fixed or kinematic collider weighs one more: at equal
                    // pairs (none yet, in a new world) the hub stays native.
                    Some(pairs) => 1 + pairs as u64 + u64::from(!dynamic),
                    None if dynamic => 1,
                    None => 1_000,
                }
            }
        })
        .sum()
}
