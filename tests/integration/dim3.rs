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

/// A soft block of half-side `half` around `center`: tetrahedra on a 4x4x4
/// grid of particles, as in Rapier's own soft-body tests.
pub fn soft_block(center: Vector, half: f32) -> SoftBodyBuilder {
    SoftBodyBuilder::cuboid(center, Vector::splat(half), 4, 4, 4)
        .cell_model(SoftBodyCellModel::Corotational)
        .softness(SpringCoefficients::new(30.0, 1.0))
}

/// A soft bar along x, `half` long each way, to cut across.
pub fn soft_bar(center: Vector, half: f32) -> SoftBodyBuilder {
    SoftBodyBuilder::cuboid(center, Vector::new(half, 0.25, 0.25), 6, 2, 2)
}

/// A 12x12 cloth at y = 1 m, 2.2 m wide, pinned at its corners.
pub fn pinned_sheet() -> SoftBodyBuilder {
    let (n, step) = (12usize, 0.2);
    let corners = [0, n - 1, n * (n - 1), n * n - 1].map(|i| i as u32);
    let (du, dv) = (Vector::new(step, 0.0, 0.0), Vector::new(0.0, 0.0, step));
    SoftBodyBuilder::cloth(Vector::new(-1.1, 1.0, -1.1), du, dv, n, n).pinned_particles(corners)
}

/// A blade across the plane x = `x`.
pub fn blade_at_x(x: f32) -> [Vector; 3] {
    [
        Vector::new(x, -10.0, -10.0),
        Vector::new(x, 20.0, -10.0),
        Vector::new(x, -10.0, 20.0),
    ]
}

/// Whether a cut of a bar torn in two gives the bar's root to the piece
/// for some blade (rapier 0.36.1 does in 2D; in 3D the side keeping the
/// handle keeps its root in every cut the tests try).
pub const CUT_MOVES_ROOT: bool = false;

/// A small soft body for the random worlds: a 3x2x2 grid of particles.
pub fn soft_piece(center: Vector) -> SoftBodyBuilder {
    SoftBodyBuilder::cuboid(center, Vector::new(0.4, 0.2, 0.2), 3, 2, 2)
}

/// A body builder turned by `angle` radians in the plane the scenes are
/// laid out in (about the depth axis).
pub fn tilted(builder: RigidBodyBuilder, angle: f32) -> RigidBodyBuilder {
    builder.rotation(Vector::new(0.0, 0.0, angle))
}

/// The surface of a box of half-extents `hx`, `hy`, `hz` as a triangle
/// mesh: a shape made of parts, hollow.
pub fn box_mesh(hx: f32, hy: f32, hz: f32) -> ColliderBuilder {
    let (vertices, indices) =
        rapier::parry::shape::Cuboid::new(Vector::new(hx, hy, hz)).to_trimesh();
    ColliderBuilder::trimesh(vertices, indices).expect("a box's triangles make a mesh")
}
