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

/// A soft block of half-side `half` around `center`: triangles on a 4x4
/// grid of particles.
pub fn soft_block(center: Vector, half: f32) -> SoftBodyBuilder {
    SoftBodyBuilder::grid(center, Vector::splat(half), 4, 4)
        .cell_model(SoftBodyCellModel::Corotational)
        .softness(SpringCoefficients::new(30.0, 1.0))
}

/// A soft bar along x, `half` long each way, to cut across.
pub fn soft_bar(center: Vector, half: f32) -> SoftBodyBuilder {
    SoftBodyBuilder::grid(center, Vector::new(half, 0.25), 6, 2)
}

/// A sheet at y = 1 m, 2.2 m wide, pinned at its edges: a rope pinned at
/// both ends (rapier2d's soft bodies have no cloth; a rope is its section).
pub fn pinned_sheet() -> SoftBodyBuilder {
    SoftBodyBuilder::rope(Vector::new(-1.1, 1.0), Vector::new(1.1, 1.0), 12)
        .pinned_particles([0, 11])
}

/// A blade across the line x = `x`.
pub fn blade_at_x(x: f32) -> [Vector; 2] {
    [Vector::new(x, -10.0), Vector::new(x, 20.0)]
}

/// Whether a cut of a bar torn in two gives the bar's root to the piece
/// for some blade (rapier 0.36.1 does in 2D; in 3D the side keeping the
/// handle keeps its root in every cut the tests try).
pub const CUT_MOVES_ROOT: bool = true;

/// A small soft body for the random worlds: a 3x2 grid of particles.
pub fn soft_piece(center: Vector) -> SoftBodyBuilder {
    SoftBodyBuilder::grid(center, Vector::new(0.4, 0.2), 3, 2)
}

/// A body builder turned by `angle` radians.
pub fn tilted(builder: RigidBodyBuilder, angle: f32) -> RigidBodyBuilder {
    builder.rotation(angle)
}

/// The outline of a box of half-extents `hx`, `hy` as a closed polyline
/// (`_hz` is the 3D scenes' depth): a shape made of parts, hollow.
pub fn box_mesh(hx: f32, hy: f32, _hz: f32) -> ColliderBuilder {
    let corners = vec![
        Vector::new(-hx, -hy),
        Vector::new(hx, -hy),
        Vector::new(hx, hy),
        Vector::new(-hx, hy),
    ];
    ColliderBuilder::polyline(corners, Some(vec![[0, 1], [1, 2], [2, 3], [3, 0]]))
}
