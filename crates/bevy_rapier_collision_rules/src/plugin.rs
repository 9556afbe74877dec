//! The plugin: where its systems run around bevy_rapier's (`docs/bevy.md`).

use bevy::ecs::intern::Interned;
use bevy::ecs::schedule::ScheduleLabel;
use bevy::prelude::*;
use bevy_rapier::plugin::PhysicsSet;
use bevy_rapier::plugin::context::{RapierContextColliders, RapierContextSimulation};
use bevy_rapier::prelude::{
    ActiveCollisionTypes, ActiveHooks, CollisionGroups, RapierRigidBodyHandle, SolverGroups,
};

use super::edits::{apply_rule_components, drop_ended_entries, name_tear_pieces};
use super::hierarchy::follow_hierarchy;
use super::ledger::Ledger;
use super::misuse::check_hooks;
use super::project::notice_project_settings;
use super::queries::{filter_controllers, restore_controller};
use super::rule_events::{CollisionRuleEvent, record_rule_events, send_rule_events};
use super::step::{finish_contexts, follow_soft_bodies, prepare_contexts};
use super::{
    CollisionRules, ContextRuleTable, OneWaySurface, PersonalRule, RuleGroup, RuleTable,
    SpecificRules,
};

/// The plugin's systems.
#[derive(SystemSet, Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RulesSystems {
    /// After bevy_rapier's `PhysicsSet::SyncBackend`: the table, the
    /// hierarchy and the rule components reach each context's rules, which
    /// prepare the world for the step.
    Prepare,
    /// After `PhysicsSet::StepSimulation`, before `PhysicsSet::Writeback`:
    /// the rules take in the pairs of the step.
    Finish,
    /// In bevy_rapier's `PhysicsSet::SyncBackend`, right before its
    /// character controllers move: what each controller with
    /// [`ControllerFollowsRules`](super::ControllerFollowsRules) may touch
    /// this frame is decided. A project that places bevy_rapier's systems
    /// itself (`with_default_system_setup(false)`) orders this set before
    /// bevy_rapier's `update_character_controls`.
    Controllers,
}

/// Adds the collision rules to a bevy_rapier app. Add it beside
/// `RapierPhysicsPlugin::<CollisionRulesHooks>` (or a project's own hooks
/// that ask [`CollisionRulesHooks`](super::CollisionRulesHooks)), in the
/// same schedule; without them there, it warns once at its first run
/// (`docs/bevy.md`, "Half a set-up").
///
/// ```
/// use bevy::prelude::*;
/// use bevy_rapier3d::prelude::*;
/// use bevy_rapier_collision_rules::prelude::*;
///
/// let mut app = App::new();
/// app.add_plugins((
///     MinimalPlugins,
///     TransformPlugin,
///     RapierPhysicsPlugin::<CollisionRulesHooks>::default(),
///     CollisionRulesPlugin::default(),
/// ));
/// let wall = app.world_mut().spawn((Transform::default(), Collider::cuboid(0.1, 2.0, 2.0))).id();
/// app.world_mut().spawn((
///     Transform::from_xyz(-1.0, 0.0, 0.0),
///     RigidBody::Dynamic,
///     Collider::ball(0.25),
///     Velocity::linear(Vec3::X * 4.0),
///     GravityScale(0.0),
///     SpecificRules::new().with(wall, CollisionRule::NoResponse),
/// ));
/// app.update();
/// ```
pub struct CollisionRulesPlugin {
    schedule: Interned<dyn ScheduleLabel>,
    hierarchy: bool,
    rule_events: bool,
}

impl Default for CollisionRulesPlugin {
    fn default() -> Self {
        CollisionRulesPlugin {
            schedule: PostUpdate.intern(),
            hierarchy: true,
            rule_events: false,
        }
    }
}

impl CollisionRulesPlugin {
    /// Runs the systems in `schedule`: the one bevy_rapier steps in
    /// (`RapierPhysicsPlugin::in_schedule`).
    #[must_use]
    pub fn in_schedule(mut self, schedule: impl ScheduleLabel) -> Self {
        self.schedule = schedule.intern();
        self
    }

    /// Runs the systems in `FixedUpdate`, as
    /// `RapierPhysicsPlugin::in_fixed_schedule` does bevy_rapier's.
    #[must_use]
    pub fn in_fixed_schedule(self) -> Self {
        self.in_schedule(FixedUpdate)
    }

    /// Leaves the parent map alone: Bevy's hierarchy (`ChildOf`) between
    /// rigid bodies is not followed, and the project sets parents through
    /// [`CollisionRules::hooks_mut`].
    #[must_use]
    pub fn without_hierarchy(mut self) -> Self {
        self.hierarchy = false;
        self
    }

    /// Sends what changes for each context's live pairs after its step as
    /// [`CollisionRuleEvent`] messages (`docs/bevy.md`, "Rule events"). Off
    /// by default: recording costs a walk of the pairs per step.
    ///
    /// ```
    /// use bevy::prelude::*;
    /// use bevy_rapier3d::prelude::*;
    /// use bevy_rapier_collision_rules::prelude::*;
    ///
    /// let mut app = App::new();
    /// app.add_plugins((
    ///     MinimalPlugins,
    ///     TransformPlugin,
    ///     RapierPhysicsPlugin::<CollisionRulesHooks>::default(),
    ///     CollisionRulesPlugin::default().with_rule_events(),
    /// ));
    /// let floor = app.world_mut().spawn((Transform::default(), Collider::cuboid(5.0, 0.5, 5.0))).id();
    /// let ball = app.world_mut().spawn((
    ///     Transform::from_xyz(0.0, 0.7, 0.0),
    ///     RigidBody::Dynamic,
    ///     Collider::ball(0.25),
    ///     PersonalRule(CollisionRule::NoResponse),
    /// )).id();
    /// app.update();
    /// app.update();
    /// let messages = app.world().resource::<Messages<CollisionRuleEvent>>();
    /// let created = messages.get_cursor().read(messages)
    ///     .any(|m| matches!(m.event, RuleEvent::PairStarted { rule: CollisionRule::NoResponse, .. })
    ///         && [m.entity1, m.entity2].contains(&ball) && [m.entity1, m.entity2].contains(&floor));
    /// assert!(created, "the ball's pair with the floor came as a message");
    /// ```
    #[must_use]
    pub fn with_rule_events(mut self) -> Self {
        self.rule_events = true;
        self
    }
}

impl Plugin for CollisionRulesPlugin {
    fn build(&self, app: &mut App) {
        app.register_required_components::<RapierContextSimulation, CollisionRules>()
            .init_resource::<RuleTable>()
            .init_resource::<Ledger>();
        app.configure_sets(
            self.schedule,
            (
                RulesSystems::Prepare
                    .after(PhysicsSet::SyncBackend)
                    .before(PhysicsSet::StepSimulation),
                RulesSystems::Finish
                    .after(PhysicsSet::StepSimulation)
                    .before(PhysicsSet::Writeback),
            ),
        );
        // What the systems would otherwise find by scanning every body
        // and child entity each frame, or could miss in a schedule that
        // does not run every frame, is noted as it happens.
        app.add_observer(note_rules_removed)
            .add_observer(note_settings_removed)
            .add_observer(note_table_dropped)
            .add_observer(note_world_replaced);
        if self.hierarchy {
            app.add_observer(note_moved).add_observer(note_unparented);
        }
        // The stages run in this order as one system, each with its own
        // parameters and change ticks: Bevy's executor spends about as much
        // on starting a system as an idle stage spends on its work
        // (`docs/performance.md`, "The Bevy frame").
        // A frame with nothing to follow skips them all, which leaves a
        // world without rules with one system before the step: the stages'
        // code and queries, idle, cost a frame more in the processor's
        // instruction cache than in instructions (`docs/bevy.md`, "Cost").
        // Skipped stages see the changes made meanwhile when they next run.
        let edits = share_table
            .pipe(follow_hierarchy)
            .pipe(follow_soft_bodies)
            .pipe(name_tear_pieces)
            .pipe(apply_rule_components)
            .pipe(notice_project_settings)
            .run_if(edits_to_follow);
        app.add_systems(
            self.schedule,
            (edits, prepare_contexts)
                .chain()
                .in_set(RulesSystems::Prepare),
        );
        count_carriers::<RuleGroup>(app);
        count_carriers::<PersonalRule>(app);
        count_carriers::<SpecificRules>(app);
        count_carriers::<OneWaySurface>(app);
        count_carriers::<ContextRuleTable>(app);
        app.add_observer(note_new_context)
            .add_observer(check_table_placement);
        // Warns once if bevy_rapier does not step with the rules' hooks here.
        app.add_systems(
            self.schedule,
            check_hooks(self.schedule)
                .run_if(run_once)
                .in_set(RulesSystems::Prepare),
        );
        // After the step, as one system: the pairs taken in, ended entries
        // dropped, and (with rule events) the messages sent.
        let finish = finish_contexts.pipe(drop_ended_entries);
        if self.rule_events {
            app.add_message::<CollisionRuleEvent>()
                .add_systems(
                    self.schedule,
                    record_rule_events
                        .after(PhysicsSet::SyncBackend)
                        .before(RulesSystems::Prepare),
                )
                .add_systems(
                    self.schedule,
                    finish.pipe(send_rule_events).in_set(RulesSystems::Finish),
                );
        } else {
            app.add_systems(self.schedule, finish.in_set(RulesSystems::Finish));
        }
        // Character controllers that follow the rules decide what they may
        // touch right before bevy_rapier moves them (`docs/bevy.md`,
        // "Queries and character controllers").
        app.configure_sets(
            self.schedule,
            RulesSystems::Controllers
                .in_set(PhysicsSet::SyncBackend)
                .before(bevy_rapier::plugin::systems::update_character_controls),
        )
        .add_systems(
            self.schedule,
            filter_controllers.in_set(RulesSystems::Controllers),
        )
        .add_observer(restore_controller);
    }
}

/// A new parent, or a new body (made by bevy_rapier, also when an entity
/// moves to another context).
fn note_moved(event: On<Insert<(ChildOf, RapierRigidBodyHandle)>>, mut ledger: ResMut<Ledger>) {
    ledger.moved.push(event.entity);
}

/// A context whose colliders were inserted again after the hooks stepped
/// it (a save restored by inserting bevy_rapier's components): its hooks
/// start over on the restored world (`docs/bevy.md`, "Saving a context").
fn note_world_replaced(
    event: On<Insert<RapierContextColliders>>,
    mut contexts: Query<&mut CollisionRules>,
) {
    if let Ok(mut rules) = contexts.get_mut(event.entity)
        && rules.prepared()
    {
        rules.world_replaced();
    }
}

/// Whether the edits have anything to do this frame (see
/// [`Ledger::at_rest`]): a change of the shared table too.
fn edits_to_follow(ledger: Res<Ledger>, shared: Res<RuleTable>) -> bool {
    !ledger.at_rest() || shared.is_changed()
}

/// Counts the entities carrying component `T` as it comes and goes.
fn count_carriers<T: Component>(app: &mut App) {
    app.add_observer(|_: On<Add<T>>, mut ledger: ResMut<Ledger>| ledger.carriers += 1)
        .add_observer(|_: On<Remove<T>>, mut ledger: ResMut<Ledger>| {
            ledger.carriers = ledger.carriers.saturating_sub(1);
        });
}

/// A new context takes the shared table.
fn note_new_context(event: On<Add<CollisionRules>>, mut ledger: ResMut<Ledger>) {
    ledger.table_dropped.push(event.entity);
}

/// A `ContextRuleTable` on an entity that is not a physics context is read
/// by nothing: warned about, naming the entity and the fix.
fn check_table_placement(
    event: On<Add<ContextRuleTable>>,
    contexts: Query<(), With<RapierContextSimulation>>,
) {
    if !contexts.contains(event.entity) {
        log::warn!("{}", super::misuse::table_off_context(event.entity));
    }
}

/// A context that dropped its own table takes the shared one again.
fn note_table_dropped(event: On<Remove<ContextRuleTable>>, mut ledger: ResMut<Ledger>) {
    ledger.table_dropped.push(event.entity);
}

fn note_unparented(event: On<Remove<ChildOf>>, mut ledger: ResMut<Ledger>) {
    ledger.moved.push(event.entity);
}

fn note_rules_removed(
    event: On<Remove<(RuleGroup, PersonalRule, SpecificRules, OneWaySurface)>>,
    mut ledger: ResMut<Ledger>,
) {
    ledger.removed.push(event.entity);
}

/// bevy_rapier writes Rapier's default when one of its settings
/// components is removed.
fn note_settings_removed(
    event: On<
        Remove<(
            CollisionGroups,
            SolverGroups,
            ActiveCollisionTypes,
            ActiveHooks,
        )>,
    >,
    mut ledger: ResMut<Ledger>,
) {
    ledger.settings_removed.push(event.entity);
}

/// Copies the group table into each context's rules: the context's own
/// [`ContextRuleTable`] if it has one, else the resource. Unchanged
/// tables are not copied.
fn share_table(
    shared: Res<RuleTable>,
    mut ledger: ResMut<Ledger>,
    mut contexts: Query<(Entity, &mut CollisionRules, Option<Ref<ContextRuleTable>>)>,
) {
    let dropped = std::mem::take(&mut ledger.table_dropped);
    for (context, mut rules, own) in &mut contexts {
        let (table, changed) = match &own {
            Some(own) => (&own.0, own.is_changed()),
            None => (&*shared, shared.is_changed()),
        };
        if changed || rules.is_added() || dropped.contains(&context) {
            rules
                .rules_mut()
                .copy_group_table(table.group_table(), table.default_rule());
        }
    }
}
