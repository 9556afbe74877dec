//! Step cost of `RuleHooks` against plain Rapier (3D), side by side in one run:
//! piles of 1,000 and 4,000 unit boxes (never sleeping) standing in columns
//! of ten, the columns side by side, on a ground slab. Every variant's rules
//! leave the physics as it is in its plain twin, so the two worlds stay the
//! same and the difference is the cost of the rules alone.
//!
//! - `none`: no rules, against `PhysicsWorld::step`;
//! - `groups`: each column in one of four groups, with group-level `NoPair`
//!   and `NoResponse` rules between neighbouring columns, against the same
//!   rules written by hand as Rapier collision and solver groups;
//! - `specific`: specific rules (`NoResponse`, `NoContacts`) on 5% of the
//!   bodies, each about a body across the pile, against plain Rapier;
//! - `hooked`: no rules but the planner off (every collider hooked), against
//!   plain Rapier;
//! - `layers`, `layers+groups`, `layers+specific`: the project's own layers
//!   on every box in both worlds (a membership bit per column, a filter that
//!   leaves out a layer no box is on), with no rules, the group rules, and
//!   the specific rules. The layers change no contact, so each plain twin is
//!   the one of the variant without layers, plus the layers.

//!
//! `cargo bench --bench step` (criterion, then the paired ratios);
//! `STEP_PAIRED_ONLY=1` skips criterion. The same piles in 2D:
//! `cargo bench --bench step2d --features dim2`.

use rapier_collision_rules::dim3 as rules;
use rapier3d as rapier;

mod common;
#[path = "common/piles.rs"]
mod piles;
#[path = "common/space3.rs"]
mod space;

fn main() {
    piles::main();
}
