//! A bevy_rapier app's frame with the rules' plugin, against the same app
//! without it, in one run: frames of the two apps alternate, and each
//! repeat gives one ratio of their summed frame times. Scenes shaped like
//! games: a pile resting on one floor (asleep), a large static level with
//! a few bodies, and a pile falling awake; with no rules, and with 5% of
//! the bodies in a group that ignores another group.
//!
//! `cargo bench --ignore-rust-version -p bevy_rapier_collision_rules --bench frame`

use std::time::{Duration, Instant};

use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_rapier_collision_rules::prelude::*;
use bevy_rapier3d::prelude::*;

#[derive(Clone, Copy, Debug, PartialEq)]
enum Scene {
    PileAsleep,
    Level,
    PileAwake,
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Rules {
    /// Plain bevy_rapier: no plugin, Rapier's default hooks.
    Plain,
    /// The plugin and its hooks, no rule.
    None,
    /// 5% of the bodies in a group with NoPair to an empty group.
    Groups,
}

fn app(scene: Scene, rules: Rules) -> App {
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, TransformPlugin))
        .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f32(
            1.0 / 60.0,
        )));
    if rules == Rules::Plain {
        app.add_plugins(RapierPhysicsPlugin::<()>::default());
    } else {
        app.add_plugins((
            RapierPhysicsPlugin::<CollisionRulesHooks>::default(),
            CollisionRulesPlugin::default(),
        ));
    }
    app.finish();
    app.cleanup();
    app.update();
    let group = (rules == Rules::Groups).then(|| {
        let mut table = app.world_mut().resource_mut::<RuleTable>();
        let (a, b) = (table.create_group(), table.create_group());
        table.set_group_rule(a, b, CollisionRule::NoPair);
        a
    });
    let world = app.world_mut();
    let (bodies, tiles) = match scene {
        Scene::PileAsleep | Scene::PileAwake => (1000, 0),
        Scene::Level => (20, 64 * 64),
    };
    world.spawn((
        Transform::from_xyz(0.0, -0.5, 0.0),
        Collider::cuboid(40.0, 0.5, 40.0),
    ));
    for i in 0..tiles {
        let (x, z) = ((i % 64) as f32 - 32.0, (i / 64) as f32 - 32.0);
        world.spawn((
            Transform::from_xyz(x, 0.25, z),
            Collider::cuboid(0.45, 0.25, 0.45),
        ));
    }
    for i in 0..bodies {
        let (x, y, z) = ((i % 10) as f32, (i / 100) as f32, ((i / 10) % 10) as f32);
        let mut body = world.spawn((
            Transform::from_xyz(x * 1.1 - 5.0, 0.5 + y * 1.05 + 1.0, z * 1.1 - 5.0),
            RigidBody::Dynamic,
            Collider::cuboid(0.5, 0.5, 0.5),
        ));
        if let Some(group) = group.filter(|_| i % 20 == 0) {
            body.insert(RuleGroup(group));
        }
    }
    if scene == Scene::PileAsleep {
        for _ in 0..900 {
            app.update();
        }
    }
    app
}

/// Seconds of `frames` frames of each app, alternating frame by frame.
fn paired(a: &mut App, b: &mut App, frames: usize) -> (f64, f64) {
    let (mut ta, mut tb) = (0.0, 0.0);
    for _ in 0..frames {
        let t = Instant::now();
        a.update();
        ta += t.elapsed().as_secs_f64();
        let t = Instant::now();
        b.update();
        tb += t.elapsed().as_secs_f64();
    }
    (ta, tb)
}

fn main() {
    // `cargo bench` passes `--bench`; nothing else is read.
    let repeats = 5;
    println!(
        "scene        rules   plain ms/frame  ratio to plain (min-max over {repeats} repeats)"
    );
    for scene in [Scene::PileAsleep, Scene::Level, Scene::PileAwake] {
        for rules in [Rules::None, Rules::Groups] {
            let mut ratios = Vec::new();
            let mut plain_ms = Vec::new();
            for _ in 0..repeats {
                let (mut plain, mut with) = (app(scene, Rules::Plain), app(scene, rules));
                let frames = if scene == Scene::PileAwake { 120 } else { 600 };
                let (tp, tw) = paired(&mut plain, &mut with, frames);
                ratios.push(tw / tp);
                plain_ms.push(tp / frames as f64 * 1e3);
            }
            let min = ratios.iter().copied().fold(f64::MAX, f64::min);
            let max = ratios.iter().copied().fold(0.0, f64::max);
            let ms = plain_ms.iter().sum::<f64>() / plain_ms.len() as f64;
            println!(
                "{:<12} {:<7} {ms:>14.3}  {min:.3}-{max:.3}",
                format!("{scene:?}"),
                format!("{rules:?}")
            );
        }
    }
}
