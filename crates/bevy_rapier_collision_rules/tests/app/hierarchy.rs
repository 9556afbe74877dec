//! Bevy's hierarchy between rigid bodies is the parent map: followed
//! through re-parenting, unparenting and despawns.

use CollisionRule::*;
use bevy::prelude::*;
use bevy_rapier::prelude::GravityScale;
use bevy_rapier_collision_rules::prelude::*;

use super::scene::{Sim, ball, fell_through, floor};

#[test]
fn a_limb_under_a_pelvis_takes_the_pelvis_rules_until_it_is_unparented() {
    let mut sim = Sim::new();
    let f = sim.spawn(floor());
    // The pelvis floats; its rule about the floor reaches the limb below
    // it in the hierarchy (a criss-cross up the limb's chain).
    let pelvis = sim.spawn((
        ball(0.0, 3.0),
        GravityScale(0.0),
        SpecificRules::new().with(f, NoResponse),
    ));
    let limb = sim.spawn((ball(1.0, 0.0), ChildOf(pelvis)));
    let other = sim.spawn((ball(-2.0, 3.0), GravityScale(0.0)));
    sim.run(2);
    let (p, l, o) = (sim.body(pelvis), sim.body(limb), sim.body(other));
    assert_eq!(
        sim.rules().rules().parent(l),
        Some(p),
        "the limb's parent is the pelvis"
    );
    sim.run(90);
    let y = sim.global_y(limb);
    assert!(
        fell_through(y),
        "the limb passes the floor as its pelvis says: y = {y}"
    );

    // Re-parented under another body, then made a root.
    sim.entity_mut(limb).insert(ChildOf(other));
    sim.run(1);
    assert_eq!(sim.rules().rules().parent(l), Some(o), "re-parented");
    sim.entity_mut(limb).remove::<ChildOf>();
    sim.run(1);
    assert_eq!(sim.rules().rules().parent(l), None, "unparented");
}

#[test]
fn a_body_between_plain_entities_finds_its_nearest_body_ancestor() {
    let mut sim = Sim::new();
    let chassis = sim.spawn((ball(0.0, 3.0), GravityScale(0.0)));
    let mount = sim.spawn((Transform::default(), ChildOf(chassis)));
    let wheel = sim.spawn((ball(1.0, 0.0), GravityScale(0.0), ChildOf(mount)));
    sim.run(2);
    let (c, w) = (sim.body(chassis), sim.body(wheel));
    assert_eq!(sim.rules().rules().parent(w), Some(c));
    // The chassis despawned with its descendants: nothing dangles.
    sim.app.world_mut().despawn(chassis);
    sim.run(2);
    assert_eq!(sim.rules().rules().parents().count(), 0);
}

#[test]
fn without_the_pelvis_rule_the_same_limb_lands() {
    // The control of the test above: bevy_rapier simulates a dynamic body
    // under a floating one, and it lands.
    let mut sim = Sim::new();
    sim.spawn(floor());
    let pelvis = sim.spawn((ball(0.0, 3.0), GravityScale(0.0)));
    let limb = sim.spawn((ball(1.0, 0.0), ChildOf(pelvis)));
    sim.run(92);
    let y = sim.global_y(limb);
    assert!(super::scene::rests(y), "the limb lands: y = {y}");
}

#[test]
fn without_the_hierarchy_the_parent_map_is_the_projects() {
    let mut sim = Sim::with_plugins(
        bevy_rapier::prelude::RapierPhysicsPlugin::<CollisionRulesHooks>::default(),
        CollisionRulesPlugin::default().without_hierarchy(),
    );
    let pelvis = sim.spawn((ball(0.0, 3.0), GravityScale(0.0)));
    let limb = sim.spawn((ball(1.0, 0.0), ChildOf(pelvis)));
    sim.run(2);
    let l = sim.body(limb);
    assert_eq!(
        sim.rules().rules().parent(l),
        None,
        "ChildOf is not followed"
    );
}
