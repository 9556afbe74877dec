//! Whether Rapier stepped without the hooks since their last step
//! (`docs/semantics.md`, "Stepping without the hooks").

use super::super::rapier::prelude::*;

use super::RuleHooks;
use super::answer::answer_overridden;
use super::super::CollisionRule;

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
            self.stats.stepped_without_hooks = true;
            self.report_unhooked(a, b, rule);
        }
    }

    #[cold]
    fn report_unhooked(&mut self, a: ColliderHandle, b: ColliderHandle, rule: CollisionRule) {
        let message = format!(
            "Rapier stepped without the RuleHooks since their last step: the {rule:?} pair of \
             colliders {a:?} and {b:?} was given contacts and impulses the rules refuse, and \
             every rule the hook decides was dropped for that step. Step with \
             `hooks.step(&mut world)` (or `hooks.step_pipeline(..)`, or pass the hooks to \
             `PhysicsPipeline::step` between `prepare` and `after_step`), never `world.step()`; \
             in Bevy, add `RapierPhysicsPlugin::<CollisionRulesHooks>`"
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
