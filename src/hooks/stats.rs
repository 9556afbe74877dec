//! What the last step did and cost: [`RuleHooks::stats`](super::RuleHooks::stats).

/// Why the hooks look at every collider of the world before each step,
/// instead of only at those the rules reach (`docs/performance.md`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum FullPass {
    /// A custom calculator decides every pair: every collider is hooked.
    Calculator,
    /// A pair-created callback sees every pair: every collider is hooked.
    PairCreatedCallback,
    /// Under `RecalculationPolicy::Manual` pairs keep the rule they were
    /// created with, which only the hook can remember: every collider is hooked.
    ManualPolicy,
    /// The planner is turned off (`RuleHooks::set_planner(false)`): every
    /// collider is hooked.
    PlannerOff,
    /// A rule reaches the default groups: a table entry on
    /// `DEFAULT_DYNAMIC` or `DEFAULT_KINEMATIC` (other than the built-in
    /// kinematic entry), or a default rule that refuses pairs or keeps their
    /// contacts out (`NoPair`, `NoContacts`: what pairs of non-dynamic
    /// bodies get where a project's collision types pair them), so colliders
    /// no other rule names still need settings of their own.
    DefaultGroups,
}

/// Why the hooks planned every collider the rules reach again before a
/// step, instead of only the colliders that step's changes reach
/// (`docs/architecture.md`, "Cost per step"): the edits and changes that
/// really change the whole plan.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum PlanCause {
    /// The hooks' first step: the rule set may have been built, or loaded,
    /// before the hooks existed.
    FirstStep,
    /// An edit that can reach any pair: the group table, the default rule,
    /// a rule set put in place of the whole set, or a change log too long
    /// to follow.
    GlobalEdit,
    /// A setting of the hooks changed: the policy, the planner, a
    /// calculator, a pair-created callback, the project's own hooks, or a
    /// full pass began or ended.
    HookSettings,
    /// The project's own settings changed: `project_settings_changed`,
    /// `restore_project_settings`, a watched collider's settings changed
    /// through Rapier, or colliders came with settings that take group bits
    /// or collision types the plan gave away.
    ProjectSettings,
    /// A live pair's override or manifold setting changed, or a pair that
    /// had one ended: one of its colliders is hooked while it lives.
    PinnedPair,
    /// A changed, added or removed collider needs what only a whole plan
    /// gives: a class (a group, with dynamic or other members) no planned
    /// collider had, or whose last member left, since the groups' settings
    /// follow which classes have members; a personal rule that came or went
    /// and changed the least restrictive first personal rule above some
    /// depth of the chains (a shallower `Normal` where chains say `NoPair`
    /// or `NoResponse` deeper, or the last of them gone), since whether
    /// Rapier's groups say a personal `NoPair` or `NoResponse` depends on
    /// it; or a pinned pair. More colliders with the personal rules the
    /// world already has are planned alone.
    NewClass,
    /// The world came to hold soft bodies, or stopped holding any: their
    /// solver reads no solver groups, so `NoResponse` moves between Rapier's
    /// groups and the hook (`docs/semantics.md`, "Soft bodies").
    SoftBodies,
}

/// What the last step of a [`RuleHooks`](super::RuleHooks) did and cost:
/// where to start when a world steps slower with the rules than without.
///
/// ```
/// use rapier3d::prelude::*;
/// use rapier_collision_rules::{CollisionRule, RuleHooks};
///
/// let mut world = PhysicsWorld::new();
/// let ground = world.insert_body(RigidBodyBuilder::fixed());
/// let floor = world.insert_collider(ColliderBuilder::cuboid(10.0, 0.5, 10.0), Some(ground));
/// let ghost = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 1.0, 0.0)));
/// world.insert_collider(ColliderBuilder::ball(0.5), Some(ghost));
/// let mut hooks = RuleHooks::default();
/// // NoResponse would be Rapier's solver groups; NoContacts needs the hook.
/// hooks.rules_mut().set_specific(ghost, floor, CollisionRule::NoContacts);
/// hooks.step(&mut world);
///
/// let stats = hooks.stats();
/// assert_eq!(stats.full_pass, None, "only what the rules reach is looked at");
/// assert_eq!(stats.hooked_colliders, 1, "the ghost carries the hook, not the floor");
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct StepStats {
    /// Colliders carrying a hook flag the crate gave them: those the hook
    /// answers the pairs of, and those whose contacts it modifies (a
    /// one-way surface, a `ManifoldUpdate::Never` setting). Their pairs
    /// lose Rapier's contact recycling.
    pub hooked_colliders: usize,
    /// Colliders the hooks watch (those the rules reach, and every collider
    /// during a full pass).
    pub watched_colliders: usize,
    /// Rigid bodies the hooks watch (bodies carrying or named by rules, and
    /// the bodies of the parent map).
    pub watched_bodies: usize,
    /// Why every collider was looked at; `None` when only the reached ones were.
    pub full_pass: Option<FullPass>,
    /// Colliders whose flags, groups or collision types were planned before
    /// the step (all reached ones after a whole plan, those the step's
    /// changes reach otherwise).
    pub planned_colliders: usize,
    /// Why every reached collider was planned before the step; `None` when
    /// only those the step's changes reach were (or none).
    pub full_plan: Option<PlanCause>,
    /// Pairs the hook answered during the step (each pair once, however
    /// many times it was asked).
    pub hooked_pairs_answered: usize,
    /// Pairs the hook met for the first time during the step.
    pub pairs_created: usize,
    /// Live pairs whose rule was recalculated before the step.
    pub pairs_recalculated: usize,
    /// Pairs the hooks keep state for (hooked pairs and overrides).
    pub tracked_pairs: usize,
    /// Live `NoResponse` pairs of a soft body's surface and a rigid
    /// collider after the step: Rapier 0.36.1 solves every contact of such
    /// a pair, so they have none, and no collision events
    /// (`docs/semantics.md`, "Soft bodies").
    pub soft_pairs_without_contacts: usize,
    /// Colliders and bodies found removed and forgotten before the step.
    pub removed_objects: usize,
    /// Whether the current plan shares Rapier's group bits or default
    /// collision types with the project's settings of every collider, so
    /// that those were read over the whole world when it was made (again
    /// whenever colliders come or go; see
    /// [`RuleHooks::project_settings_changed`](super::RuleHooks::project_settings_changed)).
    pub shares_project_bits: bool,
    /// Whether this step read every collider's own settings again, because
    /// colliders came or went while the plan shares bits with the project
    /// (`shares_project_bits`): one pass over Rapier's whole collider set,
    /// the one part of a changing world's cost that grows with the world
    /// (about 10 to 17 ns a collider; `docs/performance.md`, "Why is my
    /// world slow").
    pub read_every_collider: bool,
    /// Whether the hooks looked up hooked pairs in Rapier's graph after the
    /// step. They skip it when no body was awake before or after the step
    /// and nothing changed (a resting pair cannot have ended).
    pub swept: bool,
    /// Whether Rapier was seen to have stepped without the hooks since
    /// their last step (a debug build panics instead; a release build also
    /// logs one warning): see `docs/semantics.md`, "Stepping without the
    /// hooks".
    pub stepped_without_hooks: bool,
    /// At the hooks' first step: colliders of a loaded world that carried
    /// the crate's writes of the run it was saved from and on which the
    /// rules now write nothing: they have their project's settings back.
    /// With [`loaded_writes_changed`](Self::loaded_writes_changed), what
    /// parts the world from that run at once: other rules, edits made
    /// since loading, or decisions the world alone does not show (one
    /// warning is logged; `docs/semantics.md`, "Saving and loading").
    pub loaded_writes_given_back: usize,
    /// At the hooks' first step: colliders of a loaded world that carried
    /// the crate's writes of the run it was saved from and on which the
    /// rules now write otherwise.
    pub loaded_writes_changed: usize,
    /// Colliders the hooks wrote were seen carrying what the crate wrote in
    /// another run: a world was put in place of theirs without
    /// [`RuleHooks::world_replaced`](super::RuleHooks::world_replaced) (one
    /// warning is logged).
    pub foreign_marks: bool,
}
