//! After Rapier's step: admitting the pairs the hook saw, giving a rule to
//! those Rapier made without asking it, and forgetting the hooked pairs
//! Rapier no longer has, each looked up in its graph from the hooked side.

use std::sync::PoisonError;

use hashbrown::HashSet;
use super::super::rapier::prelude::*;

use super::step::missing;
use super::{ManifoldUpdate, PairKey, PairState, PlanCause, RecalculationPolicy, RuleHooks, Witness};
use super::super::CollisionRule;
use super::super::model::soft_rigid;
use super::super::planner::Plan;
use super::super::world::{Joints, filters_pass, pair_exists, partners_of, same_body};

/// After the step.
impl RuleHooks {
    /// [`after_step`](Self::after_step); `quiet` when no body was awake
    /// before or after the step and the world's census after it is that of
    /// the last step's end (see [`census`](super::super::world::census)), so that no pair can have ended
    /// unless something was changed before it.
    pub(super) fn finish_step(
        &mut self,
        narrow_phase: &NarrowPhase,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        joints: Option<Joints<'_>>,
        quiet: bool,
    ) {
        self.boundary.counted = false;
        if !std::mem::take(&mut self.boundary.prepared) {
            missing(
                "prepare",
                "before the step (an after_step called twice, or after RuleHooks::step, which \
                 calls both itself, looks the same)",
            );
        }
        self.soft.forget_pieces();
        self.boundary.followed = false;
        if !self.boundary.followed_at_prepare && self.soft.seen(bodies) {
            missing(
                "follow_soft_bodies",
                "before prepare, in a world with soft bodies (a `NoResponse` of a soft body is \
                 then left to Rapier's solver groups, which its soft-body solver does not read, \
                 and the pieces of cuts and tears have no rules)",
            );
        }
        if !self.queued.to_wake.is_empty() {
            missing("wake_edited", "before the step, after prepare");
        }
        if self.boundary.owe_freeze {
            missing("freeze_manifolds", "before the step, after prepare");
        }
        self.check_witness_after(narrow_phase, bodies, colliders);
        self.forget_part_standings(narrow_phase, colliders);
        let pending_empty = self
            .pending
            .get_mut()
            .unwrap_or_else(PoisonError::into_inner)
            .is_empty();
        let unchanged = pending_empty && self.queued.touched.is_empty() && self.queued.regrouped.is_empty();
        if unchanged && !self.planned.exhaustive && (quiet || self.pairs.is_empty()) {
            return;
        }
        self.stats.swept = true;
        // Rapier finds a pair by slot: a handle whose slot was reused must
        // not find the new collider's pair.
        let exists = |key: PairKey| {
            let (a, b) = key.colliders();
            colliders.contains(a) && colliders.contains(b) && pair_exists(narrow_phase, a, b)
        };
        let pending = std::mem::take(
            self.pending
                .get_mut()
                .unwrap_or_else(PoisonError::into_inner),
        );
        for (key, state) in pending {
            if !exists(key) {
                continue;
            }
            match self.pairs.get_mut(key) {
                // Calculated again for new body types (see `rule_now`).
                Some(tracked) => {
                    tracked.computed = state.computed;
                    tracked.kinds = state.kinds;
                }
                None => {
                    self.stats.pairs_created += 1;
                    self.pairs.insert(key, state);
                }
            }
        }

        // The pairs of colliders configured or changed before the step:
        // Rapier may have made some without asking the hook (the bodies
        // rest), and those of a hooked collider are live all the same.
        let touched = std::mem::take(&mut self.queued.touched);
        let hooked = |plan: &Plan, c: ColliderHandle| plan.hooks(c);
        let mut unseen = Vec::new();
        for &c in &touched {
            if !hooked(&self.planned.plan, c) {
                continue;
            }
            for other in partners_of(narrow_phase, c) {
                let key = PairKey::new(c, other);
                if self.pairs.get(key).is_none()
                    && filters_pass(bodies, colliders, joints, c, other)
                {
                    unseen.push(key);
                }
            }
        }
        for key in unseen {
            let (a, b) = key.colliders();
            let rule = self.calculate(bodies, colliders, a, b);
            let kinds = key.kinds(bodies, colliders);
            let parts = key.made_of_parts(colliders);
            self.pairs
                .insert(key, PairState::new(rule, self.boundary.step, kinds, parts));
        }

        // Forget the hooked pairs Rapier no longer has, looked up in Rapier's
        // graph: the broad phase may have dropped a pair during the step, and
        // even a pair of resting bodies ends when the project moves or
        // re-parents a collider through Rapier, which the hooks do not watch
        // unless the rules reach it.
        let step = self.boundary.step;
        let touched: HashSet<ColliderHandle> = touched.into_iter().collect();
        let regrouped = std::mem::take(&mut self.queued.regrouped);
        let (mut answered, mut pinned_ended, mut without_contacts) = (0, false, 0);
        let mut retyped = Vec::new();
        let recomputes = self.decide.policy != RecalculationPolicy::Manual;
        let plan = &self.planned.plan;
        let mut witness = None;
        self.pairs.retain(|key, state| {
            let (a, b) = key.colliders();
            state.absent = false;
            // From the hooked side, whose pairs are few (Rapier walks the
            // first collider's pairs).
            let exists_from_hooked_side = || {
                if hooked(plan, a) {
                    pair_exists(narrow_phase, a, b)
                } else {
                    pair_exists(narrow_phase, b, a)
                }
            };
            let keep = if !hooked(plan, a) && !hooked(plan, b) {
                // Both sides native now: Rapier decides the pair itself.
                false
            } else if !colliders.contains(a) || !colliders.contains(b) {
                false
            } else if (touched.contains(&a) || touched.contains(&b)) && same_body(colliders, a, b) {
                // Moved onto one body: Rapier never lets them interact.
                false
            } else if regrouped.contains(&a) || regrouped.contains(&b) {
                state.absent = !(pair_exists(narrow_phase, a, b)
                    && filters_pass(bodies, colliders, joints, a, b));
                true
            } else if state.answered_in(step) {
                // Rapier asked the hook during the step: the pair passed
                // Rapier's filters (tested before the hook) and the hook saw
                // the bodies' types. It may still have ended later in the
                // step (Rapier looks for pairs again after moving bodies).
                answered += 1;
                exists_from_hooked_side()
            } else {
                exists_from_hooked_side() && filters_pass(bodies, colliders, joints, a, b)
            };
            // A pinned pair that ends leaves the side hooked for it: the
            // plan takes it back.
            pinned_ended |= !keep && state.is_pinned();
            // The hook answers a soft-rigid pair without response with no
            // contacts, which a step without it shows as it shows them for
            // `NoContacts`.
            let soft = keep && state.rule() == CollisionRule::NoResponse && soft_rigid(colliders, a, b);
            without_contacts += usize::from(soft);
            if keep
                && witness.is_none()
                && state.answered_in(step)
                && state.manifold == ManifoldUpdate::ByRule
                && matches!(
                    state.rule(),
                    CollisionRule::NoPair | CollisionRule::NoContacts | CollisionRule::NoResponse
                )
            {
                witness = Some(Witness {
                    key,
                    rule: state.rule(),
                    answered_as: if soft { CollisionRule::NoContacts } else { state.rule() },
                });
            }
            // A body changed type (the hooks may not watch it): the rule
            // follows the default groups, and an override the special case.
            // A pair the hook answered was restated with the types it saw.
            let overridden = state.overridden.is_some();
            if keep && (overridden || !state.answered_in(step)) {
                let kinds = key.kinds(bodies, colliders);
                if kinds != state.kinds {
                    if recomputes && !overridden {
                        retyped.push((key, kinds));
                    } else {
                        state.kinds = kinds;
                    }
                }
            }
            keep
        });
        if pinned_ended {
            self.queued.replan.get_or_insert(PlanCause::PinnedPair);
        }
        self.boundary.witness = witness;
        for (key, kinds) in retyped {
            let (a, b) = key.colliders();
            let rule = self.calculate(bodies, colliders, a, b);
            if let Some(state) = self.pairs.get_mut(key) {
                state.computed = rule;
                state.kinds = kinds;
            }
        }
        // Pairs kept through their colliders' regrouping are looked up again
        // after the next step: by then Rapier has found them again, or not.
        self.queued.touched.extend(regrouped);
        self.stats.hooked_pairs_answered = answered;
        self.stats.soft_pairs_without_contacts = without_contacts;
        self.stats.tracked_pairs = self.pairs.len();
    }
}
