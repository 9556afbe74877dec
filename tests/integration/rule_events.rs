//! Rule events (`docs/semantics.md`, "Rule events"): every kind, with its
//! cause and in its order, the same with the planner on and off; none when
//! nobody asks; and recording them changes no physics. (The live-pair
//! properties check in random worlds that each step's events, applied to
//! the pairs they told before, give the live pairs.)

use super::rapier::prelude::*;
use super::rules::{CollisionRule, RuleChange, RuleEvent, RuleHooks, Until};
use super::scenes::Scene;
use super::pose_bits;

use CollisionRule::*;

/// The events of a script of edits on a cube resting on the floor, one
/// list per step.
fn scripted(planner: bool) -> (Vec<Vec<RuleEvent>>, ColliderHandle, ColliderHandle) {
    let mut scene = Scene::new();
    // The floor lets Rapier see kinematic bodies, so that a retyped cube
    // keeps its pair.
    let floor = scene.floor;
    scene.world.colliders[floor].set_active_collision_types(ActiveCollisionTypes::all());
    let (body, cube) = scene.cube(0.0, 0.5);
    let ground = scene.ground;
    let mut hooks = RuleHooks::default();
    hooks.set_planner(planner);
    hooks.record_rule_events(true);
    let mut steps = Vec::new();
    let mut step = |hooks: &mut RuleHooks, scene: &mut Scene| {
        hooks.step(&mut scene.world);
        steps.push(hooks.drain_rule_events().collect::<Vec<_>>());
    };
    step(&mut hooks, &mut scene); // 0: created
    hooks.rules_mut().set_specific(body, ground, NoResponse);
    step(&mut hooks, &mut scene); // 1: edit
    assert!(hooks.set_pair_rule(&scene.world, cube, floor, Normal));
    step(&mut hooks, &mut scene); // 2: override
    hooks.force_recalculation(body);
    step(&mut hooks, &mut scene); // 3: forced
    hooks
        .rules_mut()
        .set_specific_until(body, ground, NoContacts, Until::steps(1).even_if_overlapping());
    step(&mut hooks, &mut scene); // 4: edit
    step(&mut hooks, &mut scene); // 5: expiry
    scene.world.bodies[body].set_body_type(RigidBodyType::KinematicPositionBased, true);
    step(&mut hooks, &mut scene); // 6: body type
    hooks.rules_mut().set_specific(body, ground, NoPair);
    step(&mut hooks, &mut scene); // 7: to NoPair
    hooks.rules_mut().remove_specific(body, ground);
    step(&mut hooks, &mut scene); // 8: created again
    scene.world.remove_collider(cube);
    step(&mut hooks, &mut scene); // 9: ended
    step(&mut hooks, &mut scene); // 10: nothing
    (steps, cube, floor)
}

#[test]
fn every_rule_event_comes_with_its_cause_in_its_step() {
    let (steps, cube, floor) = scripted(true);
    let (collider1, collider2) = if cube.into_raw_parts() < floor.into_raw_parts() { (cube, floor) } else { (floor, cube) };
    let created = |rule| RuleEvent::PairCreated { collider1, collider2, rule };
    let changed = |from, to, cause| RuleEvent::RuleChanged { collider1, collider2, from, to, cause };
    let expected = [
        vec![created(Normal)],
        vec![changed(Normal, NoResponse, RuleChange::Edit)],
        vec![changed(NoResponse, Normal, RuleChange::Override)],
        vec![changed(Normal, NoResponse, RuleChange::Recalculation)],
        vec![changed(NoResponse, NoContacts, RuleChange::Edit)],
        vec![changed(NoContacts, Normal, RuleChange::Expiry)],
        // Two non-dynamic bodies cannot respond (`docs/semantics.md`, section 5).
        vec![changed(Normal, NoResponse, RuleChange::BodyType)],
        vec![changed(NoResponse, NoPair, RuleChange::Edit)],
        vec![created(NoResponse)],
        vec![RuleEvent::PairEnded { collider1, collider2, rule: NoResponse }],
        vec![],
    ];
    for (i, (got, want)) in steps.iter().zip(&expected).enumerate() {
        assert_eq!(got, want, "the events of step {i}");
    }
    assert_eq!(steps.len(), expected.len());
}

#[test]
fn the_planner_changes_no_rule_event() {
    assert_eq!(scripted(true).0, scripted(false).0);
}

#[test]
fn nobody_asking_gets_no_events_and_recording_changes_no_physics() {
    // A pile with a ghost through it and a rule that ends; stepped with
    // and without recording, and recording switched off halfway.
    let run = |record: bool| {
        let mut scene = Scene::new();
        let mut ghost = None;
        for i in 0..12 {
            let (body, _) = scene.cube((i % 3) as f32 * 1.1 - 1.1, 0.5 + (i / 3) as f32 * 1.05);
            ghost.get_or_insert(body);
        }
        let ghost = ghost.expect("a cube");
        let mut hooks = RuleHooks::default();
        hooks.record_rule_events(record);
        hooks.rules_mut().set_personal(ghost, NoResponse);
        hooks
            .rules_mut()
            .set_specific_until(ghost, scene.ground, NoContacts, Until::seconds(0.5));
        let mut events = 0;
        for step in 0..120 {
            if step == 60 {
                hooks.record_rule_events(false);
            }
            hooks.step(&mut scene.world);
            events += hooks.drain_rule_events().count();
        }
        let poses: Vec<Vec<u32>> = scene.world.bodies.iter().map(|(_, b)| pose_bits(b.position())).collect();
        (poses, events)
    };
    let (quiet, none) = run(false);
    let (recorded, some) = run(true);
    assert_eq!(none, 0, "nobody asked: no events");
    assert!(some > 12, "recording gave the pile's events: {some}");
    assert_eq!(quiet, recorded, "recording changed the physics");
}
