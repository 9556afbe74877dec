//! A ragdoll of five limbs held by Rapier's joints: the parent map is read
//! from the joints in one call, so the limbs' bodies hang under the pelvis
//! and inherit its group, which ignores itself. The limbs start
//! overlapping, fall, and land on the ground without pushing each other.
//!
//! `cargo run --example ragdoll`

use approx::abs_diff_eq;
use rapier_collision_rules::{CollisionRule, CollisionRuleSet, RuleHooks, Stage};
use rapier3d::prelude::*;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut world = PhysicsWorld::new();
    let ground =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)));
    let floor = world.insert_collider(ColliderBuilder::cuboid(10.0, 0.5, 10.0), Some(ground));
    // (name, x, half extents): overlapping boxes along x.
    let parts = [
        ("pelvis", 0.0),
        ("left thigh", 0.35),
        ("left shin", 0.7),
        ("right thigh", -0.35),
        ("right shin", -0.7),
    ];
    let mut limbs = Vec::new();
    for (name, x) in parts {
        let body =
            world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(x, 3.0, 0.0)));
        let collider = world.insert_collider(ColliderBuilder::cuboid(0.25, 0.15, 0.15), Some(body));
        limbs.push((name, body, collider));
    }
    // Hips and knees: a ball joint halfway between two limbs.
    for (a, b) in [(0, 1), (1, 2), (0, 3), (3, 4)] {
        let half = (parts[b].1 - parts[a].1) / 2.0;
        let joint = SphericalJointBuilder::new()
            .local_anchor1(Vector::new(half, 0.0, 0.0))
            .local_anchor2(Vector::new(-half, 0.0, 0.0));
        world
            .impulse_joints
            .insert(limbs[a].1, limbs[b].1, joint, true);
    }
    let mut rules = CollisionRuleSet::default();
    let ragdoll = rules.create_group();
    rules.set_group_rule(ragdoll, ragdoll, CollisionRule::NoPair);
    rules.set_group(limbs[0].1, Some(ragdoll));
    // Thighs under the pelvis, shins under the thighs, read from the joints.
    let links =
        rules.set_parents_from_impulse_joints(&world.impulse_joints, &world.bodies, limbs[0].1)?;
    println!("parent links read from the joints: {links}");
    if rules.parent(limbs[2].1) != Some(limbs[1].1) {
        return Err("the left shin does not hang under the left thigh".into());
    }
    let why = rules.explain(&world.bodies, &world.colliders, limbs[2].2, limbs[4].2);
    println!(
        "shin against shin: {:?}, decided by {:?} (groups inherited from the pelvis)",
        why.rule, why.stage
    );
    if why.rule != CollisionRule::NoPair || why.stage != Stage::Group {
        return Err("the shins do not inherit the ragdoll group".into());
    }

    let mut hooks = RuleHooks::new(rules);
    for _ in 0..120 {
        hooks.step(&mut world);
    }
    for &(name, body, collider) in &limbs {
        let p = world.bodies[body].translation();
        let on_floor = hooks.pair_rule(&world, collider, floor);
        println!(
            "{name:>12}: landed at ({:+.2}, {:.2}), pair with the floor {on_floor:?}",
            p.x, p.y
        );
        if !abs_diff_eq!(p.y, 0.15, epsilon = 0.05) || on_floor != Some(CollisionRule::Normal) {
            return Err(format!("{name} did not land on the floor").into());
        }
    }
    let limb_pairs = hooks
        .pairs(&world)
        .filter(|(a, b, _)| limbs.iter().any(|l| l.2 == *a) && limbs.iter().any(|l| l.2 == *b))
        .count();
    println!("live pairs between limbs: {limb_pairs}");
    if limb_pairs > 0 {
        return Err("limbs formed pairs".into());
    }
    Ok(())
}

#[test]
fn the_ragdoll_lands_without_fighting_itself() {
    main().expect("the example's own checks");
}
