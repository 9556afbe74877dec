//! What the rules reach, and only that, is watched, planned and hooked: a
//! specific rule is Rapier groups or hooks its cheaper side, a world without rules is left as
//! Rapier has it, and the full passes say why they run.

use super::rapier::prelude::*;
use super::rules::{CollisionGroup, CollisionRule, FullPass, Node, PlanCause, RuleHooks};

use super::scenes::Scene;
use super::{at, cuboid};
use CollisionRule::*;

fn hooked(scene: &Scene, collider: ColliderHandle) -> bool {
    !scene.world.colliders[collider].active_hooks().is_empty()
}

/// The ghost's collision (`NoPair`) or solver (`NoResponse`) groups, and
/// the floor's, as the planner left them.
fn groups(scene: &Scene, rule: CollisionRule, collider: ColliderHandle) -> InteractionGroups {
    let collider = &scene.world.colliders[collider];
    if rule == NoPair {
        collider.collision_groups()
    } else {
        collider.solver_groups()
    }
}

#[test]
fn a_specific_rule_is_rapier_groups_or_hooks_the_ghost_not_the_floor_it_names() {
    // Either side may hold the entry: the floor is a hub, the ghost is not.
    // NoPair and NoResponse are Rapier groups (a bit of the ghost's own,
    // which the floor leaves out); NoContacts has no group form and hooks
    // the ghost.
    for rule in [NoResponse, NoPair, NoContacts] {
        for floor_names_ghost in [false, true] {
            let mut scene = Scene::new();
            let (ghost, g) = scene.cube(0.0, 2.0);
            let mut others = Vec::new();
            for i in 0..4 {
                others.push(scene.cube(2.0 + 1.5 * i as f32, 0.5).1);
            }
            let mut hooks = RuleHooks::default();
            if floor_names_ghost {
                hooks.rules_mut().set_specific(scene.ground, ghost, rule);
            } else {
                hooks.rules_mut().set_specific(ghost, scene.ground, rule);
            }
            let mut paired = false;
            for _ in 0..60 {
                hooks.step(&mut scene.world);
                paired |= hooks.pair_rule(&scene.world, g, scene.floor) == Some(rule);
            }
            let stats = hooks.stats();
            let case = format!("{rule:?}, floor names ghost: {floor_names_ghost}");
            let by_groups = rule != NoContacts;
            assert!(
                hooked(&scene, g) != by_groups && !hooked(&scene, scene.floor),
                "{case}: ghost hooked {}, floor hooked {}",
                hooked(&scene, g),
                hooked(&scene, scene.floor)
            );
            assert_eq!(
                stats.hooked_colliders,
                usize::from(!by_groups),
                "{case}: {stats:?}"
            );
            if by_groups {
                let (mine, floor) = (groups(&scene, rule, g), groups(&scene, rule, scene.floor));
                assert!(
                    mine.memberships.bits().count_ones() == 1
                        && mine.filter == Group::ALL
                        && floor.memberships == Group::ALL
                        && floor.filter == Group::ALL - mine.memberships,
                    "{case}: ghost {mine:?}, floor {floor:?}"
                );
            }
            assert!(others.iter().all(|&c| !hooked(&scene, c)));
            assert!(
                paired == (rule != NoPair) && scene.y(ghost) < -1.0,
                "{case}: the ghost passed: y = {}, paired {paired}",
                scene.y(ghost)
            );
        }
    }
}

#[test]
fn entries_about_one_floor_share_one_bit_and_every_ghost_passes() {
    // 40 ghosts, each with its own NoResponse entry about the floor: the
    // entries about the floor share one bit, which every ghost carries and
    // the floor leaves out; nothing is hooked.
    let mut scene = Scene::new();
    let ghosts: Vec<_> = (0..40)
        .map(|i| scene.cube((i % 8) as f32 * 1.5 - 6.0, 2.0 + (i / 8) as f32 * 1.5))
        .collect();
    let mut hooks = RuleHooks::default();
    for &(ghost, _) in &ghosts {
        hooks
            .rules_mut()
            .set_specific(ghost, scene.ground, NoResponse);
    }
    for _ in 0..90 {
        hooks.step(&mut scene.world);
    }
    let by_bits = ghosts.iter().filter(|&&(_, g)| !hooked(&scene, g)).count();
    assert_eq!(by_bits, 40, "ghosts decided by Rapier's groups");
    let floor = scene.world.colliders[scene.floor].solver_groups();
    assert_eq!(
        (Group::ALL - floor.filter).bits().count_ones(),
        1,
        "the floor leaves out one bit: {floor:?}"
    );
    for &(ghost, g) in &ghosts {
        assert!(
            scene.y(ghost) < -1.0,
            "ghost {g:?} (hooked {}) passed the floor: y = {}",
            hooked(&scene, g),
            scene.y(ghost)
        );
    }
}

#[test]
fn entries_of_one_car_share_its_bit_and_it_drives_through_every_pickup() {
    // A car with a NoResponse entry about each of eight fixed pickups: the
    // entries share the car's one bit, which every pickup leaves out;
    // nothing is hooked (`architecture.md`, "The planner"). The car drives
    // through the five in its path. A bit is a star: a ghost's entry about
    // one of the pickups cannot make the ghost a carrier of the car's bit
    // (it would pass every pickup), so a second ghost with the same entry,
    // over another pickup, rests on it; a cube with no rule rests on a
    // third.
    let mut scene = Scene::new();
    let (car, car_collider) = scene.cube(-14.0, 0.5);
    let mut pickup = |x: f32| {
        let body = scene
            .world
            .insert_body(RigidBodyBuilder::fixed().translation(at(x, 0.5)));
        let collider = scene
            .world
            .insert_collider(cuboid(0.5, 0.5, 0.5), Some(body));
        (body, collider)
    };
    let in_path: Vec<_> = [-11.0, -9.0, -7.0, -5.0, -3.0].map(&mut pickup).into();
    let far: Vec<_> = [10.0, 14.0, 18.0].map(&mut pickup).into();
    let (g1, _) = scene.cube(10.0, 3.0);
    let (g2, _) = scene.cube(14.0, 3.0);
    let (bystander, _) = scene.cube(18.0, 3.0);
    let mut hooks = RuleHooks::default();
    for &(p, _) in in_path.iter().chain(&far) {
        hooks.rules_mut().set_specific(car, p, NoResponse);
    }
    hooks.step(&mut scene.world);
    let unhooked = in_path
        .iter()
        .chain(&far)
        .filter(|&&(_, c)| !hooked(&scene, c))
        .count();
    assert!(
        !hooked(&scene, car_collider) && unhooked == 8,
        "car hooked {}, {unhooked} of 8 pickups not hooked: {:?}",
        hooked(&scene, car_collider),
        hooks.stats()
    );
    let bit = scene.world.colliders[car_collider].solver_groups().memberships;
    assert_eq!(bit.bits().count_ones(), 1, "the car carries one bit: {bit:?}");
    for &(_, c) in in_path.iter().chain(&far) {
        let filter = scene.world.colliders[c].solver_groups().filter;
        assert_eq!(filter, Group::ALL - bit, "a pickup leaves out the car's bit");
    }
    for ghost in [g1, g2] {
        hooks.rules_mut().set_specific(ghost, far[0].0, NoResponse);
    }
    for _ in 0..150 {
        let mut v = scene.world.bodies[car].linvel();
        v.x = 6.0;
        scene.world.bodies[car].set_linvel(v, true);
        hooks.step(&mut scene.world);
    }
    assert!(
        scene.x(car) > 0.0 && (scene.y(car) - 0.5).abs() < 0.05,
        "the car drove through the pickups: x = {}, y = {}",
        scene.x(car),
        scene.y(car)
    );
    assert!(!hooked(&scene, car_collider), "the car stays unhooked");
    assert!(
        scene.y(g1) < 0.7,
        "the first ghost passed its pickup: y = {}",
        scene.y(g1)
    );
    for (name, body) in [("the second ghost", g2), ("the cube", bystander)] {
        assert!(
            scene.y(body) > 1.4,
            "{name} rests on its pickup: y = {}",
            scene.y(body)
        );
    }
}

#[test]
fn past_the_free_bits_the_ghosts_are_hooked_and_every_one_passes() {
    // 40 ghosts side by side, each with a NoResponse entry about a pad of
    // its own above the floor: each pad's entries take a bit while they last
    // (32 with no other bits in use), the rest of the ghosts are hooked.
    // Every ghost falls through its pad onto the floor.
    let mut scene = Scene::new();
    let mut ghosts = Vec::new();
    let mut hooks = RuleHooks::default();
    for i in 0..40 {
        let x = i as f32 * 1.01 - 19.7;
        let (ghost, g) = scene.cube(x, 3.0);
        let pad = scene
            .world
            .insert_body(RigidBodyBuilder::fixed().translation(at(x, 1.5)));
        scene
            .world
            .insert_collider(cuboid(0.45, 0.05, 0.45), Some(pad));
        hooks.rules_mut().set_specific(ghost, pad, NoResponse);
        ghosts.push((ghost, g));
    }
    for _ in 0..90 {
        hooks.step(&mut scene.world);
    }
    let by_bits = ghosts.iter().filter(|&&(_, g)| !hooked(&scene, g)).count();
    assert_eq!(by_bits, 32, "ghosts whose pad's entry has a bit");
    assert!(!hooked(&scene, scene.floor), "the floor is not hooked");
    for &(ghost, g) in &ghosts {
        assert!(
            scene.y(ghost) < 1.0,
            "ghost {g:?} (hooked {}) did not pass its pad: y = {}",
            hooked(&scene, g),
            scene.y(ghost)
        );
    }
}

#[test]
fn a_ghost_with_the_projects_own_groups_is_hooked_instead() {
    // The project narrows the ghost's collision groups: no single group
    // test says both, so the entry is the hook's.
    let mut scene = Scene::new();
    let (ghost, g) = scene.cube(0.0, 2.0);
    let own = InteractionGroups::new(Group::GROUP_1, Group::ALL, InteractionTestMode::And);
    scene.world.colliders[g].set_solver_groups(own);
    let mut hooks = RuleHooks::default();
    hooks
        .rules_mut()
        .set_specific(ghost, scene.ground, NoResponse);
    for _ in 0..60 {
        hooks.step(&mut scene.world);
    }
    assert!(hooked(&scene, g) && !hooked(&scene, scene.floor));
    assert_eq!(
        scene.world.colliders[g].solver_groups(),
        own,
        "the project's groups stay"
    );
    assert!(
        scene.y(ghost) < -1.0,
        "the ghost passed: y = {}",
        scene.y(ghost)
    );
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
    assert_eq!(hooks.stats().tracked_pairs, 0, "no pair is hooked: {:?}", hooks.stats());
    assert_eq!(
        hooks.pair_rule(&scene.world, cubes[0].1, scene.floor),
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
        // Found by a large level built from the docs: a plan's full pass
        // for the default groups differed from the hooks' own reasons
        // (none), so every step planned every collider again.
        for step in 1..4 {
            hooks.step(&mut scene.world);
            let stats = hooks.stats();
            assert_eq!(stats.full_pass, expected, "{name}, step {step}: {stats:?}");
            assert_eq!(
                (stats.full_plan, stats.planned_colliders),
                (None, 0),
                "{name}, step {step}: nothing changed, nothing planned: {stats:?}"
            );
        }
    }
}

#[test]
fn a_shared_table_copied_every_step_plans_only_when_it_changes() {
    // One table for several worlds (as the Bevy adapter keeps it): copying
    // it unchanged before each step is no edit.
    let mut scene = Scene::new();
    let (a, ca) = scene.cube(0.0, 0.5);
    let (w, _) = scene.cube(3.0, 0.5);
    let mut table = super::rules::GroupTable::default();
    let (ghosts, walls) = (table.create_group(), table.create_group());
    table.set_group_rule(ghosts, walls, NoResponse);
    let mut hooks = RuleHooks::default();
    hooks.rules_mut().copy_group_table(&table, Normal);
    hooks.rules_mut().set_group(a, Some(ghosts));
    hooks.rules_mut().set_group(w, Some(walls));
    hooks.step(&mut scene.world);
    assert!(hooks.stats().planned_colliders > 0, "the first step plans both");
    for _ in 0..5 {
        hooks.rules_mut().copy_group_table(&table, Normal);
        hooks.step(&mut scene.world);
        assert_eq!(
            hooks.stats().planned_colliders,
            0,
            "an unchanged copy planned {} colliders",
            hooks.stats().planned_colliders
        );
    }
    table.set_group_rule(ghosts, walls, NoPair);
    hooks.rules_mut().copy_group_table(&table, Normal);
    hooks.step(&mut scene.world);
    assert_eq!(hooks.rules().group_rule(walls, ghosts), NoPair);
    assert_ne!(
        scene.world.colliders[ca].collision_groups(),
        InteractionGroups::all(),
        "the changed table reached Rapier's groups"
    );
}

#[test]
fn when_its_last_entry_ends_a_personal_rule_decides_the_colliders_again() {
    // A cube's personal NoResponse is Rapier's solver groups while no entry
    // reaches it; a NoContacts entry about it (no group form) hooks it.
    // When the object holding the entry is removed, the decision's end is
    // the cube's change: its colliders are planned again and end as a
    // whole plan makes them, in a world built without that object.
    let settings = |scene: &Scene, c: ColliderHandle| {
        let co = &scene.world.colliders[c];
        (co.collision_groups(), co.solver_groups(), co.active_hooks())
    };
    let mut scene = Scene::new();
    let (cube, c) = scene.cube(0.0, 0.5);
    let (other, _) = scene.cube(3.0, 0.5);
    let mut hooks = RuleHooks::default();
    hooks.rules_mut().set_personal(cube, NoResponse);
    hooks.rules_mut().set_specific(other, cube, NoContacts);
    for _ in 0..5 {
        hooks.step(&mut scene.world);
    }
    assert!(hooked(&scene, c), "an entry hooks the cube: {:?}", settings(&scene, c));
    scene.world.remove_body(other);
    hooks.step(&mut scene.world);

    let mut alone = Scene::new();
    let (cube_alone, c_alone) = alone.cube(0.0, 0.5);
    let mut fresh = RuleHooks::default();
    fresh.rules_mut().set_personal(cube_alone, NoResponse);
    fresh.step(&mut alone.world);
    assert_eq!(
        settings(&scene, c),
        settings(&alone, c_alone),
        "the cube after the entry ended, and in a world without it"
    );
    assert!(!hooked(&scene, c), "{:?}", hooks.stats());
}

#[test]
fn a_project_change_on_a_reached_collider_the_crate_never_wrote_is_noticed() {
    // The ghost carries the bit of its entry about the floor; the cube it
    // falls onto is reached by the rules (a group of its own) but keeps
    // Rapier's defaults, so the crate writes nothing on it. The project
    // then narrows the cube's filter, leaving out that very bit: the bit
    // must move, or the ghost passes through the cube it should land on.
    let mut scene = Scene::new();
    let (cube, c) = scene.cube(0.0, 0.5);
    let (ghost, g) = scene.cube(0.0, 4.0);
    let mut hooks = RuleHooks::default();
    let group = hooks.rules_mut().create_group();
    hooks.rules_mut().set_group(cube, Some(group));
    hooks.rules_mut().set_specific(ghost, scene.ground, NoPair);
    hooks.step(&mut scene.world);
    let bit = scene.world.colliders[g].collision_groups().memberships;
    assert_eq!(bit.bits().count_ones(), 1, "the ghost carries a bit: {bit:?}");
    assert_eq!(
        scene.world.colliders[c].collision_groups(),
        InteractionGroups::all(),
        "the crate wrote nothing on the cube"
    );
    let narrowed = InteractionGroups::new(Group::ALL, Group::ALL - bit, InteractionTestMode::And);
    scene.world.colliders[c].set_collision_groups(narrowed);
    for _ in 0..90 {
        hooks.step(&mut scene.world);
    }
    assert_eq!(
        scene.world.colliders[c].collision_groups(),
        narrowed,
        "the project's setting stays"
    );
    assert!(
        scene.y(ghost) > 0.9,
        "the ghost lands on the cube: y = {}, its groups {:?}",
        scene.y(ghost),
        scene.world.colliders[g].collision_groups()
    );
}

#[test]
fn a_floor_that_names_its_ghosts_decides_each_new_or_changed_entry_alone() {
    // The floor's record names every ghost (`set_specific(ground, ghost,
    // NoPair)`): a ghost's bit, which the floor leaves out. An entry added
    // or changed on that record is decided by itself: the floor, whose bit
    // stays, is not planned again, and the ghost's pairs follow the rule.
    let mut scene = Scene::new();
    let mut hooks = RuleHooks::default();
    for i in 0..3 {
        let (ghost, _) = scene.cube(3.0 * i as f32, 3.0);
        hooks.rules_mut().set_specific(scene.ground, ghost, NoPair);
    }
    hooks.step(&mut scene.world);
    let (sinker, _) = scene.cube(-3.0, 0.6);
    hooks.rules_mut().set_specific(scene.ground, sinker, NoPair);
    hooks.step(&mut scene.world);
    assert_eq!(hooks.stats().planned_colliders, 1, "the new ghost alone: {:?}", hooks.stats());
    let (lander, _) = scene.cube(-6.0, 3.0);
    hooks.rules_mut().set_specific(scene.ground, lander, NoPair);
    hooks.step(&mut scene.world);
    // The lander falls towards the floor it would pass through; its entry
    // becomes Normal before it gets there.
    hooks.rules_mut().set_specific(scene.ground, lander, Normal);
    hooks.step(&mut scene.world);
    assert_eq!(hooks.stats().planned_colliders, 1, "the changed ghost alone: {:?}", hooks.stats());
    // A hooked entry (NoContacts has no group form) on a live pair: the
    // cube sinks into the floor until its entry becomes Normal, which the
    // pair's cached rule must follow.
    let (wader, _) = scene.cube(-9.0, 0.5);
    hooks.rules_mut().set_specific(scene.ground, wader, NoContacts);
    for _ in 0..10 {
        hooks.step(&mut scene.world);
    }
    let waded = scene.y(wader);
    assert!(waded < 0.45, "NoContacts lets the cube sink: y = {waded}");
    hooks.rules_mut().set_specific(scene.ground, wader, Normal);
    for _ in 0..90 {
        hooks.step(&mut scene.world);
    }
    let (sunk, landed, stood) = (scene.y(sinker), scene.y(lander), scene.y(wader));
    assert!(sunk < -1.0, "the ghost passes through the floor: y = {sunk}");
    assert!((landed - 0.5).abs() < 0.05, "the lander rests on the floor: y = {landed}");
    assert!((stood - 0.5).abs() < 0.05, "Normal pushes the cube back up: y = {stood}");
}

#[test]
fn so_many_removals_in_one_step_that_their_log_gives_up_plan_everything() {
    // A cube is a ghost through its parent's group; the parent goes in the
    // same step as 4,100 bodies a holder's entries name, whose removals
    // log more than the change log keeps. The cube's chain changed all
    // the same: it must stop being a ghost and land on the floor.
    let mut scene = Scene::new();
    let mut hooks = RuleHooks::default();
    let rules = hooks.rules_mut();
    let (ghosts, floors) = (rules.create_group(), rules.create_group());
    rules.set_group_rule(ghosts, floors, NoPair);
    rules.set_group(scene.ground, Some(floors));
    let parent = scene.world.insert_body(RigidBodyBuilder::fixed().translation(at(50.0, 5.0)));
    let (cube, _) = scene.cube(0.0, 1.5);
    let holder = scene.world.insert_body(RigidBodyBuilder::fixed().translation(at(-50.0, 5.0)));
    let named: Vec<RigidBodyHandle> = (0..4_100)
        .map(|_| scene.world.insert_body(RigidBodyBuilder::fixed().translation(at(-50.0, 9.0))))
        .collect();
    let rules = hooks.rules_mut();
    rules.set_group(parent, Some(ghosts));
    rules.set_parent(cube, parent).expect("no cycle");
    for &n in &named {
        rules.set_specific(holder, n, NoPair);
    }
    hooks.step(&mut scene.world);
    for n in named.into_iter().chain([parent]) {
        scene.world.remove_body(n);
    }
    for _ in 0..60 {
        hooks.step(&mut scene.world);
    }
    let y = scene.y(cube);
    assert!((y - 0.5).abs() < 0.05, "the cube lands on the floor: y = {y}");
}

#[test]
fn a_rider_parented_under_an_entry_is_planned_alone_as_a_whole_plan_plans_it() {
    // The floor's record says `NoPair` about a dynamic platform (a bit the
    // platform carries). A rider that carries a bit of its own (its own
    // entry about a far block) is parented to the platform: now on the
    // floor entry's side, it cannot carry both bits, so that entry is
    // checked again, as a whole plan checks every entry it meets. Only the
    // colliders the edit reaches are planned, their settings are a whole
    // plan's (the oracle's, which plans everything every step), and the
    // rider passes through the floor.
    let build = |oracle: bool| {
        let (mut scene, mut hooks) = scene_and_hooks(oracle);
        let (platform, _) = scene.cube(6.0, 3.0);
        let (rider, _) = scene.cube(0.0, 1.5);
        let block = scene.world.insert_body(RigidBodyBuilder::fixed().translation(at(-20.0, 0.5)));
        scene.world.insert_collider(cuboid(0.5, 0.5, 0.5), Some(block));
        // Props the entries reach, which a whole plan would plan again.
        for i in 0..8 {
            let (prop, _) = scene.cube(-8.0 - 2.0 * i as f32, 0.5);
            hooks.rules_mut().set_specific(prop, block, NoPair);
        }
        hooks.rules_mut().set_specific(scene.ground, platform, NoPair);
        hooks.rules_mut().set_specific(rider, block, NoPair);
        (scene, hooks, platform, rider)
    };
    let (mut scene, mut hooks, platform, rider) = build(false);
    let (mut whole, mut oracle, _, _) = build(true);
    for _ in 0..60 {
        hooks.step(&mut scene.world);
        oracle.step(&mut whole.world);
    }
    let landed = scene.y(rider);
    assert!((landed - 0.5).abs() < 0.05, "the rider stands on the floor: y = {landed}");
    hooks.rules_mut().set_parent(rider, platform).expect("no cycle");
    oracle.rules_mut().set_parent(rider, platform).expect("no cycle");
    hooks.step(&mut scene.world);
    oracle.step(&mut whole.world);
    let stats = hooks.stats();
    assert_eq!(stats.full_plan, None, "a parent edit plans what it reaches: {stats:?}");
    assert!(
        stats.planned_colliders <= 3,
        "the rider, the platform and the floor at most: {stats:?}"
    );
    assert_eq!(settings(&scene), settings(&whole), "the settings a whole plan writes");
    for _ in 0..60 {
        hooks.step(&mut scene.world);
    }
    let fell = scene.y(rider);
    assert!(fell < -1.0, "under the platform, the rider passes through the floor: y = {fell}");
}

/// Found by `the_upkeep_sees_what_a_full_pass_sees_under_churn` at sixteen
/// times its cases: a one-way surface removed in a step that plans
/// everything (here the project says its settings changed) left the
/// contact-modification flag the crate wrote on the surface's collider,
/// which no rule reached any more, so no plan wrote it again.
#[test]
fn a_collider_whose_last_rule_goes_in_a_whole_plans_step_gets_rapiers_defaults_back() {
    use super::rules::OneWay;
    let modifies = |scene: &Scene, c: ColliderHandle| {
        scene.world.colliders[c]
            .active_hooks()
            .contains(ActiveHooks::MODIFY_SOLVER_CONTACTS)
    };
    for whole in [false, true] {
        let mut scene = Scene::new();
        let (_, surface) = scene.cube(0.0, 0.5);
        let mut hooks = RuleHooks::default();
        hooks.rules_mut().set_one_way(surface, Some(OneWay::new(at(0.0, 1.0))));
        hooks.step(&mut scene.world);
        assert!(modifies(&scene, surface), "whole plan {whole}: the one-way surface is modified");
        hooks.rules_mut().set_one_way(surface, None);
        if whole {
            hooks.project_settings_changed();
        }
        hooks.step(&mut scene.world);
        let stats = hooks.stats();
        assert_eq!(stats.full_plan.is_some(), whole, "{stats:?}");
        assert!(
            !modifies(&scene, surface),
            "whole plan {whole}: no rule is left, nor the flag: {:?}",
            scene.world.colliders[surface].active_hooks()
        );
    }
}

#[test]
fn ghosts_that_come_and_go_with_a_personal_rule_are_planned_alone() {
    // A spawner: every step a ghost (a body whose personal rule is
    // `NoResponse`, which Rapier's solver groups say) comes and the oldest
    // goes, among boxes with a personal `Normal` on their bodies. Whether
    // the groups can say a ghost's rule depends on every chain's first
    // personal rule (a shallower `Normal` would override it): more ghosts
    // and boxes at the same depths change nothing of that, so each step
    // plans the new ghost alone, with the settings a whole plan writes
    // (the oracle's, which plans everything every step). The last row
    // gives a box's collider a `Normal` of its own, shallower than the
    // ghosts' rule: that plans everything, as documented.
    let build = |oracle: bool| {
        let (mut scene, mut hooks) = scene_and_hooks(oracle);
        for i in 0..6 {
            let (crate_body, _) = scene.cube(-6.0 + 2.0 * i as f32, 0.5);
            hooks.rules_mut().set_personal(crate_body, Normal);
        }
        (scene, hooks)
    };
    let (mut scene, mut hooks) = build(false);
    let (mut whole, mut oracle) = build(true);
    let mut ghosts = std::collections::VecDeque::new();
    for step in 0..40 {
        let x = -4.0 + 0.2 * step as f32;
        let (ghost, _) = scene.cube(x, 3.0);
        let (twin, _) = whole.cube(x, 3.0);
        assert_eq!(ghost, twin, "the two worlds name the same bodies");
        hooks.rules_mut().set_personal(ghost, NoResponse);
        oracle.rules_mut().set_personal(twin, NoResponse);
        ghosts.push_back(ghost);
        if ghosts.len() > 10 {
            let oldest = ghosts.pop_front().expect("a ghost");
            scene.world.remove_body(oldest);
            whole.world.remove_body(oldest);
        }
        hooks.step(&mut scene.world);
        oracle.step(&mut whole.world);
        let stats = hooks.stats();
        if step > 0 {
            assert_eq!(stats.full_plan, None, "step {step}: the ghost is planned alone: {stats:?}");
            assert!(stats.planned_colliders <= 1, "step {step}: the new ghost only: {stats:?}");
        }
        assert_eq!(settings(&scene), settings(&whole), "step {step}: a whole plan's settings");
    }
    for _ in 0..60 {
        hooks.step(&mut scene.world);
    }
    let heights: Vec<f32> = ghosts.iter().map(|&g| scene.y(g)).collect();
    assert!(
        heights.iter().all(|&y| y < -1.0),
        "the ghosts fell through the floor: heights {heights:?}"
    );
    // A box's collider says `Normal` itself: shallower than every ghost's
    // rule, it overrides them, and only a whole plan follows that.
    let (_, collider) = scene.cube(8.0, 0.5);
    hooks.rules_mut().set_personal(collider, Normal);
    hooks.step(&mut scene.world);
    let stats = hooks.stats();
    assert_eq!(stats.full_plan, Some(PlanCause::NewClass), "{stats:?}");
}

#[test]
fn an_entry_about_a_ghost_reaches_through_its_personal_rule() {
    // A ghost's personal `NoPair` is said by Rapier's groups while no entry
    // reaches it. An entry (`Normal` with the floor), on the ghost's record
    // or on the floor's, must then hook it: the ghost lands, as with a
    // whole plan every step, and the other ghosts fall through the floor.
    for ghost_owns in [true, false] {
        let build = |oracle: bool| {
            let (mut scene, mut hooks) = scene_and_hooks(oracle);
            let mut ghosts = Vec::new();
            for i in 0..4 {
                let (ghost, _) = scene.cube(-3.0 + 2.0 * i as f32, 2.0);
                hooks.rules_mut().set_personal(ghost, NoPair);
                ghosts.push(ghost);
            }
            (scene, hooks, ghosts)
        };
        let (mut scene, mut hooks, ghosts) = build(false);
        let (mut whole, mut oracle, _) = build(true);
        hooks.step(&mut scene.world);
        oracle.step(&mut whole.world);
        let (ghost, floor) = (Node::from(ghosts[0]), Node::from(scene.ground));
        let (owner, subject) = if ghost_owns { (ghost, floor) } else { (floor, ghost) };
        for rules in [hooks.rules_mut(), oracle.rules_mut()] {
            rules.set_specific(owner, subject, Normal);
        }
        for _ in 0..90 {
            hooks.step(&mut scene.world);
            oracle.step(&mut whole.world);
        }
        let (landed, fell) = (scene.y(ghosts[0]), scene.y(ghosts[1]));
        let side = if ghost_owns { "the ghost's record" } else { "the floor's record" };
        assert!((landed - 0.5).abs() < 0.05, "{side}: the ghost lands: y = {landed}");
        assert!(fell < -1.0, "{side}: the others fall through the floor: y = {fell}");
        assert_eq!(landed, whole.y(ghosts[0]), "{side}: as with a whole plan every step");
    }
}

/// Every collider's groups and hook flags, in handle order: what two plans
/// wrote, to compare them.
fn settings(scene: &Scene) -> Vec<(ColliderHandle, InteractionGroups, InteractionGroups, ActiveHooks)> {
    let mut all: Vec<_> = scene
        .world
        .colliders
        .iter()
        .map(|(h, c)| (h, c.collision_groups(), c.solver_groups(), c.active_hooks()))
        .collect();
    all.sort_by_key(|s| s.0.into_raw_parts());
    all
}

#[test]
fn a_ghost_is_native_again_once_the_owner_of_the_entry_about_it_is_removed() {
    // Found by a review of the planner: an entry owned by a body without
    // colliders (a spawner's frame) about a ghost, or about the platform a
    // ghost rides, hooks the ghost (its personal `NoResponse` is native
    // only while no entry reaches it). Removing the owner removes the
    // entry, and the ghost's colliders are planned again: the settings are
    // a whole plan's after each step, in both rows.
    for riding in [false, true] {
        let build = |oracle: bool| {
            let (mut scene, mut hooks) = scene_and_hooks(oracle);
            let (ghost, _) = scene.cube(0.0, 2.0);
            let (other, _) = scene.cube(3.0, 2.0);
            let platform = scene.world.insert_body(RigidBodyBuilder::kinematic_position_based());
            let owner = scene.world.insert_body(RigidBodyBuilder::fixed());
            let rules = hooks.rules_mut();
            for g in [ghost, other] {
                rules.set_personal(g, NoResponse);
            }
            if riding {
                rules.set_parent(ghost, platform).expect("no cycle");
            }
            (scene, hooks, ghost, platform, owner)
        };
        let (mut scene, mut hooks, ghost, platform, owner) = build(false);
        let (mut whole, mut oracle, ..) = build(true);
        let subject = if riding { platform } else { ghost };
        let row = if riding { "about the platform" } else { "about the ghost" };
        hooks.step(&mut scene.world);
        oracle.step(&mut whole.world);
        hooks.rules_mut().set_specific(owner, subject, Normal);
        oracle.rules_mut().set_specific(owner, subject, Normal);
        hooks.step(&mut scene.world);
        oracle.step(&mut whole.world);
        assert_eq!(settings(&scene), settings(&whole), "{row}: with the entry");
        scene.world.remove_body(owner);
        whole.world.remove_body(owner);
        hooks.step(&mut scene.world);
        oracle.step(&mut whole.world);
        assert_eq!(settings(&scene), settings(&whole), "{row}: once its owner is gone");
    }
}

/// A scene and its hooks; with `oracle`, the test oracle's hooks, which
/// plan everything every step: a whole plan's settings to compare with.
fn scene_and_hooks(oracle: bool) -> (Scene, RuleHooks) {
    let mut hooks = RuleHooks::default();
    hooks.set_exhaustive(oracle);
    (Scene::new(), hooks)
}

/// The README's advice for a group of fixed colliders (coins) that should
/// not meet the level's other fixed colliders, checked: both entries keep
/// every collider native (Rapier's type test sets the coins apart); the
/// `DEFAULT_KINEMATIC` entry alone gives the default groups settings of
/// their own (found by a large level built from the docs, at many times
/// Rapier's step). Either way the coin and the floor never meet.
#[test]
fn a_group_of_fixed_colliders_set_apart_from_the_level_says_both_entries() {
    for (both, expected) in [(true, None), (false, Some(FullPass::DefaultGroups))] {
        let mut scene = Scene::new();
        let body = scene
            .world
            .insert_body(RigidBodyBuilder::fixed().translation(at(2.0, 0.0)));
        let coin = scene.world.insert_collider(cuboid(0.3, 0.3, 0.3), Some(body));
        let mut hooks = RuleHooks::default();
        let coins = hooks.rules_mut().create_group();
        hooks.rules_mut().set_group(body, Some(coins));
        hooks
            .rules_mut()
            .set_group_rule(coins, CollisionGroup::DEFAULT_KINEMATIC, NoPair);
        if both {
            hooks.rules_mut().set_group_rule(coins, coins, NoPair);
        }
        for _ in 0..5 {
            hooks.step(&mut scene.world);
        }
        let stats = hooks.stats();
        assert_eq!(stats.full_pass, expected, "both entries: {both}: {stats:?}");
        let met = scene
            .world
            .narrow_phase
            .contact_pair(coin, scene.floor)
            .is_some_and(|pair| pair.manifolds().iter().any(|m| !m.points.is_empty()));
        assert!(!met, "both entries: {both}: the coin met the floor");
        assert_eq!(
            hooks.pair_rule(&scene.world, coin, scene.floor),
            None,
            "both entries: {both}: no live pair"
        );
    }
}

/// Found by a Bevy trial from the docs: a collider no rule names any more
/// (the other side of an entry whose owner was removed, both sides of an
/// entry removed, a body whose parent link went) stayed watched and
/// `Reach::Planned` for good, drawn as planned by the debug view, and a
/// world whose rules were all gone never went back to stepping as plain
/// Rapier. The plan of a few colliders now lets such a collider go, as a
/// whole plan does.
#[test]
fn a_collider_no_rule_names_any_more_is_let_go() {
    use super::rules::Reach;
    for how in ["owner removed", "entry removed", "entry removed, whole plan", "parent link removed"] {
        let mut scene = Scene::new();
        let (_, wall) = scene.cube(2.0, 0.5);
        let (ghost, shot) = scene.cube(0.0, 0.5);
        let mut hooks = RuleHooks::default();
        if how == "parent link removed" {
            let (parent, _) = scene.cube(-3.0, 0.5);
            for body in [parent, ghost] {
                scene.world.bodies[body].set_body_type(RigidBodyType::KinematicPositionBased, true);
            }
            hooks.rules_mut().set_parent(ghost, parent).expect("a link");
            for _ in 0..3 {
                hooks.step(&mut scene.world);
            }
            hooks.rules_mut().remove_parent(ghost);
            hooks.step(&mut scene.world);
            scene.world.remove_body(parent);
        } else {
            hooks.rules_mut().set_specific(ghost, wall, NoPair);
            for _ in 0..3 {
                hooks.step(&mut scene.world);
            }
            if how == "owner removed" {
                scene.world.remove_body(ghost);
            } else {
                hooks.rules_mut().remove_specific(ghost, wall);
                if how == "entry removed, whole plan" {
                    hooks.project_settings_changed();
                }
            }
        }
        for _ in 0..3 {
            hooks.step(&mut scene.world);
        }
        let stats = hooks.stats();
        assert_eq!(
            (stats.watched_colliders, stats.watched_bodies, stats.planned_colliders),
            (0, 0, 0),
            "{how}: {stats:?}"
        );
        for (what, c) in [("wall", wall), ("ghost", shot)] {
            assert_eq!(hooks.reach(c), Reach::Unreached, "{how}: the {what}");
            if let Some(collider) = scene.world.colliders.get(c) {
                let groups = (collider.collision_groups(), collider.solver_groups());
                let all = InteractionGroups::all();
                assert_eq!(groups, (all, all), "{how}: the {what} has Rapier's groups back");
            }
        }
    }
}
