//! The tests that do not depend on the dimension, against rapier2d (see
//! `dim3.rs`), and the 2D scenes.

pub use rapier::prelude::*;
pub use rapier_collision_rules::dim2 as rules;
pub use rapier2d as rapier;

dimension_free_tests!();

/// A point of the plane.
pub fn at(x: f32, y: f32) -> Vector {
    Vector::new(x, y)
}

/// A square of half-side `half`.
pub fn cube(half: f32) -> ColliderBuilder {
    ColliderBuilder::cuboid(half, half)
}

/// A slab `half` wide across the ground, `thick` half high.
pub fn slab(half: f32, thick: f32) -> ColliderBuilder {
    ColliderBuilder::cuboid(half, thick)
}

/// A pose, bit for bit.
pub fn pose_bits(pose: &Pose) -> Vec<u32> {
    let (t, r) = (pose.translation, pose.rotation);
    [t.x, t.y, r.re, r.im].map(f32::to_bits).to_vec()
}

/// A box of half-extents `hx`, `hy` (`_hz` is the 3D scenes' depth).
pub fn cuboid(hx: f32, hy: f32, _hz: f32) -> ColliderBuilder {
    ColliderBuilder::cuboid(hx, hy)
}

/// A joint that leaves the rotation free, its second anchor at `anchor2`.
pub fn ball_joint(anchor2: Vector) -> GenericJoint {
    RevoluteJointBuilder::new().local_anchor2(anchor2).into()
}
