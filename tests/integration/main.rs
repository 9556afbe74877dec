//! The integration tests, in one binary: table-driven resolution cases,
//! property tests against a naive reference resolver, and error values.

mod alloc;
mod errors;
mod live;
mod properties;
mod reference;
mod scenes;
mod stability;
mod vectors;

#[global_allocator]
static ALLOCATOR: alloc::Counting = alloc::Counting;
