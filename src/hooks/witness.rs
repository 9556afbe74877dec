//! Whether Rapier stepped without the hooks since their last step
//! (`docs/semantics.md`, "Stepping without the hooks").

use super::super::rapier::prelude::*;

use super::RuleHooks;
use super::answer::answer_overridden;

/// The witness.
impl RuleHooks {
    /// Whether Rapier stepped without these hooks since their last step: the
    /// witness pair (one hooked pair the hook answered "no contacts" or "no
    /// response") shows another answer in Rapier's graph. One look-up per
    /// step (`docs/semantics.md`, "Stepping without the hooks").
    pub(super) fn check_witness(&mut self, narrow_phase: &NarrowPhase) {
        let Some((key, rule)) = self.boundary.witness.take() else {
            return;
        };
        let (a, b) = key.colliders();
        let overridden = narrow_phase
            .contact_pair(a, b)
            .is_some_and(|pair| answer_overridden(rule, pair));
        if overridden {
            self.report_unhooked(&format!(
                "Rapier stepped without the RuleHooks since their last step: the {rule:?} pair \
                 of colliders {a:?} and {b:?} was given contacts and impulses the rules refuse, \
                 and every rule the hook decides was dropped for that step"
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
