//! The integration tests, in one binary: table-driven resolution cases,
//! property tests against a naive reference resolver, and error values.
//! What does not depend on the dimension runs against each dimension that
//! is on (`dim3.rs`, `dim2.rs`); the scenes of `scenes2d.rs` are the 2D
//! build's own.

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
#[cfg(feature = "dim3")]
mod soak;
#[cfg(feature = "dim3")]
mod stability;

#[cfg(feature = "dim3")]
#[global_allocator]
static ALLOCATOR: alloc::Counting = alloc::Counting;
