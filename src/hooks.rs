//! `RuleHooks`: the rules inside Rapier's step. The `PhysicsHooks` adapter,
//! the step wrappers, and the upkeep around each step (new and removed
//! objects, recalculation policies, waking).

use std::sync::{Mutex, PoisonError};

use hashbrown::{HashMap, HashSet};
use rapier3d::prelude::*;

use crate::native::{self, ColliderPlan, Plan};
use crate::node::HandleMap;
use crate::pairs::{self, ManifoldUpdate, PairKey, PairState, PairTable};
use crate::resolve::special_case;
use crate::rule::contact_answer;
use crate::{CollisionRule, CollisionRuleSet, Node};

/// When live pairs are recalculated after the rules change.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum RecalculationPolicy {
    /// The design document's behaviour: edits reach existing pairs only
    /// through [`RuleHooks::force_recalculation`]; new pairs use the current
    /// rules.
    Manual,
    /// Every edit recalculates the live pairs it can affect before the next
    /// step, as if `force_recalculation` had been called on the edited nodes,
    /// and wakes their bodies so that the edit takes effect.
    #[default]
    OnChange,
    /// Every live pair is recalculated before every step (for calculators
    /// that read state the crate cannot see).
    EveryStep,
}

/// What a custom calculator is given: the pair, the Rapier sets, and the
/// rules. Colliders come in no particular order.
pub struct CalculatorContext<'a> {
    /// One collider of the pair.
    pub collider1: ColliderHandle,
    /// The other collider of the pair.
    pub collider2: ColliderHandle,
    /// The world's rigid bodies.
    pub bodies: &'a RigidBodySet,
    /// The world's colliders.
    pub colliders: &'a ColliderSet,
    /// The rule set.
    pub rules: &'a CollisionRuleSet,
}

impl CalculatorContext<'_> {
    /// The default calculation for the pair: [`CollisionRuleSet::resolve`].
    #[must_use]
    pub fn default_rule(&self) -> CollisionRule {
        self.rules
            .resolve(self.bodies, self.colliders, self.collider1, self.collider2)
    }
}

/// What the pair-created callback is given. Colliders come in no particular order.
pub struct PairCreated<'a> {
    /// One collider of the pair.
    pub collider1: ColliderHandle,
    /// The other collider of the pair.
    pub collider2: ColliderHandle,
    /// The rule the calculation gave the pair.
    pub rule: CollisionRule,
    /// The world's rigid bodies.
    pub bodies: &'a RigidBodySet,
    /// The world's colliders.
    pub colliders: &'a ColliderSet,
}

type Calculator = Box<dyn Fn(&CalculatorContext<'_>) -> CollisionRule + Send + Sync>;
type CreatedCallback = Box<dyn Fn(&PairCreated<'_>) -> Option<CollisionRule> + Send + Sync>;

/// What the hooks remember of each collider, to notice changes made through Rapier.
#[derive(Clone, Copy, Debug)]
struct Known {
    body: Option<RigidBodyHandle>,
    dynamic: bool,
    /// The last step in which it was seen in the collider set.
    seen: u64,
}

/// The hook flags every managed collider carries.
const HOOKS: ActiveHooks =
    ActiveHooks::FILTER_CONTACT_PAIRS.union(ActiveHooks::FILTER_INTERSECTION_PAIR);

/// The collision rules inside Rapier's step: a [`PhysicsHooks`]
/// implementation that answers every pair from its rule, keeps the table of
/// live pairs, and configures the colliders' flags itself.
///
/// ```
/// use rapier3d::prelude::*;
/// use rapier_collision_rules::{CollisionRule, CollisionRuleSet, RuleHooks};
///
/// let mut world = PhysicsWorld::new();
/// let ground = world.insert_body(RigidBodyBuilder::fixed());
/// let floor = world.insert_collider(ColliderBuilder::cuboid(10.0, 0.5, 10.0), Some(ground));
/// let ghost = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 1.5, 0.0)));
/// let g = world.insert_collider(ColliderBuilder::ball(0.5), Some(ghost));
///
/// let mut rules = CollisionRuleSet::default();
/// rules.set_personal(ghost, CollisionRule::NoResponse);
/// let mut hooks = RuleHooks::new(rules);
/// let mut paired = false;
/// for _ in 0..60 {
///     hooks.step(&mut world);
///     paired |= hooks.pair_rule(g, floor) == Some(CollisionRule::NoResponse);
/// }
/// let y = world.bodies[ghost].translation().y;
/// assert!(y < -1.0, "the ghost fell through the floor: y = {y}");
/// assert!(paired, "the ghost and the floor formed a live NoResponse pair");
/// ```
pub struct RuleHooks {
    rules: CollisionRuleSet,
    policy: RecalculationPolicy,
    pairs: PairTable,
    /// Pairs first seen during the current step, admitted after it.
    pending: Mutex<HashMap<PairKey, PairState>>,
    calculator: Option<Calculator>,
    on_created: Option<CreatedCallback>,
    known: HandleMap<ColliderHandle, Known>,
    /// Counts steps; the hook compares it to tell the CCD's second answer.
    step: u64,
    forced: Vec<Node>,
    /// A calculator or callback changed: every pair is to be recalculated.
    recalculate_all: bool,
    to_wake: Vec<RigidBodyHandle>,
    /// Colliders given the contact-modification flag for `ManifoldUpdate::Never`.
    modifying: HashSet<ColliderHandle>,
    /// Whether each body of the parent map was dynamic at the last step.
    linked: HandleMap<RigidBodyHandle, bool>,
    /// Colliders hooked for their pairs' overrides and manifold settings.
    pinned: HashSet<ColliderHandle>,
    /// Colliders to plan again before the next step (a partial plan).
    candidates: Vec<ColliderHandle>,
    /// Whether the planner may leave colliders unhooked (see `native.rs`).
    planner: bool,
    plan: Plan,
    /// Something the plan depends on changed: plan again before the next step.
    replan: bool,
    /// Rapier's pairs whose colliders are both native, as of the last step:
    /// their rules follow from the colliders' classes.
    native_pairs: Vec<PairKey>,
    /// Colliders whose groups the last plan changed. Rapier drops and finds
    /// their pairs again, so their table entries outlive one absence.
    regrouped: HashSet<ColliderHandle>,
    /// One bit per collider slot: set for native colliders (read by the
    /// after-step scan of Rapier's pairs, which must stay cheap).
    native_bits: Vec<u64>,
}

impl std::fmt::Debug for RuleHooks {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RuleHooks")
            .field("policy", &self.policy)
            .field("live_pairs", &self.pairs().count())
            .field("calculator", &self.calculator.is_some())
            .field("on_created", &self.on_created.is_some())
            .finish_non_exhaustive()
    }
}

impl Default for RuleHooks {
    fn default() -> Self {
        RuleHooks::new(CollisionRuleSet::default())
    }
}

/// Building, and the rules.
impl RuleHooks {
    /// Hooks that apply `rules` to every collider of the worlds they step.
    pub fn new(rules: CollisionRuleSet) -> RuleHooks {
        RuleHooks {
            rules,
            policy: RecalculationPolicy::default(),
            pairs: PairTable::default(),
            pending: Mutex::new(HashMap::new()),
            calculator: None,
            on_created: None,
            known: HandleMap::default(),
            step: 0,
            forced: Vec::new(),
            recalculate_all: false,
            to_wake: Vec::new(),
            modifying: HashSet::new(),
            linked: HandleMap::default(),
            pinned: HashSet::new(),
            candidates: Vec::new(),
            planner: true,
            plan: Plan::default(),
            replan: true,
            native_pairs: Vec::new(),
            regrouped: HashSet::new(),
            native_bits: Vec::new(),
        }
    }

    /// The rules.
    #[must_use]
    pub fn rules(&self) -> &CollisionRuleSet {
        &self.rules
    }

    /// The rules, to edit. Under [`RecalculationPolicy::OnChange`] the live
    /// pairs an edit can affect are recalculated before the next step.
    pub fn rules_mut(&mut self) -> &mut CollisionRuleSet {
        &mut self.rules
    }

    /// Chooses when live pairs follow rule edits (default `OnChange`).
    pub fn set_policy(&mut self, policy: RecalculationPolicy) {
        self.policy = policy;
        self.replan = true;
    }

    /// Turns the planner on (the default) or off. On, colliders whose pairs
    /// Rapier can decide itself get collision and solver groups instead of
    /// the hook flag, which keeps Rapier's contact recycling; off, every
    /// collider is hooked (for comparison and debugging). The planner also
    /// stands aside while a calculator or a pair-created callback is
    /// registered or the policy is `Manual`: those need every pair to pass
    /// the hook.
    ///
    /// The crate owns the collision groups, solver groups, active hooks and
    /// active collision types of every collider of the worlds it steps.
    pub fn set_planner(&mut self, enabled: bool) {
        self.planner = enabled;
        self.replan = true;
    }

    /// Whether the planner is on (see [`set_planner`](Self::set_planner)).
    #[must_use]
    pub fn planner(&self) -> bool {
        self.planner
    }

    /// How many pairs the hooks keep state for (hooked live pairs, `NoPair`
    /// pairs the hook refuses, overrides): a diagnostic, bounded by the
    /// number of pairs in Rapier's narrow phase.
    #[must_use]
    pub fn tracked_pairs(&self) -> usize {
        self.pairs.iter().count()
    }

    /// How many colliders carry the hook flag as of the last plan.
    #[must_use]
    pub fn hooked_count(&self) -> usize {
        self.plan
            .colliders
            .iter()
            .filter(|(_, p)| p.hooked())
            .count()
    }

    /// The current recalculation policy.
    #[must_use]
    pub fn policy(&self) -> RecalculationPolicy {
        self.policy
    }

    /// Replaces the default calculation (specific, personal, group,
    /// default) for every pair (seed 3.D). The calculator can run the
    /// default calculation itself with [`CalculatorContext::default_rule`].
    /// The special case of two non-dynamic bodies still applies to its
    /// answer. Live pairs are recalculated with it before the next step
    /// (except under `Manual`).
    ///
    /// ```
    /// use rapier_collision_rules::{CollisionRule, RuleHooks};
    ///
    /// let mut hooks = RuleHooks::default();
    /// // Sensors aside, nothing responds to anything: a world of ghosts.
    /// hooks.set_calculator(|ctx| ctx.default_rule().most_restrictive(CollisionRule::NoResponse));
    /// ```
    pub fn set_calculator(
        &mut self,
        calculator: impl Fn(&CalculatorContext<'_>) -> CollisionRule + Send + Sync + 'static,
    ) {
        self.calculator = Some(Box::new(calculator));
        self.decision_changed();
    }

    /// Goes back to the default calculation.
    pub fn remove_calculator(&mut self) {
        self.calculator = None;
        self.decision_changed();
    }

    /// Who decides pairs changed: every pair is recalculated, every collider
    /// planned again (calculators and callbacks need every pair hooked).
    fn decision_changed(&mut self) {
        self.recalculate_all = true;
        self.replan = true;
    }

    /// Registers the pair-created callback (seed's immediate events): it
    /// runs when a pair is created, before its first contact computation,
    /// and again whenever the pair's rule is recalculated, and may replace
    /// the pair's rule by returning `Some`. Rapier may call it from several
    /// threads at once.
    ///
    /// ```
    /// use rapier_collision_rules::{CollisionRule, RuleHooks};
    ///
    /// let mut hooks = RuleHooks::default();
    /// hooks.on_pair_created(|pair| {
    ///     // Nothing may push anything in this world; contacts still report.
    ///     (pair.rule == CollisionRule::Normal).then_some(CollisionRule::NoResponse)
    /// });
    /// ```
    pub fn on_pair_created(
        &mut self,
        callback: impl Fn(&PairCreated<'_>) -> Option<CollisionRule> + Send + Sync + 'static,
    ) {
        self.on_created = Some(Box::new(callback));
        self.decision_changed();
    }

    /// Removes the pair-created callback.
    pub fn remove_pair_created(&mut self) {
        self.on_created = None;
        self.decision_changed();
    }
}

/// Live pairs (seed 3.A).
impl RuleHooks {
    /// The rule of the live pair of `a` and `b`, in either order; `None` if
    /// they form no live pair (a `NoPair` pair is not live).
    #[must_use]
    pub fn pair_rule(&self, a: ColliderHandle, b: ColliderHandle) -> Option<CollisionRule> {
        let key = PairKey::new(a, b);
        match self.pairs.get(key) {
            Some(state) => Some(state.rule()),
            None => self
                .native_rule(key)
                .filter(|_| self.native_pairs.contains(&key)),
        }
        .filter(|&rule| rule != CollisionRule::NoPair)
    }

    /// Every live pair with its rule, in no particular order.
    pub fn pairs(
        &self,
    ) -> impl Iterator<Item = (ColliderHandle, ColliderHandle, CollisionRule)> + '_ {
        let hooked = self
            .pairs
            .iter()
            .map(|(key, state)| (key, Some(state.rule())));
        let native = self
            .native_pairs
            .iter()
            .map(|&key| (key, self.native_rule(key)));
        hooked.chain(native).filter_map(|(key, rule)| {
            let (a, b) = key.colliders();
            rule.filter(|&r| r != CollisionRule::NoPair)
                .map(|r| (a, b, r))
        })
    }

    /// Replaces the rule of the live pair of `a` and `b` for the rest of the
    /// pair's life (automatic recalculation leaves it alone;
    /// [`force_recalculation`](Self::force_recalculation) drops it). `Defer`
    /// drops the override. `NoPair` ends the pair for the crate. Returns
    /// `false`, changing nothing, if `a` and `b` form no live pair.
    pub fn set_pair_rule(
        &mut self,
        a: ColliderHandle,
        b: ColliderHandle,
        rule: CollisionRule,
    ) -> bool {
        let Some(state) = self.live_state(a, b) else {
            return false;
        };
        state.overridden = rule.is_decided().then_some(rule);
        self.replan = true;
        self.wake_pair(a, b);
        true
    }

    /// Sets how the live pair of `a` and `b` updates its contacts. Returns
    /// `false`, changing nothing, if they form no live pair.
    pub fn set_manifold_update(
        &mut self,
        a: ColliderHandle,
        b: ColliderHandle,
        update: ManifoldUpdate,
    ) -> bool {
        let Some(state) = self.live_state(a, b) else {
            return false;
        };
        state.manifold = update;
        *state
            .frozen
            .get_mut()
            .unwrap_or_else(PoisonError::into_inner) = None;
        self.replan = true;
        self.wake_pair(a, b);
        true
    }

    /// The manifold setting of the live pair of `a` and `b`.
    #[must_use]
    pub fn manifold_update(&self, a: ColliderHandle, b: ColliderHandle) -> Option<ManifoldUpdate> {
        match self.pairs.get(PairKey::new(a, b)) {
            Some(state) => (state.rule() != CollisionRule::NoPair).then_some(state.manifold),
            None => self.pair_rule(a, b).map(|_| ManifoldUpdate::ByRule),
        }
    }

    /// Recalculates, before the next step, every live pair of `node` and of
    /// its descendants (seed's `ForceCollisionRuleRecalculation`), dropping
    /// their overrides. A pair that becomes `NoPair` stops being live.
    pub fn force_recalculation(&mut self, node: impl Into<Node>) {
        self.forced.push(node.into());
    }

    /// The rule of a pair of two native colliders, from their classes.
    fn native_rule(&self, key: PairKey) -> Option<CollisionRule> {
        let (a, b) = key.colliders();
        let class = |c| self.plan.colliders.get(c).and_then(|p| p.class);
        Some(native::class_rule(&self.rules, class(a)?, class(b)?))
    }

    /// The table entry of a live pair; a native pair gets one made from its
    /// native rule (and is hooked from the next step on).
    fn live_state(&mut self, a: ColliderHandle, b: ColliderHandle) -> Option<&mut PairState> {
        let key = PairKey::new(a, b);
        if self.pairs.get(key).is_none() && self.native_pairs.contains(&key) {
            let rule = self.native_rule(key)?;
            self.pairs.insert(key, PairState::new(rule, self.step));
        }
        self.pairs
            .get_mut(key)
            .filter(|state| state.rule() != CollisionRule::NoPair)
    }

    fn wake_pair(&mut self, a: ColliderHandle, b: ColliderHandle) {
        self.to_wake.extend(self.known.get(a).and_then(|k| k.body));
        self.to_wake.extend(self.known.get(b).and_then(|k| k.body));
    }
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
        self.prepare(&world.bodies, &mut world.colliders);
        self.freeze_manifolds(&world.narrow_phase);
        self.wake_edited(&mut world.islands, &mut world.bodies);
        world.step_with_events(&*self, events);
        self.after_step(&world.narrow_phase, &world.bodies, &world.colliders);
    }

    /// Before a bare `PhysicsPipeline::step`: notices colliders and bodies
    /// added, removed or changed through Rapier, plans every collider's
    /// flags and groups again if anything they depend on changed, and
    /// recalculates live pairs as the policy says. Call
    /// [`wake_edited`](Self::wake_edited) next, then step with these hooks,
    /// then [`after_step`](Self::after_step).
    pub fn prepare(&mut self, bodies: &RigidBodySet, colliders: &mut ColliderSet) {
        self.step += 1;
        let mut changed = self.sync_colliders(bodies, colliders);
        self.sync_linked_bodies(bodies, &mut changed);
        // Objects removed through Rapier (bodies without colliders, slots
        // reused since the last step, edits through dead handles): forgotten
        // by one sweep over the rule set's own nodes, links and entries.
        self.rules.remove_missing(bodies, colliders);
        let changes = self.rules.take_changes();
        match self.rules.touched_nodes(&changes) {
            Some(touched) => changed.extend(touched),
            None => self.replan = true,
        }
        // The colliders whose chains an edit or a change through Rapier
        // touched: planned again, and their pairs recalculated.
        let mut under = HashSet::new();
        for &node in &changed {
            under.extend(self.colliders_under(node, bodies, colliders));
        }
        if self.replan {
            self.apply_plan(bodies, colliders);
        } else {
            self.candidates.extend(under.iter().copied());
            if !self.candidates.is_empty() {
                self.apply_partial_plan(bodies, colliders);
            }
        }

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
    }

    /// Settles `ManifoldUpdate::Never` settings made since the last step
    /// for pairs that have no contacts now: they are frozen empty. (Pairs
    /// with contacts are frozen in their next contact update, in each body's
    /// frame.) Part of [`step`](Self::step); call it after
    /// [`prepare`](Self::prepare) when stepping a bare pipeline.
    pub fn freeze_manifolds(&mut self, narrow_phase: &NarrowPhase) {
        for (key, state) in self.pairs.iter() {
            if state.manifold != ManifoldUpdate::Never {
                continue;
            }
            let mut frozen = state.frozen.lock().unwrap_or_else(PoisonError::into_inner);
            let (a, b) = key.colliders();
            let touching = narrow_phase
                .contact_pair(a, b)
                .is_some_and(|pair| pair.has_any_active_contact());
            if frozen.is_none() && !touching {
                // Step 0 never comes again: no manifold is frozen later.
                *frozen = Some((0, Vec::new()));
            }
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

    /// After a bare `PhysicsPipeline::step`: admits the pairs created during
    /// the step, forgets the pairs Rapier no longer has, notes the pairs
    /// Rapier decides natively, and gives a rule to hooked pairs Rapier made
    /// without asking the hook (pairs of resting bodies).
    pub fn after_step(
        &mut self,
        narrow_phase: &NarrowPhase,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
    ) {
        // Rapier finds a pair by slot: a handle whose slot was reused must
        // not find the new collider's pair.
        let exists = |key: PairKey| {
            let (a, b) = key.colliders();
            colliders.contains(a)
                && colliders.contains(b)
                && (narrow_phase.contact_pair(a, b).is_some()
                    || narrow_phase.intersection_pair(a, b).is_some())
        };
        let pending = std::mem::take(
            self.pending
                .get_mut()
                .unwrap_or_else(PoisonError::into_inner),
        );
        for (key, state) in pending {
            if exists(key) {
                self.pairs.insert(key, state);
            }
        }
        let mut never_ended = false;
        let regrouped = std::mem::take(&mut self.regrouped);
        self.pairs.retain(|key, state| {
            let (a, b) = key.colliders();
            let keep = exists(key) || regrouped.contains(&a) || regrouped.contains(&b);
            never_ended |= !keep && state.manifold == ManifoldUpdate::Never;
            keep
        });
        self.replan |= never_ended;

        // The native pairs: Rapier's pairs of two colliders without the hook.
        let bits = &self.native_bits;
        let native = |c: ColliderHandle| {
            let index = c.into_raw_parts().0 as usize;
            bits.get(index / 64)
                .is_some_and(|w| w >> (index % 64) & 1 == 1)
        };
        self.native_pairs.clear();
        let contacts = narrow_phase
            .contact_pairs()
            .map(|p| (p.collider1, p.collider2));
        let sensors = narrow_phase.intersection_pairs().map(|(a, b, _)| (a, b));
        // A hooked pair the hook was not asked about: Rapier made it but
        // skipped it (its bodies rest, or a collider just became hooked).
        // It is live all the same: it gets its rule now, before Rapier
        // computes any contact for it.
        let mut unseen = Vec::new();
        for (a, b) in contacts.chain(sensors) {
            let key = PairKey::new(a, b);
            if native(a) && native(b) {
                self.native_pairs.push(key);
            } else if self.pairs.get(key).is_none() {
                unseen.push(key);
            }
        }
        for key in unseen {
            let (a, b) = key.colliders();
            let rule = self.calculate(bodies, colliders, a, b);
            self.pairs.insert(key, PairState::new(rule, self.step));
        }
    }

    /// Notices bodies of the parent map that changed type: a body without
    /// colliders (a pelvis, a chassis frame) is not seen through colliders,
    /// yet its default group is part of its descendants' chains.
    fn sync_linked_bodies(&mut self, bodies: &RigidBodySet, changed: &mut Vec<Node>) {
        for (child, parent) in self.rules.parents() {
            for body in [child, parent] {
                let Some(rigid_body) = bodies.get(body) else {
                    continue;
                };
                let dynamic = rigid_body.is_dynamic();
                if self
                    .linked
                    .insert(body, dynamic)
                    .is_some_and(|was| was != dynamic)
                {
                    changed.push(Node::Body(body));
                }
            }
        }
    }

    /// Notices colliders added, removed, moved to another body, or whose
    /// body changed type; returns the nodes whose chains changed.
    fn sync_colliders(&mut self, bodies: &RigidBodySet, colliders: &ColliderSet) -> Vec<Node> {
        // One pass over the set (Rapier's memory is the cost here), then one
        // over the hooks' own compact table for what was not seen.
        let step = self.step;
        let mut changed = Vec::new();
        let mut evicted = Vec::new();
        for (handle, collider) in colliders.iter() {
            let body = collider.parent();
            let dynamic = body
                .and_then(|b| bodies.get(b))
                .is_some_and(|b| b.is_dynamic());
            if let Some(known) = self.known.get_mut(handle) {
                known.seen = step;
                if known.body == body && known.dynamic == dynamic {
                    continue;
                }
                if known.body != body {
                    changed.push(Node::Collider(handle));
                } else {
                    changed.extend(body.map(Node::Body));
                }
                known.body = body;
                known.dynamic = dynamic;
            } else {
                let known = Known {
                    body,
                    dynamic,
                    seen: step,
                };
                // A collider in a reused slot: the slot's former collider was
                // removed, so it is forgotten with the other removals below.
                if let Some((old, former)) = self.known.insert_evicting(handle, known) {
                    evicted.push((old, former.body));
                }
            }
            self.candidates.push(handle);
        }

        let mut removed = evicted;
        self.known.retain(|handle, known| {
            let gone = known.seen != step;
            if gone {
                removed.push((handle, known.body));
            }
            !gone
        });
        if !removed.is_empty() {
            let gone: HashSet<ColliderHandle> = removed.iter().map(|r| r.0).collect();
            self.pairs.retain(|key, _| {
                let (a, b) = key.colliders();
                !gone.contains(&a) && !gone.contains(&b)
            });
        }
        for &(handle, body) in &removed {
            self.rules.remove_node(handle);
            self.plan.colliders.remove(handle);
            let index = handle.into_raw_parts().0 as usize;
            if let Some(word) = self.native_bits.get_mut(index / 64) {
                *word &= !(1 << (index % 64));
            }
            if let Some(body) = body.filter(|&b| !bodies.contains(b)) {
                self.rules.remove_node(body);
            }
        }
        changed
    }

    /// Plans every collider again (see `native.rs`) and gives each the
    /// flags, groups and types of its plan, touching only those that differ.
    fn apply_plan(&mut self, bodies: &RigidBodySet, colliders: &mut ColliderSet) {
        let all_hooked = self.all_hooked();
        let (mut pinned, mut modifying) = (HashSet::new(), HashSet::new());
        for (key, state) in self.pairs.iter() {
            let (a, b) = key.colliders();
            if state.overridden.is_some() || state.manifold != ManifoldUpdate::ByRule {
                pinned.extend([a, b]);
            }
            if state.manifold == ManifoldUpdate::Never {
                modifying.extend([a, b]);
            }
        }
        let plan = native::plan(&self.rules, bodies, colliders, &pinned, all_hooked);
        self.modifying = modifying;
        self.pinned = pinned;
        self.native_bits.clear();
        let entries: Vec<_> = plan.colliders.iter().map(|(h, e)| (h, *e)).collect();
        for (handle, entry) in entries {
            self.configure(colliders, handle, entry);
        }
        self.plan = plan;
        self.replan = false;
        self.candidates.clear();
        self.drop_native_pairs_from_table();
    }

    /// Plans the candidate colliders alone when the rest of the plan stands
    /// (see `native::replan_some`), else everything.
    fn apply_partial_plan(&mut self, bodies: &RigidBodySet, colliders: &mut ColliderSet) {
        let mut handles = std::mem::take(&mut self.candidates);
        handles.sort_unstable_by_key(|h| h.into_raw_parts());
        handles.dedup();
        let all_hooked = self.all_hooked();
        let planned = native::replan_some(
            &self.plan,
            &self.rules,
            bodies,
            colliders,
            &handles,
            &self.pinned,
            all_hooked,
        );
        let Some(planned) = planned else {
            return self.apply_plan(bodies, colliders);
        };
        for (handle, entry) in planned {
            self.configure(colliders, handle, entry);
            self.plan.colliders.insert(handle, entry);
        }
        self.drop_native_pairs_from_table();
    }

    fn all_hooked(&self) -> bool {
        !self.planner
            || self.calculator.is_some()
            || self.on_created.is_some()
            || self.policy == RecalculationPolicy::Manual
    }

    /// Gives one collider the flags, groups and types of its plan entry,
    /// touching it only if they differ, and keeps the bookkeeping that
    /// follows (waking, newly hooked colliders, regrouping, native bits).
    fn configure(
        &mut self,
        colliders: &mut ColliderSet,
        handle: ColliderHandle,
        entry: ColliderPlan,
    ) {
        let before = self.plan.colliders.get(handle).copied();
        if self.policy != RecalculationPolicy::Manual && before.is_some_and(|b| b != entry) {
            self.to_wake
                .extend(self.known.get(handle).and_then(|k| k.body));
        }
        // OK since handles in the plan are those of the set as of now: a
        // slot's bit describes its current collider until it is planned again.
        let index = handle.into_raw_parts().0 as usize;
        if index / 64 >= self.native_bits.len() {
            self.native_bits.resize(index / 64 + 1, 0);
        }
        let bit = 1 << (index % 64);
        if entry.hooked() {
            self.native_bits[index / 64] &= !bit;
        } else {
            self.native_bits[index / 64] |= bit;
        }

        let mut hooks = if entry.hooked() {
            HOOKS
        } else {
            ActiveHooks::empty()
        };
        if self.modifying.contains(&handle) {
            hooks |= ActiveHooks::MODIFY_SOLVER_CONTACTS;
        }
        let Some(current) = colliders.get(handle) else {
            return;
        };
        let same = current.active_hooks() == hooks
            && current.collision_groups() == entry.collision
            && current.solver_groups() == entry.solver
            && current.active_collision_types() == entry.types;
        if same {
            return;
        }
        if current.collision_groups() != entry.collision || current.solver_groups() != entry.solver
        {
            self.regrouped.insert(handle);
        }
        // A collider of a non-dynamic body may never wake: when the hook
        // takes over (or lets go of) its pairs, Rapier must look at them.
        let never_wakes = self.known.get(handle).is_none_or(|k| !k.dynamic);
        let rehook = before.is_some() && current.active_hooks() != hooks && never_wakes;
        if rehook {
            self.regrouped.insert(handle);
        }
        // `get_mut` marks a collider modified: only for those that differ.
        let collider = &mut colliders[handle];
        collider.set_active_hooks(hooks);
        collider.set_solver_groups(entry.solver);
        if collider.active_collision_types() != entry.types || rehook {
            collider.set_active_collision_types(entry.types);
            // Changing the collision types alone sets no change flag:
            // nudging the collision groups makes Rapier look again.
            collider.set_collision_groups(InteractionGroups::none());
        }
        collider.set_collision_groups(entry.collision);
    }

    /// Pairs of two native colliders leave the table: their rules follow
    /// from the plan (pinned pairs are hooked, so they stay).
    fn drop_native_pairs_from_table(&mut self) {
        let plan = &self.plan;
        let hooked = |c| plan.colliders.get(c).is_none_or(|p| p.hooked());
        self.pairs.retain(|key, _| {
            let (a, b) = key.colliders();
            hooked(a) || hooked(b)
        });
    }

    /// `node` itself if it is a collider, and every collider below it.
    fn colliders_under(
        &self,
        node: Node,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
    ) -> Vec<ColliderHandle> {
        let mut below: Vec<ColliderHandle> = self
            .rules
            .descendants(node, bodies, colliders)
            .into_iter()
            .filter_map(|n| match n {
                Node::Collider(c) => Some(c),
                Node::Body(_) => None,
            })
            .collect();
        if let Node::Collider(c) = node {
            below.push(c);
        }
        below
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
            let force = forced.contains(&a) || forced.contains(&b);
            if force || everything || affected.contains(&a) || affected.contains(&b) {
                updates.push((key, self.calculate(bodies, colliders, a, b), force));
            }
        }
        for (key, computed, force) in updates {
            let state = self
                .pairs
                .get_mut(key)
                .expect("the key came from the table");
            let before = state.rule();
            state.computed = computed;
            if force {
                state.overridden = None;
            }
            if state.rule() != before {
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

    /// A pair's rule: the calculator or the default calculation, then the
    /// pair-created callback.
    fn calculate(
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

    fn pending(&self) -> std::sync::MutexGuard<'_, HashMap<PairKey, PairState>> {
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
