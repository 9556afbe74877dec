//! What a shape and a vector are in each dimension, for the targets that
//! the 3D and the 2D crate share (the headless tests, the showcase app,
//! the frame bench): each target's root names its dimension's bevy_rapier
//! as `bevy_rapier` and mounts this file.

use bevy_rapier::prelude::{Collider, Vect};

/// A box with these half extents (the third is dropped in 2D).
pub fn cuboid(hx: f32, hy: f32, hz: f32) -> Collider {
    #[cfg(feature = "dim3")]
    return Collider::cuboid(hx, hy, hz);
    #[cfg(feature = "dim2")]
    {
        let _ = hz;
        Collider::cuboid(hx, hy)
    }
}

/// A vector of the dimension (`z` is dropped in 2D).
pub fn vect(x: f32, y: f32, z: f32) -> Vect {
    #[cfg(feature = "dim3")]
    return Vect::new(x, y, z);
    #[cfg(feature = "dim2")]
    {
        let _ = z;
        Vect::new(x, y)
    }
}
