//! Recalculating live pairs as the policy says, after an edit or a forced
//! recalculation; a pair whose rule changed has its bodies woken.

use hashbrown::HashSet;
use super::super::rapier::prelude::*;

use super::{PairKey, PlanCause, RuleHooks};
use super::super::Node;
use super::super::model::CollidersUnder;

/// Recalculation.
impl RuleHooks {
    /// `node` itself if it is a collider, and every collider below it.
    pub(super) fn colliders_under(
        &self,
        node: Node,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
    ) -> CollidersUnder {
        self.decide.rules.colliders_under(node, bodies, colliders)
    }

    /// Recalculates the live pairs that are `everything`, or touch an
    /// `affected` collider, or a `forced` one (whose overrides are dropped).
    /// Returns colliders of changed pairs between fixed bodies, which Rapier
    /// must be made to look at again.
    pub(super) fn recalculate(
        &mut self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        everything: bool,
        affected: &HashSet<ColliderHandle>,
        forced: &HashSet<ColliderHandle>,
    ) -> Vec<ColliderHandle> {
        let mut refresh = Vec::new();
        // Everything, or the pairs of the colliders reached (through the
        // table's index: an edit costs its colliders' pairs).
        let mut keys: Vec<PairKey> = if everything {
            self.pairs.iter().map(|(key, _)| key).collect()
        } else {
            affected
                .iter()
                .chain(forced)
                .flat_map(|&c| self.pairs.keys_of(c).iter().copied())
                .collect()
        };
        // The table's order is its hasher's, seeded per process: the
        // wake-ups and nudges below reach Rapier in the pair order instead,
        // which the updates keep.
        keys.sort_unstable();
        keys.dedup();
        let mut updates = Vec::new();
        let mut unpinned = false;
        for key in keys {
            let (a, b) = key.colliders();
            // Rapier removed one of them (unwatched): the pair is forgotten
            // after the step and has nothing to wake.
            if !colliders.contains(a) || !colliders.contains(b) {
                continue;
            }
            let force = forced.contains(&a) || forced.contains(&b);
            updates.push((key, self.calculate(bodies, colliders, a, b), force));
        }
        self.stats.pairs_recalculated = updates.len();
        for (key, computed, force) in updates {
            let state = self
                .pairs
                .get_mut(key)
                .expect("the key came from the table");
            let before = state.rule();
            let kinds = key.kinds(bodies, colliders);
            // A body changed type since the pair was calculated: Rapier looks
            // at its colliders' pairs again by itself and wakes it as
            // `set_body_type` was told, so the new rule needs neither a nudge
            // nor a wake-up (`docs/semantics.md`, "Decisions about live pairs").
            let retyped = kinds != state.kinds;
            state.computed = computed;
            state.kinds = kinds;
            if force && state.overridden.take().is_some() {
                // Unless a manifold setting still pins the pair, the side
                // hooked for the override goes back to its plan.
                unpinned |= !state.is_pinned();
            }
            if state.rule() != before && !retyped {
                let (a, b) = key.colliders();
                self.wake_pair(a, b);
                // Fixed bodies never wake: Rapier looks at their pair again
                // only if a collider changed.
                let fixed = |c| {
                    colliders
                        .get(c)
                        .and_then(|c| c.parent())
                        .and_then(|b| bodies.get(b))
                        .is_none_or(|b| b.is_fixed())
                };
                if fixed(a) && fixed(b) {
                    refresh.push(a);
                }
            }
        }
        if unpinned {
            // Planned at the next step's prepare: the side stays hooked one
            // step more, answering by the rules.
            self.queued.replan.get_or_insert(PlanCause::PinnedPair);
        }
        refresh
    }
}
