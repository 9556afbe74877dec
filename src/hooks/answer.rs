//! The `PhysicsHooks` answers during Rapier's step: each pair looked up in
//! the table of hooked pairs (no lock, no allocation), a pair met for the
//! first time calculated on the slow path, and the contacts of
//! `ManifoldUpdate::Never` pairs replayed (`docs/architecture.md`).

use std::sync::{MutexGuard, PoisonError};

use hashbrown::HashMap;
use rapier3d::prelude::*;

use super::{CalculatorContext, PairCreated, RuleHooks};
use crate::CollisionRule;
use crate::pairs::{self, ManifoldUpdate, PairKey, PairState};
use crate::resolve::special_case;
use crate::rule::contact_answer;

impl RuleHooks {
    /// A pair's rule: the calculator or the default calculation, then the
    /// pair-created callback.
    pub(super) fn calculate(
        &self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        a: ColliderHandle,
        b: ColliderHandle,
    ) -> CollisionRule {
        let mut rule = match &self.calculator {
            Some(calculator) => {
                let context = CalculatorContext {
                    collider1: a,
                    collider2: b,
                    bodies,
                    colliders,
                    rules: &self.rules,
                };
                special_case(bodies, colliders, a, b, calculator(&context))
            }
            None => self.rules.resolve(bodies, colliders, a, b),
        };
        if let Some(callback) = &self.on_created {
            let created = PairCreated {
                collider1: a,
                collider2: b,
                rule,
                bodies,
                colliders,
            };
            if let Some(replaced) = callback(&created) {
                rule = replaced;
            }
        }
        rule
    }

    /// The hook's slow path: a pair not in the table. Calculates its rule
    /// and keeps it as pending until the step ends. Returns the rule, the
    /// manifold setting, and whether this answer must be read as the CCD's.
    #[cold]
    fn first_sighting(
        &self,
        context: &PairFilterContext<'_>,
        key: PairKey,
    ) -> (CollisionRule, ManifoldUpdate, bool) {
        if let Some(state) = self.pending().get(&key) {
            return (
                state.rule(),
                state.manifold,
                state.answered_again(self.step),
            );
        }
        let (a, b) = key.colliders();
        let rule = self.calculate(context.bodies, context.colliders, a, b);
        self.pending()
            .entry(key)
            .or_insert_with(|| PairState::new(rule, self.step));
        // The CCD sweeps only bodies it marked active; a first answer to such
        // a body may be the sweep's, so a pair without response stays out of
        // it (its contacts start with the next step).
        let maybe_ccd = context
            .rigid_body1
            .and_then(|body| context.bodies.get(body))
            .is_some_and(|body| body.is_ccd_active());
        (rule, ManifoldUpdate::ByRule, maybe_ccd)
    }

    fn pending(&self) -> MutexGuard<'_, HashMap<PairKey, PairState>> {
        self.pending.lock().unwrap_or_else(PoisonError::into_inner)
    }

    #[inline]
    fn lookup(&self, context: &PairFilterContext<'_>) -> (CollisionRule, ManifoldUpdate, bool) {
        let key = PairKey::new(context.collider1, context.collider2);
        match self.pairs.get(key) {
            Some(state) => (
                state.rule(),
                state.manifold,
                state.answered_again(self.step),
            ),
            None => self.first_sighting(context, key),
        }
    }
}

impl PhysicsHooks for RuleHooks {
    fn filter_contact_pair(&self, context: &PairFilterContext<'_>) -> Option<SolverFlags> {
        let (rule, manifold, again) = self.lookup(context);
        let computes = rule.computes_contacts()
            || (manifold == ManifoldUpdate::Always && rule != CollisionRule::NoPair);
        contact_answer(computes, rule.responds(), again)
    }

    fn filter_intersection_pair(&self, context: &PairFilterContext<'_>) -> bool {
        let (rule, manifold, _) = self.lookup(context);
        rule.computes_contacts()
            || (manifold == ManifoldUpdate::Always && rule != CollisionRule::NoPair)
    }

    fn modify_solver_contacts(&self, context: &mut ContactModificationContext<'_>) {
        let key = PairKey::new(context.collider1, context.collider2);
        let Some(state) = self
            .pairs
            .get(key)
            .filter(|s| s.manifold == ManifoldUpdate::Never)
        else {
            return;
        };
        let (bodies, body1, body2) = (context.bodies, context.rigid_body1, context.rigid_body2);
        let Some(rigid) = context.rigid_mut() else {
            return;
        };
        let subshapes = (rigid.manifold.subshape1, rigid.manifold.subshape2);
        let mut frozen = state.frozen.lock().unwrap_or_else(PoisonError::into_inner);
        let (step, manifolds) = frozen.get_or_insert_with(|| (self.step, Vec::new()));
        match manifolds.iter().find(|m| m.subshapes() == subshapes) {
            Some(manifold) => pairs::thaw(
                bodies,
                body1,
                body2,
                manifold,
                rigid.normal,
                rigid.solver_contacts,
            ),
            // Manifolds are frozen in the step the setting took effect; one
            // that appears later had no contacts then.
            None if *step == self.step => {
                let manifold = pairs::freeze(
                    bodies,
                    body1,
                    body2,
                    subshapes,
                    *rigid.normal,
                    rigid.solver_contacts,
                );
                manifolds.push(manifold);
            }
            None => rigid.solver_contacts.clear(),
        }
    }
}
