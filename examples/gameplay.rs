//! A platformer's everyday rules, each asserted: a turret fires from
//! inside itself and its shots ignore it until they are out
//! (`Until::apart`), then hit it when they fall back; the player stands on
//! a one-way platform, drops through it for a quarter of a second
//! (`Until::seconds`), and jumps back up through it onto it; an item
//! dropped inside the player ignores the player until they are apart and
//! is not thrown; and rule events tell the game when a rule ended on a
//! live pair.
//!
//! `cargo run --release --example gameplay`

use rapier_collision_rules::{CollisionRule, OneWay, RuleChange, RuleEvent, RuleHooks, Until};
use rapier3d::prelude::*;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut world = PhysicsWorld::new();
    let ground =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)));
    world.insert_collider(ColliderBuilder::cuboid(30.0, 0.5, 30.0), Some(ground));
    let platform =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, 3.0, 0.0)));
    world.insert_collider(ColliderBuilder::cuboid(3.0, 0.1, 3.0), Some(platform));
    let player = world.insert_body(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, 3.9, 0.0))
            .lock_rotations(),
    );
    world.insert_collider(ColliderBuilder::cuboid(0.3, 0.8, 0.3), Some(player));
    let turret =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(10.0, 1.0, 0.0)));
    world.insert_collider(ColliderBuilder::cuboid(0.5, 1.0, 0.5), Some(turret));

    let mut hooks = RuleHooks::default();
    hooks.record_rule_events(true);
    hooks
        .rules_mut()
        .set_one_way(platform, Some(OneWay::new(Vector::Y)));
    let mut ended = Vec::new();
    let mut step = |hooks: &mut RuleHooks, world: &mut PhysicsWorld, n: usize| {
        for _ in 0..n {
            hooks.step(world);
            for event in hooks.drain_rule_events() {
                if let RuleEvent::RuleChanged {
                    from,
                    to,
                    cause: RuleChange::Expiry,
                    ..
                } = event
                {
                    ended.push((from, to));
                }
            }
        }
    };
    step(&mut hooks, &mut world, 60);
    let y = world.bodies[player].translation().y;
    check(
        (y - 3.9).abs() < 0.02,
        format!("the player stands on the one-way platform: y = {y:.3}"),
    )?;

    // The turret fires straight up from inside itself.
    let shot = world.insert_body(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(10.0, 1.0, 0.0))
            .linvel(Vector::new(0.0, 8.0, 0.0))
            .ccd_enabled(true),
    );
    world.insert_collider(ColliderBuilder::ball(0.1).restitution(0.5), Some(shot));
    hooks
        .rules_mut()
        .set_specific_until(shot, turret, CollisionRule::NoContacts, Until::apart());
    // The player drops through the platform for a quarter of a second.
    hooks.rules_mut().set_specific_until(
        player,
        platform,
        CollisionRule::NoContacts,
        Until::seconds(0.25),
    );
    let mut shot_bounced = false;
    let mut fell = false;
    for _ in 0..150 {
        step(&mut hooks, &mut world, 1);
        let v = world.bodies[shot].linvel().y;
        fell |= v < 0.0;
        shot_bounced |= fell && v > 0.0;
    }
    check(
        hooks.rules().specific(shot, turret) == CollisionRule::Defer,
        "the shot left the turret: its rule ended".into(),
    )?;
    check(
        shot_bounced,
        "falling back, the shot bounced off the turret".into(),
    )?;
    let y = world.bodies[player].translation().y;
    check(
        (y - 0.8).abs() < 0.02,
        format!("the player dropped through to the ground: y = {y:.3}"),
    )?;

    // An item dropped half inside the player, who walks away from it.
    let item =
        world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.4, 0.5, 0.0)));
    world.insert_collider(ColliderBuilder::cuboid(0.3, 0.3, 0.3), Some(item));
    hooks
        .rules_mut()
        .set_specific_until(item, player, CollisionRule::NoContacts, Until::apart());
    for _ in 0..60 {
        let vy = world.bodies[player].linvel().y;
        world.bodies[player].set_linvel(Vector::new(-1.5, vy, 0.0), true);
        step(&mut hooks, &mut world, 1);
    }
    world.bodies[player].set_linvel(Vector::ZERO, true);
    // Pushed out of an overlap, it would have moved by tens of centimetres.
    let moved = (world.bodies[item].translation().x - 0.4).abs();
    check(
        hooks.rules().specific(item, player) == CollisionRule::Defer && moved < 0.02,
        format!(
            "the item ignored the player until apart and was not thrown: it moved {moved:.3} m sideways"
        ),
    )?;

    // Back up through the platform from below, onto it.
    world.bodies[player].set_translation(Vector::new(0.0, 0.8, 0.0), true);
    world.bodies[player].set_linvel(Vector::new(0.0, 9.0, 0.0), true);
    step(&mut hooks, &mut world, 180);
    let y = world.bodies[player].translation().y;
    check(
        (y - 3.9).abs() < 0.02,
        format!("the player jumped up through the platform onto it: y = {y:.3}"),
    )?;

    // A rule that ends at apart meets a live pair only while Rapier still
    // holds it (within its prediction distance): those ends are events.
    check(
        !ended.is_empty()
            && ended
                .iter()
                .all(|&e| e == (CollisionRule::NoContacts, CollisionRule::Normal)),
        format!("the ends that met a live pair came as events: {ended:?}"),
    )?;
    println!("every outcome as the rules say; rule ends reported: {ended:?}");
    Ok(())
}

fn check(ok: bool, what: String) -> Result<(), Box<dyn std::error::Error>> {
    println!("{} {what}", if ok { "ok:" } else { "FAILED:" });
    if ok { Ok(()) } else { Err(what.into()) }
}

#[test]
fn every_gameplay_outcome_holds() {
    main().expect("the example's own checks");
}
