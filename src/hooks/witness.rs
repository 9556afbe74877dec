//! Whether Rapier stepped without the hooks since their last step
//! (`docs/semantics.md`, "Stepping without the hooks").

use super::super::rapier::prelude::*;

use super::{PairKey, RuleHooks};
use super::super::CollisionRule;
use super::answer::answer_overridden;

/// The witness.
impl RuleHooks {
    /// Whether Rapier stepped without these hooks since their last step: the
    /// witness pair (one hooked pair the hook answered "no contacts" or "no
    /// response") shows another answer in Rapier's graph. One look-up per
    /// step (`docs/semantics.md`, "Stepping without the hooks"). The witness
    /// stays for [`check_witness_after`](Self::check_witness_after).
    pub(super) fn check_witness(&mut self, narrow_phase: &NarrowPhase) {
        let Some((key, rule)) = self.boundary.witness else {
            return;
        };
        if witness_overridden(narrow_phase, key, rule) {
            let (a, b) = key.colliders();
            self.report_unhooked(&format!(
                "Rapier stepped without the RuleHooks since their last step: the {rule:?} pair \
                 of colliders {a:?} and {b:?} was given contacts and impulses the rules refuse, \
                 and every rule the hook decides was dropped for that step"
            ));
        }
    }

    /// After a step in which Rapier asked the hook nothing: whether that
    /// step was taken without the hooks, between their `prepare` and
    /// `after_step` (`world.step()` where the hooks should have been
    /// passed). The witness of the last step, still hooked with the same
    /// rule, shows another answer in Rapier's graph.
    /// A step with the hooks that asks nothing (the bodies sleep) leaves
    /// the pair's contacts as the hook left them. Takes the witness.
    pub(super) fn check_witness_after(&mut self, narrow_phase: &NarrowPhase, colliders: &ColliderSet) {
        let Some((key, rule)) = self.boundary.witness.take() else {
            return;
        };
        if *self.boundary.stepped.get_mut() {
            return;
        }
        let (a, b) = key.colliders();
        let plan = &self.planned.plan;
        // Asked nothing, so not this pair either: still hooked with the
        // same rule, its contacts are the hook's last answer or Rapier's own.
        let same = self.pairs.get(key).is_some_and(|state| state.rule() == rule);
        if same
            && colliders.contains(a)
            && colliders.contains(b)
            && (plan.hooks(a) || plan.hooks(b))
            && witness_overridden(narrow_phase, key, rule)
        {
            self.report_unhooked(&format!(
                "Rapier stepped without the RuleHooks between their `prepare` and `after_step`: \
                 the {rule:?} pair of colliders {a:?} and {b:?} was given contacts and impulses \
                 the rules refuse, and every rule the hook decides was dropped for that step"
            ));
        }
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
        let message = format!(
            "{what}. Step with `hooks.step(&mut world)` (or `hooks.step_pipeline(..)`, or pass \
             the hooks to `PhysicsPipeline::step` between `prepare` and `after_step`), never \
             `world.step()`; in Bevy, add `RapierPhysicsPlugin::<CollisionRulesHooks>`"
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
/// the hook's `rule`.
fn witness_overridden(narrow_phase: &NarrowPhase, key: PairKey, rule: CollisionRule) -> bool {
    let (a, b) = key.colliders();
    narrow_phase
        .contact_pair(a, b)
        .is_some_and(|pair| answer_overridden(rule, pair))
}
