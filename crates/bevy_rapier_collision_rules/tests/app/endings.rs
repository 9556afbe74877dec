//! Rules with an end in components (`docs/bevy.md`, "Rules with an end"):
//! a `SpecificRules` entry with an end holds for its frames or its
//! simulated time, frames with no step count nothing, editing the
//! component's other entries does not restart the count, and the entry
//! leaves the component in the frame it ends.

use std::time::Duration;

use CollisionRule::*;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_rapier::prelude::*;
use bevy_rapier_collision_rules::prelude::*;

use super::scene::{Sim, ball, floor};

/// A ball resting on the floor, and the floor.
fn resting(sim: &mut Sim) -> (Entity, Entity) {
    let f = sim.spawn(floor());
    let b = sim.spawn(ball(0.0, 0.25));
    sim.run(30);
    (b, f)
}

fn until(sim: &Sim, ball: Entity, floor: Entity) -> Option<Until> {
    sim.app
        .world()
        .get::<SpecificRules>(ball)
        .and_then(|r| r.until(floor))
}

/// The frames (counted from the one after the entry was given) in which
/// the entry was still in the component after the frame ran.
fn frames_held(sim: &mut Sim, ball: Entity, floor: Entity, limit: usize) -> usize {
    (1..=limit)
        .take_while(|_| {
            sim.run(1);
            until(sim, ball, floor).is_some()
        })
        .count()
}

#[test]
fn an_entry_with_an_end_holds_its_frames_then_leaves_the_component() {
    let mut sim = Sim::new();
    let (b, f) = resting(&mut sim);
    let y0 = sim.y(b);
    let end = Until::steps(10).even_if_overlapping();
    sim.entity_mut(b)
        .insert(SpecificRules::new().with_until(f, NoResponse, end));
    let held = frames_held(&mut sim, b, f, 40);
    // Ten steps with the rule; it ends before the eleventh, in that frame.
    assert_eq!(held, 10, "the entry held {held} frames");
    let sunk = y0 - sim.y(b);
    assert!(
        sunk > 0.05,
        "the ball sank into the floor while it held: {sunk} m"
    );
    let rules = sim.app.world().get::<SpecificRules>(b).unwrap();
    assert!(
        rules.is_empty(),
        "the ended entry left the component: {rules:?}"
    );
    let ball_collider = b;
    assert_eq!(
        sim.pair_rule(ball_collider, f),
        Some(Normal),
        "the pair took the rules' rule again"
    );
}

#[test]
fn editing_other_entries_does_not_restart_the_count() {
    let mut sim = Sim::new();
    let (b, f) = resting(&mut sim);
    let other = sim.spawn(ball(3.0, 0.25));
    let end = Until::steps(10).even_if_overlapping();
    sim.entity_mut(b)
        .insert(SpecificRules::new().with_until(f, NoResponse, end));
    sim.run(4);
    sim.app
        .world_mut()
        .get_mut::<SpecificRules>(b)
        .unwrap()
        .set(other, NoPair);
    let held = frames_held(&mut sim, b, f, 40);
    assert_eq!(
        held, 6,
        "the entry held {held} more frames after the edit, 6 expected"
    );
    let rules = sim.app.world().get::<SpecificRules>(b).unwrap();
    assert_eq!(rules.get(other), NoPair, "the other entry stays");
    // Setting the entry again does restart it.
    sim.app
        .world_mut()
        .get_mut::<SpecificRules>(b)
        .unwrap()
        .set_until(f, NoResponse, end);
    let held = frames_held(&mut sim, b, f, 40);
    assert_eq!(held, 10, "the entry set again held {held} frames");
    // And set again the same while it runs: from the start again (a
    // drop-through pressed twice).
    sim.app
        .world_mut()
        .get_mut::<SpecificRules>(b)
        .unwrap()
        .set_until(f, NoResponse, end);
    sim.run(4);
    sim.app
        .world_mut()
        .get_mut::<SpecificRules>(b)
        .unwrap()
        .set_until(f, NoResponse, end);
    let held = frames_held(&mut sim, b, f, 40);
    assert_eq!(
        held, 10,
        "the entry set again while it ran held {held} more frames, 10 expected"
    );
}

#[test]
fn frames_with_no_step_count_nothing() {
    let mut sim = Sim::new();
    let (b, f) = resting(&mut sim);
    let context = sim.context();
    let end = Until::seconds(10.0 / 60.0).even_if_overlapping();
    sim.entity_mut(b)
        .insert(SpecificRules::new().with_until(f, NoResponse, end));
    sim.run(4);
    sim.app
        .world_mut()
        .get_mut::<RapierConfiguration>(context)
        .unwrap()
        .physics_pipeline_active = false;
    sim.run(30);
    assert!(until(&sim, b, f).is_some(), "a paused game held the entry");
    sim.app
        .world_mut()
        .get_mut::<RapierConfiguration>(context)
        .unwrap()
        .physics_pipeline_active = true;
    let held = frames_held(&mut sim, b, f, 40);
    assert_eq!(
        held, 6,
        "after the pause the entry held {held} more frames, 6 expected"
    );
}

#[test]
fn a_time_counts_the_simulated_time_of_each_frame() {
    // A quarter of a second: 15 frames of one 1/60 s step (substeps or
    // not), 5 frames of three catch-up steps each.
    let cases = [
        (
            TimestepMode::Fixed {
                dt: 1.0 / 60.0,
                substeps: 3,
            },
            1.0 / 60.0,
            15,
        ),
        (
            TimestepMode::Interpolated {
                dt: 1.0 / 60.0,
                time_scale: 1.0,
                substeps: 1,
            },
            1.0 / 20.0,
            5,
        ),
        (
            TimestepMode::Variable {
                max_dt: 1.0 / 30.0,
                time_scale: 0.5,
                substeps: 2,
            },
            1.0 / 60.0,
            30,
        ),
    ];
    for (mode, frame, frames) in cases {
        let mut sim = Sim::new();
        sim.app
            .insert_resource(mode)
            .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f32(
                frame,
            )));
        let (b, f) = resting(&mut sim);
        let end = Until::seconds(0.25).even_if_overlapping();
        sim.entity_mut(b)
            .insert(SpecificRules::new().with_until(f, NoResponse, end));
        let held = frames_held(&mut sim, b, f, 100);
        assert_eq!(
            held, frames,
            "{mode:?}: the entry held {held} frames, {frames} expected"
        );
    }
}
