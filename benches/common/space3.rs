//! What the benches' scenes mean in 3D.

use rapier3d::prelude::*;

/// A point; `z` is depth.
pub fn at(x: f32, y: f32, z: f32) -> Vector {
    Vector::new(x, y, z)
}

/// A box of half-extents `hx`, `hy`, `hz`.
pub fn cuboid(hx: f32, hy: f32, hz: f32) -> ColliderBuilder {
    ColliderBuilder::cuboid(hx, hy, hz)
}

/// Where the `i`-th of `columns` columns of a pile stands, `(x, z)`: the
/// columns fill a square, 1.01 apart.
pub fn column(i: usize, columns: usize) -> (f32, f32) {
    let side = (columns as f32).sqrt().ceil() as usize;
    ((i % side) as f32 * 1.01, (i / side) as f32 * 1.01)
}
