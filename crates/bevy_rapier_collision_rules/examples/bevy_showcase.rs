//! A headless Bevy app (`MinimalPlugins`) with the rules as components: a
//! ragdoll whose limbs ignore each other, a ghost walking through a wall,
//! and debris falling through the player. It prints what each actor did,
//! checks it, and exits (non-zero if a rule did not hold).
//!
//! `cargo run --ignore-rust-version -p bevy_rapier_collision_rules --example bevy_showcase`
//! (3D), `-p bevy_rapier_collision_rules2d --example bevy_showcase2d` for the
//! same app over bevy_rapier2d: one source, whose few differences are the shape helpers
//! below.

// One example source for both crates: each names its dimension's
// bevy_rapier and crate under one name.
#[cfg(feature = "dim2")]
extern crate bevy_rapier2d as bevy_rapier;
#[cfg(feature = "dim3")]
extern crate bevy_rapier3d as bevy_rapier;
#[cfg(feature = "dim2")]
extern crate bevy_rapier_collision_rules2d as bevy_rapier_collision_rules;

use std::time::Duration;

use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_rapier::prelude::*;

#[path = "../tests/dimension/mod.rs"]
mod dimension;
use bevy_rapier_collision_rules::prelude::*;
use dimension::{cuboid, vect};

/// Collision events seen between two entities, either order.
#[derive(Resource, Default)]
struct Events(Vec<(Entity, Entity)>);

fn record(mut reader: MessageReader<CollisionEvent>, mut events: ResMut<Events>) {
    for event in reader.read() {
        if let CollisionEvent::Started(a, b, _) = *event {
            events.0.push((a, b));
        }
    }
}

struct Actors {
    pelvis: Entity,
    limbs: Vec<Entity>,
    ghost: Entity,
    wall: Entity,
    player: Entity,
    debris: Vec<Entity>,
}

/// A limb's joint to the pelvis: a ball joint in 3D, a hinge in 2D.
fn limb_joint(on_pelvis: Vect, on_limb: Vect) -> impl Into<TypedJoint> {
    #[cfg(feature = "dim3")]
    let joint = SphericalJointBuilder::new();
    #[cfg(feature = "dim2")]
    let joint = RevoluteJointBuilder::new();
    joint.local_anchor1(on_pelvis).local_anchor2(on_limb)
}

/// Where the debris starts: side by side within the player's width, so
/// that none lands on another (two rows of three in 3D, one row of four
/// in the 2D plane).
fn debris_starts() -> Vec<Vec3> {
    #[cfg(feature = "dim3")]
    let starts = (0..6)
        .map(|i| {
            Vec3::new(
                5.85 + 0.3 * (i % 2) as f32,
                3.0 + 0.5 * i as f32,
                -0.25 + 0.25 * (i / 2) as f32,
            )
        })
        .collect();
    #[cfg(feature = "dim2")]
    let starts = (0..4)
        .map(|i| Vec3::new(5.67 + 0.22 * i as f32, 3.0 + 0.5 * i as f32, 0.0))
        .collect();
    starts
}

fn build(world: &mut World) -> Actors {
    let (ragdoll, player_group, debris_group) = {
        let mut table = world.resource_mut::<RuleTable>();
        let groups = (
            table.create_group(),
            table.create_group(),
            table.create_group(),
        );
        // A ragdoll's parts overlap at the joints: they ignore each other.
        table.set_group_rule(groups.0, groups.0, CollisionRule::NoPair);
        // Debris passes through the player.
        table.set_group_rule(groups.1, groups.2, CollisionRule::NoPair);
        groups
    };
    world.spawn((Transform::from_xyz(0.0, -0.5, 0.0), cuboid(20.0, 0.5, 20.0)));

    // The ragdoll: a pelvis and four limbs, each jointed to it and
    // overlapping it. The limbs are not Bevy children of the pelvis:
    // bevy_rapier moves a dynamic body under a moving one with its parent
    // too (docs/bevy.md), so the group holds the ragdoll together.
    let pelvis = world
        .spawn((
            Transform::from_xyz(-6.0, 2.0, 0.0),
            RigidBody::Dynamic,
            cuboid(0.3, 0.2, 0.2),
            Velocity::zero(),
            RuleGroup(ragdoll),
        ))
        .id();
    let limbs = [(-0.3, -0.4), (0.3, -0.4), (-0.4, 0.2), (0.4, 0.2)]
        .into_iter()
        .map(|(x, y)| {
            let joint = limb_joint(vect(x, y * 0.5, 0.0), vect(0.0, -y * 0.5, 0.0));
            world
                .spawn((
                    Transform::from_xyz(-6.0 + x, 2.0 + y, 0.0),
                    RuleGroup(ragdoll),
                    RigidBody::Dynamic,
                    Collider::capsule_y(0.25, 0.1),
                    Velocity::zero(),
                    ImpulseJoint::new(pelvis, joint),
                ))
                .id()
        })
        .collect();

    // A ghost walking through a wall: contacts and events, no response.
    let wall = world
        .spawn((
            Transform::from_xyz(0.0, 1.0, 0.0),
            cuboid(0.1, 1.0, 2.0),
            ActiveEvents::COLLISION_EVENTS,
        ))
        .id();
    let ghost = world
        .spawn((
            Transform::from_xyz(-2.0, 0.5, 0.0),
            RigidBody::Dynamic,
            Collider::ball(0.5),
            Velocity::linear(vect(2.0, 0.0, 0.0)),
            Friction::new(0.0),
            SpecificRules::new().with(wall, CollisionRule::NoResponse),
        ))
        .id();

    // Debris raining on the player falls through to the floor.
    let player = world
        .spawn((
            Transform::from_xyz(6.0, 1.0, 0.0),
            RigidBody::Dynamic,
            Collider::capsule_y(0.5, 0.4),
            LockedAxes::ROTATION_LOCKED,
            RuleGroup(player_group),
        ))
        .id();
    let debris = debris_starts()
        .into_iter()
        .map(|start| {
            world
                .spawn((
                    Transform::from_translation(start),
                    RigidBody::Dynamic,
                    cuboid(0.1, 0.1, 0.1),
                    RuleGroup(debris_group),
                ))
                .id()
        })
        .collect();
    Actors {
        pelvis,
        limbs,
        ghost,
        wall,
        player,
        debris,
    }
}

fn main() -> Result<(), String> {
    let mut app = App::new();
    app.add_plugins((
        MinimalPlugins,
        TransformPlugin,
        RapierPhysicsPlugin::<CollisionRulesHooks>::default(),
        CollisionRulesPlugin::default(),
    ))
    .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f32(
        1.0 / 60.0,
    )))
    .init_resource::<Events>()
    .add_systems(PostUpdate, record.after(PhysicsSet::Writeback));
    app.finish();
    app.cleanup();
    app.update();
    let actors = build(app.world_mut());
    let player_start = GlobalTransform::from(Transform::from_xyz(6.0, 1.0, 0.0)).translation();
    for _ in 0..240 {
        app.update();
    }

    let world = app.world();
    let at = |e: Entity| world.get::<GlobalTransform>(e).unwrap().translation();
    let speed = |e: Entity| world.get::<Velocity>(e).map_or(0.0, |v| v.linear.length());
    let mut broken = Vec::new();
    let mut row = |actor: &str, rule: &str, measured: String, holds: bool| {
        println!(
            "{actor:<8} {rule:<32} {measured:<40} {}",
            if holds { "ok" } else { "BROKEN" }
        );
        if !holds {
            broken.push(actor.to_string());
        }
    };
    println!("{:<8} {:<32} {:<40}", "actor", "rule", "after 4 s");

    let parts: Vec<Entity> = std::iter::once(actors.pelvis)
        .chain(actors.limbs.iter().copied())
        .collect();
    let fastest = parts.iter().map(|&e| speed(e)).fold(0.0, f32::max);
    let lowest = parts.iter().map(|&e| at(e).y).fold(f32::MAX, f32::min);
    row(
        "ragdoll",
        "own parts NoPair (group)",
        format!("fastest part {fastest:.3} m/s, lowest y {lowest:.2}"),
        fastest < 0.5 && lowest > 0.0,
    );

    let ghost = at(actors.ghost);
    let met = world.resource::<Events>().0.iter().any(|&(a, b)| {
        (a, b) == (actors.ghost, actors.wall) || (b, a) == (actors.ghost, actors.wall)
    });
    row(
        "ghost",
        "NoResponse with the wall",
        format!("x {:.2} (wall at 0), event: {met}", ghost.x),
        ghost.x > 2.0 && met,
    );

    let player = at(actors.player);
    let drift = (player - player_start).with_y(0.0).length();
    let landed = actors.debris.iter().filter(|&&d| at(d).y < 0.2).count();
    row(
        "debris",
        "NoPair with the player",
        format!(
            "{landed} of {} on the floor, player drift {drift:.4} m",
            actors.debris.len()
        ),
        landed == actors.debris.len() && drift < 1e-3,
    );

    let rules = app
        .world_mut()
        .query::<&CollisionRules>()
        .single(app.world())
        .unwrap();
    let stats = rules.hooks().stats();
    println!(
        "hooked colliders {}, watched colliders {}",
        stats.hooked_colliders, stats.watched_colliders
    );
    if broken.is_empty() {
        Ok(())
    } else {
        Err(format!("broken: {}", broken.join(", ")))
    }
}

#[test]
fn every_actor_does_what_its_rule_says() {
    main().expect("the example's own checks");
}
