//! A bevy_rapier app's frame with the rules' plugin, against the same app
//! without it, in one run: frames of the two apps alternate, and each
//! repeat gives one ratio of their summed frame times. Scenes shaped like
//! games: a pile resting on one floor (asleep), a large static level with
//! a few bodies, and a pile falling awake; with no rules, and with 5% of
//! the bodies in a group that ignores another group.
//!
//! `cargo bench --ignore-rust-version -p bevy_rapier_collision_rules --bench frame`
//! (3D), `-p bevy_rapier_collision_rules2d --bench frame2d` for the same
//! scenes over bevy_rapier2d (the pile in a wall 40 boxes wide, the level's
//! tiles in rows under the floor).

// One bench source for both crates.
#[cfg(feature = "dim2")]
extern crate bevy_rapier2d as bevy_rapier;
#[cfg(feature = "dim3")]
extern crate bevy_rapier3d as bevy_rapier;
#[cfg(feature = "dim2")]
extern crate bevy_rapier_collision_rules2d as bevy_rapier_collision_rules;

use std::time::{Duration, Instant};

use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_rapier::prelude::*;

#[path = "../tests/dimension/mod.rs"]
#[allow(dead_code)]
mod dimension;
use bevy_rapier_collision_rules::prelude::*;
use dimension::cuboid;

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
    /// Four character controllers walking over the level, each through a
    /// door 1 m ahead that its rules open (`ControllerFollowsRules`, a
    /// `NoPair` with the door), against plain bevy_rapier's same
    /// controllers with the door in `exclude_colliders`: the same moves.
    Controllers,
}

/// Walks every character controller along +x.
fn walk(mut controllers: Query<&mut KinematicCharacterController>) {
    for mut controller in &mut controllers {
        controller.translation = Some(Vect::X * 0.02);
    }
}

/// Where tile `i` of the level lies: a 64 x 64 grid on the floor in 3D,
/// 64 rows of 64 under the floor in 2D.
fn tile_at(i: usize) -> Vec3 {
    let (column, row) = ((i % 64) as f32 - 32.0, (i / 64) as f32);
    #[cfg(feature = "dim3")]
    return Vec3::new(column, 0.25, row - 32.0);
    #[cfg(feature = "dim2")]
    Vec3::new(column, -1.5 - 0.6 * row, 0.0)
}

/// Where character `i` starts.
fn character_at(i: usize) -> Vec3 {
    // On the ground: on the tiles (tops at 0.5) in 3D, on the floor in 2D.
    #[cfg(feature = "dim3")]
    return tile_at(64 * 16 * i + 8) + Vec3::Y * 0.61;
    #[cfg(feature = "dim2")]
    Vec3::new(-20.0 + 10.0 * i as f32, 0.31, 0.0)
}

/// Where box `i` of the pile starts: 10 x 10 x 10 in 3D, a wall 40 wide
/// in 2D.
fn pile_at(i: usize) -> Vec3 {
    #[cfg(feature = "dim3")]
    {
        let (x, y, z) = ((i % 10) as f32, (i / 100) as f32, ((i / 10) % 10) as f32);
        Vec3::new(x * 1.1 - 5.0, 0.5 + y * 1.05 + 1.0, z * 1.1 - 5.0)
    }
    #[cfg(feature = "dim2")]
    {
        let (x, y) = ((i % 40) as f32, (i / 40) as f32);
        Vec3::new(x * 1.1 - 22.0, 0.5 + y * 1.05 + 1.0, 0.0)
    }
}

/// The app of `scene` with `rules`; `controllers`: with the four walking
/// characters (the plain twin of `Rules::Controllers` has them too).
fn app(scene: Scene, rules: Rules, controllers: bool) -> App {
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
    world.spawn((Transform::from_xyz(0.0, -0.5, 0.0), cuboid(40.0, 0.5, 40.0)));
    for i in 0..tiles {
        world.spawn((
            Transform::from_translation(tile_at(i)),
            cuboid(0.45, 0.25, 0.45),
        ));
    }
    for i in 0..bodies {
        let mut body = world.spawn((
            Transform::from_translation(pile_at(i)),
            RigidBody::Dynamic,
            cuboid(0.5, 0.5, 0.5),
        ));
        if let Some(group) = group.filter(|_| i % 20 == 0) {
            body.insert(RuleGroup(group));
        }
    }
    if controllers {
        for i in 0..4 {
            let start = character_at(i);
            let door = world
                .spawn((
                    Transform::from_translation(start + Vec3::X),
                    cuboid(0.1, 1.0, 1.0),
                ))
                .id();
            let mut controller = KinematicCharacterController::default();
            if rules != Rules::Controllers {
                controller.exclude_colliders.insert(door);
            }
            let mut character = world.spawn((
                Transform::from_translation(start),
                RigidBody::KinematicPositionBased,
                Collider::ball(0.3),
                controller,
            ));
            if rules == Rules::Controllers {
                character.insert((
                    ControllerFollowsRules::default(),
                    SpecificRules::new().with(door, CollisionRule::NoPair),
                ));
            }
        }
        app.add_systems(Update, walk);
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

/// `FRAME_COUNT=<scene>,<rules>,<frames>` (for example
/// `Level,Plain,600`): builds that one app, runs that many frames and
/// stops, for an instruction counter (`valgrind --tool=callgrind`) to
/// count; two frame counts give the instructions of a frame, without the
/// set-up.
fn count_only() -> bool {
    let Ok(what) = std::env::var("FRAME_COUNT") else {
        return false;
    };
    let parts: Vec<&str> = what.split(',').collect();
    let scene = [Scene::PileAsleep, Scene::Level, Scene::PileAwake]
        .into_iter()
        .find(|s| format!("{s:?}") == parts[0])
        .expect("FRAME_COUNT: a scene (PileAsleep, Level, PileAwake)");
    let (rules, controllers) = match parts[1] {
        "Plain" => (Rules::Plain, false),
        "PlainControllers" => (Rules::Plain, true),
        "None" => (Rules::None, false),
        "Groups" => (Rules::Groups, false),
        "Controllers" => (Rules::Controllers, true),
        other => panic!("FRAME_COUNT: no rules {other}"),
    };
    let frames: usize = parts[2].parse().expect("FRAME_COUNT: a frame count");
    let mut app = app(scene, rules, controllers);
    for _ in 0..frames {
        app.update();
    }
    true
}

fn main() {
    // `cargo bench` passes `--bench`; nothing else is read.
    if count_only() {
        return;
    }
    // Enough repeats for a median that a busy machine's stray slow frames
    // do not move (the minimum and maximum are printed beside it).
    let repeats = 11;
    println!(
        "scene        rules   plain ms/frame  ratio to plain (min, median, max over {repeats} repeats)"
    );
    // `FRAME_ONLY=<scene>,<rules>` (for example `Level,None`): that row alone.
    let only = std::env::var("FRAME_ONLY").ok();
    for scene in [Scene::PileAsleep, Scene::Level, Scene::PileAwake] {
        let with_controllers = (scene == Scene::Level).then_some(Rules::Controllers);
        for rules in [Rules::None, Rules::Groups]
            .into_iter()
            .chain(with_controllers)
            .filter(|rules| {
                only.as_ref()
                    .is_none_or(|o| *o == format!("{scene:?},{rules:?}"))
            })
        {
            let mut ratios = Vec::new();
            let mut plain_ms = Vec::new();
            for _ in 0..repeats {
                let controllers = rules == Rules::Controllers;
                let (mut plain, mut with) = (
                    app(scene, Rules::Plain, controllers),
                    app(scene, rules, controllers),
                );
                let frames = if scene == Scene::PileAwake { 120 } else { 600 };
                let (tp, tw) = paired(&mut plain, &mut with, frames);
                ratios.push(tw / tp);
                plain_ms.push(tp / frames as f64 * 1e3);
            }
            ratios.sort_by(f64::total_cmp);
            let (min, median, max) = (ratios[0], ratios[repeats / 2], ratios[repeats - 1]);
            let ms = plain_ms.iter().sum::<f64>() / plain_ms.len() as f64;
            println!(
                "{:<12} {:<7} {ms:>14.3}  {min:.3}, {median:.3}, {max:.3}",
                format!("{scene:?}"),
                format!("{rules:?}")
            );
        }
    }
}
