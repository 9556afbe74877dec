//! What the benches' scenes mean in 2D.

use rapier2d::prelude::*;

/// A point of the plane (`_z`, the 3D scenes' depth, is dropped).
pub fn at(x: f32, y: f32, _z: f32) -> Vector {
    Vector::new(x, y)
}

/// A box of half-extents `hx`, `hy` (`_hz` is the 3D scenes' depth).
pub fn cuboid(hx: f32, hy: f32, _hz: f32) -> ColliderBuilder {
    ColliderBuilder::cuboid(hx, hy)
}

/// Where the `i`-th column of a pile stands, `(x, z)`: the columns stand in
/// one row, 1.01 apart, centred on the ground.
pub fn column(i: usize, columns: usize) -> (f32, f32) {
    ((i as f32 - columns as f32 / 2.0) * 1.01, 0.0)
}
