//! The showcase in 2D, over `rapier2d`: the same scene, written once
//! (`../showcase/scene.rs`), seen from the side as a platformer sees it. A
//! ragdoll whose limbs ignore each other but land on the ground, a vehicle,
//! a ghost passing one way through a wall with its contact events, a pickup
//! zone, debris that falls through the player, kinematic platforms that do
//! not push each other, and CCD bullets through a `NoResponse` shield and
//! against a `Normal` wall; and soft bodies: a jelly dropped through a gate
//! it does not respond to, a net (a rope pinned at both ends) a walker
//! passes through while debris lands on it, and a rope cut in two whose
//! halves keep their `NoPair` with the floor.
//!
//! Prints one row per actor with the measured outcome, draws one panel per
//! actor (its trajectory, the other object of its rule, the rule and the
//! outcome in words) to `target/showcase/scene2d.svg` and
//! `docs/showcase_scene2d.svg`, and exits non-zero if any outcome is not
//! what the rule promises.
//!
//! Run it with `cargo run --release --example showcase2d --features dim2`.

use rapier_collision_rules::dim2 as rules;
use rapier2d as rapier;
use rapier2d::prelude::*;

#[path = "../common/legend.rs"]
mod legend;
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

/// A jelly square of half-extent 0.4 centred at `center`.
fn jelly(center: Vector) -> SoftBodyBuilder {
    SoftBodyBuilder::grid(center, Vector::splat(0.4), 4, 4)
}

/// A horizontal net from `x0` to `x1` at height `y`, pinned at both ends:
/// a rope, the plane's cloth.
fn net(x0: f32, x1: f32, y: f32) -> SoftBodyBuilder {
    let n = 13;
    SoftBodyBuilder::rope(Vector::new(x0, y), Vector::new(x1, y), n)
        .pinned_particles([0, n as u32 - 1])
}

/// A blade across the line `y`.
fn blade_at_y(x: f32, y: f32) -> [Vector; 2] {
    [Vector::new(x - 10.0, y), Vector::new(x + 10.0, y)]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    scene::run("scene2d.svg")
}

#[test]
fn every_actor_does_what_its_rule_promises() {
    main().expect("the showcase's own checks");
}
