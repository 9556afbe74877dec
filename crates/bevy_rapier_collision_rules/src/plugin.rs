//! The plugin: where its systems run around bevy_rapier's (`docs/bevy.md`).

use bevy::ecs::intern::Interned;
use bevy::ecs::schedule::ScheduleLabel;
use bevy::prelude::*;
use bevy_rapier3d::plugin::PhysicsSet;
use bevy_rapier3d::plugin::context::RapierContextSimulation;
use bevy_rapier3d::prelude::{ActiveCollisionTypes, ActiveHooks, CollisionGroups, SolverGroups};

use super::edits::apply_rule_components;
use super::hierarchy::follow_hierarchy;
use super::ledger::Ledger;
use super::project::notice_project_settings;
use super::step::{finish_contexts, prepare_contexts};
use super::{CollisionRules, ContextRuleTable, PersonalRule, RuleGroup, RuleTable, SpecificRules};

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
}

/// Adds the collision rules to a bevy_rapier app. Add it beside
/// `RapierPhysicsPlugin::<CollisionRulesHooks>` (or a project's own hooks
/// that ask [`CollisionRulesHooks`](super::CollisionRulesHooks)), in the
/// same schedule.
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
}

impl Default for CollisionRulesPlugin {
    fn default() -> Self {
        CollisionRulesPlugin {
            schedule: PostUpdate.intern(),
            hierarchy: true,
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
        // Removals are read in the main schedule, which never misses them
        // (a fixed schedule may not run in a frame).
        let collect = collect_removals.before(RulesSystems::Prepare);
        if self.schedule == PostUpdate.intern() {
            app.add_systems(PostUpdate, collect);
        } else {
            app.add_systems(PostUpdate, collect_removals);
        }
        let prepare = (
            share_table,
            follow_hierarchy.run_if(follow(self.hierarchy)),
            apply_rule_components,
            notice_project_settings,
            prepare_contexts,
        )
            .chain()
            .in_set(RulesSystems::Prepare);
        app.add_systems(self.schedule, prepare);
        app.add_systems(self.schedule, finish_contexts.in_set(RulesSystems::Finish));
    }
}

fn follow(enabled: bool) -> impl FnMut() -> bool + Clone {
    move || enabled
}

/// Keeps the entities that lost rule components, a parent or one of
/// bevy_rapier's settings components, for the next application.
#[allow(clippy::too_many_arguments)]
fn collect_removals(
    mut ledger: ResMut<Ledger>,
    mut groups: RemovedComponents<RuleGroup>,
    mut personal: RemovedComponents<PersonalRule>,
    mut specific: RemovedComponents<SpecificRules>,
    mut parents: RemovedComponents<ChildOf>,
    mut collision_groups: RemovedComponents<CollisionGroups>,
    mut solver_groups: RemovedComponents<SolverGroups>,
    mut types: RemovedComponents<ActiveCollisionTypes>,
    mut hooks: RemovedComponents<ActiveHooks>,
) {
    let ledger = &mut *ledger;
    ledger
        .removed
        .extend(groups.read().chain(personal.read()).chain(specific.read()));
    ledger.unparented.extend(parents.read());
    ledger.settings_removed.extend(
        collision_groups
            .read()
            .chain(solver_groups.read())
            .chain(types.read())
            .chain(hooks.read()),
    );
}

/// Copies the group table into each context's rules: the context's own
/// [`ContextRuleTable`] if it has one, else the resource. Unchanged
/// tables are not copied.
fn share_table(
    shared: Res<RuleTable>,
    mut contexts: Query<(&mut CollisionRules, Option<Ref<ContextRuleTable>>)>,
    mut dropped: RemovedComponents<ContextRuleTable>,
) {
    let dropped: Vec<Entity> = dropped.read().collect();
    for (mut rules, own) in &mut contexts {
        let (table, changed) = match &own {
            Some(own) => (&own.0, own.is_changed()),
            None => (&*shared, shared.is_changed()),
        };
        if changed || rules.is_added() || !dropped.is_empty() {
            rules.rules_mut().copy_group_table(table.as_rule_set());
        }
    }
}
