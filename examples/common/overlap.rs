//! Two unit cubes on a ground slab, overlapping by a share of their width,
//! switched from `NoResponse` to `Normal`: the measurement shared by
//! `examples/stability.rs` (the sweep over the depth) and
//! `tests/integration/stability.rs` (one depth).

use rapier_collision_rules::{CollisionRule, CollisionRuleSet, RuleHooks};
use rapier3d::prelude::*;

/// The world and the two cubes' bodies and colliders.
pub struct Overlap {
    pub world: PhysicsWorld,
    pub bodies: (RigidBodyHandle, RigidBodyHandle),
    pub colliders: (ColliderHandle, ColliderHandle),
}

/// Two unit cubes resting on a ground slab, the second `depth` (a share of
/// their width, 0 to 1) into the first along x.
pub fn overlapping_cubes(depth: f32) -> Overlap {
    let mut world = PhysicsWorld::new();
    let ground =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)));
    world.insert_collider(ColliderBuilder::cuboid(20.0, 0.5, 20.0), Some(ground));
    let a = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.5, 0.0)));
    let b = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(
        1.0 - depth,
        0.5,
        0.0,
    )));
    let ca = world.insert_collider(ColliderBuilder::cuboid(0.5, 0.5, 0.5), Some(a));
    let cb = world.insert_collider(ColliderBuilder::cuboid(0.5, 0.5, 0.5), Some(b));
    Overlap {
        world,
        bodies: (a, b),
        colliders: (ca, cb),
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Switch {
    /// Plain Rapier: the two cubes made overlapping, no rules.
    Plain,
    /// `NoResponse`, switched to `Normal` after one step.
    Abrupt,
    /// `NoResponse` while they touch, separated by hand 1 cm a step, then
    /// `Normal`.
    Staged,
}

/// The peak separation speed of two unit cubes on a floor overlapping by
/// `depth` (a share of their width), over two seconds, from their poses
/// step to step.
pub fn overlap(depth: f32, switch: Switch) -> f32 {
    let Overlap {
        mut world,
        bodies: (a, b),
        colliders: (ca, cb),
    } = overlapping_cubes(depth);
    let mut rules = CollisionRuleSet::default();
    if switch != Switch::Plain {
        rules.set_specific(a, b, CollisionRule::NoResponse);
    }
    let mut hooks = RuleHooks::new(rules);
    hooks.step(&mut world);
    if switch == Switch::Abrupt {
        hooks.rules_mut().set_specific(a, b, CollisionRule::Normal);
    }
    let dt = world.integration_parameters.dt;
    let gap = |world: &PhysicsWorld| world.bodies[b].translation() - world.bodies[a].translation();
    let mut peak: f32 = 0.0;
    for _ in 0..120 {
        let before = gap(&world);
        if switch == Switch::Staged {
            let touching = world
                .narrow_phase
                .contact_pair(ca, cb)
                .is_some_and(|p| p.has_any_active_contact());
            if touching {
                let pa = world.bodies[a].translation();
                world.bodies[a].set_translation(pa - Vector::new(0.01, 0.0, 0.0), true);
            } else {
                hooks.rules_mut().set_specific(a, b, CollisionRule::Normal);
            }
        }
        hooks.step(&mut world);
        // From the poses, so that the hand's separation counts too.
        peak = peak.max((gap(&world) - before).length() / dt);
    }
    peak
}
