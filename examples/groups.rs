//! A game's collision table with groups: players, enemies, projectiles and
//! debris. Prints the table as `resolve` decides it and checks each entry,
//! then drops debris on a player to show it in a world.
//!
//! `cargo run --example groups`

use approx::abs_diff_eq;
use rapier_collision_rules::{CollisionGroup, CollisionRule, CollisionRuleSet, RuleHooks};
use rapier3d::prelude::*;

/// The game's groups and their table: players, enemies, projectiles, debris.
fn game_rules() -> (CollisionRuleSet, [CollisionGroup; 4]) {
    let mut rules = CollisionRuleSet::default();
    let [players, enemies, projectiles, debris] = [(); 4].map(|_| rules.create_group());
    // Players and enemies collide with everything by default (no entry).
    // Projectiles pass through each other; enemies walk through each other.
    rules.set_group_rule(projectiles, projectiles, CollisionRule::NoPair);
    rules.set_group_rule(enemies, enemies, CollisionRule::NoResponse);
    // Debris never bothers a player or a projectile, but lands on the world.
    rules.set_group_rules_with_set(debris, &[players, projectiles], CollisionRule::NoPair);
    (rules, [players, enemies, projectiles, debris])
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (mut rules, [players, enemies, projectiles, debris]) = game_rules();

    // One body per group, and a collider on each.
    let (mut bodies, mut colliders) = (RigidBodySet::new(), ColliderSet::new());
    let names = ["player", "enemy", "projectile", "debris"];
    let mut handles = Vec::new();
    for group in [players, enemies, projectiles, debris] {
        for _ in 0..2 {
            let body = bodies.insert(RigidBodyBuilder::dynamic());
            rules.set_group(body, Some(group));
            handles.push(colliders.insert_with_parent(
                ColliderBuilder::ball(0.5),
                body,
                &mut bodies,
            ));
        }
    }
    use CollisionRule::*;
    let expected = [
        [Normal, Normal, Normal, NoPair],
        [Normal, NoResponse, Normal, Normal],
        [Normal, Normal, NoPair, NoPair],
        [NoPair, Normal, NoPair, Normal],
    ];
    print!("{:>12}", "");
    for name in names {
        print!("{name:>12}");
    }
    println!();
    for (i, row) in expected.iter().enumerate() {
        print!("{:>12}", names[i]);
        for (j, &want) in row.iter().enumerate() {
            // The second member of group i against the first of group j.
            let got = rules.resolve(&bodies, &colliders, handles[2 * i + 1], handles[2 * j]);
            print!("{:>12}", format!("{got:?}"));
            if got != want {
                return Err(
                    format!("{} vs {}: {got:?}, expected {want:?}", names[i], names[j]).into(),
                );
            }
        }
        println!();
    }

    // In a world: debris falls through a standing player onto the ground. A
    // rule set belongs to one world (its rules are keyed by the world's
    // handles), so the world gets its own.
    let (mut rules, [players, _, _, debris]) = game_rules();
    let mut world = PhysicsWorld::new();
    let ground =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)));
    world.insert_collider(ColliderBuilder::cuboid(10.0, 0.5, 10.0), Some(ground));
    let player =
        world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 1.0, 0.0)));
    world.insert_collider(ColliderBuilder::capsule_y(0.5, 0.5), Some(player));
    let rock =
        world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 4.0, 0.0)));
    world.insert_collider(ColliderBuilder::cuboid(0.2, 0.2, 0.2), Some(rock));
    rules.set_group(player, Some(players));
    rules.set_group(rock, Some(debris));
    let mut hooks = RuleHooks::new(rules);
    for _ in 0..120 {
        hooks.step(&mut world);
    }
    let (py, ry) = (
        world.bodies[player].translation().y,
        world.bodies[rock].translation().y,
    );
    println!("after 2 s: the player stands at y = {py:.2}, the rock lies at y = {ry:.2}");
    if !abs_diff_eq!(py, 1.0, epsilon = 0.05) || !abs_diff_eq!(ry, 0.2, epsilon = 0.05) {
        return Err("the debris did not fall through the player onto the ground".into());
    }
    println!(
        "{} of {} colliders needed the hook",
        hooks.stats().hooked_colliders,
        world.colliders.len()
    );
    Ok(())
}

#[test]
fn the_table_and_the_world_agree() {
    main().expect("the example's own checks");
}
