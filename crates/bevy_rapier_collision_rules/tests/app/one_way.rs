//! A one-way platform as a component (`docs/semantics.md`, "One-way
//! surfaces"): a ball thrown up from below passes and lands on top;
//! without the component the platform stops it from below.

use bevy::prelude::*;
use bevy_rapier::prelude::*;
use bevy_rapier_collision_rules::prelude::*;

use crate::scene::{Sim, cuboid, vect};

/// Throws a ball up from under a platform at height 2 (a one-way surface
/// if `one_way`); returns the highest it reached and where it ended.
fn thrown_up(one_way: bool) -> (f32, f32) {
    let mut sim = Sim::new();
    sim.spawn(crate::scene::floor());
    let platform = sim.spawn((Transform::from_xyz(0.0, 2.0, 0.0), cuboid(2.0, 0.1, 2.0)));
    if one_way {
        sim.entity_mut(platform)
            .insert(OneWaySurface(OneWay::new(vect(0.0, 1.0, 0.0))));
    }
    let ball = sim.spawn((
        Transform::from_xyz(0.0, 0.5, 0.0),
        RigidBody::Dynamic,
        Collider::ball(0.25),
        Velocity::linear(vect(0.0, 8.0, 0.0)),
    ));
    let heights: Vec<f32> = sim.track(ball, 150).iter().map(|at| at.y).collect();
    let highest = heights.iter().copied().fold(f32::MIN, f32::max);
    (highest, *heights.last().expect("frames"))
}

#[test]
fn a_one_way_surface_component_lets_a_ball_up_through_and_holds_it_on_top() {
    let (highest, y) = thrown_up(true);
    assert!(
        highest > 2.5,
        "the ball went up through the platform: highest {highest}"
    );
    assert!(
        (y - 2.35).abs() < 0.03,
        "the ball rests on the platform: y = {y}"
    );
    let (highest, y) = thrown_up(false);
    assert!(
        highest < 2.0 && y < 0.5,
        "without the component the platform stops the ball: highest {highest}, y = {y}"
    );
}

#[test]
fn removing_the_component_takes_the_surface_away() {
    let mut sim = Sim::new();
    let platform = sim.spawn((
        Transform::from_xyz(0.0, 2.0, 0.0),
        cuboid(2.0, 0.1, 2.0),
        OneWaySurface(OneWay::new(vect(0.0, 1.0, 0.0))),
    ));
    sim.run(2);
    let context = sim.context();
    let handle = sim
        .app
        .world()
        .get::<RapierColliderHandle>(platform)
        .expect("a collider")
        .0;
    let node = bevy_rapier_collision_rules::Node::Collider(handle);
    assert!(sim.rules_of(context).rules().one_way(node).is_some());
    sim.entity_mut(platform).remove::<OneWaySurface>();
    sim.run(2);
    assert!(
        sim.rules_of(context).rules().one_way(node).is_none(),
        "the rule set forgot the surface"
    );
}
