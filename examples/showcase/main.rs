//! Every rule at work in one scene, stepped for three seconds with
//! `RuleHooks`: a ragdoll whose limbs ignore each other but land on the
//! world, a vehicle whose wheels sit under the chassis in the parent map, a
//! ghost walking through a wall while its contact events fire, a pickup zone
//! (a live `NoContacts` pair, no contacts), debris that never pairs with the
//! player, kinematic platforms that do not push each other, and CCD bullets
//! against a `NoResponse` shield and a `Normal` wall.
//!
//! Prints one row per actor (rule, who decided it, pairs, contacts, events,
//! the measured outcome), writes side views of the scene at a few instants
//! to `target/showcase/scene.svg`, and exits non-zero if any outcome is not
//! what the rule promises. The scene is written once (`scene.rs`) and run in
//! 2D too by `showcase2d`.
//!
//! Run it with `cargo run --release --example showcase`.

use rapier_collision_rules::dim3 as rules;
use rapier3d as rapier;
use rapier3d::prelude::*;

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

fn main() -> Result<(), Box<dyn std::error::Error>> {
    scene::run("scene.svg")
}

#[test]
fn every_actor_does_what_its_rule_promises() {
    main().expect("the showcase's own checks");
}
