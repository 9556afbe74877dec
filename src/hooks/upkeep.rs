//! What runs around Rapier's step: before it, noticing what changed (edits,
//! objects removed or changed through Rapier), planning the colliders'
//! settings and recalculating live pairs; after it, admitting new pairs and
//! forgetting ended ones. Everything here costs in proportion to what the
//! rules reach, the edits since the last step, and the hooked pairs: a
//! world the rules do not reach costs nothing per step
//! (`docs/architecture.md`, "Cost per step").

use std::sync::PoisonError;

use hashbrown::HashSet;
use super::super::rapier::prelude::*;

use super::{RecalculationPolicy, RuleHooks};
use super::super::native::{self, ColliderPlan, Request};
use super::super::pairs::{ManifoldUpdate, PairKey, PairState, made_of_parts};
use super::super::project::{Settings, Written, body_types};
use super::super::rule::answer_overridden;
use super::super::{CollisionRule, FullPass, Node, StepStats};

/// Whether Rapier holds a pair of `a` and `b` (a contact or a sensor pair).
pub(super) fn pair_exists(
    narrow_phase: &NarrowPhase,
    a: ColliderHandle,
    b: ColliderHandle,
) -> bool {
    narrow_phase.contact_pair(a, b).is_some() || narrow_phase.intersection_pair(a, b).is_some()
}

/// Whether `a` and `b` are on one rigid body: Rapier never lets them
/// interact (its graph may still hold their pair), so they form no pair.
pub(super) fn same_body(colliders: &ColliderSet, a: ColliderHandle, b: ColliderHandle) -> bool {
    let body = |c: ColliderHandle| colliders.get(c).and_then(|c| c.parent());
    body(a).is_some() && body(a) == body(b)
}

/// A world's joint sets: Rapier asks no hook about the pairs of two bodies
/// that a joint with contacts disabled links.
#[derive(Clone, Copy)]
pub(super) struct Joints<'a> {
    pub(super) impulse: &'a ImpulseJointSet,
    pub(super) multibody: &'a MultibodyJointSet,
}

impl Joints<'_> {
    /// Whether a joint keeps the bodies of `a` and `b` from touching, as
    /// Rapier's narrow phase reads it: an impulse joint with contacts
    /// disabled, or the same multibody without self-contacts or with such
    /// a link between them.
    fn keep_apart(self, colliders: &ColliderSet, a: ColliderHandle, b: ColliderHandle) -> bool {
        let body = |c: ColliderHandle| colliders.get(c).and_then(|c| c.parent());
        let (Some(b1), Some(b2)) = (body(a), body(b)) else {
            return false;
        };
        if self
            .impulse
            .joints_between(b1, b2)
            .any(|(_, joint)| !joint.data.contacts_enabled)
        {
            return true;
        }
        let (Some(l1), Some(l2)) = (
            self.multibody.rigid_body_link(b1),
            self.multibody.rigid_body_link(b2),
        ) else {
            return false;
        };
        l1.multibody == l2.multibody
            && (self
                .multibody
                .get_multibody(l1.multibody)
                .is_some_and(|mb| !mb.self_contacts_enabled())
                || self
                    .multibody
                    .joint_between(b1, b2)
                    .is_some_and(|(_, _, link)| !link.joint.data.contacts_enabled))
    }
}

/// Whether Rapier's own filters before the hook let the pair of `a` and `b`
/// through: two rigid bodies, joints (when the world's joint sets are
/// known), collision types, collision groups (as they are now: the
/// project's combined with the plan). Rapier's graph keeps an edge for a
/// pair they stop, which is no pair.
pub(super) fn filters_pass(
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    joints: Option<Joints<'_>>,
    a: ColliderHandle,
    b: ColliderHandle,
) -> bool {
    let (Some(ca), Some(cb)) = (colliders.get(a), colliders.get(b)) else {
        return false;
    };
    let types = body_types(bodies, colliders, a, b);
    !same_body(colliders, a, b)
        && !joints.is_some_and(|j| j.keep_apart(colliders, a, b))
        && (ca.active_collision_types().test(types.0, types.1)
            || cb.active_collision_types().test(types.0, types.1))
        && ca.collision_groups().test(cb.collision_groups())
}

/// Whether the body of each collider of `key` is dynamic, in key order.
pub(super) fn kinds_of(
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    key: PairKey,
) -> (bool, bool) {
    let (a, b) = key.colliders();
    let types = body_types(bodies, colliders, a, b);
    (types.0.is_dynamic(), types.1.is_dynamic())
}

/// Every collider Rapier pairs with `collider`.
pub(super) fn partners_of(
    narrow_phase: &NarrowPhase,
    collider: ColliderHandle,
) -> impl Iterator<Item = ColliderHandle> + '_ {
    let other = move |a: ColliderHandle, b: ColliderHandle| if a == collider { b } else { a };
    narrow_phase
        .contact_pairs_with(collider)
        .map(move |p| other(p.collider1, p.collider2))
        .chain(
            narrow_phase
                .intersection_pairs_with(collider)
                .map(move |(a, b, _)| other(a, b)),
        )
}

/// How many colliders, bodies, contact-graph and intersection-graph nodes
/// and edges the world holds: what changes when the project removes, adds or
/// moves objects through Rapier, which the hooks do not watch unless the
/// rules reach them. A removed collider of a hooked pair leaves Rapier's
/// graphs (its node and its edges), so between two steps in which no body
/// is awake, an unchanged census means no hooked pair can have ended.
fn census(
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    narrow_phase: &NarrowPhase,
) -> [usize; 6] {
    let (contacts, intersections) = (
        narrow_phase.contact_graph().raw_graph(),
        narrow_phase.intersection_graph().raw_graph(),
    );
    [
        colliders.len(),
        bodies.len(),
        contacts.raw_nodes().len(),
        contacts.raw_edges().len(),
        intersections.raw_nodes().len(),
        intersections.raw_edges().len(),
    ]
}

/// Names the call a bare-pipeline user left out; the physics would
/// otherwise change silently (`docs/architecture.md`, "The step boundary").
#[cold]
#[track_caller]
fn missing(call: &str, when: &str) -> ! {
    panic!(
        "RuleHooks::{call} was not called {when}: without it the rules do not \
         hold. Step with RuleHooks::step, RuleHooks::step_pipeline, or call \
         prepare, freeze_manifolds and wake_edited before PhysicsPipeline::step \
         and after_step after it"
    )
}

/// Stepping.
impl RuleHooks {
    /// Steps `world` with the rules: [`prepare`](Self::prepare), waking what
    /// the edits need awake, Rapier's step, and [`after_step`](Self::after_step).
    pub fn step(&mut self, world: &mut PhysicsWorld) {
        self.step_with_events(world, &());
    }

    /// [`step`](Self::step), with Rapier's events sent to `events`.
    pub fn step_with_events(&mut self, world: &mut PhysicsWorld, events: &dyn EventHandler) {
        self.step_pipeline(
            &mut world.physics_pipeline,
            world.gravity,
            &world.integration_parameters,
            &mut world.islands,
            &mut world.broad_phase,
            &mut world.narrow_phase,
            &mut world.bodies,
            &mut world.colliders,
            &mut world.impulse_joints,
            &mut world.multibody_joints,
            &mut world.soft_bodies,
            &mut world.ccd_solver,
            events,
        );
    }

    /// Steps a bare `PhysicsPipeline` with the rules: everything
    /// [`step_with_events`](Self::step_with_events) does around Rapier's
    /// step. Takes `PhysicsPipeline::step`'s arguments in its order, but
    /// the hooks.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, RuleHooks};
    ///
    /// let (mut bodies, mut colliders) = (RigidBodySet::new(), ColliderSet::new());
    /// let floor = bodies.insert(RigidBodyBuilder::fixed());
    /// colliders.insert_with_parent(ColliderBuilder::cuboid(5.0, 0.5, 5.0), floor, &mut bodies);
    /// let ghost = bodies.insert(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 1.5, 0.0)));
    /// colliders.insert_with_parent(ColliderBuilder::ball(0.5), ghost, &mut bodies);
    /// let mut hooks = RuleHooks::default();
    /// hooks.rules_mut().set_specific(ghost, floor, CollisionRule::NoResponse);
    ///
    /// let (mut pipeline, mut islands) = (PhysicsPipeline::new(), IslandManager::new());
    /// let (mut broad_phase, mut narrow_phase) = (BroadPhaseBvh::new(), NarrowPhase::new());
    /// let (mut impulse_joints, mut multibody_joints) = (ImpulseJointSet::new(), MultibodyJointSet::new());
    /// let (mut soft_bodies, mut ccd) = (SoftBodySet::new(), CCDSolver::new());
    /// let params = IntegrationParameters::default();
    /// for _ in 0..60 {
    ///     hooks.step_pipeline(
    ///         &mut pipeline, Vector::Y * -9.81, &params, &mut islands,
    ///         &mut broad_phase, &mut narrow_phase, &mut bodies, &mut colliders,
    ///         &mut impulse_joints, &mut multibody_joints, &mut soft_bodies, &mut ccd, &(),
    ///     );
    /// }
    /// assert!(bodies[ghost].translation().y < 0.0, "the ghost fell through the floor");
    /// ```
    #[allow(clippy::too_many_arguments)]
    pub fn step_pipeline(
        &mut self,
        pipeline: &mut PhysicsPipeline,
        gravity: Vector,
        integration_parameters: &IntegrationParameters,
        islands: &mut IslandManager,
        broad_phase: &mut BroadPhaseBvh,
        narrow_phase: &mut NarrowPhase,
        bodies: &mut RigidBodySet,
        colliders: &mut ColliderSet,
        impulse_joints: &mut ImpulseJointSet,
        multibody_joints: &mut MultibodyJointSet,
        soft_bodies: &mut SoftBodySet,
        ccd_solver: &mut CCDSolver,
        events: &dyn EventHandler,
    ) {
        let idle = self.idle();
        if idle {
            // No collider carries the hook flag: Rapier never calls the hook.
            self.step += 1;
            self.stats = StepStats::default();
        } else {
            self.prepare(bodies, colliders);
            self.freeze_manifolds(narrow_phase);
            self.wake_edited(islands, bodies);
        }
        let resting = islands.num_active_bodies() == 0;
        pipeline.step(
            gravity,
            integration_parameters,
            islands,
            broad_phase,
            narrow_phase,
            bodies,
            colliders,
            impulse_joints,
            multibody_joints,
            soft_bodies,
            ccd_solver,
            &*self,
            events,
        );
        if idle {
            return;
        }
        // Rapier applies removals to its graphs during the step.
        let census = census(bodies, colliders, narrow_phase);
        let unchanged = std::mem::replace(&mut self.census, census) == census;
        let quiet = resting && unchanged && islands.num_active_bodies() == 0;
        let joints = Joints {
            impulse: impulse_joints,
            multibody: multibody_joints,
        };
        self.finish_step(narrow_phase, bodies, colliders, Some(joints), quiet);
    }

    /// Before a bare `PhysicsPipeline::step`: notices what the edits touched
    /// and what changed through Rapier among the objects the rules reach
    /// (removed, moved to another body, changed type, new colliders on a
    /// watched body), plans those colliders' flags and groups (every
    /// reached collider if anything they all depend on changed), and
    /// recalculates live pairs as the policy says. Call
    /// [`wake_edited`](Self::wake_edited) next, then step with these hooks,
    /// then [`after_step`](Self::after_step).
    ///
    /// # Panics
    ///
    /// If Rapier stepped with these hooks since the last `prepare` and
    /// [`after_step`](Self::after_step) was not called after it.
    pub fn prepare(&mut self, bodies: &RigidBodySet, colliders: &mut ColliderSet) {
        if self.prepared && *self.stepped.get_mut() {
            missing("after_step", "after the last step");
        }
        self.prepared = true;
        *self.stepped.get_mut() = false;
        self.owe_freeze = self.unsettled;
        self.step += 1;
        self.stats = StepStats {
            hooked_colliders: self.hooked,
            tracked_pairs: self.pairs.len(),
            ..StepStats::default()
        };
        let full = self.full_pass();
        self.replan |= self.exhaustive;
        if self.idle() {
            return;
        }
        if full != self.plan.full && (full.is_some() || self.plan.full.is_some()) {
            self.replan = true;
        }

        // 1. What the edits touched starts being watched.
        let changes = self.rules.take_changes();
        // Re-parenting moves colliders from under one side of a specific
        // entry to another: which side is cheaper to hook may change.
        self.replan |= changes.parents && self.rules.has_specific();
        let mut changed = match self.rules.touched_nodes(&changes) {
            // The first step reads the whole rule set: it may have been
            // built, or loaded, before the hooks existed.
            Some(nodes) if !self.exhaustive && self.step > 1 => nodes,
            // The nodes the edits touched stay in, rules or not: a node
            // whose rules were just cleared has pairs to recalculate.
            touched => {
                self.replan = true;
                let mut nodes = self.rules.ruled_nodes();
                nodes.extend(touched.into_iter().flatten());
                nodes
            }
        };
        for &node in &changed {
            self.watch(bodies, colliders, node);
        }

        // 2. Look at what is watched: removals, changes, additions.
        let everything = self.plan.full.is_some() || full.is_some() || self.exhaustive;
        // Whether the rules still reach a watched object changes only with an
        // edit of it (marked by `watch`), or with a global one.
        let ask_all = self.replan;
        let look = {
            let (rules, plan) = (&self.rules, &self.plan);
            self.roster
                .look(bodies, colliders, everything, ask_all, |node| {
                    reached(rules, plan, bodies, colliders, node)
                })
        };
        // Which side of a specific entry is cheaper to hook follows the
        // colliders under each side and their bodies' types (asked before
        // removed bodies leave the parent map).
        self.replan |= look
            .left
            .iter()
            .map(|&b| Node::Body(b))
            .chain(look.added.iter().map(|&c| Node::Collider(c)))
            .chain(look.changed.iter().copied())
            .any(|node| native::touches_entries(&self.rules, bodies, colliders, node));
        self.forget_removed(bodies, &look.removed_colliders, &look.removed_bodies);
        for &c in &look.released {
            self.plan.colliders.remove(c);
        }
        if !(look.removed_colliders.is_empty() && look.released.is_empty()) {
            self.count_hooked();
        }
        changed.extend(look.changed);
        // Forgetting a removed parent changes its children's chains.
        let removal_changes = self.rules.take_changes();
        if let Some(more) = self.rules.touched_nodes(&removal_changes) {
            changed.extend(more);
        }
        // The project changed a setting the plan is combined with, or
        // colliders came or went in a world whose plan shares bits or types
        // with every collider's project settings: plan again.
        let recount = self
            .plan
            .room
            .is_some_and(|(_, count)| count != colliders.len());
        if recount || !look.project_changed.is_empty() {
            self.replan = true;
        }
        // A project setting can change a pair's rule (the kinematic entry
        // gives way to wider types): those colliders' pairs are recalculated.
        changed.extend(look.project_changed.iter().map(|&c| Node::Collider(c)));

        // 3. Plan the colliders under every changed node, and those newly
        // watched (a collider moved onto a watched body may have hooked pairs
        // whose rule its new chain changes).
        let mut under: HashSet<ColliderHandle> = look.added.iter().copied().collect();
        self.candidates.extend(look.added);
        for &node in &changed {
            under.extend(self.colliders_under(node, bodies, colliders));
        }
        // Their pairs may have changed in Rapier too: looked up after the step.
        self.touched.extend(under.iter().copied());
        self.touched.extend(self.candidates.iter().copied());
        if self.replan {
            self.apply_plan(bodies, colliders);
        } else {
            self.candidates.extend(under.iter().copied());
            if !self.candidates.is_empty() {
                self.apply_partial_plan(bodies, colliders);
            }
        }

        // 4. Recalculate live pairs as the policy says.
        let mut drop_overrides = HashSet::new();
        for node in std::mem::take(&mut self.forced) {
            drop_overrides.extend(self.colliders_under(node, bodies, colliders));
        }
        let everything = self.policy == RecalculationPolicy::EveryStep
            || (self.policy == RecalculationPolicy::OnChange
                && (changes.everything || std::mem::take(&mut self.recalculate_all)));
        let mut affected = HashSet::new();
        if self.policy == RecalculationPolicy::OnChange && !everything {
            affected = under;
        }
        if self.policy == RecalculationPolicy::Manual {
            self.recalculate_all = false;
        }
        if everything || !affected.is_empty() || !drop_overrides.is_empty() {
            let refresh =
                self.recalculate(bodies, colliders, everything, &affected, &drop_overrides);
            for handle in refresh {
                if let Some(collider) = colliders.get_mut(handle) {
                    let groups = collider.collision_groups();
                    collider.set_collision_groups(InteractionGroups::none());
                    collider.set_collision_groups(groups);
                    self.regrouped.insert(handle);
                }
            }
        }
        for c in std::mem::take(&mut self.wake_colliders) {
            self.to_wake
                .extend(colliders.get(c).and_then(|c| c.parent()));
        }
        self.stats.hooked_colliders = self.hooked;
        self.stats.full_pass = self.plan.full;
        self.stats.shares_project_bits = self.plan.room.is_some();
        self.stats.watched_colliders = self.roster.collider_count();
        self.stats.watched_bodies = self.roster.body_count();
    }

    /// Settles `ManifoldUpdate::Never` settings made since the last step
    /// for pairs that have no contacts now: they are frozen empty. (Pairs
    /// with contacts are frozen in their next contact update, in each body's
    /// frame.) Part of [`step`](Self::step); call it after
    /// [`prepare`](Self::prepare) when stepping a bare pipeline.
    pub fn freeze_manifolds(&mut self, narrow_phase: &NarrowPhase) {
        self.check_witness(narrow_phase);
        self.owe_freeze = false;
        if !std::mem::take(&mut self.unsettled) {
            return;
        }
        for (key, state) in self.pairs.iter() {
            if state.manifold != ManifoldUpdate::Never {
                continue;
            }
            let mut frozen = state.frozen.lock().unwrap_or_else(PoisonError::into_inner);
            if frozen.is_some() {
                continue;
            }
            let (a, b) = key.colliders();
            let touching = narrow_phase
                .contact_pair(a, b)
                .is_some_and(|pair| pair.has_any_active_contact());
            if !touching {
                // Step 0 never comes again: no manifold is frozen later.
                *frozen = Some((0, Vec::new()));
            }
        }
    }

    /// Whether Rapier stepped without these hooks since their last step: the
    /// witness pair (one hooked pair the hook answered "no contacts" or "no
    /// response") shows another answer in Rapier's graph. One look-up per
    /// step (`docs/semantics.md`, "Stepping without the hooks").
    fn check_witness(&mut self, narrow_phase: &NarrowPhase) {
        let Some((key, rule)) = self.witness.take() else {
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
        } else if !std::mem::replace(&mut self.reported_unhooked, true) {
            log::warn!("{message}");
        }
    }

    /// Wakes the bodies of pairs whose rule an edit changed, so that the
    /// change takes effect on sleeping bodies too. Part of
    /// [`step`](Self::step); call it after [`prepare`](Self::prepare) when
    /// stepping a bare pipeline.
    pub fn wake_edited(&mut self, islands: &mut IslandManager, bodies: &mut RigidBodySet) {
        for body in self.to_wake.drain(..) {
            if bodies.contains(body) {
                islands.wake_up(bodies, body, true);
            }
        }
    }

    /// After a bare `PhysicsPipeline::step`: admits the pairs the hook met
    /// during the step, forgets hooked pairs Rapier no longer has, and gives
    /// a rule to pairs of newly hooked colliders that Rapier made without
    /// asking the hook (pairs of resting bodies).
    ///
    /// Rapier may step several times between [`prepare`](Self::prepare)
    /// and `after_step` (substeps, catch-up steps): the rules hold in each.
    ///
    /// # Panics
    ///
    /// If [`prepare`](Self::prepare) was not called before the step, or if
    /// [`wake_edited`](Self::wake_edited) or
    /// [`freeze_manifolds`](Self::freeze_manifolds) was left out when the
    /// edits before it needed them.
    pub fn after_step(
        &mut self,
        narrow_phase: &NarrowPhase,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
    ) {
        self.finish_step(narrow_phase, bodies, colliders, None, false);
    }

    /// [`after_step`](Self::after_step); `quiet` when no body was awake
    /// before or after the step and the world's census after it is that of
    /// the last step's end (see [`census`]), so that no pair can have ended
    /// unless something was changed before it.
    fn finish_step(
        &mut self,
        narrow_phase: &NarrowPhase,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        joints: Option<Joints<'_>>,
        quiet: bool,
    ) {
        if !std::mem::take(&mut self.prepared) {
            missing("prepare", "before the step");
        }
        if !self.to_wake.is_empty() {
            missing("wake_edited", "before the step, after prepare");
        }
        if self.owe_freeze {
            missing("freeze_manifolds", "before the step, after prepare");
        }
        let pending_empty = self
            .pending
            .get_mut()
            .unwrap_or_else(PoisonError::into_inner)
            .is_empty();
        let unchanged = pending_empty && self.touched.is_empty() && self.regrouped.is_empty();
        if unchanged && !self.exhaustive && (quiet || self.pairs.is_empty()) {
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
        let touched = std::mem::take(&mut self.touched);
        let hooked = |plan: &native::Plan, c: ColliderHandle| {
            plan.colliders.get(c).is_some_and(|p| p.hooked())
        };
        let mut unseen = Vec::new();
        for &c in &touched {
            if !hooked(&self.plan, c) {
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
            let kinds = kinds_of(bodies, colliders, key);
            let parts = made_of_parts(colliders, key);
            self.pairs
                .insert(key, PairState::new(rule, self.step, kinds, parts));
        }

        // Forget the hooked pairs Rapier no longer has, looked up in Rapier's
        // graph: the broad phase may have dropped a pair during the step, and
        // even a pair of resting bodies ends when the project moves or
        // re-parents a collider through Rapier, which the hooks do not watch
        // unless the rules reach it.
        let step = self.step;
        let touched: HashSet<ColliderHandle> = touched.into_iter().collect();
        let regrouped = std::mem::take(&mut self.regrouped);
        let (mut answered, mut never_ended) = (0, false);
        let mut retyped = Vec::new();
        let recomputes = self.policy != RecalculationPolicy::Manual;
        let plan = &self.plan;
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
            never_ended |= !keep && state.manifold == ManifoldUpdate::Never;
            if keep
                && witness.is_none()
                && state.answered_in(step)
                && state.manifold == ManifoldUpdate::ByRule
                && matches!(state.rule(), CollisionRule::NoContacts | CollisionRule::NoResponse)
            {
                witness = Some((key, state.rule()));
            }
            // A body changed type (the hooks may not watch it): the rule
            // follows the default groups, and an override the special case.
            // A pair the hook answered was restated with the types it saw.
            let overridden = state.overridden.is_some();
            if keep && (overridden || !state.answered_in(step)) {
                let kinds = kinds_of(bodies, colliders, key);
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
        self.replan |= never_ended;
        self.witness = witness;
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
        self.touched.extend(regrouped);
        self.stats.hooked_pairs_answered = answered;
        self.stats.tracked_pairs = self.pairs.len();
    }

    /// Whether the rules reach nothing and nothing waits: the common case
    /// of a world without rules, which costs a few branches per step.
    fn idle(&self) -> bool {
        self.roster.collider_count() == 0
            && self.roster.body_count() == 0
            && self.pairs.is_empty()
            && self.plan.full.is_none()
            && !self.replan
            && !self.rules.has_changes()
            && self.candidates.is_empty()
            && self.forced.is_empty()
            && self.wake_colliders.is_empty()
            && self.touched.is_empty()
            && self.regrouped.is_empty()
            && !self.recalculate_all
            && self.policy != RecalculationPolicy::EveryStep
            && self.full_pass().is_none()
    }

    /// Why every collider must be looked at and hooked, if it must.
    fn full_pass(&self) -> Option<FullPass> {
        if self.calculator.is_some() {
            Some(FullPass::Calculator)
        } else if self.on_created.is_some() {
            Some(FullPass::PairCreatedCallback)
        } else if self.policy == RecalculationPolicy::Manual {
            Some(FullPass::ManualPolicy)
        } else if !self.planner {
            Some(FullPass::PlannerOff)
        } else {
            None
        }
    }

    /// Starts watching `node` and every collider under it.
    fn watch(&mut self, bodies: &RigidBodySet, colliders: &ColliderSet, node: Node) {
        match node {
            Node::Body(body) => {
                self.roster.watch_body(bodies, body);
            }
            // Watched even if Rapier removed it: the look then forgets it.
            Node::Collider(c) => {
                if self.roster.watch_collider(bodies, colliders, c) {
                    self.candidates.push(c);
                }
            }
        }
        self.roster.mark(node);
        for c in self.colliders_under(node, bodies, colliders) {
            if self.roster.watch_collider(bodies, colliders, c) {
                self.candidates.push(c);
            }
            self.roster.mark(Node::Collider(c));
        }
    }

    /// Forgets objects Rapier removed: their rules, the entries naming
    /// them, their parent links, their plan and their pairs. A handle Rapier
    /// reuses therefore starts with no rules.
    fn forget_removed(
        &mut self,
        bodies: &RigidBodySet,
        removed: &[(ColliderHandle, Option<RigidBodyHandle>)],
        removed_bodies: &[RigidBodyHandle],
    ) {
        if !removed.is_empty() {
            let gone: HashSet<ColliderHandle> = removed.iter().map(|r| r.0).collect();
            self.pairs.retain(|key, _| {
                let (a, b) = key.colliders();
                !gone.contains(&a) && !gone.contains(&b)
            });
        }
        for &(handle, body) in removed {
            self.rules.remove_node(handle);
            self.plan.colliders.remove(handle);
            self.written.remove(handle);
            // A body that keeps other colliders is in the look's `left`.
            if let Some(body) = body.filter(|&b| !bodies.contains(b)) {
                self.rules.remove_node(body);
            }
        }
        for &body in removed_bodies {
            self.rules.remove_node(body);
        }
        self.stats.removed_objects = removed.len() + removed_bodies.len();
    }

    /// The pinned pairs: an override or a manifold setting keeps them hooked.
    fn pinned(&self) -> Vec<PairKey> {
        let mut pinned: Vec<PairKey> = self
            .pairs
            .iter()
            .filter(|(_, s)| s.overridden.is_some() || s.manifold != ManifoldUpdate::ByRule)
            .map(|(k, _)| k)
            .collect();
        pinned.sort_unstable_by_key(|k| {
            let (a, b) = k.colliders();
            (a.into_raw_parts(), b.into_raw_parts())
        });
        pinned
    }

    /// Plans every reached collider again (every collider in a full pass)
    /// and gives each the flags, groups and types of its plan, touching only
    /// those that differ; colliders no longer reached get Rapier's defaults back.
    fn apply_plan(&mut self, bodies: &RigidBodySet, colliders: &mut ColliderSet) {
        let pinned = self.pinned();
        let ruled = self.rules.ruled_nodes();
        let reached: Vec<ColliderHandle> = self.roster.colliders().to_vec();
        let own = |h: ColliderHandle, c: &Collider| self.own_settings(h, c);
        let request = Request {
            rules: &self.rules,
            bodies,
            colliders,
            reached: &reached,
            ruled: &ruled,
            pinned: &pinned,
            all_hooked: self.full_pass(),
            own: &own,
        };
        let plan = native::plan(&request);
        // Never pairs: the hooked side also modifies the pair's contacts.
        self.modifying = self
            .pairs
            .iter()
            .filter(|(_, s)| s.manifold == ManifoldUpdate::Never)
            .map(|(k, _)| {
                let (a, b) = k.colliders();
                if plan.colliders.get(a).is_some_and(|p| p.hooked()) {
                    a
                } else {
                    b
                }
            })
            .collect();
        // Colliders planned before and not now go back to Rapier's defaults.
        for &handle in &reached {
            if plan.colliders.get(handle).is_none() {
                if let Some(collider) = colliders.get(handle) {
                    let dynamic = collider
                        .parent()
                        .and_then(|b| bodies.get(b))
                        .is_some_and(|b| b.is_dynamic());
                    self.configure(bodies, colliders, handle, ColliderPlan::unreached(dynamic));
                }
                self.plan.colliders.remove(handle);
            }
        }
        let mut entries: Vec<_> = plan.colliders.iter().map(|(h, e)| (h, *e)).collect();
        entries.sort_unstable_by_key(|(h, _)| h.into_raw_parts());
        self.stats.planned_colliders = entries.len();
        for &(handle, _) in &entries {
            self.roster.watch_collider(bodies, colliders, handle);
        }
        for (handle, entry) in entries {
            self.configure(bodies, colliders, handle, entry);
        }
        self.plan = plan;
        self.replan = false;
        self.candidates.clear();
        self.count_hooked();
    }

    /// Plans the candidate colliders alone when the rest of the plan stands
    /// (see `native::replan_some`), else everything reached.
    fn apply_partial_plan(&mut self, bodies: &RigidBodySet, colliders: &mut ColliderSet) {
        let mut handles = std::mem::take(&mut self.candidates);
        handles.sort_unstable_by_key(|h| h.into_raw_parts());
        handles.dedup();
        let pinned = self.pinned();
        let own = |h: ColliderHandle, c: &Collider| self.own_settings(h, c);
        let request = Request {
            rules: &self.rules,
            bodies,
            colliders,
            reached: &handles,
            ruled: &[],
            pinned: &pinned,
            all_hooked: self.full_pass(),
            own: &own,
        };
        let Some(planned) = native::replan_some(&self.plan, &request, &handles) else {
            return self.apply_plan(bodies, colliders);
        };
        self.stats.planned_colliders = planned.len();
        for (handle, entry) in planned {
            self.configure(bodies, colliders, handle, entry);
            self.plan.colliders.insert(handle, entry);
        }
        self.count_hooked();
    }

    fn count_hooked(&mut self) {
        self.hooked = self
            .roster
            .colliders()
            .iter()
            .filter(|&&c| self.plan.colliders.get(c).is_some_and(|p| p.hooked()))
            .count();
    }

    /// Gives one collider its plan entry combined with the project's own
    /// settings, touching it only if they differ, and keeps the bookkeeping
    /// that follows (waking, newly hooked colliders, regrouping).
    fn configure(
        &mut self,
        bodies: &RigidBodySet,
        colliders: &mut ColliderSet,
        handle: ColliderHandle,
        entry: ColliderPlan,
    ) {
        let Some(current) = colliders.get(handle) else {
            return;
        };
        let body = current.parent().and_then(|b| bodies.get(b));
        let dynamic = body.is_some_and(|b| b.is_dynamic());
        let planned_before = self.plan.colliders.get(handle).is_some();
        let before = self.plan.entry(handle, dynamic);
        let now = Settings::of(current);
        let own = self.own_settings(handle, current);
        let target = entry.combined(own, self.modifying.contains(&handle));
        // The project changed a setting through Rapier: its pairs may have
        // ended (Rapier's own filters stop them), looked up after the step.
        if self.written.get(handle).is_some_and(|w| w.own != own) {
            self.touched.push(handle);
        }
        // The collider is the project's again once the crate adds nothing.
        if target == own {
            self.written.remove(handle);
            self.roster.wrote(handle, None);
        } else {
            let written = Written { own, wrote: target };
            self.written.insert_evicting(handle, written);
            self.roster.wrote(handle, Some(target));
        }
        if target == now {
            return;
        }
        // New settings take effect on a sleeping body once it wakes (a pair
        // whose rule an edit changed wakes its bodies on its own).
        if self.policy != RecalculationPolicy::Manual && before != entry {
            self.to_wake.extend(current.parent());
        }
        self.touched.push(handle);
        if now.collision != target.collision || now.solver != target.solver {
            self.regrouped.insert(handle);
        }
        // A collider of a non-dynamic body may never wake: when the hook
        // takes over (or lets go of) its pairs, Rapier must look at them.
        let rehook = planned_before && now.hooks != target.hooks && !dynamic;
        if rehook {
            self.regrouped.insert(handle);
        }
        // `get_mut` marks a collider modified: only for those that differ.
        let collider = &mut colliders[handle];
        if rehook && now.types == target.types {
            collider.set_collision_groups(InteractionGroups::none());
        }
        target.write(collider);
    }

    /// `node` itself if it is a collider, and every collider below it.
    pub(super) fn colliders_under(
        &self,
        node: Node,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
    ) -> Vec<ColliderHandle> {
        self.rules.colliders_under(node, bodies, colliders)
    }

    /// Recalculates the live pairs that are `everything`, or touch an
    /// `affected` collider, or a `forced` one (whose overrides are dropped).
    /// Returns colliders of changed pairs between fixed bodies, which Rapier
    /// must be made to look at again.
    fn recalculate(
        &mut self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        everything: bool,
        affected: &HashSet<ColliderHandle>,
        forced: &HashSet<ColliderHandle>,
    ) -> Vec<ColliderHandle> {
        let mut refresh = Vec::new();
        let mut updates = Vec::new();
        for (key, _) in self.pairs.iter() {
            let (a, b) = key.colliders();
            // Rapier removed one of them (unwatched): the pair is forgotten
            // after the step and has nothing to wake.
            if !colliders.contains(a) || !colliders.contains(b) {
                continue;
            }
            let force = forced.contains(&a) || forced.contains(&b);
            if force || everything || affected.contains(&a) || affected.contains(&b) {
                updates.push((key, self.calculate(bodies, colliders, a, b), force));
            }
        }
        self.stats.pairs_recalculated = updates.len();
        // The table's order is its hasher's, seeded per process: the
        // wake-ups and nudges below reach Rapier in handle order instead.
        updates.sort_unstable_by_key(|(key, _, _)| {
            let (a, b) = key.colliders();
            (a.into_raw_parts(), b.into_raw_parts())
        });
        for (key, computed, force) in updates {
            let state = self
                .pairs
                .get_mut(key)
                .expect("the key came from the table");
            let before = state.rule();
            let kinds = kinds_of(bodies, colliders, key);
            // A body changed type since the pair was calculated: Rapier looks
            // at its colliders' pairs again by itself and wakes it as
            // `set_body_type` was told, so the new rule needs neither a nudge
            // nor a wake-up (`docs/semantics.md`, section 5).
            let retyped = kinds != state.kinds;
            state.computed = computed;
            state.kinds = kinds;
            if force {
                state.overridden = None;
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
        refresh
    }
}

/// Whether the rules reach `node`: it carries or is named by rules, is in
/// the parent map, lies under such a node, or has settings of its own in
/// the plan. The hooks watch exactly these.
fn reached(
    rules: &super::super::CollisionRuleSet,
    plan: &native::Plan,
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    node: Node,
) -> bool {
    if let Node::Collider(c) = node {
        if plan
            .colliders
            .get(c)
            .is_some_and(|p| !p.is_rapier_default())
        {
            return true;
        }
    }
    let mut current = Some(node);
    while let Some(n) = current {
        let linked = match n {
            Node::Body(b) => rules.in_hierarchy(b),
            Node::Collider(_) => false,
        };
        if linked || rules.record(n).is_some() || rules.is_named(n) {
            return true;
        }
        current = rules.hierarchy.next(bodies, colliders, n);
    }
    false
}
