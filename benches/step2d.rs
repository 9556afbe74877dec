//! Step cost of `RuleHooks` against plain `rapier2d`, side by side in one
//! run: the piles and variants of `benches/step.rs` (`common/piles.rs`), the
//! columns of ten standing in one row (100 and 400 columns) on a ground
//! line.
//!
//! `cargo bench --bench step2d --features dim2`; `STEP_PAIRED_ONLY=1` skips
//! criterion.

use rapier_collision_rules::dim2 as rules;
use rapier2d as rapier;

mod common;
#[path = "common/piles.rs"]
mod piles;
#[path = "common/space2.rs"]
mod space;

fn main() {
    piles::main();
}
