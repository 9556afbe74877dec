//! Bytes to edits: the driver shared by the fuzz target (`fuzz/`) and the
//! bounded property test below. Each byte string is decoded into a small
//! world and a sequence of edits, insertions, removals and steps; the world
//! checks after every step that nothing panicked, the rule set is clean,
//! and every live pair is exact (see `world.rs`).

use super::rules::CollisionRule;

use super::world::{Edit, GROUPS, KINDS, LAYERS, Run, TYPES};

/// Runs the world and edits that `data` decodes to. With `DRIVER_LOG` set,
/// each edit is printed before it is applied (to read a failing input).
pub fn drive(data: &[u8]) {
    run_of(data, false);
}

/// The world `data` decodes to, after its edits and steps; with `locked`,
/// its dynamic bodies never move (see `Run::new`).
pub fn run_of(data: &[u8], locked: bool) -> Run {
    let mut bytes = data.iter().copied();
    let mut next = move || bytes.next();
    let byte = |b: Option<u8>| b.unwrap_or(0) as usize;
    let position = |b: Option<u8>| (b.unwrap_or(0) as f32 / 255.0) * 3.0 - 1.5;
    let rule = |b: Option<u8>| CollisionRule::ALL[byte(b) % CollisionRule::ALL.len()];

    let cubes: Vec<(f32, f32, usize)> = (0..2 + byte(next()) % 6)
        .map(|_| {
            (
                position(next()),
                0.4 + byte(next()) as f32 / 100.0,
                byte(next()) % KINDS.len(),
            )
        })
        .collect();
    let mut run = Run::new(&cubes, byte(next()) % 4 != 0, locked);
    run.apply(&Edit::Step(1));
    while let Some(op) = next() {
        let edit = match op % 17 {
            0 => Edit::Personal(byte(next()), rule(next())),
            1 => Edit::Group(
                byte(next()),
                Some(byte(next()) % GROUPS).filter(|&g| g != 0),
            ),
            2 => Edit::Specific(byte(next()), byte(next()), rule(next())),
            3 => Edit::GroupRule(byte(next()) % GROUPS, byte(next()) % GROUPS, rule(next())),
            4 => Edit::Parent(byte(next()), byte(next())),
            5 => Edit::Unparent(byte(next())),
            6 => Edit::Share(byte(next()), byte(next())),
            7 => Edit::DefaultRule(rule(next())),
            8 => Edit::Kind(byte(next()), byte(next()) % KINDS.len()),
            9 => Edit::RemoveCollider(byte(next())),
            10 => Edit::RemoveBody(byte(next())),
            11 => Edit::AddCube(
                position(next()),
                0.4 + byte(next()) as f32 / 100.0,
                byte(next()) % KINDS.len(),
            ),
            12 => Edit::ProjectCollision(
                byte(next()),
                byte(next()) % LAYERS.len(),
                byte(next()) % LAYERS.len(),
            ),
            13 => Edit::ProjectSolver(
                byte(next()),
                byte(next()) % LAYERS.len(),
                byte(next()) % LAYERS.len(),
            ),
            14 => Edit::ProjectTypes(byte(next()), byte(next()) % TYPES.len()),
            15 => match byte(next()) % 16 {
                0 => Edit::RemoveSpecific(byte(next()), byte(next())),
                1 => Edit::Recursive(byte(next())),
                2 => Edit::InSet(
                    (0..byte(next()) % 4).map(|_| byte(next())).collect(),
                    rule(next()),
                    rule(next()),
                    byte(next()) % 3 == 0,
                ),
                3 => Edit::AddBody(byte(next())),
                4 => Edit::Bracket(1 + byte(next()) % 3),
                5 => Edit::Reload(byte(next()) % 2 == 0),
                6 => Edit::AddSoft(position(next()), 0.5 + byte(next()) as f32 / 128.0),
                7 => Edit::CutSoft(byte(next())),
                8 => Edit::TearSoft(byte(next())),
                9 => Edit::RemoveSoft(byte(next())),
                10 => Edit::AddTearable(position(next()), 0.5 + byte(next()) as f32 / 128.0),
                11 => Edit::SleepSoft(byte(next())),
                12 => Edit::NewSoftRoot(byte(next())),
                13 => Edit::SpecificUntil(byte(next()), byte(next()), rule(next()), byte(next())),
                14 => Edit::OneWay(byte(next()), byte(next()) % 4),
                _ => Edit::Corrupt(byte(next()), byte(next()) as u32 * 4),
            },
            _ => Edit::Step(1 + byte(next()) % 3),
        };
        if std::env::var("DRIVER_LOG").is_ok() {
            eprintln!("{edit:?}");
        }
        run.apply(&edit);
    }
    run.apply(&Edit::Step(1));
    run
}

#[cfg(test)]
mod bounded {
    use proptest::prelude::*;
    use proptest::test_runner::{Config, RngSeed};

    proptest! {
        #![proptest_config(Config {
            cases: super::super::world::env_or("DRIVER_CASES", 300, |v| v.parse().ok()),
            rng_seed: RngSeed::Fixed(super::super::world::env_or("DRIVER_SEED", 0xf022_ed17, |v| u64::from_str_radix(v, 16).ok())),
            failure_persistence: None,
            ..Config::default()
        })]

        /// The fuzz target's driver, on random bytes: no panic, a clean rule
        /// set and exact live pairs after every step.
        #[test]
        fn random_bytes_never_break_the_hooks(data in proptest::collection::vec(any::<u8>(), 0..300)) {
            super::drive(&data);
        }
    }
}
