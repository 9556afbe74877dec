//! Determinism: the same scene with the same edits gives bit-identical
//! positions, rules and live pairs in two separate processes. Hash tables
//! are seeded per process, so anything the hooks do in an order that
//! reaches Rapier (wake-ups, group nudges, plans) must not follow their
//! iteration order. The test runs the scenes in two child processes (this
//! test binary, asked for `child_digest` alone) and compares what they
//! print with each other and with this process. `.ci/run` also compares
//! the live pairs and rules of locked worlds between builds with and
//! without the `parallel` feature (`RULES=` in the child's output).

use std::hash::{DefaultHasher, Hash, Hasher};
use std::process::Command;

use crate::dim3::driver::run_of;
use crate::dim3::world::Run;

/// The environment variable that makes `child_digest` print its digest.
const CHILD: &str = "RULES_DETERMINISM_CHILD";

/// The bytes of edit script `i`, from a fixed generator.
fn script(i: u64) -> Vec<u8> {
    let mut state: u64 = 0x0dd_ba11 ^ i.wrapping_mul(0x9e37_79b9_7f4a_7c15);
    (0..400)
        .map(|_| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 33) as u8
        })
        .collect()
}

/// Decodes 40 edit scripts (the fuzz driver's decoding of bytes from a
/// fixed generator), steps each world (its dynamic bodies `locked` or not),
/// and hashes what `what` says of each. `DefaultHasher::new()` has fixed
/// keys: the same value in every process.
fn digest_of(locked: bool, what: impl Fn(&Run, &mut DefaultHasher)) -> u64 {
    let mut hasher = DefaultHasher::new();
    for i in 0..40 {
        what(&run_of(&script(i), locked), &mut hasher);
    }
    hasher.finish()
}

/// Every body's pose bit for bit, the live pairs and their rules.
fn digest() -> u64 {
    digest_of(false, |run, hasher| {
        run.poses().hash(hasher);
        run.live().hash(hasher);
        run.hooks.stats().hooked_colliders.hash(hasher);
    })
}

/// On worlds whose dynamic bodies never move, only the live pairs, their
/// rules and the hooked counts: what must be the same with and without the
/// `parallel` feature, whose solver may move bodies otherwise than the
/// serial one.
fn rules_digest() -> u64 {
    digest_of(true, |run, hasher| {
        run.live().hash(hasher);
        run.known().hash(hasher);
        run.hooks.stats().hooked_colliders.hash(hasher);
    })
}

/// Run alone by `two_processes_step_alike`, in a child process.
#[test]
#[ignore = "run by two_processes_step_alike in a child process"]
fn child_digest() {
    if std::env::var_os(CHILD).is_some() {
        println!("\nDIGEST={:016x}", digest());
        // Compared by `.ci/run` between builds with and without `parallel`.
        println!("\nRULES={:016x}", rules_digest());
    }
}

fn child() -> String {
    let exe = std::env::current_exe().expect("the test binary");
    let output = Command::new(exe)
        .args([
            "determinism::child_digest",
            "--exact",
            "--ignored",
            "--nocapture",
            "--test-threads=1",
        ])
        .env(CHILD, "1")
        .output()
        .expect("the child process runs");
    assert!(output.status.success(), "child failed: {output:?}");
    let stdout = String::from_utf8_lossy(&output.stdout);
    // The test harness prints the test's name on the same line.
    stdout
        .split("DIGEST=")
        .nth(1)
        .and_then(|rest| rest.get(..16))
        .unwrap_or_else(|| panic!("no digest in the child's output: {stdout}"))
        .to_owned()
}

#[test]
fn two_processes_step_alike() {
    let (first, second) = (child(), child());
    let here = format!("{:016x}", digest());
    assert_eq!(first, second, "two processes moved the same worlds apart");
    assert_eq!(
        first, here,
        "a child and this process moved the same worlds apart"
    );
}
