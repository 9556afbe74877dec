//! bevy_rapier's stepping modes: substeps and catch-up steps run several
//! Rapier steps between the rules' preparation and their after-step.

use std::time::Duration;

use CollisionRule::*;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_rapier::prelude::*;
use bevy_rapier_collision_rules::prelude::*;

use super::scene::{Sim, ball, cuboid, fell_through, floor, rests, vect};

fn modes() -> [(TimestepMode, f32); 4] {
    [
        (
            TimestepMode::Variable {
                max_dt: 1.0 / 30.0,
                time_scale: 1.0,
                substeps: 4,
            },
            1.0 / 45.0,
        ),
        (
            TimestepMode::Fixed {
                dt: 1.0 / 60.0,
                substeps: 3,
            },
            1.0 / 60.0,
        ),
        // Three steps per frame to catch up with the clock.
        (
            TimestepMode::Interpolated {
                dt: 1.0 / 60.0,
                time_scale: 1.0,
                substeps: 1,
            },
            1.0 / 20.0,
        ),
        (
            TimestepMode::Interpolated {
                dt: 1.0 / 60.0,
                time_scale: 1.0,
                substeps: 2,
            },
            1.0 / 30.0,
        ),
    ]
}

#[test]
fn every_rule_holds_with_substeps_and_catch_up_steps() {
    for (mode, frame) in modes() {
        let mut sim = Sim::new();
        sim.app
            .insert_resource(mode)
            .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f32(
                frame,
            )));
        let f = sim.spawn(floor());
        // A wall across the bullet's path, beyond the balls.
        let wall = sim.spawn((Transform::from_xyz(4.5, 3.0, 0.0), cuboid(0.1, 3.0, 5.0)));
        let lands = sim.spawn(ball(-2.0, 1.0));
        let ghost = sim.spawn((ball(0.0, 1.0), SpecificRules::new().with(f, NoContacts)));
        let through = sim.spawn((ball(2.0, 1.0), PersonalRule(NoResponse)));
        // A fast ball across the wall, above the balls: NoPair with it.
        let bullet = sim.spawn((
            Transform::from_xyz(-4.0, 3.0, 0.0),
            RigidBody::Dynamic,
            Collider::ball(0.1),
            GravityScale(0.0),
            Ccd::enabled(),
            Velocity::linear(vect(60.0, 0.0, 0.0)),
            SpecificRules::new().with(wall, NoPair),
        ));
        let frames = (2.0 / frame) as usize;
        sim.run(frames);
        let case = format!("{mode:?}, frames of {frame:.4} s");
        assert!(rests(sim.y(lands)), "{case}: y = {}", sim.y(lands));
        assert!(
            fell_through(sim.y(ghost)),
            "{case}: ghost y = {}",
            sim.y(ghost)
        );
        assert!(
            fell_through(sim.y(through)),
            "{case}: NoResponse y = {}",
            sim.y(through)
        );
        let x = sim.at(bullet).x;
        assert!(x > 10.0, "{case}: the bullet crossed the wall: x = {x}");
        assert_eq!(
            sim.pair_rule(ghost, f),
            None,
            "{case}: the ghost's pair ended once it fell away"
        );
    }
}

#[test]
fn in_the_fixed_schedule_edits_and_removals_are_not_missed() {
    let mut sim = Sim::with_plugins(
        RapierPhysicsPlugin::<CollisionRulesHooks>::default().in_fixed_schedule(),
        CollisionRulesPlugin::default().in_fixed_schedule(),
    );
    // A fixed schedule at 10 Hz runs once every six frames of 1/60 s.
    sim.app
        .insert_resource(Time::<Fixed>::from_hz(10.0))
        .insert_resource(TimestepMode::Fixed {
            dt: 0.1,
            substeps: 1,
        });
    let f = sim.spawn(floor());
    let ghost = sim.spawn((ball(0.0, 1.0), SpecificRules::new().with(f, NoContacts)));
    let late = sim.spawn((ball(1.0, 2.0), PersonalRule(NoPair)));
    // Removed in a frame in which the fixed schedule does not run, which
    // is kept for the next one that does.
    sim.run(8);
    sim.entity_mut(late).remove::<PersonalRule>();
    sim.run(150);
    assert!(fell_through(sim.y(ghost)), "ghost y = {}", sim.y(ghost));
    assert!(
        rests(sim.y(late)),
        "the removal reached the rules: y = {}",
        sim.y(late)
    );
}
