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

/// Inputs the bounded property once failed on, replayed as they were found.
#[cfg(test)]
mod found {
    /// In 2D with `serde`: a saved rule set corrupted to name generation 4
    /// of the slot whose body Rapier had at generation 2, then a cut whose
    /// piece took that body as its root: the piece lost its rules (the rule
    /// set counted the live body as removed).
    const UNBORN_GENERATION: &[u8] = &[
        156, 0, 0, 0, 0, 0, 0, 1, 158, 0, 249, 0, 0, 0, 147, 0, 0, 0, 124, 0, 51, 216, 1, 37,
        42, 28, 91, 190, 1, 38, 61, 44, 18, 21, 44, 49, 201, 0, 0, 48, 0, 0, 104, 21, 0, 1, 50,
        0, 68, 31, 0, 80, 0, 0, 0, 38, 23, 0, 111, 0, 7, 0, 21, 3, 0, 60, 0, 36, 185, 0, 56,
        21, 43, 0, 39, 0, 168, 158, 124, 4, 199, 0, 0, 0, 189, 31, 1, 1, 51, 42, 1, 133, 0, 0,
        56, 0, 41, 0, 87, 74, 0, 61, 230, 0, 34, 141, 0, 158, 9, 199, 0, 0, 0, 239, 14, 5, 43,
        0, 155, 177, 0, 1, 194, 0, 185, 182, 0, 0, 32, 143, 41, 1, 197, 76, 144, 0, 0, 0, 161,
        1, 39, 0, 87, 0, 0, 0, 65, 0, 0, 151, 247,
    ];

    #[test]
    fn a_save_naming_a_generation_rapier_has_not_handed_out() {
        super::drive(UNBORN_GENERATION);
    }
}
