//! Random edits, steps, insertions and removals against `RuleHooks`: no
//! panic, a clean rule set and exact live pairs after every step. The same
//! driver runs, bounded, in `cargo test` (`driver::bounded`).

#![no_main]

use libfuzzer_sys::fuzz_target;

#[path = "../../tests/integration/world.rs"]
#[allow(dead_code)]
mod world;

#[path = "../../tests/integration/driver.rs"]
mod driver;

fuzz_target!(|data: &[u8]| driver::drive(data));
