//! Random edit sequences while stepping real worlds: after every step, each
//! live pair's rule equals a fresh `resolve` (policy `OnChange`, no
//! overrides), every pair in Rapier's graph is known to the hooks, no
//! live pair names a removed collider, and the rule events of the step,
//! applied to the live pairs they told before, give the live pairs, also with soft bodies added, cut,
//! torn (by hand and by strain during a step) and removed, and rules with
//! an end given and ending. And the planner
//! changes nothing a user can see: the same world stepped with the planner
//! on and off, those soft-body edits included, has the same live pairs
//! with the same rules (while the edits name the same objects in both: a
//! soft body that moved differently in each may be cut differently), and
//! the same touching pairs while the two worlds' poses agree (hooking
//! every collider does not step bit for bit as Rapier's unhooked path); at
//! the fixed seed the live pairs are compared in 1,632 of 1,642 steps in 3D
//! and all 1,642 in 2D, the touching pairs in 1,595 and 1,616, and the test
//! fails if fewer than 95% and 90% of the steps are compared.
//! And the upkeep that looks only at what the rules reach, and plans only
//! what each step's changes reach, sees what a full pass over every
//! collider sees, those soft-body edits included, also under heavy churn.
//!
//! The seed and the number of cases are fixed, so that a run is repeatable;
//! `LIVE_SEED` (hex) and `LIVE_CASES` try others, for example
//! `LIVE_SEED=5eed0003 LIVE_CASES=1024 cargo test --release --test integration live::`.

use super::rapier::prelude::ColliderHandle;
use super::rules::CollisionRule;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed, TestCaseError};

use super::world::{Edit, GROUPS, KINDS, LAYERS, Raw, Run, TYPES, ends, env_or, one_ways};

fn rule() -> impl Strategy<Value = CollisionRule> {
    proptest::sample::select(CollisionRule::ALL.to_vec())
}

/// The fixed seed and number of cases (see the module's doc), the cases
/// divided by `share` and the seed varied by `salt` for a test of its own.
fn live_config(share: u32, salt: u64) -> Config {
    Config {
        cases: env_or("LIVE_CASES", 256, |v| v.parse().ok()) / share,
        rng_seed: RngSeed::Fixed(
            env_or("LIVE_SEED", 0x11fe_9a11, |v| u64::from_str_radix(v, 16).ok()) ^ salt,
        ),
        failure_persistence: None,
        ..Config::default()
    }
}

fn edit() -> impl Strategy<Value = Edit> {
    let n = 0..64usize;
    prop_oneof![
        3 => (n.clone(), rule()).prop_map(|(x, r)| Edit::Personal(x, r)),
        2 => (n.clone(), proptest::option::of(0..GROUPS)).prop_map(|(x, g)| Edit::Group(x, g)),
        3 => (n.clone(), n.clone(), rule()).prop_map(|(x, y, r)| Edit::Specific(x, y, r)),
        1 => (n.clone(), n.clone(), rule(), 0..ends().len()).prop_map(|(x, y, r, u)| Edit::SpecificUntil(x, y, r, u)),
        1 => (n.clone(), 0..one_ways().len() + 1).prop_map(|(x, w)| Edit::OneWay(x, w)),
        2 => (0..GROUPS, 0..GROUPS, rule()).prop_map(|(a, b, r)| Edit::GroupRule(a, b, r)),
        2 => (n.clone(), n.clone()).prop_map(|(c, p)| Edit::Parent(c, p)),
        1 => n.clone().prop_map(Edit::Unparent),
        1 => (n.clone(), n.clone()).prop_map(|(a, b)| Edit::Share(a, b)),
        1 => rule().prop_map(Edit::DefaultRule),
        1 => (n.clone(), 0..KINDS.len()).prop_map(|(b, k)| Edit::Kind(b, k)),
        1 => n.clone().prop_map(Edit::RemoveCollider),
        1 => n.clone().prop_map(Edit::RemoveBody),
        2 => (-1.5f32..1.5, 0.4f32..3.0, 0..KINDS.len()).prop_map(|(x, y, k)| Edit::AddCube(x, y, k)),
        1 => n.clone().prop_map(Edit::AddCollider),
        1 => (n.clone(), n.clone()).prop_map(|(c, b)| Edit::MoveCollider(c, b)),
        1 => n.clone().prop_map(Edit::Sleep),
        1 => n.clone().prop_map(Edit::Wake),
        1 => (n.clone(), 0..LAYERS.len(), 0..LAYERS.len()).prop_map(|(c, m, f)| Edit::ProjectCollision(c, m, f)),
        1 => (n.clone(), 0..LAYERS.len(), 0..LAYERS.len()).prop_map(|(c, m, f)| Edit::ProjectSolver(c, m, f)),
        1 => (n.clone(), 0..TYPES.len()).prop_map(|(c, t)| Edit::ProjectTypes(c, t)),
        1 => (n.clone(), n.clone()).prop_map(|(x, y)| Edit::RemoveSpecific(x, y)),
        1 => n.clone().prop_map(Edit::Recursive),
        1 => (proptest::collection::vec(0..GROUPS, 0..4), rule(), rule(), any::<bool>())
            .prop_map(|(set, a, b, remove)| Edit::InSet(set, a, b, remove)),
        1 => (0..KINDS.len()).prop_map(Edit::AddBody),
        6 => (1..4usize).prop_map(Edit::Step),
    ]
}

/// Every edit, and soft bodies added, cut, torn (by hand and by strain) and
/// removed.
fn edit_with_soft() -> impl Strategy<Value = Edit> {
    prop_oneof![
        16 => edit(),
        1 => (-1.5f32..1.5, 0.5f32..2.5).prop_map(|(x, y)| Edit::AddSoft(x, y)),
        1 => (0..64usize).prop_map(Edit::CutSoft),
        1 => (0..64usize).prop_map(Edit::TearSoft),
        1 => (0..64usize).prop_map(Edit::RemoveSoft),
        1 => (0..64usize).prop_map(Edit::SleepSoft),
        1 => (0..64usize).prop_map(Edit::NewSoftRoot),
        1 => (-1.5f32..1.5, 0.5f32..2.5).prop_map(|(x, y)| Edit::AddTearable(x, y)),
    ]
}

proptest! {
    #![proptest_config(live_config(1, 0))]

    #[test]
    fn live_pairs_follow_every_edit(
        cubes in proptest::collection::vec((-1.5f32..1.5, 0.4f32..3.0, 0..KINDS.len()), 2..8),
        edits in proptest::collection::vec(edit_with_soft(), 1..40),
    ) {
        let mut run = Run::new(&cubes, true, false);
        run.record_rule_events();
        run.apply(&Edit::Step(1));
        for edit in &edits {
            run.apply(edit);
        }
        run.apply(&Edit::Step(2));
    }

    #[test]
    fn the_upkeep_sees_what_a_full_pass_sees(
        cubes in proptest::collection::vec((-1.5f32..1.5, 0.4f32..3.0, 0..KINDS.len()), 2..8),
        edits in proptest::collection::vec(edit_with_soft(), 1..40),
    ) {
        upkeep_sees_what_a_full_pass_sees(&cubes, &edits)?;
    }
}

/// How many steps of the planner on/off runs compared what (see
/// `the_planner_changes_nothing_a_user_sees`).
#[derive(Clone, Copy, Debug, Default)]
struct Compared {
    steps: usize,
    /// The edits named the same objects: live pairs compared.
    named: usize,
    /// The poses agreed too: touching pairs compared.
    alike: usize,
}

#[test]
fn the_planner_changes_nothing_a_user_sees() {
    let cubes = proptest::collection::vec((-1.5f32..1.5, 0.4f32..3.0, 0..KINDS.len()), 2..8);
    let edits = proptest::collection::vec(edit_with_soft(), 1..40);
    let compared = std::cell::Cell::new(Compared::default());
    let mut runner = proptest::test_runner::TestRunner::new(live_config(1, 0));
    let result = runner.run(&(cubes, edits), |(cubes, edits)| {
        let mut on = Run::new(&cubes, true, true);
        let mut off = Run::new(&cubes, false, true);
        // With the planner off every collider is hooked, and Rapier's
        // hooked path need not reproduce its unhooked one to the last bit
        // (its contact recycling differs): the touching pairs are compared
        // while the poses agree, the rules of the live pairs while the
        // edits name the same objects in both (a soft body that moved
        // differently in each may be cut differently).
        let (mut alike, mut named) = (true, true);
        in_lockstep(&mut on, &mut off, &edits, |on, off| {
            let mut count = compared.get();
            count.steps += 1;
            named = named && on.names_alike(off);
            if !named {
                compared.set(count);
                return Ok(());
            }
            count.named += 1;
            alike = alike && on.poses() == off.poses();
            if alike {
                count.alike += 1;
                prop_assert_eq!(on.touching(), off.touching(), "touching pairs differ");
            }
            compared.set(count);
            let (on_live, off_live) = live_in_both(on, off);
            prop_assert_eq!(on_live, off_live, "live pairs differ");
            Ok(())
        })?;
        // Hooking every collider hooks at least what the planner hooks (of
        // the same objects).
        let hooked = |run: &Run| run.hooks.stats().hooked_colliders;
        prop_assert!(!named || hooked(&off) >= hooked(&on), "hooked {} off, {} on", hooked(&off), hooked(&on));
        Ok(())
    });
    if let Err(failure) = result {
        panic!("{failure}");
    }
    // The comparisons stop where the runs part; most steps must be compared.
    let count = compared.get();
    eprintln!("planner on/off: {count:?}");
    assert!(count.named * 100 >= count.steps * NAMED_SHARE, "live pairs compared in too few steps: {count:?}");
    assert!(count.alike * 100 >= count.steps * ALIKE_SHARE, "touching pairs compared in too few steps: {count:?}");
}

/// The least shares (in percent) of the planner on/off steps whose live
/// pairs and touching pairs are compared.
const NAMED_SHARE: usize = 95;
const ALIKE_SHARE: usize = 90;

/// One step of a world that changes every step: objects come (with every
/// kind of body), get rules of every kind (specific entries that Rapier's
/// groups decide and those the hook carries, personal rules, groups), the
/// project sets layers on some, bodies are parented and unparented, objects
/// go, and the world steps once.
fn churn_round() -> impl Strategy<Value = Vec<Edit>> {
    let n = 0..256usize;
    let arrive = (-1.5f32..1.5, 0.4f32..3.0, 0..KINDS.len())
        .prop_map(|(x, y, k)| Edit::AddCube(x, y, k));
    let rule_edit = prop_oneof![
        4 => (n.clone(), n.clone(), rule()).prop_map(|(x, y, r)| Edit::Specific(x, y, r)),
        1 => (n.clone(), n.clone(), rule(), 0..ends().len()).prop_map(|(x, y, r, u)| Edit::SpecificUntil(x, y, r, u)),
        1 => (n.clone(), 0..one_ways().len() + 1).prop_map(|(x, w)| Edit::OneWay(x, w)),
        2 => (n.clone(), rule()).prop_map(|(x, r)| Edit::Personal(x, r)),
        2 => (n.clone(), proptest::option::of(0..GROUPS)).prop_map(|(x, g)| Edit::Group(x, g)),
        1 => (n.clone(), n.clone()).prop_map(|(x, y)| Edit::RemoveSpecific(x, y)),
        1 => (n.clone(), 0..LAYERS.len(), 0..LAYERS.len())
            .prop_map(|(c, m, f)| Edit::ProjectCollision(c, m, f)),
        1 => (n.clone(), 0..LAYERS.len(), 0..LAYERS.len())
            .prop_map(|(c, m, f)| Edit::ProjectSolver(c, m, f)),
        1 => (n.clone(), n.clone()).prop_map(|(c, b)| Edit::MoveCollider(c, b)),
        // Riders onto platforms and off again: chains change under entries.
        1 => (n.clone(), n.clone()).prop_map(|(c, p)| Edit::Parent(c, p)),
        1 => n.clone().prop_map(Edit::Unparent),
    ];
    let leave = prop_oneof![
        2 => n.clone().prop_map(Edit::RemoveBody),
        1 => n.clone().prop_map(Edit::RemoveCollider),
    ];
    (
        proptest::collection::vec(arrive, 6..20),
        proptest::collection::vec(rule_edit, 6..24),
        proptest::collection::vec(leave, 4..18),
    )
        .prop_map(|(arrive, rules, leave)| {
            let mut round = arrive;
            round.extend(rules);
            round.extend(leave);
            round.push(Edit::Step(1));
            round
        })
}

proptest! {
    // A case is several steps of dozens of edits: an eighth of the cases.
    #![proptest_config(live_config(8, 0xc4))]

    /// Heavy churn: dozens of objects in and out every step, with every
    /// rule kind, entry bits and project layers; the plans of the changes
    /// alone see what a whole plan every step sees.
    #[test]
    fn the_upkeep_sees_what_a_full_pass_sees_under_churn(
        cubes in proptest::collection::vec((-1.5f32..1.5, 0.4f32..3.0, 0..KINDS.len()), 2..8),
        rounds in proptest::collection::vec(churn_round(), 3..7),
    ) {
        let edits: Vec<Edit> = rounds.into_iter().flatten().collect();
        upkeep_sees_what_a_full_pass_sees(&cubes, &edits)?;
    }
}

/// The upkeep that plans what the changes reach, against the test oracle
/// that plans everything every step, stepped in lockstep through `edits`.
fn upkeep_sees_what_a_full_pass_sees(
    cubes: &[(f32, f32, usize)],
    edits: &[Edit],
) -> Result<(), TestCaseError> {
    let mut upkeep = Run::new(cubes, true, false);
    let mut oracle = Run::new(cubes, true, false);
    oracle.hooks.set_exhaustive(true);
    let mut parted = false;
    in_lockstep(&mut upkeep, &mut oracle, edits, |upkeep, oracle| {
        // The poses may part in the last bits: with a one-way surface in
        // the world (see below), and where Rapier's parallel pipeline steps
        // soft bodies, which it does differently from run to run
        // (`docs/semantics.md`, "Soft bodies"). A soft body pulled apart
        // may then tear a step sooner in one run, and the same edits name
        // other objects in each: the runs are compared until then.
        let may_part =
            upkeep.one_ways || (cfg!(feature = "parallel") && upkeep.has_soft_bodies());
        if !upkeep.names_alike(oracle) {
            prop_assert!(may_part, "the runs name other objects, yet their poses may not part");
            parted = true;
        }
        if parted {
            return Ok(());
        }
        // The oracle plans, and so marks modified, every collider every
        // step: Rapier's broad phase refits other AABBs when, so a pair
        // without contacts may be in one graph only (see
        // `live_in_both`); the touching pairs are compared whole.
        let (upkeep_both, oracle_both) = live_in_both(upkeep, oracle);
        prop_assert_eq!(upkeep_both, oracle_both, "live pairs differ");
        // The upkeep writes the contact-modification flag where a full pass
        // does: on every collider under a one-way node (of the colliders in
        // both: once the poses part, a soft body may tear in one only). A
        // soft surface also has it where it is hooked, and which side of an
        // entry is hooked follows the pairs each side has: once the poses
        // part, soft surfaces are left out.
        let (upkeep_flags, oracle_flags) = (modifying(upkeep), modifying(oracle));
        let parted_poses = upkeep.poses() != oracle.poses();
        let compared = |(c, _): &(Raw, bool)| -> bool {
            let handle = ColliderHandle::from_raw_parts(c.0, c.1);
            !parted_poses
                || [upkeep, oracle].iter().all(|run| {
                    let collider = run.world.colliders.get(handle);
                    collider.is_some_and(|c| c.deformable_mesh_ref().is_none())
                })
        };
        let in_both = |of: &[(Raw, bool)], other: &[(Raw, bool)]| -> Vec<(Raw, bool)> {
            of.iter()
                .filter(|(c, _)| other.iter().any(|(o, _)| o == c))
                .filter(|f| compared(f))
                .copied()
                .collect()
        };
        prop_assert_eq!(
            in_both(&upkeep_flags, &oracle_flags),
            in_both(&oracle_flags, &upkeep_flags),
            "the contact-modification flags differ"
        );
        // Rapier solves a pair whose contacts a hook may modify through
        // contacts rebuilt in the world's frame, and the oracle marks every
        // collider modified every step: with a one-way surface in the world
        // the two runs part in the last bits of the poses. So the physics is
        // compared where the poses may not part (soft bodies included, in
        // the build without `parallel`, which `cargo test` runs).
        if may_part {
            return Ok(());
        }
        prop_assert_eq!(upkeep.touching(), oracle.touching(), "touching pairs differ");
        // Each run knows the pairs its own hook met: each of them must be a
        // live pair of the other with the same rule.
        let (upkeep_live, oracle_live) = (upkeep.live(), oracle.live());
        for known in upkeep.known().into_iter().filter(|k| holds(oracle, k)) {
            prop_assert!(oracle_live.contains(&known), "the upkeep knows {:?}, not live so in the oracle", known);
        }
        for known in oracle.known().into_iter().filter(|k| holds(upkeep, k)) {
            prop_assert!(upkeep_live.contains(&known), "the oracle knows {:?}, not live so in the upkeep", known);
        }
        prop_assert_eq!(upkeep.poses(), oracle.poses(), "the worlds moved apart");
        Ok(())
    })
}

/// The colliders with the contact-modification flag, by handle.
fn modifying(run: &Run) -> Vec<(Raw, bool)> {
    let flag = super::rapier::prelude::ActiveHooks::MODIFY_SOLVER_CONTACTS;
    let mut all: Vec<_> = run
        .world
        .colliders
        .iter()
        .map(|(h, c)| (h.into_raw_parts(), c.active_hooks().contains(flag)))
        .collect();
    all.sort_unstable();
    all
}

/// A live pair and its rule.
type Live = (Raw, Raw, CollisionRule);

/// The live pairs of each run that Rapier's graph holds in both. Which
/// colliders a run marks modified (the planner writes different settings
/// than the hook-everything run) changes which AABBs Rapier's broad phase
/// refits when, so a pair without contacts may be in one graph and not the
/// other; the touching pairs are compared whole.
fn live_in_both(a: &Run, b: &Run) -> (Vec<Live>, Vec<Live>) {
    let (a_live, b_live) = (a.live(), b.live());
    let keys =
        |live: &[Live]| -> Vec<(Raw, Raw)> { live.iter().map(|&(x, y, _)| (x, y)).collect() };
    let (a_keys, b_keys) = (keys(&a_live), keys(&b_live));
    let a_live = a_live
        .into_iter()
        .filter(|&(x, y, _)| b_keys.contains(&(x, y)))
        .collect();
    let b_live = b_live
        .into_iter()
        .filter(|&(x, y, _)| a_keys.contains(&(x, y)))
        .collect();
    (a_live, b_live)
}

/// Whether `run`'s Rapier graph holds the pair of `live`.
fn holds(run: &Run, live: &Live) -> bool {
    let (a, b) = (
        ColliderHandle::from_raw_parts(live.0.0, live.0.1),
        ColliderHandle::from_raw_parts(live.1.0, live.1.1),
    );
    let narrow_phase = &run.world.narrow_phase;
    narrow_phase.contact_pair(a, b).is_some() || narrow_phase.intersection_pair(a, b).is_some()
}

/// Applies `edits` (and two last steps) to both runs, and `compare`s them
/// after every step.
fn in_lockstep(
    a: &mut Run,
    b: &mut Run,
    edits: &[Edit],
    mut compare: impl FnMut(&Run, &Run) -> Result<(), TestCaseError>,
) -> Result<(), TestCaseError> {
    for edit in edits.iter().chain([&Edit::Step(2)]) {
        let steps = match edit {
            Edit::Step(n) => *n,
            other => {
                a.apply(other);
                b.apply(other);
                0
            }
        };
        for _ in 0..steps {
            a.step();
            b.step();
            compare(a, b)?;
        }
    }
    Ok(())
}

/// Found by `the_upkeep_sees_what_a_full_pass_sees`: a specific entry that
/// found no free bit while a project collider narrowed the room gets one
/// once that collider is removed, in the upkeep as in the full pass (the
/// plan is made again when colliders come or go), so both worlds keep the
/// same settings and move the same.
#[test]
fn an_entry_takes_a_bit_once_the_collider_that_held_the_room_is_gone() {
    use super::world::Edit::*;
    let cubes = [(0.0, 0.4, 0), (0.0, 0.4, 0), (0.0, 0.4, 0), (0.0, 0.4, 0)];
    let edits = [
        ProjectTypes(0, 0),
        Specific(17, 25, CollisionRule::NoResponse),
        ProjectCollision(4, 1, 1),
        AddCube(-0.658, 0.4, 0),
        AddCube(1.173, 0.4, 0),
        Personal(17, CollisionRule::Defer),
        Group(10, None),
        Step(1),
        RemoveCollider(53),
        AddBody(0),
    ];
    planned_alike(&cubes, &edits, |_| Ok(()));
}

/// The upkeep and the full-pass oracle stepped through `edits`: after each
/// step both give every collider the same settings and move the same, and
/// `also` holds of the upkeep.
fn planned_alike(
    cubes: &[(f32, f32, usize)],
    edits: &[Edit],
    also: impl Fn(&Run) -> Result<(), TestCaseError>,
) {
    let mut upkeep = Run::new(cubes, true, false);
    let mut oracle = Run::new(cubes, true, false);
    oracle.hooks.set_exhaustive(true);
    in_lockstep(&mut upkeep, &mut oracle, edits, |upkeep, oracle| {
        also(upkeep)?;
        prop_assert_eq!(settings(upkeep), settings(oracle));
        prop_assert_eq!(upkeep.poses(), oracle.poses());
        Ok(())
    })
    .unwrap();
}

/// Found by `the_upkeep_sees_what_a_full_pass_sees`: a group rule that
/// wants bits while a project collider leaves only one reaches no collider,
/// so the hooks have nothing to watch; when that collider is removed the
/// room grows, and the hooks, though idle, make the plan again as the full
/// pass does (the floor, a fixed body, gets its group's bit in both).
#[test]
fn an_idle_plan_is_made_again_when_the_collider_that_held_the_room_is_gone() {
    use super::world::Edit::*;
    let cubes = [(0.0, 0.4, 0), (0.0, 0.4, 0), (-1.466, 0.4, 0)];
    let edits = [
        ProjectSolver(1, 4, 0),
        InSet(vec![2, 1], CollisionRule::NoPair, CollisionRule::NoResponse, false),
        Step(1),
        RemoveCollider(1),
        Step(2),
    ];
    planned_alike(&cubes, &edits, |upkeep| {
        prop_assert!(
            upkeep.hooks.stats().shares_project_bits,
            "an idle step still says the plan shares the project's bits"
        );
        Ok(())
    });
}

/// Each collider's hook flags and groups, to compare two runs' plans.
fn settings(r: &Run) -> Vec<String> {
    r.world
        .colliders
        .iter()
        .map(|(h, c)| {
            let (col, sol) = (c.collision_groups(), c.solver_groups());
            format!(
                "{:?}: hooks {:?}, collision {:x}/{:x}, solver {:x}/{:x}",
                h.into_raw_parts(),
                c.active_hooks(),
                col.memberships.bits(),
                col.filter.bits(),
                sol.memberships.bits(),
                sol.filter.bits()
            )
        })
        .collect()
}

/// Found by `the_upkeep_sees_what_a_full_pass_sees` once soft bodies came
/// in: the upkeep and the full pass wrote the same settings to the same
/// two colliders in different orders, which Rapier's broad phase kept
/// (its tree, then the order of new pairs), and a soft body added over a
/// cube the next step pushed it differently in each. Both now write in the
/// node order, and move the same, bit for bit.
#[test]
fn a_plan_of_a_few_colliders_writes_them_in_the_order_a_whole_plan_does() {
    use super::world::Edit::*;
    let cubes = [(0.348, 1.991, 0), (0.0, 0.4, 1), (-1.113, 1.254, 0), (0.0, 0.4, 0)];
    let edits = [
        Specific(38, 27, CollisionRule::NoResponse),
        AddCube(0.662, 0.4, 1),
        RemoveBody(6),
        AddBody(0),
        Step(1),
        RemoveCollider(22),
        Kind(10, 1),
        Step(1),
        AddCollider(4),
        AddSoft(0.455, 0.5),
    ];
    planned_alike(&cubes, &edits, |_| Ok(()));
}

/// Found by `the_upkeep_sees_what_a_full_pass_sees`: a cut soft body's
/// piece has Rapier's copies of the source's colliders, with what the crate
/// wrote on them; the upkeep planned them only once something else reached
/// them, and the full pass at once. Both plan them before the next step.
#[test]
fn a_pieces_colliders_are_planned_before_the_step_after_the_cut() {
    use super::world::Edit::*;
    let cubes = [(0.0, 1.225, 0), (0.0, 0.4, 0), (0.0, 0.4, 0)];
    let edits = [
        AddSoft(0.0, 0.5),
        Personal(23, CollisionRule::NoPair),
        AddCube(0.0, 0.4, 0),
        Share(51, 10),
        Step(1),
        CutSoft(0),
    ];
    planned_alike(&cubes, &edits, |_| Ok(()));
}

/// Found by `the_upkeep_sees_what_a_full_pass_sees`: a cut gives the piece
/// the soft body's root and the side that keeps the handle a new one
/// (rapier 0.36.1), so the rules are found on the root the hooks knew; the
/// new root takes them, and both sides keep their `NoPair`.
#[test]
fn both_sides_of_a_cut_keep_the_rules_of_the_root_before_it() {
    use super::world::Edit::*;
    let cubes = [(0.0, 0.4, 0); 3];
    let edits = [
        AddSoft(-1.031_893_1, 0.5),
        AddCube(0.0, 0.4, 0),
        Personal(28, CollisionRule::NoPair),
        Step(1),
        AddCube(0.0, 0.4, 0),
        AddCollider(18),
        CutSoft(0),
    ];
    planned_alike(&cubes, &edits, |upkeep| {
        for (_, soft) in upkeep.world.soft_bodies.iter() {
            let root = soft.root_body();
            let personal = upkeep.hooks.rules().personal(root);
            prop_assert_eq!(personal, CollisionRule::NoPair, "root {:?}", root);
        }
        Ok(())
    });
}

/// Found by `the_upkeep_sees_what_a_full_pass_sees`: a `NoResponse`
/// between the default dynamic group and a group with no member yet is
/// said by Rapier's groups until a soft body comes, then by the hook; the
/// upkeep, which watched nothing, planned again as the full pass does.
#[test]
fn the_first_soft_body_plans_a_default_group_rule_again() {
    use super::world::Edit::*;
    let cubes = [(-0.345, 0.4, 0), (0.0, 0.4, 0), (0.0, 0.4, 0)];
    let edits = [
        GroupRule(0, 2, CollisionRule::NoResponse),
        ProjectCollision(0, 0, 1),
        Step(1),
        AddSoft(0.0, 0.5),
        AddBody(0),
    ];
    planned_alike(&cubes, &edits, |_| Ok(()));
}

/// Found by `the_upkeep_sees_what_a_full_pass_sees`: a cut piece's copy of
/// a surface collider waits for a plan, and the plan of a few colliders
/// that gave way to a whole plan (a parent edit in the same step) dropped
/// it; the whole plan plans the colliders waiting too.
#[test]
fn a_whole_plan_in_place_of_a_partial_one_plans_the_colliders_waiting() {
    use super::world::Edit::*;
    let cubes = [(0.0, 0.4, 0); 6];
    let edits = [
        Personal(46, CollisionRule::Normal),
        AddSoft(0.0, 0.5),
        Personal(15, CollisionRule::NoPair),
        Step(1),
        AddBody(0),
        Parent(13, 0),
        CutSoft(0),
    ];
    planned_alike(&cubes, &edits, |_| Ok(()));
}

/// Found by `the_planner_changes_nothing_a_user_sees` once soft bodies
/// came in: a soft body cut in two pieces whose source's collider the
/// project removed before the step. The pieces' colliders are Rapier's
/// copies of the removed one, with what the crate wrote on it; they take
/// its project settings from the hooks' record of the source before the
/// cut, and are planned (the personal `Normal` their roots took keeps
/// their pair with each other, as with the planner off).
#[test]
fn copies_of_a_collider_removed_after_the_cut_are_planned() {
    use super::world::Edit::*;
    let cubes = [(0.534_796, 2.415_479, 1), (0.0, 0.4, 0), (0.0, 0.4, 0), (0.0, 0.4, 0), (0.0, 0.4, 0)];
    let edits = [
        AddSoft(-0.366_327_17, 2.360_961),
        AddBody(0),
        CutSoft(0),
        DefaultRule(CollisionRule::NoPair),
        AddCube(0.0, 0.4, 0),
        Step(1),
        Personal(25, CollisionRule::Normal),
        CutSoft(62),
        RemoveCollider(6),
        AddCollider(0),
        Kind(0, 0),
    ];
    planner_on_off_alike(&cubes, &edits);
}

/// Found by `the_planner_changes_nothing_a_user_sees` once soft bodies
/// were removed in the random worlds: a soft body cut and then removed
/// before the step. Its piece takes its rules from the hooks' record of it
/// (a personal `NoPair` on its root), and the piece's collider, a copy with
/// what the crate wrote on the source's, is planned as a copy, not taken
/// for a collider whose settings are the project's.
#[test]
fn a_piece_whose_source_was_removed_before_the_step_keeps_its_rules() {
    use super::world::Edit::*;
    let cubes = [(-1.275_033_1, 0.4, 0), (0.0, 0.4, 0), (0.0, 0.4, 0), (0.0, 0.4, 0), (0.0, 0.4, 0)];
    let edits = [
        AddTearable(0.0, 0.5),
        Personal(20, CollisionRule::NoPair),
        Step(1),
        CutSoft(0),
        DefaultRule(CollisionRule::NoResponse),
        ProjectSolver(0, 0, 0),
        AddTearable(0.0, 0.5),
        RemoveSoft(42),
        RemoveBody(9),
    ];
    planner_on_off_alike(&cubes, &edits);
    planned_alike(&cubes, &edits, |_| Ok(()));
}

/// Found by `the_upkeep_sees_what_a_full_pass_sees` at 2,048 cases: a
/// rule taken away in the step of an edit that plans everything (a group
/// table edit names no node) left what the crate wrote on the collider it
/// reached (a one-way surface's contact-modification flag). The rules no
/// longer reached it, so the look let it go, and the whole plan only reset
/// the colliders it still watched. Each row takes a rule of another kind
/// away that way (the one-way row is the one that failed; the others keep
/// an empty record, which the look keeps watching): the collider gets the
/// project's settings back, as in the full pass.
#[test]
fn a_rule_taken_away_with_a_global_edit_gives_the_collider_back() {
    use super::world::Edit::*;
    let global = || InSet(vec![], CollisionRule::Defer, CollisionRule::Defer, false);
    let rows: [(&str, Vec<Edit>, Edit); 4] = [
        ("one-way", vec![OneWay(1, 0)], OneWay(1, 3)),
        ("personal", vec![Personal(1, CollisionRule::NoPair)], Personal(1, CollisionRule::Defer)),
        ("specific", vec![Specific(1, 2, CollisionRule::NoContacts)], RemoveSpecific(1, 2)),
        (
            "group",
            vec![GroupRule(1, 2, CollisionRule::NoPair), Group(1, Some(1))],
            Group(1, None),
        ),
    ];
    for (what, give, take) in rows {
        let cubes = [(0.0, 0.4, 0); 3];
        let edits: Vec<Edit> = give.into_iter().chain([Step(1), take, global(), Step(1)]).collect();
        eprintln!("row: {what}");
        planned_alike(&cubes, &edits, |_| Ok(()));
    }
}

/// The world stepped through `edits` with the planner on and off: the
/// same poses, touching pairs and live pairs after every step.
fn planner_on_off_alike(cubes: &[(f32, f32, usize)], edits: &[Edit]) {
    let mut on = Run::new(cubes, true, true);
    let mut off = Run::new(cubes, false, true);
    in_lockstep(&mut on, &mut off, edits, |on, off| {
        prop_assert_eq!(on.poses(), off.poses(), "the worlds moved apart");
        prop_assert_eq!(on.touching(), off.touching(), "touching pairs differ");
        prop_assert_eq!(on.live(), off.live(), "live pairs differ");
        Ok(())
    })
    .unwrap();
}

/// Found by the random worlds' own check of pieces (torn, given a rule,
/// cut, all before a step): the rules of a body split twice before a step
/// are the ones it held when the hooks last saw it. The run follows before
/// each split, as its check does, so the body cut before the hooks saw it
/// at all is `soft::a_soft_body_cut_before_its_first_step_keeps_its_rule_on_both_sides`.
#[test]
fn a_soft_body_cut_before_the_hooks_saw_it_keeps_the_rules_given_to_its_root() {
    use super::world::Edit::*;
    let cubes = [(0.0, 0.4, 0); 4];
    let mut run = Run::new(&cubes, true, false);
    run.apply(&Step(1));
    let edits = [
        AddCollider(0),
        AddTearable(0.0, 0.5),
        TearSoft(0),
        Personal(39, CollisionRule::Normal),
        AddCube(0.0, 0.4, 0),
        CutSoft(9),
    ];
    // The run checks each piece of the cut against the source's rules.
    for edit in &edits {
        run.apply(edit);
    }
    run.apply(&Step(2));
}

/// Found by `the_planner_changes_nothing_a_user_sees` at 2,048 cases: a
/// one-way surface given to a fixed cube that touches another fixed cube
/// (a pair Rapier computes because the other is hooked, which gives it
/// every collision type). The crate wrote the contact-modification flag,
/// but a change of hook flags alone sets no change flag that Rapier's
/// narrow phase reads, and neither body moves, so the pair kept its
/// contacts, and its contact events. With the planner off the contacts
/// went. The first write of hook flags on a non-dynamic collider now nudges
/// its groups, as later writes did.
#[test]
fn a_one_way_given_to_a_fixed_cube_reaches_its_pair_at_once() {
    use super::world::Edit::*;
    let cubes = [
        (0.0, 0.4, 0),
        (-0.935_754_8, 0.4, 0),
        (-0.956_819, 0.4, 1),
        (0.0, 2.361_630_7, 2),
        (0.0, 0.4, 0),
        (0.0, 0.4, 0),
        (0.0, 0.4, 0),
    ];
    let edits = [
        AddTearable(0.0, 0.5),
        AddCube(0.0, 2.765_876_3, 2),
        Personal(34, CollisionRule::Normal),
        Step(1),
        ProjectTypes(0, 0),
        OneWay(9, 0),
    ];
    let mut on = Run::new(&cubes, true, true);
    let mut off = Run::new(&cubes, false, true);
    in_lockstep(&mut on, &mut off, &edits, |on, off| {
        prop_assert_eq!(on.poses(), off.poses(), "the locked worlds move alike");
        prop_assert_eq!(on.touching(), off.touching(), "touching pairs differ");
        Ok(())
    })
    .unwrap();
}

/// Found by a large level built from the docs: a plan's full pass for the
/// default groups (a group's rule with `DEFAULT_KINEMATIC`) was taken for
/// the hooks' own reasons to hook everything, which it never equals, so
/// every step planned every collider again for "hook settings". A world
/// that changes every step under such rules is what a whole plan every
/// step makes of it, and its whole plans name the changes that make them
/// (a new class, a class emptied), never the hooks' settings.
#[test]
fn default_group_rules_in_a_world_that_changes_every_step_are_kept_by_the_upkeep() {
    use CollisionRule::{NoPair, NoResponse};
    // Bodies: 0 the ground, 1 to 5 the cubes below (kinds: 0 dynamic, 1
    // kinematic, 2 fixed), each round's cube after them. Groups: 0 and 1
    // the default dynamic and kinematic ones, 2 and 3 the rule set's own.
    let cubes = [(-1.0, 0.6, 0), (0.0, 0.6, 2), (1.0, 0.6, 1), (0.5, 1.6, 0), (-0.5, 2.0, 2)];
    let mut edits = vec![
        Edit::GroupRule(2, 1, NoPair),
        Edit::GroupRule(3, 0, NoResponse),
        // A fixed pickup in group 2, a dynamic box in group 3: the
        // classes the rounds' cubes join.
        Edit::Group(2, Some(2)),
        Edit::Group(1, Some(3)),
        Edit::Step(1),
    ];
    for round in 0..16usize {
        let x = -1.2 + 0.15 * round as f32;
        let y = 0.6 + 0.4 * (round % 4) as f32;
        let (kind, group) = if round % 2 == 0 { (0, 3) } else { (2, 2) };
        edits.push(Edit::AddCube(x, y, kind));
        edits.push(Edit::Group(6 + round, Some(group)));
        if round >= 3 {
            edits.push(Edit::RemoveBody(6 + round - 3));
        }
        edits.push(Edit::Step(1));
    }
    if let Err(e) = upkeep_sees_what_a_full_pass_sees(&cubes, &edits) {
        panic!("{e}");
    }
    let mut run = Run::new(&cubes, true, false);
    let mut steps = 0;
    let mut whole = Vec::new();
    for edit in &edits {
        run.apply(edit);
        if matches!(edit, Edit::Step(_)) {
            let stats = run.hooks.stats();
            assert_eq!(stats.full_pass, Some(super::rules::FullPass::DefaultGroups), "{stats:?}");
            if steps > 0 {
                assert_ne!(stats.full_plan, Some(super::rules::PlanCause::HookSettings), "{stats:?}");
                // A cube in a class the plan has, and the oldest one out:
                // the plan of the changes alone, a few colliders.
                if stats.full_plan.is_some() || stats.planned_colliders > 4 {
                    whole.push((steps, stats.full_plan, stats.planned_colliders));
                }
            }
            steps += 1;
        }
    }
    assert!(
        whole.is_empty(),
        "steps that planned more than their changes (step, cause, colliders planned): {whole:?}"
    );
}
