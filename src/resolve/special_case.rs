//! The special case (`docs/semantics.md`, "Special case"), written once:
//! two colliders neither of whose own bodies is dynamic cannot respond, so
//! `Normal` becomes `NoResponse`, whoever decided it (the default
//! calculation, a calculator, the pair-created callback or an override).

use super::super::CollisionRule;
use super::super::model::BodyKinds;

/// `rule` after the special case, for a pair whose bodies are `kinds`.
#[inline]
pub(crate) fn special_case(kinds: BodyKinds, rule: CollisionRule) -> CollisionRule {
    if rule == CollisionRule::Normal && kinds.neither_dynamic() {
        CollisionRule::NoResponse
    } else {
        rule
    }
}
