//! The integration tests, in one binary: table-driven resolution cases,
//! property tests against a naive reference resolver, and error values.

mod alloc;
mod boundary;
mod determinism;
mod driver;
mod edges;
mod errors;
mod joints;
mod live;
mod project;
mod properties;
mod query;
mod reach;
mod reference;
#[cfg(feature = "serde")]
mod saving;
mod scenes;
mod soak;
mod stability;
mod vectors;
mod world;

#[global_allocator]
static ALLOCATOR: alloc::Counting = alloc::Counting;
