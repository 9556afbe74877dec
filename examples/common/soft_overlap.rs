//! A rigid cube put into a settled soft block by a share of their width,
//! switched from `NoResponse` to `Normal`: the measurement shared by
//! `examples/stability.rs` (the sweep over the depth) and
//! `tests/integration/stability.rs` (the depths where it was once thought
//! to differ from Rapier's own switch).

use rapier_collision_rules::{CollisionRule, RuleHooks};
use rapier3d::prelude::*;

/// A soft block (4x4x4 particles, as in `soft_rest`) settled on a floor for
/// a second, then a rigid unit cube put `depth` (a share of their width)
/// into it along x and switched from `NoResponse` to `Normal` as `switch`
/// says (plain: made overlapping, no rules); returns the cube's peak speed
/// (m/s), step to step, over two seconds. A soft-rigid `NoResponse` pair
/// has no contacts (`docs/semantics.md`, "Soft bodies"), so the staged
/// switch separates them by hand while their boxes overlap.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SoftSwitch {
    /// Plain Rapier: made overlapping, no rules.
    Plain,
    /// Plain Rapier: the block's surface in a group of its own, which the
    /// cube's collision groups leave out for the first step, then let in:
    /// Rapier's own abrupt switch.
    PlainGroups,
    /// `NoResponse`, switched to `Normal` after one step.
    Abrupt,
    /// `NoResponse` while their boxes overlap, separated by hand 1 cm a
    /// step, then `Normal`.
    Staged,
}

pub fn soft_overlap(depth: f32, switch: SoftSwitch) -> f32 {
    let mut world = PhysicsWorld::new();
    let ground =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)));
    world.insert_collider(ColliderBuilder::cuboid(20.0, 0.5, 20.0), Some(ground));
    let block = SoftBodyBuilder::cuboid(Vector::new(0.0, 0.55, 0.0), Vector::splat(0.5), 4, 4, 4)
        .cell_model(SoftBodyCellModel::Corotational)
        .softness(SpringCoefficients::new(30.0, 1.0));
    let block = world.insert_soft_body(block);
    let root = world.soft_bodies[block].root_body();
    let mut hooks = RuleHooks::default();
    for _ in 0..60 {
        hooks.step(&mut world);
    }
    // The block's right face: its particles and their radius.
    let right = |world: &PhysicsWorld| {
        let body = &world.soft_bodies[block];
        let x = body
            .particle_positions()
            .map(|p| p.x)
            .fold(f32::MIN, f32::max);
        x + body.particle_radius()
    };
    let x = right(&world) + 0.5 - depth;
    let cube = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(x, 0.5, 0.0)));
    let box_collider = world.insert_collider(ColliderBuilder::cuboid(0.5, 0.5, 0.5), Some(cube));
    match switch {
        SoftSwitch::Plain => {}
        SoftSwitch::PlainGroups => {
            // The block's surface in group 2, which the cube's filter leaves
            // out (the cube still meets the floor).
            let surface: Vec<ColliderHandle> = world.soft_bodies[block]
                .meshes()
                .map(|m| m.collider())
                .collect();
            let block_group =
                InteractionGroups::new(Group::GROUP_2, Group::ALL, InteractionTestMode::And);
            for collider in surface {
                world.colliders[collider].set_collision_groups(block_group);
            }
            let apart = InteractionGroups::new(
                Group::GROUP_1,
                Group::ALL - Group::GROUP_2,
                InteractionTestMode::And,
            );
            world.colliders[box_collider].set_collision_groups(apart);
        }
        SoftSwitch::Abrupt | SoftSwitch::Staged => {
            hooks
                .rules_mut()
                .set_specific(cube, root, CollisionRule::NoResponse);
        }
    }
    hooks.step(&mut world);
    match switch {
        SoftSwitch::PlainGroups => {
            world.colliders[box_collider].set_collision_groups(InteractionGroups::all());
        }
        SoftSwitch::Abrupt => hooks
            .rules_mut()
            .set_specific(cube, root, CollisionRule::Normal),
        _ => {}
    }
    let dt = world.integration_parameters.dt;
    let mut peak: f32 = 0.0;
    for _ in 0..120 {
        let before = world.bodies[cube].translation();
        if switch == SoftSwitch::Staged {
            let cube_left = world.colliders[box_collider].compute_aabb().mins.x;
            if cube_left < right(&world) {
                world.bodies[cube].set_translation(before + Vector::new(0.01, 0.0, 0.0), true);
            } else {
                hooks
                    .rules_mut()
                    .set_specific(cube, root, CollisionRule::Normal);
            }
        }
        hooks.step(&mut world);
        peak = peak.max((world.bodies[cube].translation() - before).length() / dt);
    }
    peak
}
