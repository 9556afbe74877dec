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
    let created = |rule| RuleEvent::PairStarted { collider1, collider2, rule };
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

/// A cube on the floor made kinematic, with Rapier's default collision
/// types (which drop a kinematic-fixed pair): its pair's rule becomes
/// `NoPair` for the body type, whether Rapier drops the pair (the planner
/// leaves the pair to Rapier) or the hook answers it. Found by a trial: the
/// planner's world read `PairEnded`, the hooked one `RuleChanged`.
#[test]
fn a_pair_rapier_drops_for_a_body_type_reads_alike_with_the_planner_on_and_off() {
    let events = |planner: bool| {
        let mut scene = Scene::new();
        let (body, cube) = scene.cube(0.0, 0.5);
        let floor = scene.floor;
        let mut hooks = RuleHooks::default();
        hooks.set_planner(planner);
        hooks.record_rule_events(true);
        hooks.step(&mut scene.world);
        hooks.drain_rule_events().for_each(drop);
        scene.world.bodies[body].set_body_type(RigidBodyType::KinematicPositionBased, true);
        hooks.step(&mut scene.world);
        let events: Vec<RuleEvent> = hooks.drain_rule_events().collect();
        let (collider1, collider2) = if cube.into_raw_parts() < floor.into_raw_parts() { (cube, floor) } else { (floor, cube) };
        (events, collider1, collider2)
    };
    for planner in [true, false] {
        let (got, collider1, collider2) = events(planner);
        let want = vec![RuleEvent::RuleChanged {
            collider1,
            collider2,
            from: Normal,
            to: NoPair,
            cause: RuleChange::BodyType,
        }];
        assert_eq!(got, want, "planner {planner}: the events of the step the cube became kinematic");
    }
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

#[test]
fn a_handler_gets_the_events_drain_would_give() {
    let run = |push: bool| {
        let mut scene = Scene::new();
        let (body, _) = scene.cube(0.0, 0.5);
        let (other, _) = scene.cube(0.0, 1.55);
        let mut hooks = RuleHooks::default();
        let (sender, receiver) = std::sync::mpsc::channel();
        if push {
            hooks.set_rule_event_handler(sender);
        } else {
            hooks.record_rule_events(true);
        }
        hooks.rules_mut().set_specific_until(body, scene.ground, NoResponse, Until::steps(3).even_if_overlapping());
        hooks.rules_mut().set_specific(other, body, NoContacts);
        let mut events = Vec::new();
        for step in 0..40 {
            if step == 20 {
                hooks.rules_mut().remove_specific(other, body);
            }
            hooks.step(&mut scene.world);
            events.extend(hooks.drain_rule_events());
            events.extend(receiver.try_iter());
        }
        events
    };
    let (pulled, pushed) = (run(false), run(true));
    assert!(pulled.len() >= 4, "the script gave its events: {pulled:?}");
    assert_eq!(pushed, pulled, "the handler got what drain gives, in its order");
}

#[test]
fn a_bare_pipeline_with_joints_counts_no_jointed_pair_as_live() {
    // A box held in the floor by a joint with contacts off: Rapier keeps
    // the pair from colliding; it is not live.
    let run = |with_joints: bool| {
        let mut scene = Scene::new();
        let (body, _) = scene.cube(0.0, 0.3);
        let joint = FixedJointBuilder::new().contacts_enabled(false);
        scene.world.impulse_joints.insert(scene.ground, body, joint, true);
        let mut hooks = RuleHooks::default();
        hooks.rules_mut().set_specific(body, scene.ground, NoResponse);
        hooks.record_rule_events(true);
        let mut events = Vec::new();
        for _ in 0..10 {
            let w = &mut scene.world;
            hooks.prepare(&w.bodies, &mut w.colliders);
            hooks.freeze_manifolds(&w.narrow_phase);
            hooks.wake_edited(&mut w.islands, &mut w.bodies);
            w.step_with_events(&hooks, &());
            if with_joints {
                hooks.after_step_with_joints(&w.narrow_phase, &w.bodies, &w.colliders, &w.impulse_joints, &w.multibody_joints);
            } else {
                hooks.after_step(&w.narrow_phase, &w.bodies, &w.colliders);
            }
            events.extend(hooks.drain_rule_events());
        }
        events
    };
    let with = run(true);
    assert!(with.is_empty(), "the jointed pair is not live: {with:?}");
    // Without the joint sets the same pair reads as live: what the method
    // is for (`docs/semantics.md`, "Rule events").
    let without = run(false);
    assert!(!without.is_empty(), "without the joints the pair read as live");
}
