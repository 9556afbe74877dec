//! Every rule at work in one scene, stepped for three seconds with
//! `RuleHooks`: a ragdoll whose limbs ignore each other but land on the
//! world, a vehicle whose wheels sit under the chassis in the parent map, a
//! ghost walking through a wall while its contact events fire, a pickup zone
//! (a live `NoContacts` pair, no contacts), debris that never pairs with the
//! player, kinematic platforms that do not push each other, and CCD bullets
//! against a `NoResponse` shield and a `Normal` wall; and soft bodies: a
//! jelly dropped through a gate it does not respond to, a net a walker
//! passes through while debris lands on it, and a rope cut in two whose
//! halves keep their `NoPair` with the floor.
//!
//! Prints one row per actor (rule, who decided it, pairs, contacts, events,
//! the measured outcome), draws one panel per actor (its path in its
//! rule's colour, the other object of its rule, the outcome in words) to
//! `target/showcase/scene.svg` and `docs/showcase_scene.svg`, and exits
//! non-zero if any outcome is not
//! what the rule promises. The scene is written once (`scene.rs`) and run in
//! 2D too by `showcase2d`.
//!
//! Run it with `cargo run --release --example showcase`.

use rapier_collision_rules::dim3 as rules;
use rapier3d as rapier;
use rapier3d::prelude::*;

#[path = "../common/legend.rs"]
mod legend;
mod scene;
mod view;

/// A point of the x-y plane the scene stands in.
fn at(x: f32, y: f32) -> Vector {
    Vector::new(x, y, 0.0)
}

/// A box of half-extents `hx`, `hy`, `hz`.
fn cuboid(hx: f32, hy: f32, hz: f32) -> ColliderBuilder {
    ColliderBuilder::cuboid(hx, hy, hz)
}

/// A wheel's axle (along z), anchored at `anchor1` on the chassis.
fn axle(anchor1: Vector) -> RevoluteJointBuilder {
    RevoluteJointBuilder::new(Vector::Z)
        .local_anchor1(anchor1)
        .local_anchor2(Vector::ZERO)
}

/// A jelly cube of half-extent 0.4 centred at `center`.
fn jelly(center: Vector) -> SoftBodyBuilder {
    SoftBodyBuilder::cuboid(center, Vector::splat(0.4), 3, 3, 3)
}

/// A horizontal net from `x0` to `x1` at height `y`, pinned at its
/// corners: a cloth.
fn net(x0: f32, x1: f32, y: f32) -> SoftBodyBuilder {
    let (nu, nv) = (13, 5);
    let du = Vector::new((x1 - x0) / (nu - 1) as f32, 0.0, 0.0);
    let dv = Vector::new(0.0, 0.0, 1.2 / (nv - 1) as f32);
    let corners = [0, nv - 1, (nu - 1) * nv, nu * nv - 1].map(|i| i as u32);
    SoftBodyBuilder::cloth(Vector::new(x0, y, -0.6), du, dv, nu, nv).pinned_particles(corners)
}

/// A blade across the plane `y` (a triangle spanning the scene's depth).
fn blade_at_y(x: f32, y: f32) -> [Vector; 3] {
    [
        Vector::new(x - 10.0, y, -10.0),
        Vector::new(x + 10.0, y, -10.0),
        Vector::new(x, y, 20.0),
    ]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    scene::run("scene.svg")
}

#[test]
fn every_actor_does_what_its_rule_promises() {
    main().expect("the showcase's own checks");
}
