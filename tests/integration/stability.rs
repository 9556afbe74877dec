//! Stability where methods fail, each with its measured figure (quoted in
//! `docs/stability.md`): a deep overlap switched from `NoResponse` to
//! `Normal`, a stack that ghosts pass through, and a heavy compound with
//! group rules.

use approx::abs_diff_eq;
use rapier_collision_rules::{CollisionRule, CollisionRuleSet, RuleError, RuleHooks};
use rapier3d::prelude::*;

#[path = "../../examples/common/overlap.rs"]
mod overlap;

#[path = "../../examples/common/soft_overlap.rs"]
mod soft_overlap;

// The floor is the stability example's, which gives plain Rapier its groups.
#[allow(dead_code)]
#[path = "../../examples/common/stack.rs"]
mod stack;

use overlap::{Switch, overlap};
use soft_overlap::{SoftSwitch, soft_overlap};
use stack::{GhostStack, ghost_stack};

#[test]
fn switching_a_deep_overlap_to_normal_separates_and_a_staged_switch_is_gentle() {
    let abrupt = overlap(0.5, Switch::Abrupt);
    let gentle = overlap(0.5, Switch::Staged);
    println!("peak separation speed: abrupt {abrupt:.2} m/s, staged {gentle:.2} m/s");
    assert!(abrupt > 0.1, "the overlap did not push apart: {abrupt} m/s");
    assert!(
        gentle < abrupt,
        "the staged switch was not gentler: {gentle} vs {abrupt} m/s"
    );
}

/// A rigid cube put into a soft block, `NoResponse` for a step and then
/// `Normal`, leaves it as under Rapier's own switch (groups that let the
/// block in a step later): the peak speeds agree within 1% at the depths
/// where the stability sweep once compared it with a reference that did
/// not switch at all (10% and 70%, `docs/stability.md`), and at 50%. The
/// only difference left is that Rapier's switch, which regroups the
/// block's surface, wakes the block a step earlier.
#[test]
fn a_rigid_cube_switched_into_a_soft_block_leaves_it_as_under_rapiers_own_switch() {
    for depth in [0.1, 0.5, 0.7] {
        let rapier = soft_overlap(depth, SoftSwitch::PlainGroups);
        let abrupt = soft_overlap(depth, SoftSwitch::Abrupt);
        let plain = soft_overlap(depth, SoftSwitch::Plain);
        println!(
            "depth {depth}: Rapier's switch {rapier:.4} m/s, the rules' {abrupt:.4} m/s, made overlapping {plain:.4} m/s"
        );
        assert!(
            (abrupt - rapier).abs() <= 0.01 * rapier + 0.005,
            "depth {depth}: the rules' switch peaks at {abrupt} m/s, Rapier's own at {rapier} m/s"
        );
    }
}

/// How ghosts are made in [`stack_drift`].
#[derive(Clone, Copy, PartialEq, Debug)]
enum Ghosts {
    None,
    /// Plain Rapier: solver groups that leave the stack out.
    RapierSolverGroups,
    /// This crate: a group whose rule with everything is `NoResponse`.
    GroupRule,
    /// This crate: a personal `NoResponse` (the hook decides).
    Personal,
}

/// A 20-box stack, with five ghosts falling through it; returns the stack's
/// largest horizontal drift after 3 s.
fn stack_drift(ghosts: Ghosts) -> f32 {
    let GhostStack {
        mut world,
        boxes,
        ghosts: made,
        mut rules,
        spirits,
        ..
    } = ghost_stack(IntegrationParameters::default().dt, ghosts != Ghosts::None);
    for &(ghost, shape) in &made {
        match ghosts {
            Ghosts::RapierSolverGroups => {
                let bit = Group::from_bits_retain(2);
                let groups = InteractionGroups::new(bit, Group::NONE, InteractionTestMode::And);
                world.colliders[shape].set_solver_groups(groups);
            }
            Ghosts::GroupRule => rules.set_group(ghost, Some(spirits)),
            Ghosts::Personal => rules.set_personal(ghost, CollisionRule::NoResponse),
            Ghosts::None => {}
        }
    }
    let mut hooks = RuleHooks::new(rules);
    for _ in 0..180 {
        if ghosts == Ghosts::RapierSolverGroups {
            world.step();
        } else {
            hooks.step(&mut world);
        }
    }
    boxes
        .iter()
        .map(|&(b, _)| {
            let p = world.bodies[b].translation();
            (p.x * p.x + p.z * p.z).sqrt()
        })
        .fold(0.0, f32::max)
}

#[test]
fn ghosts_passing_through_a_stack_drift_it_as_plain_rapier_does() {
    let drift = [
        Ghosts::None,
        Ghosts::RapierSolverGroups,
        Ghosts::GroupRule,
        Ghosts::Personal,
    ]
    .map(stack_drift);
    println!(
        "20-box stack drift after 3 s: alone {:.4} m; ghosts by Rapier solver groups {:.4} m, \
         by a group rule {:.4} m, by a personal rule {:.4} m",
        drift[0], drift[1], drift[2], drift[3]
    );
    assert_eq!(
        drift[2], drift[1],
        "group-rule ghosts differ from Rapier's own solver groups"
    );
    for (what, d) in [
        ("solver-group", drift[1]),
        ("group-rule", drift[2]),
        ("personal", drift[3]),
    ] {
        assert!(d < 0.05, "the {what} ghosts toppled the stack: drift {d} m");
    }
}

#[test]
fn a_heavy_compound_with_group_rules_rests() -> Result<(), RuleError> {
    let mut world = PhysicsWorld::new();
    let ground =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)));
    world.insert_collider(ColliderBuilder::cuboid(20.0, 0.5, 20.0), Some(ground));
    // A heavy hull with a light mast jointed on top, overlapping it: masses
    // 16 and 0.16, a ratio of 100:1.
    let hull =
        world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.5, 0.0)));
    world.insert_collider(
        ColliderBuilder::cuboid(1.0, 0.5, 1.0).density(4.0),
        Some(hull),
    );
    let mast =
        world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 1.4, 0.0)));
    world.insert_collider(
        ColliderBuilder::cuboid(0.2, 0.5, 0.2).density(1.0),
        Some(mast),
    );
    let joint = FixedJointBuilder::new()
        .local_anchor1(Vector::new(0.0, 0.9, 0.0))
        .local_anchor2(Vector::ZERO);
    world.insert_impulse_joint(hull, mast, joint);
    let mut rules = CollisionRuleSet::default();
    let ship = rules.create_group();
    rules.set_group_rule(ship, ship, CollisionRule::NoPair);
    rules.set_group(hull, Some(ship));
    rules.set_parent(mast, hull)?;
    let ratio = world.bodies[hull].mass() / world.bodies[mast].mass();
    let mut hooks = RuleHooks::new(rules);
    let mut peak: f32 = 0.0;
    for step in 0..240 {
        hooks.step(&mut world);
        if step > 60 {
            peak = peak.max(world.bodies[mast].linvel().length());
        }
    }
    let (hy, my) = (
        world.bodies[hull].translation().y,
        world.bodies[mast].translation().y,
    );
    println!(
        "mass ratio {ratio:.0}:1; rest at hull y = {hy:.3}, mast y = {my:.3}; peak mast speed after 1 s {peak:.4} m/s"
    );
    assert!(ratio > 90.0, "mass ratio {ratio}");
    assert!(
        abs_diff_eq!(hy, 0.5, epsilon = 0.02) && abs_diff_eq!(my, 1.4, epsilon = 0.05),
        "did not rest: hull {hy}, mast {my}"
    );
    assert!(peak < 0.05, "the compound jitters: {peak} m/s");
    Ok(())
}
