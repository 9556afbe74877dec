//! Two unit cubes on a ground slab, overlapping by a share of their width:
//! the scene of the switch from `NoResponse` to `Normal`, shared by
//! `examples/stability.rs` (the sweep) and `tests/integration/stability.rs`.

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
