//! **Step**: the rules inside Rapier's step.
//!
//! [`RuleHooks`] is a drop-in [`PhysicsHooks`]. Around each of Rapier's
//! steps ([`step`]) it runs the phases before ([`prepare`]: the rules
//! whose end came removed by [`expiry`]; what changed, through the
//! [`roster`] of what the rules reach; the plan written into
//! the colliders by [`writer`]; live pairs recalculated by [`recalculate`];
//! the [`witness`] of a step taken without the hooks) and after ([`sweep`]:
//! the pairs Rapier made and ended; [`soft_bodies`]: what a soft body is to
//! the rules, and the pieces of cuts and tears). During the step Rapier asks it about
//! the pairs of hooked colliders ([`answer`]), which it answers from the
//! table of live pairs ([`pair_state`]); [`tears`] hears the strain tears
//! of a step, for the next steps before the next `prepare`. [`live`] is the live-pair API,
//! answered on demand from Rapier's graph; [`reach`] says how far the
//! rules reach a collider or a pair; [`rule_events`] reports what
//! changed for live pairs to a game that asks; [`stats`] says what the
//! last step did.
//!
//! It stands on the [`planner`](super::planner), which decides what Rapier
//! can test itself, and on [`world`](super::world), which reads and writes
//! Rapier.

mod answer;
mod expiry;
mod live;
mod one_way_contacts;
mod pair_state;
mod prepare;
mod reach;
mod recalculate;
mod roster;
mod rule_events;
mod soft_bodies;
mod stats;
mod step;
mod sweep;
mod tears;
mod witness;
mod writer;

use std::sync::Mutex;
use std::sync::atomic::AtomicBool;

use hashbrown::{HashMap, HashSet};
use super::rapier::prelude::*;

use super::model::HandleMap;
use super::planner::Plan;
use super::world::{Census, Mark, ProjectSettings, Settings, Written};
use super::{CollisionRule, CollisionRuleSet, Node};

pub use pair_state::ManifoldUpdate;
pub(crate) use pair_state::{PairState, PairTable};
pub(crate) use super::world::PairKey;
pub use stats::{FullPass, PlanCause, StepStats};
pub use live::WorldRef;
pub use reach::Reach;
#[cfg(feature = "debug-render")]
pub(crate) use reach::PairReach;
pub use rule_events::{RuleChange, RuleEvent, RuleEventHandler};
pub use soft_bodies::SplitPiece;
pub use tears::TearListener;
use roster::Roster;

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

/// The collision rules inside Rapier's step: a [`PhysicsHooks`]
/// implementation that answers every pair from its rule, keeps the table of
/// live pairs, and configures the colliders' flags itself.
///
/// The hooks step the world themselves: [`step`](Self::step) (or
/// [`step_with_events`](Self::step_with_events), or
/// [`step_pipeline`](Self::step_pipeline) on bare sets), or
/// [`prepare`](Self::prepare) before and [`after_step`](Self::after_step)
/// after a bare `PhysicsPipeline::step` given the hooks. Given to
/// `world.step_with_events(&hooks, ..)` alone they plan nothing: a rule that
/// Rapier's groups carry is not written, and a new object has no rule.
/// After a step of their own, the hooks notice Rapier asking them before
/// the next: a debug build panics there, naming the fix, and a release
/// build warns once. Hooks that never stepped cannot tell
/// (`docs/semantics.md`, "Stepping without the hooks").
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
///     paired |= hooks.pair_rule(&world, g, floor) == Some(CollisionRule::NoResponse);
/// }
/// let y = world.bodies[ghost].translation().y;
/// assert!(y < -1.0, "the ghost fell through the floor: y = {y}");
/// assert!(paired, "the ghost and the floor formed a live NoResponse pair");
/// ```
pub struct RuleHooks {
    /// What decides each pair.
    decide: Deciders,
    /// The hooked pairs: every pair with a hooked collider that Rapier holds.
    pairs: PairTable,
    /// Pairs first seen during the current step, admitted after it.
    pending: Mutex<HashMap<PairKey, PairState>>,
    /// Where the hooks stand between `prepare` and `after_step`.
    boundary: Boundary,
    /// The work queued for the next step.
    queued: Queued,
    /// The plan, what the hooks watch, and what they wrote into Rapier.
    planned: Planned,
    /// What the last step did.
    stats: StepStats,
    /// What the hooks follow of the world's soft bodies.
    soft: soft_bodies::SoftBodies,
    /// The ends of pair overrides given one (see
    /// [`RuleHooks::set_pair_rule_until`]).
    pair_ends: HashMap<PairKey, super::model::Countdown>,
    /// The rule events, while a game asks for them (see
    /// [`RuleHooks::record_rule_events`]).
    recording: Option<Box<rule_events::Recording>>,
    /// The one-way standings of the manifolds of pairs made of parts,
    /// which Rapier cannot keep in their `user_data` (see
    /// `one_way_contacts.rs`).
    one_way_parts: Mutex<one_way_contacts::PartStandings>,
    /// The one-way standings of pairs with a soft body.
    soft_one_ways: Mutex<one_way_contacts::SoftStandings>,
}

/// What decides each pair: the rules, the policy, the code a project
/// registered.
struct Deciders {
    rules: CollisionRuleSet,
    policy: RecalculationPolicy,
    calculator: Option<Calculator>,
    on_created: Option<CreatedCallback>,
    /// The project's own hooks (see [`RuleHooks::set_user_hooks`]).
    user: Option<Box<dyn PhysicsHooks + Send + Sync>>,
}

/// The step boundary (`docs/architecture.md`, "The step boundary").
struct Boundary {
    /// Counts steps; the hook compares it to tell the CCD's second answer.
    step: u64,
    /// The rule set the hooks last looked at (`model/identity.rs`): another
    /// one put in place of it is followed whole.
    rules_seen: u64,
    /// `prepare` ran and `after_step` has not yet.
    prepared: bool,
    /// The hook answered since the last `prepare`.
    stepped: AtomicBool,
    /// The hooks' last step was their own (`step`, `step_with_events`,
    /// `step_pipeline`), which brackets Rapier's step itself: until the
    /// next, Rapier asks them nothing. (Hooks stepped with `prepare` and
    /// `after_step` around a step of the project's, as Bevy's, are asked
    /// where the project steps, and check only the bracket.)
    own_step: bool,
    /// The hook answered after the hooks' own step and before the next:
    /// Rapier stepped with them but without their `prepare` (the hooks
    /// given to `world.step_with_events(&hooks, ..)`). The next `prepare`
    /// says so.
    unprepared: AtomicBool,
    /// The rules with an end counted the step of the open bracket: another
    /// `prepare` before that step (the project's, then the one of the
    /// hooks' own step) does not count it again.
    counted: bool,
    /// `follow_soft_bodies` ran since the last `after_step`.
    followed: bool,
    /// It had when the last `prepare` began: a bracket whose `prepare`
    /// planned without it, in a world with soft bodies, left `NoResponse`
    /// to the solver groups Rapier's soft-body solver does not read.
    followed_at_prepare: bool,
    /// A `ManifoldUpdate::Never` setting waits for `freeze_manifolds`.
    unsettled: bool,
    /// One did at `prepare`: `after_step` checks that it was settled.
    owe_freeze: bool,
    /// The world's census after the last step (see `world::census`): a
    /// different one means the project removed, added or moved objects,
    /// whose pairs the after-step sweep must look at even if no body moved.
    census: Census,
    /// A hooked pair the hook answered "no pair", "no contacts" or "no
    /// response" in the last step, with its rule: if Rapier's graph shows
    /// another answer before the next step, or after a step that asked the
    /// hooks nothing, Rapier stepped without the hooks.
    witness: Option<Witness>,
    /// A convex pair with a one-way surface whose contacts the hook dropped
    /// in this step, its manifold's standing forbidden (the first the hook
    /// met; `one_way_noting` says one was): at `after_step` it becomes
    /// `one_way_witness`.
    one_way_noted: Mutex<Option<PairKey>>,
    one_way_noting: AtomicBool,
    /// The one-way witness of the last step: a forbidden standing keeps
    /// the pair's solver contacts empty at every step with the hooks, so
    /// solver contacts there mean Rapier stepped without them.
    one_way_witness: Option<PairKey>,
    /// Whether stepping without the hooks was reported (once).
    reported_unhooked: bool,
    /// Whether a world put in place without `world_replaced` was reported
    /// (once).
    reported_foreign_marks: bool,
    /// How long a step is, for rules given for a time.
    dt: Real,
}

/// The witness pair of a step (see [`Boundary::witness`]).
#[derive(Clone, Copy, Debug)]
struct Witness {
    key: PairKey,
    /// Its rule.
    rule: CollisionRule,
    /// The rule the hook's answer says in Rapier's graph: `NoContacts` for a
    /// soft-rigid `NoResponse` pair, which Rapier's soft-body solver gets no
    /// contacts of (`docs/semantics.md`, "Soft bodies"); else its rule.
    answered_as: CollisionRule,
}

/// The work queued for the next step.
struct Queued {
    /// Nodes whose pairs `force_recalculation` asked for.
    forced: Vec<Node>,
    /// A calculator or callback changed: every pair is to be recalculated.
    recalculate_all: bool,
    /// Bodies to wake before the next step.
    to_wake: Vec<RigidBodyHandle>,
    /// Colliders whose bodies are to be woken before the next step.
    wake_colliders: Vec<ColliderHandle>,
    /// Colliders to plan again before the next step (a partial plan).
    candidates: Vec<ColliderHandle>,
    /// Rapier's copies of a cut soft body's colliders, each with the
    /// colliders it may copy: what a copy holds now is the crate's write
    /// and the project's settings of the original, as Rapier copied them
    /// (see `RuleHooks::settle_pieces`).
    pieces: Vec<soft_bodies::Copied>,
    /// Something the whole plan depends on changed: plan again before the
    /// next step, for this reason.
    replan: Option<PlanCause>,
    /// Colliders whose groups the last plan changed. Rapier drops and finds
    /// their pairs again, so their table entries outlive one absence.
    regrouped: HashSet<ColliderHandle>,
    /// Watched colliders whose crate's mark is not the one written (see
    /// `RuleHooks::give_marks_back`).
    unmarked: Vec<ColliderHandle>,
    /// Colliders configured or changed before this step: after it, their
    /// pairs are looked up in Rapier's graph (a pair Rapier made without
    /// asking the hook gets its rule; one it dropped is forgotten).
    touched: Vec<ColliderHandle>,
    /// The objects removed before this step are forgotten without being
    /// remembered as removed: the step reads the whole rule set (the
    /// first, as after `world_replaced`) or the edit log gave up, so no
    /// edit names the nodes given rules since the last step (see
    /// `Look::spared`).
    spare_removed: bool,
}

impl Planned {
    /// Whether `collider` carries a hook flag the crate gave it: a rule the
    /// hook decides, or contact modification (a one-way surface, a `Never`
    /// manifold setting; `modifies`: the rules have either). Rapier turns
    /// its pairs' contact recycling off.
    fn carries_hook(&self, collider: ColliderHandle, modifies: bool) -> bool {
        self.plan.hooks(collider)
            || modifies
                && self.written.get(collider).is_some_and(|w| {
                    (w.wrote.hooks - w.own.hooks).contains(ActiveHooks::MODIFY_SOLVER_CONTACTS)
                })
    }

    /// How many of `handles` are watched and carry a hook flag the crate
    /// gave them (each once in `handles`), as `hooked` counts them.
    fn hooked_among(&self, handles: impl Iterator<Item = ColliderHandle>) -> usize {
        self.carrying_hook(handles.filter(|&c| self.roster.watches(c)))
    }

    /// How many of `handles` carry a hook flag the crate gave them, watched
    /// or not (the colliders a look just let go of).
    fn carrying_hook(&self, handles: impl Iterator<Item = ColliderHandle>) -> usize {
        let modifies = self.counted_modifies;
        handles.filter(|&c| self.carries_hook(c, modifies)).count()
    }
}

impl RuleHooks {
    /// Whether the crate may give colliders contact modification (see
    /// [`Planned::carries_hook`]): one read, so that counting the hooked
    /// colliders of a world without one-way surfaces costs no more.
    fn modifies_contacts(&self) -> bool {
        self.decide.rules.uses_one_ways() || !self.planned.modifying.is_empty()
    }
}

/// The plan and what it was written into.
struct Planned {
    /// Whether the planner may leave colliders unhooked (see
    /// [`RuleHooks::set_planner`]).
    enabled: bool,
    /// Test oracle: look at every collider and plan everything every step.
    exhaustive: bool,
    plan: Plan,
    /// The colliders and bodies the hooks watch.
    roster: Roster,
    /// How many watched colliders carry a hook flag the crate gave them:
    /// kept up by the changes of a step (a plan of a few colliders, the
    /// colliders that went), counted whole after a whole plan.
    hooked: usize,
    /// A whole plan was written since `hooked` was counted: counted once,
    /// at the end of `prepare`.
    recount: bool,
    /// Whether the crate could give contact modification when `hooked` was
    /// counted (see [`Planned::carries_hook`]): counted again when that
    /// changes.
    counted_modifies: bool,
    /// The colliders whose settings differ from the project's: what the
    /// project set and what the crate wrote.
    written: HandleMap<ColliderHandle, Written>,
    /// Colliders given the contact-modification flag for `ManifoldUpdate::Never`.
    modifying: HashSet<ColliderHandle>,
    /// The colliders of a loaded world whose mark the hooks read at their
    /// first step (see `RuleHooks::adopt_marks`), with the settings they
    /// held, until that step's plan.
    loaded: Vec<(ColliderHandle, Settings)>,
}

impl std::fmt::Debug for RuleHooks {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("RuleHooks")
            .field("policy", &self.decide.policy)
            .field("tracked_pairs", &self.pairs.len())
            .field("calculator", &self.decide.calculator.is_some())
            .field("on_created", &self.decide.on_created.is_some())
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
        let rules_seen = rules.identity.number();
        RuleHooks {
            decide: Deciders {
                rules,
                policy: RecalculationPolicy::default(),
                calculator: None,
                on_created: None,
                user: None,
            },
            pairs: PairTable::default(),
            pending: Mutex::new(HashMap::new()),
            boundary: Boundary {
                step: 0,
                rules_seen,
                prepared: false,
                stepped: AtomicBool::new(false),
                own_step: false,
                unprepared: AtomicBool::new(false),
                counted: false,
                unsettled: false,
                owe_freeze: false,
                census: Census::default(),
                witness: None,
                followed: false,
                followed_at_prepare: false,
                one_way_noted: Mutex::new(None),
                one_way_noting: AtomicBool::new(false),
                one_way_witness: None,
                reported_unhooked: false,
                reported_foreign_marks: false,
                dt: IntegrationParameters::default().dt,
            },
            queued: Queued {
                forced: Vec::new(),
                recalculate_all: false,
                to_wake: Vec::new(),
                wake_colliders: Vec::new(),
                pieces: Vec::new(),
                candidates: Vec::new(),
                replan: Some(PlanCause::FirstStep),
                regrouped: HashSet::new(),
                touched: Vec::new(),
                unmarked: Vec::new(),
                spare_removed: false,
            },
            planned: Planned {
                enabled: true,
                exhaustive: false,
                plan: Plan::default(),
                roster: Roster::default(),
                hooked: 0,
                recount: false,
                counted_modifies: false,
                written: HandleMap::default(),
                modifying: HashSet::new(),
                loaded: Vec::new(),
            },
            stats: StepStats::default(),
            soft: soft_bodies::SoftBodies::default(),
            pair_ends: HashMap::new(),
            recording: None,
            one_way_parts: Mutex::default(),
            soft_one_ways: Mutex::default(),
        }
    }

    /// The rules.
    #[must_use]
    pub fn rules(&self) -> &CollisionRuleSet {
        &self.decide.rules
    }

    /// The rules, to edit. Under [`RecalculationPolicy::OnChange`] the live
    /// pairs an edit can affect are recalculated before the next step. A
    /// whole rule set may be put in place of the hooks' one (`*hooks.rules_mut()
    /// = loaded`, a new set, a copy, two hooks' sets swapped): every set is
    /// another to the hooks, copies included, so every live pair and the plan
    /// follow the new one at the next step.
    pub fn rules_mut(&mut self) -> &mut CollisionRuleSet {
        &mut self.decide.rules
    }

    /// Chooses when live pairs follow rule edits (default `OnChange`).
    pub fn set_policy(&mut self, policy: RecalculationPolicy) {
        self.decide.policy = policy;
        self.queued.replan = Some(PlanCause::HookSettings);
    }

    /// Turns the planner on (the default) or off. On, colliders whose pairs
    /// Rapier can decide itself get collision and solver groups instead of
    /// the hook flag, which keeps Rapier's contact recycling; off, every
    /// collider is hooked (for comparison and debugging). The planner also
    /// stands aside while a calculator or a pair-created callback is
    /// registered or the policy is `Manual`: those need every pair to pass
    /// the hook.
    ///
    /// The crate never writes over a project's own settings: it combines
    /// its plan with each collider's collision groups, solver groups,
    /// collision types and hook bits (`docs/semantics.md`, "The project's own settings"), and a
    /// collider the rules no longer reach gets the project's settings back.
    pub fn set_planner(&mut self, enabled: bool) {
        self.planned.enabled = enabled;
        self.queued.replan = Some(PlanCause::HookSettings);
    }

    /// The tests' oracle: with `true`, every step looks at every collider,
    /// rebuilds the roster from the rule set and plans everything, as the
    /// hooks did before they followed what the rules reach. Slow; for
    /// comparing against the incremental upkeep.
    #[cfg(feature = "test-oracle")]
    pub fn set_exhaustive(&mut self, exhaustive: bool) {
        self.planned.exhaustive = exhaustive;
    }

    /// The project's own settings of `collider`: what it has now, except
    /// where the crate wrote and the project has not changed them since.
    pub(crate) fn own_settings(&self, handle: ColliderHandle, collider: &Collider) -> Settings {
        own_settings(&self.planned.written, handle, collider)
    }

    /// Whether the planner is on (see [`set_planner`](Self::set_planner)).
    #[must_use]
    pub fn planner(&self) -> bool {
        self.planned.enabled
    }

    /// What the last step did and cost: hooked and watched colliders, hook
    /// answers, recalculated pairs, whether every collider was looked at and
    /// why. A world that steps slower with the rules than without: start
    /// here (`docs/performance.md`, "Why is my world slow").
    #[must_use]
    pub fn stats(&self) -> StepStats {
        self.stats
    }

    /// The current recalculation policy.
    #[must_use]
    pub fn policy(&self) -> RecalculationPolicy {
        self.decide.policy
    }

    /// Replaces the default calculation (specific, personal, group,
    /// default) for every pair. The calculator can run the
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
    ///
    /// The calculator answers when a pair's rule is calculated: when Rapier
    /// first finds the pair, and under the default
    /// [`OnChange`](RecalculationPolicy::OnChange) policy when an edit or
    /// [`force_recalculation`](Self::force_recalculation) reaches it. A
    /// calculator that reads state of its own (a flag, a timer, a score) is
    /// not asked again when that state changes: call `force_recalculation`
    /// on the nodes whose pairs the change reaches, or, for state that
    /// changes every step, set [`EveryStep`](RecalculationPolicy::EveryStep).
    ///
    /// ```
    /// use std::sync::Arc;
    /// use std::sync::atomic::{AtomicBool, Ordering};
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, RuleHooks};
    ///
    /// let mut world = PhysicsWorld::new();
    /// world.gravity = Vector::ZERO;
    /// // Two team mates walking through each other.
    /// let mate = |world: &mut PhysicsWorld, x: f32, vx: f32| {
    ///     let body = world.insert_body(
    ///         RigidBodyBuilder::dynamic().translation(Vector::new(x, 0.0, 0.0)).linvel(Vector::new(vx, 0.0, 0.0)),
    ///     );
    ///     (body, world.insert_collider(ColliderBuilder::ball(0.5), Some(body)))
    /// };
    /// let ((a, ca), (b, cb)) = (mate(&mut world, -0.3, 1.0), mate(&mut world, 0.3, -1.0));
    /// let friendly_fire = Arc::new(AtomicBool::new(false));
    /// let mut hooks = RuleHooks::default();
    /// let flag = friendly_fire.clone();
    /// hooks.set_calculator(move |_| {
    ///     if flag.load(Ordering::Relaxed) { CollisionRule::Normal } else { CollisionRule::NoResponse }
    /// });
    /// hooks.step(&mut world);
    /// assert_eq!(hooks.pair_rule(&world, ca, cb), Some(CollisionRule::NoResponse));
    /// // The flag alone reaches no live pair: the calculator is asked again
    /// // for the pairs of the nodes forced.
    /// friendly_fire.store(true, Ordering::Relaxed);
    /// hooks.step(&mut world);
    /// assert_eq!(hooks.pair_rule(&world, ca, cb), Some(CollisionRule::NoResponse));
    /// hooks.force_recalculation(a);
    /// hooks.step(&mut world);
    /// assert_eq!(hooks.pair_rule(&world, ca, cb), Some(CollisionRule::Normal));
    /// for _ in 0..60 {
    ///     hooks.step(&mut world);
    /// }
    /// // The team mates pushed each other back instead of walking through.
    /// assert!(world.bodies[a].translation().x < world.bodies[b].translation().x);
    /// ```
    pub fn set_calculator(
        &mut self,
        calculator: impl Fn(&CalculatorContext<'_>) -> CollisionRule + Send + Sync + 'static,
    ) {
        self.decide.calculator = Some(Box::new(calculator));
        self.decision_changed();
    }

    /// Goes back to the default calculation.
    pub fn remove_calculator(&mut self) {
        self.decide.calculator = None;
        self.decision_changed();
    }

    /// Who decides pairs changed: every pair is recalculated, every collider
    /// planned again (calculators and callbacks need every pair hooked).
    fn decision_changed(&mut self) {
        self.queued.recalculate_all = true;
        self.queued.replan = Some(PlanCause::HookSettings);
    }

    /// Registers the pair-created callback (the BEPU design's immediate
    /// pair events): it runs when a pair is created, before its first
    /// contact computation, and again whenever the pair's rule is
    /// recalculated, and may replace the pair's rule by returning `Some`.
    /// Rapier may call it from several threads at once.
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
        self.decide.on_created = Some(Box::new(callback));
        self.decision_changed();
    }

    /// Removes the pair-created callback.
    pub fn remove_pair_created(&mut self) {
        self.decide.on_created = None;
        self.decision_changed();
    }

    /// Keeps the project's own [`PhysicsHooks`] working beside the rules.
    /// Rapier asks them what it would have asked them without the rules: a
    /// collider whose own hook bits (`ActiveHooks`, set through Rapier as
    /// before) ask for a filter or for contact modification gets it, for
    /// the pairs the rules let through. For those pairs (`Normal`,
    /// `NoResponse`) the project's `filter_contact_pair` and
    /// `filter_intersection_pair` may only restrict further (their solver
    /// flags are combined with the rule's); `NoPair` and `NoContacts` pairs
    /// never reach them. Their `modify_solver_contacts` runs after the
    /// crate's own (frozen contacts of `ManifoldUpdate::Never`). The hooks
    /// must be `Send + Sync`, as [`RuleHooks`] is.
    ///
    /// Rapier's one-way platform works as it does without the rules. The
    /// platform's collider asks for contact modification itself (its
    /// `ActiveHooks`), and the allowed normal is given in the frame of
    /// Rapier's `collider1`, which may be the platform or the other body, as
    /// Rapier's own one-way example does it:
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, RuleHooks};
    ///
    /// /// The platform lets bodies through from below.
    /// struct OneWay(ColliderHandle);
    /// impl PhysicsHooks for OneWay {
    ///     fn modify_solver_contacts(&self, context: &mut ContactModificationContext) {
    ///         // The allowed normal is in collider1's frame: up out of the
    ///         // platform when it is collider1, down onto it otherwise.
    ///         let up = if context.collider1 == self.0 { Vector::Y } else { -Vector::Y };
    ///         context.update_as_oneway_platform(up, 0.1);
    ///     }
    /// }
    ///
    /// let mut world = PhysicsWorld::new();
    /// // Inserted before the platform, the box is Rapier's collider1.
    /// let rider = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(1.0, 3.0, 0.0)));
    /// world.insert_collider(ColliderBuilder::cuboid(0.25, 0.25, 0.25), Some(rider));
    /// let deck = world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, 2.0, 0.0)));
    /// let platform = world.insert_collider(
    ///     ColliderBuilder::cuboid(2.0, 0.1, 2.0).active_hooks(ActiveHooks::MODIFY_SOLVER_CONTACTS),
    ///     Some(deck),
    /// );
    /// let ball = world.insert_body(RigidBodyBuilder::dynamic().linvel(Vector::new(0.0, 8.0, 0.0)));
    /// world.insert_collider(ColliderBuilder::ball(0.25), Some(ball));
    ///
    /// let mut hooks = RuleHooks::default();
    /// hooks.rules_mut().set_personal(ball, CollisionRule::Normal);
    /// hooks.set_user_hooks(OneWay(platform));
    /// for _ in 0..120 {
    ///     hooks.step(&mut world);
    /// }
    /// let y = |body: RigidBodyHandle| world.bodies[body].translation().y;
    /// assert!((2.2..2.5).contains(&y(ball)), "up through the platform, then resting on it: y = {}", y(ball));
    /// assert!((2.2..2.5).contains(&y(rider)), "the box landed on the platform: y = {}", y(rider));
    /// ```
    pub fn set_user_hooks(&mut self, hooks: impl PhysicsHooks + Send + Sync + 'static) {
        self.decide.user = Some(Box::new(hooks));
    }

    /// Tells the hooks that the project changed, through Rapier, the
    /// collision groups, solver groups or collision types of colliders the
    /// rules do not reach. Changes on colliders the rules reach are noticed
    /// by themselves (unless collision detection ran between the hooks'
    /// steps after them, `world.detect_collisions`, which clears Rapier's
    /// change flags the hooks read: call this after it, or they are read
    /// within 32 steps), and so are colliders added or removed where the
    /// number of colliders changed (Rapier keeps its lists of added and
    /// removed colliders to its pipeline): after a step that removed as many
    /// colliders as it added, some of them with layers of their own, call
    /// this too. The hooks do not look at the others every step, which would
    /// cost in proportion to the world. It matters while the plan gives groups bits shared with
    /// the project's settings (`stats().shares_project_bits`), and for the
    /// collision types of non-dynamic colliders paired with hooked ones: the
    /// next step reads every collider's settings, plans again and
    /// recalculates the hooked pairs.
    pub fn project_settings_changed(&mut self) {
        self.queued.replan = Some(PlanCause::ProjectSettings);
        // The kinematic entry gives way to the project's types: a pair's
        // rule may follow a type changed on either of its colliders.
        self.queued.recalculate_all = true;
    }

    /// Gives every collider the crate wrote to its project's own settings
    /// back, as if the rules had never reached it (and takes its mark
    /// away); the next step writes them again. No save needs it (a world
    /// saved as it is reloads exactly, `docs/semantics.md`, "Saving and
    /// loading"), except one meant for plain Rapier, without the hooks.
    ///
    /// A run that goes on stepping after it is not the run that did not
    /// call it: the settings written twice make Rapier find those
    /// colliders' pairs again, without their contact history (measured in
    /// a trial: poses differed from the next step, by 0.5 mm at first). It
    /// is meant for where a run ends, or hands its world to plain Rapier.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, RuleHooks};
    ///
    /// let mut world = PhysicsWorld::new();
    /// let body = world.insert_body(RigidBodyBuilder::dynamic());
    /// let ball = world.insert_collider(ColliderBuilder::ball(0.5), Some(body));
    /// let mut hooks = RuleHooks::default();
    /// // Rapier's solver groups say NoResponse: the crate writes them.
    /// hooks.rules_mut().set_personal(body, CollisionRule::NoResponse);
    /// hooks.step(&mut world);
    /// assert_ne!(world.colliders[ball].solver_groups(), InteractionGroups::all(), "written by the crate");
    /// hooks.restore_project_settings(&mut world.colliders);
    /// assert_eq!(world.colliders[ball].solver_groups(), InteractionGroups::all(), "the project's");
    /// ```
    pub fn restore_project_settings(&mut self, colliders: &mut ColliderSet) {
        for (handle, written) in self.planned.written.iter() {
            if let Some(collider) = colliders.get_mut(handle) {
                written.own_as_of(Settings::of(collider)).write(collider);
                collider.set_active_events(Mark::default().in_events(collider.active_events()));
            }
            self.planned.roster.wrote(handle, None);
        }
        self.planned.written = HandleMap::default();
        self.queued.replan = Some(PlanCause::ProjectSettings);
    }

    /// The project's own settings of `collider`: its collision and solver
    /// groups, collision types and hook bits as the project set them,
    /// without what the rules wrote (`None` for a handle of no collider).
    /// While the rules reach a collider, Rapier's getters show the two
    /// combined: a project that changes one of its settings by reading it
    /// and writing it back reads it here, since a value read from the
    /// collider carries the rules' bits, which the crate then takes as the
    /// project's own (`docs/semantics.md`, "The project's own settings").
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, RuleHooks};
    ///
    /// let mut world = PhysicsWorld::new();
    /// let ground = world.insert_body(RigidBodyBuilder::fixed());
    /// let floor = world.insert_collider(ColliderBuilder::cuboid(10.0, 0.5, 10.0), Some(ground));
    /// let ghost = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 2.0, 0.0)));
    /// world.insert_collider(ColliderBuilder::ball(0.5), Some(ghost));
    /// let mut hooks = RuleHooks::default();
    /// hooks.rules_mut().set_specific(ghost, ground, CollisionRule::NoPair);
    /// hooks.step(&mut world);
    /// // The project takes a layer out of the floor's memberships.
    /// let own = hooks.project_settings(&world.colliders, floor).unwrap().collision_groups;
    /// world.colliders[floor].set_collision_groups(InteractionGroups::new(
    ///     own.memberships - Group::GROUP_5,
    ///     own.filter,
    ///     own.test_mode,
    /// ));
    /// hooks.step(&mut world);
    /// hooks.rules_mut().remove_specific(ghost, ground);
    /// hooks.step(&mut world);
    /// // The rule gone, the floor has the project's groups, and only those.
    /// let groups = world.colliders[floor].collision_groups();
    /// assert_eq!((groups.memberships, groups.filter), (Group::ALL - Group::GROUP_5, Group::ALL));
    /// ```
    #[must_use]
    pub fn project_settings(
        &self,
        colliders: &ColliderSet,
        collider: ColliderHandle,
    ) -> Option<ProjectSettings> {
        let settings = self.own_settings(collider, colliders.get(collider)?);
        Some(settings.into())
    }

    /// Starts over on a world put in place of the one these hooks stepped,
    /// such as a save loaded into the running game: forgets what the hooks
    /// learned of the old world (what they wrote, their plan and its
    /// decisions, live pairs, pair overrides and manifold settings, the
    /// soft bodies they followed, the objects it removed) and keeps the
    /// rules and what code set (the policy, a calculator, a pair-created
    /// callback, the project's hooks, the planner, the step length, rule
    /// events and their handler). The next step reads the loaded world as
    /// fresh hooks given the same rules would, so it goes on as the run it
    /// was saved from (`docs/semantics.md`, "Saving and loading"). The
    /// rules are kept as they are now: rules the old world's events took
    /// away since the save (objects removed, ends that came) are given
    /// again by code, or come with the rule set saved beside the world (put
    /// in place before or after this call).
    ///
    /// ```
    /// # #[cfg(feature = "serde")] {
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, RuleHooks};
    ///
    /// let mut world = PhysicsWorld::new();
    /// let ground = world.insert_body(RigidBodyBuilder::fixed());
    /// world.insert_collider(ColliderBuilder::cuboid(10.0, 0.5, 10.0), Some(ground));
    /// let ghost = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 2.0, 0.0)));
    /// world.insert_collider(ColliderBuilder::ball(0.5), Some(ghost));
    /// let mut hooks = RuleHooks::default();
    /// hooks.rules_mut().set_specific(ghost, ground, CollisionRule::NoResponse);
    /// hooks.step(&mut world);
    /// let quicksave = serde_json::to_string(&world).expect("saved");
    /// for _ in 0..30 {
    ///     hooks.step(&mut world);
    /// }
    /// // Quickload: the saved world in place of the running one.
    /// world = serde_json::from_str(&quicksave).expect("loaded");
    /// hooks.world_replaced();
    /// for _ in 0..120 {
    ///     hooks.step(&mut world);
    /// }
    /// assert!(world.bodies[ghost].translation().y < -1.0, "the rule still holds");
    /// # }
    /// ```
    pub fn world_replaced(&mut self) {
        let old = std::mem::take(self);
        let Deciders {
            mut rules,
            policy,
            calculator,
            on_created,
            user,
        } = old.decide;
        // The set's copy of the writes is the hooks' own unless a loaded
        // set was put in its place, whose copy is the loaded world's: a set
        // the hooks have not looked at yet (`model/identity.rs`), even one
        // whose writes happen to equal theirs (its decisions may not), or
        // one whose writes differ from theirs.
        let put_in_place = rules.identity.number() != old.boundary.rules_seen;
        let mirrored = rules
            .writes
            .iter()
            .map(|(h, w)| (h, *w))
            .eq(old.planned.written.iter().map(|(h, w)| (h, *w)));
        rules.start_over(put_in_place || !mirrored);
        self.decide = Deciders {
            rules,
            policy,
            calculator,
            on_created,
            user,
        };
        self.planned.enabled = old.planned.enabled;
        self.planned.exhaustive = old.planned.exhaustive;
        self.boundary.dt = old.boundary.dt;
        self.soft.copy_to_pieces(old.soft.copies_to_pieces());
        // A listener installed as the step's event handler stays in place.
        self.soft.keep_tear_log(&old.soft);
        self.recording = old.recording.map(|r| Box::new(r.started_over()));
    }

    /// Removes the project's hooks and gives them back.
    pub fn remove_user_hooks(&mut self) -> Option<Box<dyn PhysicsHooks + Send + Sync>> {
        self.decide.user.take()
    }
}

/// The project's own settings of a collider, given what the crate wrote
/// (`docs/semantics.md`, "The project's own settings").
pub(crate) fn own_settings(
    written: &HandleMap<ColliderHandle, Written>,
    handle: ColliderHandle,
    collider: &Collider,
) -> Settings {
    let now = Settings::of(collider);
    written
        .get(handle)
        .map_or(now, |written| written.own_as_of(now))
}
