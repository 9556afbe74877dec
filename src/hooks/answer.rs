//! The `PhysicsHooks` answers during Rapier's step: each pair looked up in
//! the table of hooked pairs (no lock, no allocation), a pair met for the
//! first time calculated on the slow path, and the contacts of
//! `ManifoldUpdate::Never` pairs replayed (`docs/architecture.md`).

use std::sync::atomic::Ordering;
use std::sync::{MutexGuard, PoisonError};

use hashbrown::HashMap;
use super::super::rapier::prelude::*;

use super::one_way_contacts::STANDING_BITS;
use super::{CalculatorContext, ManifoldUpdate, PairCreated, PairKey, PairState, RecalculationPolicy, RuleHooks};
use super::super::CollisionRule;
use super::super::model::{BodyKinds, dynamic_body, soft_rigid};
use super::super::resolve::{Alias, special_case};
use super::super::world::body_types;

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
        let mut rule = match &self.decide.calculator {
            Some(calculator) => {
                let context = CalculatorContext {
                    collider1: a,
                    collider2: b,
                    bodies,
                    colliders,
                    rules: &self.decide.rules,
                };
                special_case(BodyKinds::of(bodies, colliders, a, b), calculator(&context))
            }
            None => self.resolve(bodies, colliders, a, b),
        };
        if let Some(callback) = &self.decide.on_created {
            let created = PairCreated {
                collider1: a,
                collider2: b,
                rule,
                bodies,
                colliders,
            };
            // The callback's answer takes the special case too.
            if let Some(replaced) = callback(&created) {
                rule = special_case(BodyKinds::of(bodies, colliders, a, b), replaced);
            }
        }
        rule
    }

    /// The default calculation, where the project's settings take part: a
    /// pair of two non-dynamic bodies that the project's own collision types
    /// let Rapier look at is not refused by the `(DEFAULT_KINEMATIC,
    /// DEFAULT_KINEMATIC)` entry (see `CollisionRuleSet::by_kinematic_entry`).
    pub(super) fn resolve(
        &self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        a: ColliderHandle,
        b: ColliderHandle,
    ) -> CollisionRule {
        // A piece torn during this bracket's steps stands on the body its
        // source's rules are on (`hooks/tears.rs`).
        let alias = |body| self.torn_alias(body);
        let torn = self.soft.tear_log().any().then_some(&alias as Alias<'_>);
        let why = self.decide.rules.explain_rule_as(bodies, colliders, a, b, torn);
        if why.rule != CollisionRule::NoPair || !why.by_kinematic_entry() {
            return why.rule;
        }
        let (Some(ca), Some(cb)) = (colliders.get(a), colliders.get(b)) else {
            return why.rule;
        };
        let kinds = BodyKinds::of(bodies, colliders, a, b);
        let types = body_types(bodies, colliders, a, b);
        if kinds.neither_dynamic()
            && self
                .own_settings(a, ca)
                .types_allow(self.own_settings(b, cb), types)
        {
            special_case(kinds, self.decide.rules.default_rule())
        } else {
            why.rule
        }
    }

    /// A tracked pair's rule now. Two things a computed rule rests on can
    /// change without an edit, on colliders the hooks may not watch: a
    /// body's type (the default groups follow it), and the project's
    /// collision types (the rule of two non-dynamic bodies, see
    /// [`resolve`](Self::resolve)). Such a pair is decided again.
    /// Overrides and the `Manual` policy keep their answers.
    pub(super) fn rule_now(
        &self,
        state: &PairState,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        a: ColliderHandle,
        b: ColliderHandle,
    ) -> CollisionRule {
        let kinds = PairKey::new(a, b).kinds(bodies, colliders);
        let rule = state.rule_for(kinds);
        if !self.recomputes(state) {
            return rule;
        }
        // Two non-dynamic bodies: the rule may rest on the project's types.
        let typed = kinds.neither_dynamic() && self.decide.calculator.is_none() && self.decide.on_created.is_none();
        if kinds != state.kinds || typed {
            self.calculate(bodies, colliders, a, b)
        } else {
            rule
        }
    }

    /// Whether the project's own types of a collider of the pair pair
    /// non-dynamic bodies, so that the pair's rule may rest on them (see
    /// [`resolve`](Self::resolve)): the hot path decides such a pair again
    /// (a pair whose types were narrowed back is recalculated when the
    /// change is noticed, or by the hot path if the project narrowed them
    /// on a collider the hooks do not watch). Other pairs of non-dynamic
    /// bodies that the rules refuse, a moving kinematic platform's with a
    /// level's tiles, keep the plain look-up.
    #[inline]
    fn widened_pair(&self, context: &PairFilterContext<'_>) -> bool {
        if self.decide.calculator.is_some() || self.decide.on_created.is_some() {
            return false;
        }
        let widened = |c: ColliderHandle| {
            context
                .colliders
                .get(c)
                .is_some_and(|collider| self.own_settings(c, collider).widened())
        };
        widened(context.collider1) || widened(context.collider2)
    }

    /// Whether a tracked pair's rule follows what it rests on (see
    /// [`rule_now`](Self::rule_now)).
    fn recomputes(&self, state: &PairState) -> bool {
        state.overridden.is_none() && self.decide.policy != RecalculationPolicy::Manual
    }

    /// The hot path found `state` computed for other body types than the
    /// pair's now: its rule is calculated again and kept as pending, which
    /// replaces the table's computed rule when the step ends.
    #[cold]
    fn restate(
        &self,
        context: &PairFilterContext<'_>,
        key: PairKey,
        state: &PairState,
        kinds: BodyKinds,
    ) -> Verdict {
        let pending = self.pending().get(&key).map(PairState::rule);
        let rule = pending.unwrap_or_else(|| {
            let (a, b) = key.colliders();
            let rule = self.calculate(context.bodies, context.colliders, a, b);
            self.pending()
                .insert(key, PairState::new(rule, self.boundary.step, kinds, state.parts));
            rule
        });
        let again = self.answered_by_ccd(context, state, rule, state.manifold);
        Verdict {
            rule,
            manifold: state.manifold,
            again,
        }
    }

    /// The hook's slow path: a pair not in the table. Calculates its rule
    /// and keeps it as pending until the step ends. Returns the rule, the
    /// manifold setting, and whether this answer must be read as the CCD's.
    #[cold]
    fn first_sighting(
        &self,
        context: &PairFilterContext<'_>,
        key: PairKey,
    ) -> Verdict {
        if let Some(state) = self.pending().get(&key) {
            let (rule, manifold) = (state.rule(), state.manifold);
            return Verdict {
                rule,
                manifold,
                again: self.answered_by_ccd(context, state, rule, manifold),
            };
        }
        let (a, b) = key.colliders();
        let rule = self.calculate(context.bodies, context.colliders, a, b);
        let kinds = kinds_in(context, key);
        let parts = key.made_of_parts(context.colliders);
        let state = PairState::new(rule, self.boundary.step, kinds, parts);
        // Later answers in this step at the same poses are the CCD's.
        state.poses.store(poses(context), Ordering::Relaxed);
        self.pending().entry(key).or_insert(state);
        // The CCD sweeps only bodies it marked active; a first answer to such
        // a body may be the sweep's, so a pair without response stays out of
        // it (its contacts start with the next step).
        let maybe_ccd = context
            .rigid_body1
            .and_then(|body| context.bodies.get(body))
            .is_some_and(|body| body.is_ccd_active());
        Verdict {
            rule,
            manifold: ManifoldUpdate::ByRule,
            again: maybe_ccd,
        }
    }

    /// Records an answer for `state`; `true` if it is the CCD's (see
    /// [`PairState::answered_by_ccd`]). Only a pair whose contacts get no
    /// response answers the CCD differently, so only its bodies' poses are
    /// read.
    #[inline]
    fn answered_by_ccd(
        &self,
        context: &PairFilterContext<'_>,
        state: &PairState,
        rule: CollisionRule,
        manifold: ManifoldUpdate,
    ) -> bool {
        if computes(rule, manifold) && !rule.responds() {
            state.answered_by_ccd(self.boundary.step, poses(context))
        } else {
            state.answered_again(self.boundary.step)
        }
    }

    /// Notes that Rapier stepped with the hooks (`prepare` checks that
    /// `after_step` followed), or, after their own step, without their
    /// `prepare` (which the next `prepare` reports). Written once per step:
    /// the other answers only read it.
    #[inline]
    pub(super) fn answering(&self) {
        let seen = if self.boundary.prepared {
            &self.boundary.stepped
        } else if self.boundary.own_step {
            &self.boundary.unprepared
        } else {
            return;
        };
        if !seen.load(Ordering::Relaxed) {
            seen.store(true, Ordering::Relaxed);
        }
    }

    fn pending(&self) -> MutexGuard<'_, HashMap<PairKey, PairState>> {
        self.pending.lock().unwrap_or_else(PoisonError::into_inner)
    }

    #[inline]
    fn lookup(&self, context: &PairFilterContext<'_>) -> Verdict {
        let key = PairKey::new(context.collider1, context.collider2);
        match self.pairs.get(key) {
            Some(state) => {
                let kinds = kinds_in(context, key);
                // A pair of non-dynamic bodies that is not refused may owe
                // its rule to types the project has narrowed since, on a
                // collider the hooks do not watch: decided again too.
                let typed = kinds.neither_dynamic()
                    && (state.computed != CollisionRule::NoPair || self.widened_pair(context));
                if (kinds != state.kinds || typed) && self.recomputes(state) {
                    return self.restate(context, key, state, kinds);
                }
                let rule = state.rule_for(kinds);
                let again = self.answered_by_ccd(context, state, rule, state.manifold);
                Verdict {
                    rule,
                    manifold: state.manifold,
                    again,
                }
            }
            None => self.first_sighting(context, key),
        }
    }
}

/// Whether the narrow phase computes contacts for a pair with `rule` and
/// `manifold` (an `Always` pair computes them whatever its rule but
/// `NoPair`).
#[inline]
fn computes(rule: CollisionRule, manifold: ManifoldUpdate) -> bool {
    rule.computes_contacts()
        || (manifold == ManifoldUpdate::Always && rule != CollisionRule::NoPair)
}

/// Where the pair's bodies are, folded into one number (equal poses give
/// equal numbers, in either collider order). Bodies move only between the
/// narrow phase's passes, and the CCD asks at the poses of the last one.
#[inline]
fn poses(context: &PairFilterContext<'_>) -> u64 {
    let pose = |body: Option<RigidBodyHandle>| {
        let Some(body) = body.and_then(|b| context.bodies.get(b)) else {
            return 0;
        };
        let pose = body.position();
        let (t, r) = (pose.translation, pose.rotation);
        t.to_array()
            .into_iter()
            .chain(super::super::rotation_words(r))
            .fold(0xcbf2_9ce4_8422_2325_u64, |hash, value| {
                (hash ^ u64::from(value.to_bits())).wrapping_mul(0x0100_0000_01b3)
            })
    };
    pose(context.rigid_body1).wrapping_add(pose(context.rigid_body2))
}

/// Whether either collider of the pair is a sensor.
#[cold]
fn sensor_pair(context: &PairFilterContext<'_>) -> bool {
    let sensor = |c: ColliderHandle| context.colliders.get(c).is_some_and(|c| c.is_sensor());
    sensor(context.collider1) || sensor(context.collider2)
}

/// Whether the body of each collider of `key` is dynamic, in key order,
/// read from the hook's context.
#[inline]
fn kinds_in(context: &PairFilterContext<'_>, key: PairKey) -> BodyKinds {
    let kinds = BodyKinds {
        first: dynamic_body(context.bodies, context.rigid_body1),
        second: dynamic_body(context.bodies, context.rigid_body2),
    };
    if key.colliders().0 == context.collider1 {
        kinds
    } else {
        kinds.swapped()
    }
}

/// The project's own hooks, and whether Rapier would have asked them.
impl RuleHooks {
    /// Whether the crate decides the pair: a collider of it carries the
    /// crate's hook flag. Other pairs reach the hook only for the project's
    /// own hook bits.
    /// So does a collider the plan has not met on a soft body the hooks
    /// knew that tore during this bracket's steps: Rapier copied it, the
    /// crate's settings with it, from a collider of the source
    /// (`hooks/tears.rs`).
    #[inline]
    fn decides(&self, colliders: &ColliderSet, a: ColliderHandle, b: ColliderHandle) -> bool {
        let plan = &self.planned.plan;
        plan.hooks(a) || plan.hooks(b) || (self.soft.tear_log().any() && (self.torn_copy(colliders, a) || self.torn_copy(colliders, b)))
    }

    /// The project's hooks, if the project's own bits on `a` or `b` ask for
    /// `bit` (as Rapier would ask them without the rules).
    #[inline]
    fn user_for(
        &self,
        colliders: &ColliderSet,
        a: ColliderHandle,
        b: ColliderHandle,
        bit: ActiveHooks,
    ) -> Option<&dyn PhysicsHooks> {
        let user = self.decide.user.as_deref()?;
        self.project_asks(colliders, a, b, bit)
            .then_some(user as &dyn PhysicsHooks)
    }

    /// Whether the project's own hook bits (its `ActiveHooks`, as it set
    /// them, without the bits the crate adds) on `a` or `b` ask for `bit`:
    /// whether Rapier would call the project's hooks for this pair without
    /// the rules. For project hooks that call the crate's answers
    /// themselves instead of going through
    /// [`set_user_hooks`](Self::set_user_hooks) (bevy_rapier's hooks are
    /// one type per app): since the crate's bits make Rapier call the hooks
    /// for more pairs, such hooks run their own logic only where this says
    /// so.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, RuleHooks};
    ///
    /// let mut world = PhysicsWorld::new();
    /// let ground = world.insert_body(RigidBodyBuilder::fixed());
    /// let floor = world.insert_collider(
    ///     ColliderBuilder::cuboid(5.0, 0.5, 5.0).active_hooks(ActiveHooks::MODIFY_SOLVER_CONTACTS),
    ///     Some(ground),
    /// );
    /// let ghost = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 1.0, 0.0)));
    /// let g = world.insert_collider(ColliderBuilder::ball(0.5), Some(ghost));
    /// let mut hooks = RuleHooks::default();
    /// hooks.rules_mut().set_specific(ghost, floor, CollisionRule::NoContacts);
    /// hooks.step(&mut world);
    /// let asks = |bit| hooks.project_asks(&world.colliders, g, floor, bit);
    /// assert!(asks(ActiveHooks::MODIFY_SOLVER_CONTACTS), "the floor's own bit");
    /// assert!(!asks(ActiveHooks::FILTER_CONTACT_PAIRS), "the crate's bit on the ghost is not the project's");
    /// ```
    pub fn project_asks(
        &self,
        colliders: &ColliderSet,
        a: ColliderHandle,
        b: ColliderHandle,
        bit: ActiveHooks,
    ) -> bool {
        let asks = |c: ColliderHandle| {
            colliders
                .get(c)
                .is_some_and(|collider| self.own_settings(c, collider).hooks.contains(bit))
        };
        asks(a) || asks(b)
    }

    /// Replays the frozen contacts of a `ManifoldUpdate::Never` pair.
    fn replay_frozen(&self, context: &mut ContactModificationContext<'_>) {
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
        let (step, manifolds) = frozen.get_or_insert_with(|| (self.boundary.step, Vec::new()));
        match manifolds.iter().find(|m| m.subshapes() == subshapes) {
            Some(manifold) => {
                let thawed = super::pair_state::thaw(bodies, body1, body2, manifold, rigid.normal);
                rigid.solver_contacts.clear();
                rigid.solver_contacts.extend(thawed);
            }
            // Manifolds are frozen in the step the setting took effect; one
            // that appears later had no contacts then.
            None if *step == self.boundary.step => {
                let manifold = super::pair_state::freeze(
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

/// What the hook knows of a pair when Rapier asks: its rule, its manifold
/// setting, and whether this answer is the CCD's second question in the
/// step (a pair without response must then be invisible to the sweep).
#[derive(Clone, Copy)]
struct Verdict {
    rule: CollisionRule,
    manifold: ManifoldUpdate,
    again: bool,
}

impl PhysicsHooks for RuleHooks {
    fn filter_contact_pair(&self, context: &PairFilterContext<'_>) -> Option<SolverFlags> {
        let (a, b) = (context.collider1, context.collider2);
        let ours = if self.decides(context.colliders, a, b) {
            self.answering();
            let Verdict {
                rule,
                manifold,
                again,
            } = self.lookup(context);
            // Rapier's soft-body solver answers every soft-rigid pair with
            // contacts: one without response has none (`docs/semantics.md`,
            // "Soft bodies").
            let computes = computes(rule, manifold) && (rule.responds() || !soft_rigid(context.colliders, a, b));
            // The CCD's sweep takes a sensor for a pass-through hit, which
            // clamps nothing and gives the intersection events: a sensor
            // pair stays in the sweep.
            let again = again && !sensor_pair(context);
            // NoPair and NoContacts never reach the project's hooks.
            contact_answer(computes, rule.responds(), again)?
        } else {
            SolverFlags::default()
        };
        if self.soft_one_way_bars(context) {
            return None;
        }
        match self.user_for(context.colliders, a, b, ActiveHooks::FILTER_CONTACT_PAIRS) {
            // The project's hooks may only restrict.
            Some(user) => user
                .filter_contact_pair(context)
                .map(|theirs| ours & theirs),
            None => Some(ours),
        }
    }

    fn filter_intersection_pair(&self, context: &PairFilterContext<'_>) -> bool {
        let (a, b) = (context.collider1, context.collider2);
        if self.decides(context.colliders, a, b) {
            self.answering();
            let verdict = self.lookup(context);
            if !computes(verdict.rule, verdict.manifold) {
                return false;
            }
        }
        self.user_for(
            context.colliders,
            a,
            b,
            ActiveHooks::FILTER_INTERSECTION_PAIR,
        )
        .is_none_or(|user| user.filter_intersection_pair(context))
    }

    fn modify_solver_contacts(&self, context: &mut ContactModificationContext<'_>) {
        self.replay_frozen(context);
        let standings_kept = self.apply_one_ways(context);
        let (a, b) = (context.collider1, context.collider2);
        // Two soft surfaces without response keep their pair and its
        // events, and their contacts are disabled (`docs/semantics.md`,
        // "Soft bodies").
        if context.soft_mut().is_some() && self.decides(context.colliders, a, b) {
            let key = PairKey::new(a, b);
            let responds = match self.pairs.get(key) {
                Some(state) => state.rule().responds(),
                None => self.pending().get(&key).is_none_or(|s| s.rule().responds()),
            };
            if !responds {
                if let Some(soft) = context.soft_mut() {
                    soft.disable_all();
                }
            }
        }
        if let Some(user) =
            self.user_for(context.colliders, a, b, ActiveHooks::MODIFY_SOLVER_CONTACTS)
        {
            // The project's hook sees the manifold's `user_data` without the
            // one-way standings the crate keeps in its top bits: Rapier's own
            // `update_as_oneway_platform` panics on a value it did not write
            // (`docs/semantics.md`, "One-way surfaces").
            let standings = context.rigid_mut().filter(|_| standings_kept).map(|rigid| {
                let standings = *rigid.user_data & STANDING_BITS;
                *rigid.user_data &= !STANDING_BITS;
                standings
            });
            user.modify_solver_contacts(context);
            if let (Some(standings), Some(rigid)) = (standings, context.rigid_mut()) {
                *rigid.user_data = (*rigid.user_data & !STANDING_BITS) | standings;
            }
        }
    }
}

/// The contact filter's answer for a pair: `None` for no contacts, else the
/// solver flags. `computes` and `responds` come from the pair's rule and
/// manifold setting; `again` is true for a second answer in one step, which
/// only the CCD asks: a pair without response must then be invisible to the
/// sweep (`Some(empty)` would stop the fast body at it).
#[inline]
pub(crate) fn contact_answer(computes: bool, responds: bool, again: bool) -> Option<SolverFlags> {
    match (computes, responds) {
        (false, _) => None,
        (true, true) => Some(SolverFlags::COMPUTE_RIGID_IMPULSES),
        (true, false) if again => None,
        (true, false) => Some(SolverFlags::empty()),
    }
}

/// Whether Rapier's contact pair shows another answer than the one the
/// hook gives a pair with `rule` (its manifold setting `ByRule`): contact
/// points where the hook removes them, or points the solver would solve
/// where the hook says no response. After a step with the hooks that cannot
/// be, so it tells that Rapier stepped without them (`docs/semantics.md`,
/// "Stepping without the hooks").
pub(crate) fn answer_overridden(rule: CollisionRule, pair: &ContactPair) -> bool {
    let with_points = || pair.manifolds().iter().filter(|m| !m.points.is_empty());
    match contact_answer(rule.computes_contacts(), rule.responds(), false) {
        None => with_points().next().is_some(),
        Some(flags) if flags.is_empty() => with_points()
            .any(|m| m.data.solver_flags.contains(SolverFlags::COMPUTE_RIGID_IMPULSES)),
        Some(_) => false,
    }
}
