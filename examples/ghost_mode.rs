//! Ghost mode switched on and off between steps: a runner heads for two
//! walls; ghost mode (a personal `NoResponse`) is on while it crosses the
//! first and off before the second, which stops it. The default policy,
//! `OnChange`, applies each switch before the next step.
//!
//! `cargo run --example ghost_mode`

use rapier_collision_rules::{CollisionRule, RuleHooks};
use rapier3d::prelude::*;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut world = PhysicsWorld::new();
    world.gravity = Vector::ZERO;
    let runner = world.insert_body(
        RigidBodyBuilder::dynamic()
            .linvel(Vector::new(4.0, 0.0, 0.0))
            .enabled_rotations(false, false, false),
    );
    let body = world.insert_collider(ColliderBuilder::cuboid(0.4, 0.4, 0.4), Some(runner));
    let wall = |world: &mut PhysicsWorld, x: f32| {
        let b = world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(x, 0.0, 0.0)));
        world.insert_collider(ColliderBuilder::cuboid(0.1, 2.0, 2.0), Some(b))
    };
    let (first, second) = (wall(&mut world, 2.0), wall(&mut world, 5.0));

    let mut hooks = RuleHooks::default();
    let mut through_first = false;
    for step in 0..150 {
        let x = world.bodies[runner].translation().x;
        // Ghost mode from x = 1 to x = 3.5: on around the first wall only.
        let ghost = (1.0..3.5).contains(&x);
        let rule = if ghost {
            CollisionRule::NoResponse
        } else {
            CollisionRule::Defer
        };
        if hooks.rules().personal(runner) != rule {
            hooks.rules_mut().set_personal(runner, rule);
            println!(
                "step {step:>3}: x = {x:.2}, ghost mode {}",
                if ghost { "on" } else { "off" }
            );
        }
        hooks.step(&mut world);
        through_first |= hooks.pair_rule(&world, body, first) == Some(CollisionRule::NoResponse);
    }
    let x = world.bodies[runner].translation().x;
    println!("the runner crossed the first wall and stopped at the second: x = {x:.2}");
    if !through_first
        || !(3.5..5.0).contains(&x)
        || hooks.pair_rule(&world, body, second) != Some(CollisionRule::Normal)
    {
        return Err(format!("unexpected end at x = {x}").into());
    }
    Ok(())
}

#[test]
fn ghost_mode_crosses_one_wall_only() {
    main().expect("the example's own checks");
}
