//! What the rules reach, and only that, is watched, planned and hooked: a
//! specific rule hooks its cheaper side, a world without rules is left as
//! Rapier has it, and the full passes say why they run.

use super::rapier::prelude::*;
use super::rules::{CollisionGroup, CollisionRule, FullPass, RuleHooks};

use super::scenes::Scene;
use CollisionRule::*;

fn hooked(scene: &Scene, collider: ColliderHandle) -> bool {
    !scene.world.colliders[collider].active_hooks().is_empty()
}

#[test]
fn a_specific_rule_hooks_the_ghost_not_the_floor_it_names() {
    // Either side may hold the entry: the floor is a hub, the ghost is not.
    for floor_names_ghost in [false, true] {
        let mut scene = Scene::new();
        let (ghost, g) = scene.cube(0.0, 2.0);
        let mut others = Vec::new();
        for i in 0..4 {
            others.push(scene.cube(2.0 + 1.5 * i as f32, 0.5).1);
        }
        let mut hooks = RuleHooks::default();
        if floor_names_ghost {
            hooks
                .rules_mut()
                .set_specific(scene.ground, ghost, NoResponse);
        } else {
            hooks
                .rules_mut()
                .set_specific(ghost, scene.ground, NoResponse);
        }
        let mut paired = false;
        for _ in 0..60 {
            hooks.step(&mut scene.world);
            paired |= hooks.pair_rule(g, scene.floor) == Some(NoResponse);
        }
        let stats = hooks.stats();
        assert!(
            hooked(&scene, g) && !hooked(&scene, scene.floor),
            "floor names ghost: {floor_names_ghost}: ghost hooked {}, floor hooked {}",
            hooked(&scene, g),
            hooked(&scene, scene.floor)
        );
        assert_eq!(stats.hooked_colliders, 1, "{stats:?}");
        assert!(others.iter().all(|&c| !hooked(&scene, c)));
        assert!(
            paired && scene.y(ghost) < -1.0,
            "the ghost passed: y = {}, paired {paired}",
            scene.y(ghost)
        );
    }
}

#[test]
fn a_world_without_rules_is_left_as_rapier_has_it() {
    let mut scene = Scene::new();
    let cubes: Vec<_> = (0..5).map(|i| scene.cube(i as f32 * 1.5, 0.5)).collect();
    let mut hooks = RuleHooks::default();
    for _ in 0..30 {
        hooks.step(&mut scene.world);
    }
    let stats = hooks.stats();
    assert_eq!(
        (
            stats.watched_colliders,
            stats.watched_bodies,
            stats.hooked_colliders
        ),
        (0, 0, 0),
        "{stats:?}"
    );
    for (handle, collider) in scene.world.colliders.iter() {
        assert!(
            collider.active_hooks().is_empty()
                && collider.collision_groups() == InteractionGroups::all()
                && collider.solver_groups() == InteractionGroups::all()
                && collider.active_collision_types() == ActiveCollisionTypes::default(),
            "{handle:?} was configured"
        );
    }
    assert_eq!(hooks.pairs().count(), 0, "no pair is hooked");
    assert_eq!(
        hooks.pair_rule_in(&scene.world, cubes[0].1, scene.floor),
        Some(Normal),
        "Rapier's pair, asked on demand"
    );
}

/// A setting, how to make it, and the full pass it should cause.
type Case = (&'static str, fn(&mut RuleHooks), Option<FullPass>);

#[test]
fn full_passes_say_why_they_run() {
    let cases: [Case; 5] = [
        ("nothing", |_| {}, None),
        (
            "a rule on the default dynamic group",
            |h| {
                let d = CollisionGroup::DEFAULT_DYNAMIC;
                h.rules_mut().set_group_rule(d, d, NoResponse);
            },
            Some(FullPass::DefaultGroups),
        ),
        (
            "a default rule of NoResponse",
            |h| h.rules_mut().set_default_rule(NoResponse),
            Some(FullPass::DefaultGroups),
        ),
        (
            "a calculator",
            |h| h.set_calculator(|ctx| ctx.default_rule()),
            Some(FullPass::Calculator),
        ),
        (
            "the planner off",
            |h| h.set_planner(false),
            Some(FullPass::PlannerOff),
        ),
    ];
    for (name, setup, expected) in cases {
        let mut scene = Scene::new();
        let (body, _) = scene.cube(0.0, 0.5);
        let mut hooks = RuleHooks::default();
        hooks.rules_mut().set_personal(body, NoResponse);
        setup(&mut hooks);
        hooks.step(&mut scene.world);
        let stats = hooks.stats();
        assert_eq!(stats.full_pass, expected, "{name}: {stats:?}");
        let all = scene.world.colliders.len();
        if expected.is_some() {
            assert_eq!(stats.watched_colliders, all, "{name}: {stats:?}");
        } else {
            assert_eq!(stats.watched_colliders, 1, "{name}: {stats:?}");
        }
    }
}
