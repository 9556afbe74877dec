//! Random edits, steps, insertions and removals against `RuleHooks`: no
//! panic, a clean rule set and exact live pairs after every step. The same
//! driver runs, bounded, in `cargo test` (`driver::bounded`).

#![no_main]

use libfuzzer_sys::fuzz_target;

/// The test files the target needs: the driver and its random worlds.
macro_rules! dimension_free_tests {
    () => {
        #[path = "driver.rs"]
        pub mod driver;
        #[allow(dead_code)]
        #[path = "world.rs"]
        pub mod world;
    };
}

// Mounted over rapier3d as the integration tests mount them.
#[allow(dead_code)]
#[path = "../../tests/integration/dim3.rs"]
mod dim3;

fuzz_target!(|data: &[u8]| dim3::driver::drive(data));
