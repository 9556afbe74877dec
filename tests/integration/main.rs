//! The integration tests, in one binary: table-driven resolution cases,
//! property tests against a naive reference resolver, and error values.
//! What does not depend on the dimension (the scenes included, through a
//! few shape helpers) runs against each dimension that is on (`dim3.rs`,
//! `dim2.rs`); the rest (allocation counts, the soak, serde round trips,
//! the stability sweeps, meshes and voxels) is the 3D build's.

/// The test files that do not depend on the dimension, mounted by `dim3.rs`
/// and `dim2.rs` over their Rapier (each file names Rapier, the crate and
/// the shape helpers through `super::`).
macro_rules! dimension_free_tests {
    () => {
        #[path = "boundary.rs"]
        mod boundary;
        #[path = "cloth.rs"]
        mod cloth;
        #[cfg(feature = "debug-render")]
        #[path = "debug_view.rs"]
        mod debug_view;
        #[path = "driver.rs"]
        pub mod driver;
        #[path = "endings.rs"]
        mod endings;
        #[path = "errors.rs"]
        mod errors;
        #[path = "hierarchy.rs"]
        mod hierarchy;
        #[path = "joints.rs"]
        mod joints;
        #[path = "live.rs"]
        mod live;
        #[path = "one_way.rs"]
        mod one_way;
        #[path = "project.rs"]
        mod project;
        #[path = "properties.rs"]
        mod properties;
        #[path = "query.rs"]
        mod query;
        #[path = "reach.rs"]
        mod reach;
        #[path = "reference.rs"]
        mod reference;
        // Some helpers of the scenes serve only the 3D build's other tests.
        #[allow(dead_code)]
        #[path = "rule_events.rs"]
        mod rule_events;
        #[path = "scenes.rs"]
        pub mod scenes;
        #[path = "soft.rs"]
        mod soft;
        #[path = "soft_pairs.rs"]
        mod soft_pairs;
        #[path = "vectors.rs"]
        mod vectors;
        #[path = "world.rs"]
        pub mod world;
    };
}

// Both dimensions mount the same test files on purpose.
#[cfg(feature = "dim2")]
#[allow(clippy::duplicate_mod)]
mod dim2;
#[cfg(feature = "dim3")]
#[allow(clippy::duplicate_mod)]
mod dim3;

#[cfg(feature = "dim3")]
mod alloc;
#[cfg(feature = "dim3")]
mod determinism;
#[cfg(feature = "dim3")]
mod edges;
#[cfg(all(feature = "dim3", feature = "serde"))]
mod saving;
#[cfg(all(feature = "dim3", feature = "serde"))]
mod snapshots;
#[cfg(feature = "dim3")]
mod soak;
#[cfg(feature = "dim3")]
mod soft_meshes;
#[cfg(feature = "dim3")]
mod stability;

#[cfg(feature = "dim3")]
#[global_allocator]
static ALLOCATOR: alloc::Counting = alloc::Counting;
