//! A custom rule calculator (the BEPU design's `CollisionRuleCalculator`): teams read from each collider's
//! `user_data`. Team mates pass through each other (`NoResponse`); everyone
//! else gets the default calculation, which the calculator delegates to.
//!
//! `cargo run --example custom_calculator`

use rapier_collision_rules::{CollisionRule, RuleHooks};
use rapier3d::prelude::*;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut world = PhysicsWorld::new();
    world.gravity = Vector::ZERO;
    // Two blue units walk into each other, and a red one into a blue one.
    let unit = |world: &mut PhysicsWorld, x: f32, z: f32, vx: f32, team: u128| {
        let body = world.insert_body(
            RigidBodyBuilder::dynamic()
                .translation(Vector::new(x, 0.0, z))
                .linvel(Vector::new(vx, 0.0, 0.0)),
        );
        world.insert_collider(ColliderBuilder::ball(0.5).user_data(team), Some(body));
        body
    };
    let blue_a = unit(&mut world, -2.0, 0.0, 2.0, 1);
    let blue_b = unit(&mut world, 2.0, 0.0, -2.0, 1);
    let red = unit(&mut world, -2.0, 5.0, 2.0, 2);
    let blue_c = unit(&mut world, 2.0, 5.0, -2.0, 1);

    let mut hooks = RuleHooks::default();
    hooks.set_calculator(|ctx| {
        let team = |c| ctx.colliders.get(c).map(|c| c.user_data);
        if team(ctx.collider1) == team(ctx.collider2) {
            CollisionRule::NoResponse
        } else {
            ctx.default_rule()
        }
    });
    for _ in 0..120 {
        hooks.step(&mut world);
    }
    let x = |b: RigidBodyHandle| world.bodies[b].translation().x;
    println!(
        "blue team mates crossed: x = {:.2} and {:.2}",
        x(blue_a),
        x(blue_b)
    );
    println!(
        "red and blue bounced:    x = {:.2} and {:.2}",
        x(red),
        x(blue_c)
    );
    if !(x(blue_a) > 1.5 && x(blue_b) < -1.5) {
        return Err("team mates did not pass through each other".into());
    }
    if !(x(red) < 0.0 && x(blue_c) > 0.0) {
        return Err("opponents passed through each other".into());
    }
    Ok(())
}

#[test]
fn team_mates_pass_and_opponents_collide() {
    main().expect("the example's own checks");
}
