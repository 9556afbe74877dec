//! A 20-box stack that five ghosts fall through: the scene of the stack
//! sweeps, shared by `examples/stability.rs` (over the time step) and
//! `tests/integration/stability.rs` (over the ways ghosts are made).

use rapier_collision_rules::{CollisionGroup, CollisionRule, CollisionRuleSet};
use rapier3d::prelude::*;

/// The world, its parts, and a rule set with the ghosts' group: `spirits`
/// is `NoResponse` with both default groups. The ghosts are in no group
/// yet: the caller decides how they pass.
pub struct GhostStack {
    pub world: PhysicsWorld,
    pub boxes: Vec<(RigidBodyHandle, ColliderHandle)>,
    pub floor: ColliderHandle,
    pub ghosts: Vec<(RigidBodyHandle, ColliderHandle)>,
    pub rules: CollisionRuleSet,
    pub spirits: CollisionGroup,
}

/// A stack of 20 unit boxes on a ground slab, stepping at `dt`, with five
/// ghosts (gravity off, 8 m/s down) above it unless `ghosts` is false.
pub fn ghost_stack(dt: f32, ghosts: bool) -> GhostStack {
    let mut world = PhysicsWorld::new();
    world.integration_parameters.dt = dt;
    let ground =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)));
    let floor = world.insert_collider(ColliderBuilder::cuboid(20.0, 0.5, 20.0), Some(ground));
    let boxes = (0..20)
        .map(|i| {
            let body = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(
                0.0,
                0.5 + i as f32,
                0.0,
            )));
            let collider =
                world.insert_collider(ColliderBuilder::cuboid(0.5, 0.5, 0.5), Some(body));
            (body, collider)
        })
        .collect();
    let mut rules = CollisionRuleSet::default();
    let spirits = rules.create_group();
    for g in [
        CollisionGroup::DEFAULT_DYNAMIC,
        CollisionGroup::DEFAULT_KINEMATIC,
    ] {
        rules.set_group_rule(spirits, g, CollisionRule::NoResponse);
    }
    let count = if ghosts { 5 } else { 0 };
    let ghosts = (0..count)
        .map(|i| {
            let ghost = world.insert_body(
                RigidBodyBuilder::dynamic()
                    .translation(Vector::new(0.2, 25.0 + 3.0 * i as f32, 0.1))
                    .gravity_scale(0.0)
                    .linvel(Vector::new(0.0, -8.0, 0.0)),
            );
            (
                ghost,
                world.insert_collider(ColliderBuilder::ball(0.6), Some(ghost)),
            )
        })
        .collect();
    GhostStack {
        world,
        boxes,
        floor,
        ghosts,
        rules,
        spirits,
    }
}
