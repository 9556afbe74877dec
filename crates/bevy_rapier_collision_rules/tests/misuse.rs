//! Half a set-up is loud (`docs/bevy.md`, "Half a set-up"): the plugin
//! without the rules' hooks in bevy_rapier's step, and the hooks without
//! the plugin, each warn once through the `log` facade; whole set-ups and
//! plain bevy_rapier do not.
//!
//! A binary of its own: the test installs the process's one `log` logger,
//! which records what this crate logs, and the tests take turns so that
//! each reads only its own app's records.

// One test source for both crates (the 2D one links this folder).
#[cfg(feature = "dim2")]
extern crate bevy_rapier2d as bevy_rapier;
#[cfg(feature = "dim3")]
extern crate bevy_rapier3d as bevy_rapier;
#[cfg(feature = "dim2")]
extern crate bevy_rapier_collision_rules2d as bevy_rapier_collision_rules;

use std::sync::{Mutex, MutexGuard, PoisonError};
use std::time::Duration;

use CollisionRule::*;
use bevy::app::Plugins;
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_rapier::prelude::*;
use bevy_rapier_collision_rules::prelude::*;

#[path = "dimension/mod.rs"]
#[allow(dead_code)]
mod dimension;

/// Every warning this crate logged since the current test began.
static WARNINGS: Mutex<Vec<String>> = Mutex::new(Vec::new());
/// Held by each test for its whole run.
static TURN: Mutex<()> = Mutex::new(());

struct Recorder;

impl log::Log for Recorder {
    fn enabled(&self, metadata: &log::Metadata) -> bool {
        metadata.target().starts_with("bevy_rapier_collision_rules")
    }

    fn log(&self, record: &log::Record) {
        if self.enabled(record.metadata()) && record.level() == log::Level::Warn {
            let mut warnings = WARNINGS.lock().unwrap_or_else(PoisonError::into_inner);
            warnings.push(record.args().to_string());
        }
    }

    fn flush(&self) {}
}

static RECORDER: Recorder = Recorder;

/// This test's turn, with the warnings of earlier tests forgotten.
fn turn() -> MutexGuard<'static, ()> {
    let turn = TURN.lock().unwrap_or_else(PoisonError::into_inner);
    // The first test installs the logger; later ones find it installed.
    if log::set_logger(&RECORDER).is_ok() {
        log::set_max_level(log::LevelFilter::Warn);
    }
    WARNINGS
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .clear();
    turn
}

fn warnings() -> Vec<String> {
    WARNINGS
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .clone()
}

/// A headless app with `physics`, to be stepped by hand in frames of 1/60 s.
fn headless<M>(physics: impl Plugins<M>) -> App {
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, TransformPlugin))
        .add_plugins(physics)
        .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f32(
            1.0 / 60.0,
        )));
    app.finish();
    app.cleanup();
    app
}

/// A dynamic ball of radius 0.25 at (x, 0.5), over the floor.
fn ball(x: f32) -> impl Bundle {
    (
        Transform::from_xyz(x, 0.5, 0.0),
        RigidBody::Dynamic,
        Collider::ball(0.25),
    )
}

/// bevy_rapier stepping with the rules' hooks, and the rules' plugin.
fn whole_set_up() -> (
    RapierPhysicsPlugin<CollisionRulesHooks<'static, 'static>>,
    CollisionRulesPlugin,
) {
    (
        RapierPhysicsPlugin::<CollisionRulesHooks>::default(),
        CollisionRulesPlugin::default(),
    )
}

/// A headless app with `physics`, stepped by hand for 60 frames of 1/60 s,
/// a ball over a floor whose rule with it is `NoContacts` (a rule only the
/// hooks can keep). Returns the ball's height.
fn run<M>(physics: impl Plugins<M>) -> f32 {
    let mut app = headless(physics);
    let floor = app
        .world_mut()
        .spawn((
            Transform::from_xyz(0.0, -0.5, 0.0),
            dimension::cuboid(5.0, 0.5, 5.0),
        ))
        .id();
    let ball = app
        .world_mut()
        .spawn((ball(0.0), SpecificRules::new().with(floor, NoContacts)))
        .id();
    for _ in 0..60 {
        app.update();
    }
    app.world().get::<Transform>(ball).unwrap().translation.y
}

/// Whether a ball of radius 0.25 rests on the floor.
fn rests(y: f32) -> bool {
    (0.2..0.3).contains(&y)
}

#[test]
fn the_plugin_with_plain_bevy_rapier_warns_once_and_the_hooked_rule_is_dropped() {
    let _turn = turn();
    let y = run((
        RapierPhysicsPlugin::<()>::default(),
        CollisionRulesPlugin::default(),
    ));
    let warnings = warnings();
    println!("y = {y}, warnings: {warnings:#?}");
    assert_eq!(warnings.len(), 1, "one warning in 60 frames: {warnings:#?}");
    let warning = &warnings[0];
    assert!(
        warning.contains("does not step with CollisionRulesHooks there")
            && warning.contains("RapierPhysicsPlugin::<CollisionRulesHooks>"),
        "names the missing hooks and the fix: {warning}"
    );
    // What the warning is about: NoContacts is the hooks' to keep, so
    // without them the ball lands.
    assert!(rests(y), "the NoContacts rule was dropped: y = {y}");
}

/// A project's own hooks that do not ask the rules.
#[derive(SystemParam)]
struct OwnHooks<'w, 's> {
    names: Query<'w, 's, &'static Name>,
}

impl BevyPhysicsHooks for OwnHooks<'_, '_> {
    fn filter_contact_pair(&self, context: PairFilterContextView) -> Option<SolverFlags> {
        let _ = self.names.get(context.collider1());
        Some(SolverFlags::COMPUTE_RIGID_IMPULSES)
    }
}

#[test]
fn the_plugin_with_a_projects_hooks_that_leave_the_rules_out_warns_once() {
    let _turn = turn();
    let y = run((
        RapierPhysicsPlugin::<OwnHooks>::default(),
        CollisionRulesPlugin::default(),
    ));
    let warnings = warnings();
    println!("y = {y}, warnings: {warnings:#?}");
    assert_eq!(warnings.len(), 1, "{warnings:#?}");
    assert!(
        warnings[0].contains("CollisionRulesHooks field"),
        "{}",
        warnings[0]
    );
}

#[test]
fn the_hooks_without_the_plugin_warn_once() {
    let _turn = turn();
    let y = run(RapierPhysicsPlugin::<CollisionRulesHooks>::default());
    let warnings = warnings();
    println!("y = {y}, warnings: {warnings:#?}");
    assert_eq!(warnings.len(), 1, "one warning in 60 frames: {warnings:#?}");
    let warning = &warnings[0];
    assert!(
        warning.contains("CollisionRulesPlugin was not added")
            && warning.contains("CollisionRulesPlugin::default()"),
        "names the missing plugin and the fix: {warning}"
    );
    assert!(rests(y), "no rule without the plugin: y = {y}");
}

#[test]
fn the_plugin_outside_bevy_rapiers_schedule_warns_once() {
    let _turn = turn();
    // bevy_rapier in FixedUpdate, which does not run in the first frame;
    // the rules in PostUpdate, which does. The hooks do answer in
    // FixedUpdate, but the rules prepare after its steps, not before.
    let y = run((
        RapierPhysicsPlugin::<CollisionRulesHooks>::default().in_fixed_schedule(),
        CollisionRulesPlugin::default(),
    ));
    let warnings = warnings();
    println!("y = {y}, warnings: {warnings:#?}");
    assert_eq!(warnings.len(), 1, "{warnings:#?}");
    assert!(
        warnings[0].contains("CollisionRulesPlugin runs in PostUpdate")
            && warnings[0].contains("in the same schedule as CollisionRulesPlugin"),
        "{}",
        warnings[0]
    );
}

/// A project's own hooks that ask the rules first.
#[derive(SystemParam)]
struct GameHooks<'w, 's> {
    rules: CollisionRulesHooks<'w, 's>,
}

impl BevyPhysicsHooks for GameHooks<'_, '_> {
    fn filter_contact_pair(&self, context: PairFilterContextView) -> Option<SolverFlags> {
        self.rules.filter_contact_pair(&context)
    }

    fn filter_intersection_pair(&self, context: PairFilterContextView) -> bool {
        self.rules.filter_intersection_pair(&context)
    }

    fn modify_solver_contacts(&self, mut context: ContactModificationContextView) {
        self.rules.modify_solver_contacts(&mut context);
    }
}

#[test]
fn whole_set_ups_and_plain_bevy_rapier_do_not_warn() {
    let _turn = turn();
    let whole = [
        (
            "the rules' hooks",
            run((
                RapierPhysicsPlugin::<CollisionRulesHooks>::default(),
                CollisionRulesPlugin::default(),
            )),
        ),
        (
            "a project's hooks that ask the rules",
            run((
                RapierPhysicsPlugin::<GameHooks>::default(),
                CollisionRulesPlugin::default(),
            )),
        ),
        (
            "both in the fixed schedule",
            run((
                RapierPhysicsPlugin::<CollisionRulesHooks>::default().in_fixed_schedule(),
                CollisionRulesPlugin::default().in_fixed_schedule(),
            )),
        ),
    ];
    for (case, y) in whole {
        assert!(y < -1.0, "{case}: NoContacts holds, y = {y}");
    }
    let plain = run(RapierPhysicsPlugin::<()>::default());
    assert!(rests(plain), "plain bevy_rapier: y = {plain}");
    let warnings = warnings();
    assert!(warnings.is_empty(), "{warnings:#?}");
}

/// A rule component on a plain entity (no rigid body, collider or soft
/// body) whose Bevy child is the body: the rules reach nothing, which the
/// components table says, and a warning, once, names the entity and the
/// fix. Found by trying the 2D adapter from its docs alone: the child
/// rested on the floor in silence. The same rules on the body itself warn
/// nothing and hold.
#[test]
fn rules_on_an_entity_without_a_physics_object_warn_once_naming_it() {
    let _turn = turn();
    let mut app = headless(whole_set_up());
    let world = app.world_mut();
    world.spawn((
        Transform::from_xyz(0.0, -0.5, 0.0),
        dimension::cuboid(5.0, 0.5, 5.0),
    ));
    // Two plain parents, each with a ball under it, and a ball with its
    // rule on itself.
    let parents: Vec<Entity> = [-2.0, 2.0]
        .map(|x| {
            let parent = world
                .spawn((Transform::default(), PersonalRule(NoResponse)))
                .id();
            world.spawn((ball(x), ChildOf(parent)));
            parent
        })
        .into();
    let own = world.spawn((ball(0.0), PersonalRule(NoResponse))).id();
    for _ in 0..60 {
        app.update();
    }
    let warnings = warnings();
    let y = app.world().get::<Transform>(own).unwrap().translation.y;
    println!("the ball with its own rule at y = {y}, warnings: {warnings:#?}");
    assert_eq!(warnings.len(), 1, "once for the two parents: {warnings:#?}");
    assert!(
        parents.iter().any(|p| warnings[0].contains(&p.to_string()))
            && warnings[0].contains("no RigidBody, Collider or SoftBody")
            && warnings[0].contains("Fix: put the component on the rigid body entity"),
        "names one of the parents ({parents:?}) and the fix: {}",
        warnings[0]
    );
    assert!(
        y < -1.0,
        "the rule on the ball itself holds: it fell through, y = {y}"
    );
}

/// A `ContextRuleTable` on a rigid body (not a physics context) is read by
/// nothing: a warning names the entity and the fix. Found by trying the 3D
/// adapter from its docs alone, where the ball rested in silence. On the
/// context itself it warns nothing.
#[test]
fn a_context_table_off_a_context_warns_naming_it() {
    use bevy_rapier::plugin::context::DefaultRapierContext;
    let _turn = turn();
    let mut app = headless(whole_set_up());
    app.update();
    let ghostly = || {
        let mut table = RuleTable::default();
        table.set_default_rule(NoContacts);
        ContextRuleTable(table)
    };
    let context = app
        .world_mut()
        .query_filtered::<Entity, With<DefaultRapierContext>>()
        .single(app.world())
        .unwrap();
    app.world_mut().entity_mut(context).insert(ghostly());
    assert!(warnings().is_empty(), "on the context: {:?}", warnings());
    app.world_mut()
        .entity_mut(context)
        .remove::<ContextRuleTable>();
    let ball = app.world_mut().spawn((ball(0.0), ghostly())).id();
    let warnings = warnings();
    assert_eq!(warnings.len(), 1, "{warnings:#?}");
    assert!(
        warnings[0].contains(&ball.to_string())
            && warnings[0].contains("Fix: insert it on the context's entity"),
        "names the ball ({ball}) and the fix: {}",
        warnings[0]
    );
}
