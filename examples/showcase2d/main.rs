//! The showcase in 2D, over `rapier2d`: the same scene, written once
//! (`../showcase/scene.rs`), seen from the side as a platformer sees it. A
//! ragdoll whose limbs ignore each other but land on the ground, a vehicle,
//! a ghost passing one way through a wall with its contact events, a pickup
//! zone, debris that falls through the player, kinematic platforms that do
//! not push each other, and CCD bullets through a `NoResponse` shield and
//! against a `Normal` wall.
//!
//! Prints one row per actor with the measured outcome, writes the side
//! views to `target/showcase/scene2d.svg`, and exits non-zero if any
//! outcome is not what the rule promises.
//!
//! Run it with `cargo run --release --example showcase2d --features dim2`.

use rapier_collision_rules::dim2 as rules;
use rapier2d as rapier;
use rapier2d::prelude::*;

#[path = "../showcase/scene.rs"]
mod scene;
#[path = "../showcase/view.rs"]
mod view;

/// A point of the plane.
fn at(x: f32, y: f32) -> Vector {
    Vector::new(x, y)
}

/// A box of half-extents `hx`, `hy` (`_hz` is the 3D scene's depth).
fn cuboid(hx: f32, hy: f32, _hz: f32) -> ColliderBuilder {
    ColliderBuilder::cuboid(hx, hy)
}

/// A wheel's axle, anchored at `anchor1` on the chassis.
fn axle(anchor1: Vector) -> RevoluteJointBuilder {
    RevoluteJointBuilder::new()
        .local_anchor1(anchor1)
        .local_anchor2(Vector::ZERO)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    scene::run("scene2d.svg")
}

#[test]
fn every_actor_does_what_its_rule_promises() {
    main().expect("the showcase's own checks");
}
