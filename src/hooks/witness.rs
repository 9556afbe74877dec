//! Whether Rapier stepped without the hooks since their last step
//! (`docs/semantics.md`, "Stepping without the hooks").

use super::super::rapier::prelude::*;

use std::sync::PoisonError;
use std::sync::atomic::Ordering;

use super::{PairKey, RuleHooks, Witness};
use super::super::CollisionRule;
use super::answer::answer_overridden;
use super::one_way_contacts::forbids;
use super::super::model::Named;

/// The witness.
impl RuleHooks {
    /// Whether Rapier stepped without these hooks since their last step: the
    /// witness pair (one hooked pair the hook answered "no pair", "no
    /// contacts" or "no response") shows another answer in Rapier's graph,
    /// or the one-way witness solver contacts its surface refuses. One
    /// look-up each per step (`docs/semantics.md`, "Stepping without the
    /// hooks"). The witnesses stay for
    /// [`check_witness_after`](Self::check_witness_after).
    pub(super) fn check_witness(&mut self, narrow_phase: &NarrowPhase) {
        if let Some(key) = self.boundary.one_way_witness
            && one_way_overridden(narrow_phase, key)
        {
            self.report_one_way_unhooked(key, "since their last step");
        }
        let Some(Witness { key, rule, answered_as }) = self.boundary.witness else {
            return;
        };
        if witness_overridden(narrow_phase, key, answered_as) {
            let (a, b) = key.colliders();
            let (a, b) = (Named(a.into()), Named(b.into()));
            self.report_unhooked(&format!(
                "Rapier stepped without the RuleHooks since their last step: the {rule:?} pair \
                 of {a} and {b} was given contacts and impulses the rules refuse, \
                 and every rule the hook decides was dropped for that step"
            ));
        }
    }

    /// Whether a witness of the last step shows another answer in Rapier's
    /// graph: Rapier stepped without the hooks since. Asked before their
    /// own step's `prepare`, so that its look reads what that step's
    /// clearing of Rapier's change flags hid (`docs/architecture.md`,
    /// "Rapier's change flags"); [`check_witness`](Self::check_witness)
    /// then says which.
    pub(super) fn witness_overridden(&self, narrow_phase: &NarrowPhase) -> bool {
        self.boundary
            .one_way_witness
            .is_some_and(|key| one_way_overridden(narrow_phase, key))
            || self
                .boundary
                .witness
                .is_some_and(|w| witness_overridden(narrow_phase, w.key, w.answered_as))
    }

    /// After a step in which Rapier asked the hook nothing: whether that
    /// step was taken without the hooks, between their `prepare` and
    /// `after_step` (`world.step()` where the hooks should have been
    /// passed). The witness of the last step, still hooked with the same
    /// rule, shows another answer in Rapier's graph.
    /// A step with the hooks that asks nothing (the bodies sleep) leaves
    /// the pair's contacts as the hook left them. Takes the witness.
    pub(super) fn check_witness_after(
        &mut self,
        narrow_phase: &NarrowPhase,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
    ) {
        let one_way = self.boundary.one_way_witness.take();
        // This step's, for the next checks.
        if std::mem::take(self.boundary.one_way_noting.get_mut()) {
            self.boundary.one_way_witness = self
                .boundary
                .one_way_noted
                .get_mut()
                .unwrap_or_else(PoisonError::into_inner)
                .take();
        }
        let witness = self.boundary.witness.take();
        if *self.boundary.stepped.get_mut() {
            return;
        }
        if let Some(key) = one_way {
            let (a, b) = key.colliders();
            // Still a one-way pair the hook is asked about: a step with the
            // hooks that updated its contacts asked them, so this one was
            // not, or left them as the hook did.
            let asked = |c: ColliderHandle| {
                colliders.get(c).is_some_and(|co| {
                    co.active_hooks().contains(ActiveHooks::MODIFY_SOLVER_CONTACTS)
                })
            };
            let rules = &self.decide.rules;
            let one_way_of = |c| rules.one_way_of(bodies, colliders, c).is_some();
            if colliders.contains(a)
                && colliders.contains(b)
                && (asked(a) || asked(b))
                && (one_way_of(a) || one_way_of(b))
                && one_way_overridden(narrow_phase, key)
            {
                self.report_one_way_unhooked(key, "between their `prepare` and `after_step`");
            }
        }
        let Some(Witness { key, rule, answered_as }) = witness else {
            return;
        };
        let (a, b) = key.colliders();
        let plan = &self.planned.plan;
        // Asked nothing, so not this pair either: still hooked with the
        // same rule, its contacts are the hook's last answer or Rapier's own.
        let same = self.pairs.get(key).is_some_and(|state| state.rule() == rule);
        if same
            && colliders.contains(a)
            && colliders.contains(b)
            && (plan.hooks(a) || plan.hooks(b))
            && witness_overridden(narrow_phase, key, answered_as)
        {
            let (a, b) = (Named(a.into()), Named(b.into()));
            self.report_unhooked(&format!(
                "Rapier stepped without the RuleHooks between their `prepare` and `after_step`: \
                 the {rule:?} pair of {a} and {b} was given contacts and impulses \
                 the rules refuse, and every rule the hook decides was dropped for that step"
            ));
        }
    }

    /// Notes `key`, a convex pair whose contacts the hook dropped for a
    /// forbidden standing, as this step's one-way witness if it has none:
    /// one lock a step at most.
    pub(super) fn note_one_way_witness(&self, key: PairKey) {
        // A load first: the swap's write is taken once a step, not at every
        // dropped manifold.
        let noting = &self.boundary.one_way_noting;
        if self.boundary.prepared
            && !noting.load(Ordering::Relaxed)
            && !noting.swap(true, Ordering::Relaxed)
        {
            *self
                .boundary
                .one_way_noted
                .lock()
                .unwrap_or_else(PoisonError::into_inner) = Some(key);
        }
    }

    #[cold]
    fn report_one_way_unhooked(&mut self, key: PairKey, when: &str) {
        let (a, b) = key.colliders();
        let (a, b) = (Named(a.into()), Named(b.into()));
        self.report_unhooked(&format!(
            "Rapier stepped without the RuleHooks {when}: the pair of {a} and {b}, \
             blocked from one side of a one-way surface and let through by the hook, was given \
             contacts the surface refuses, and every rule the hook decides was dropped for that step"
        ));
    }

    /// Whether Rapier stepped with these hooks but without their `prepare`
    /// since their last step: the hook answered a pair outside `prepare` ..
    /// `after_step` (`docs/semantics.md`, "Stepping without the hooks").
    pub(super) fn check_prepared(&mut self) {
        if std::mem::take(self.boundary.unprepared.get_mut()) {
            self.report_unhooked(
                "Rapier stepped with the RuleHooks but without their `prepare` since their last \
                 step (the hook answered a pair outside `prepare` .. `after_step`, as when the \
                 hooks are given to `world.step_with_events(&hooks, ..)`): nothing that changed \
                 was planned, and no pair the step made or ended was kept",
            );
        }
    }

    /// Says that Rapier stepped without the hooks (`what` happened), with
    /// the fix, and notes it in the step's stats.
    #[cold]
    fn report_unhooked(&mut self, what: &str) {
        self.stats.stepped_without_hooks = true;
        // That step cleared Rapier's change flags of what the project
        // changed before it (`docs/architecture.md`, "Rapier's change flags").
        self.planned.roster.read_all_next();
        let message = format!(
            "{what}. Step with `hooks.step(&mut world)` (or `hooks.step_pipeline(..)`, or pass \
             the hooks to `PhysicsPipeline::step` between `prepare` and `after_step`), never \
             `world.step()`; in Bevy, add `RapierPhysicsPlugin::<CollisionRulesHooks>`. \
             Another `RuleHooks` stepping this world in turn looks the same: give each world \
             one `RuleHooks`"
        );
        // A debug build stops at the first such step, where the developer
        // looks; a release build keeps running and says it once.
        if cfg!(debug_assertions) {
            panic!("{message}");
        } else if !std::mem::replace(&mut self.boundary.reported_unhooked, true) {
            log::warn!("{message}");
        }
    }
}

/// Whether Rapier's graph shows the witness pair with another answer than
/// the hook's for `rule` (the rule it answered as).
fn witness_overridden(narrow_phase: &NarrowPhase, key: PairKey, rule: CollisionRule) -> bool {
    let (a, b) = key.colliders();
    narrow_phase
        .contact_pair(a, b)
        .is_some_and(|pair| answer_overridden(rule, pair))
}

/// Whether Rapier's graph shows the one-way witness with solver contacts in
/// a manifold whose standing is forbidden: the hook drops them at every
/// update (`docs/semantics.md`, "Stepping without the hooks").
fn one_way_overridden(narrow_phase: &NarrowPhase, key: PairKey) -> bool {
    let (a, b) = key.colliders();
    narrow_phase.contact_pair(a, b).is_some_and(|pair| {
        pair.manifolds()
            .iter()
            .any(|m| forbids(m.data.user_data) && !m.data.solver_contacts.is_empty())
    })
}
