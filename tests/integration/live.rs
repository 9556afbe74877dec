//! Random edit sequences while stepping real worlds: after every step, each
//! live pair's rule equals a fresh `resolve` (policy `OnChange`, no
//! overrides), every pair in Rapier's graph is known to the hooks, and no
//! live pair names a removed collider. And the planner changes nothing a
//! user can see: the same world stepped with the planner on and off has the
//! same live pairs with the same rules, and the same touching pairs. And the
//! upkeep that looks only at what the rules reach sees what a full pass over
//! every collider sees.

use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed, TestCaseError};
use rapier_collision_rules::CollisionRule;

use crate::world::{Edit, GROUPS, KINDS, LAYERS, Run, TYPES};

fn rule() -> impl Strategy<Value = CollisionRule> {
    proptest::sample::select(CollisionRule::ALL.to_vec())
}

fn edit() -> impl Strategy<Value = Edit> {
    let n = 0..64usize;
    prop_oneof![
        3 => (n.clone(), rule()).prop_map(|(x, r)| Edit::Personal(x, r)),
        2 => (n.clone(), proptest::option::of(0..GROUPS)).prop_map(|(x, g)| Edit::Group(x, g)),
        3 => (n.clone(), n.clone(), rule()).prop_map(|(x, y, r)| Edit::Specific(x, y, r)),
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
        6 => (1..4usize).prop_map(Edit::Step),
    ]
}

proptest! {
    #![proptest_config(Config {
        cases: 256,
        rng_seed: RngSeed::Fixed(0x11fe_9a11),
        failure_persistence: None,
        ..Config::default()
    })]

    #[test]
    fn live_pairs_follow_every_edit(
        cubes in proptest::collection::vec((-1.5f32..1.5, 0.4f32..3.0, 0..KINDS.len()), 2..8),
        edits in proptest::collection::vec(edit(), 1..40),
    ) {
        let mut run = Run::new(&cubes, true, false);
        run.apply(&Edit::Step(1));
        for edit in &edits {
            run.apply(edit);
        }
        run.apply(&Edit::Step(2));
    }

    #[test]
    fn the_planner_changes_nothing_a_user_sees(
        cubes in proptest::collection::vec((-1.5f32..1.5, 0.4f32..3.0, 0..KINDS.len()), 2..8),
        edits in proptest::collection::vec(edit(), 1..40),
    ) {
        let mut on = Run::new(&cubes, true, true);
        let mut off = Run::new(&cubes, false, true);
        in_lockstep(&mut on, &mut off, &edits, |on, off| {
            prop_assert_eq!(on.live(), off.live(), "live pairs differ");
            prop_assert_eq!(on.touching(), off.touching(), "touching pairs differ");
            Ok(())
        })?;
        prop_assert!(off.hooks.hooked_count() >= on.hooks.hooked_count());
    }

    #[test]
    fn the_upkeep_sees_what_a_full_pass_sees(
        cubes in proptest::collection::vec((-1.5f32..1.5, 0.4f32..3.0, 0..KINDS.len()), 2..8),
        edits in proptest::collection::vec(edit(), 1..40),
    ) {
        let mut upkeep = Run::new(&cubes, true, false);
        let mut oracle = Run::new(&cubes, true, false);
        oracle.hooks.set_exhaustive(true);
        in_lockstep(&mut upkeep, &mut oracle, &edits, |upkeep, oracle| {
            prop_assert_eq!(upkeep.live(), oracle.live(), "live pairs differ");
            prop_assert_eq!(upkeep.touching(), oracle.touching(), "touching pairs differ");
            prop_assert_eq!(upkeep.known(), oracle.known_among(&upkeep.known()), "known pairs differ");
            prop_assert_eq!(upkeep.poses(), oracle.poses(), "the worlds moved apart");
            Ok(())
        })?;
    }
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
