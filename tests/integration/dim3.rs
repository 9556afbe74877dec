//! The tests that do not depend on the dimension, against rapier3d: the
//! table-driven resolution cases, the property tests against the reference
//! model, and the random worlds of the fuzz driver.

pub use rapier::prelude::*;
pub use rapier_collision_rules::dim3 as rules;
pub use rapier3d as rapier;

dimension_free_tests!();

/// A point of the plane the scenes are laid out in.
pub fn at(x: f32, y: f32) -> Vector {
    Vector::new(x, y, 0.0)
}

/// A cube of half-side `half`.
pub fn cube(half: f32) -> ColliderBuilder {
    ColliderBuilder::cuboid(half, half, half)
}

/// A slab `half` wide each way across the ground, `thick` half high.
pub fn slab(half: f32, thick: f32) -> ColliderBuilder {
    ColliderBuilder::cuboid(half, thick, half)
}

/// A pose, bit for bit.
pub fn pose_bits(pose: &Pose) -> Vec<u32> {
    let (t, r) = (pose.translation, pose.rotation);
    t.to_array()
        .into_iter()
        .chain(r.to_array())
        .map(f32::to_bits)
        .collect()
}

/// A box of half-extents `hx`, `hy`, `hz`.
pub fn cuboid(hx: f32, hy: f32, hz: f32) -> ColliderBuilder {
    ColliderBuilder::cuboid(hx, hy, hz)
}

/// A joint that leaves the rotations free, its second anchor at `anchor2`.
pub fn ball_joint(anchor2: Vector) -> GenericJoint {
    SphericalJointBuilder::new().local_anchor2(anchor2).into()
}
