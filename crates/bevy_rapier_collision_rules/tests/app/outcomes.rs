//! Every rule, given by each component, against the ball's fall with no
//! floor at all.

use CollisionRule::*;
use bevy::prelude::*;
use bevy_rapier_collision_rules::prelude::*;

use super::scene::{Sim, ball, cuboid, fell_through, floor, rests};

/// How the rule between the ball and the floor is given.
#[derive(Clone, Copy, Debug)]
enum Given {
    /// The ball's `SpecificRules` names the floor.
    BallNamesFloor,
    /// The floor's `SpecificRules` names the ball.
    FloorNamesBall,
    /// The ball's `PersonalRule`.
    Personal,
    /// `RuleGroup`s and the `RuleTable`.
    Groups,
}

const FRAMES: usize = 90;

/// The ball's path with `rule` given as `given`, and its pair with the
/// floor as seen each frame (the most severe rule seen, and whether it
/// ever touched).
fn fall(rule: CollisionRule, given: Given) -> (Vec<Vec3>, Option<CollisionRule>, bool) {
    let mut sim = Sim::new();
    // The ball first: its handles are those of the floorless run.
    let b = sim.spawn(ball(0.0, 1.0));
    let f = sim.spawn(floor());
    match given {
        Given::BallNamesFloor => {
            sim.entity_mut(b).insert(SpecificRules::new().with(f, rule));
        }
        Given::FloorNamesBall => {
            sim.entity_mut(f).insert(SpecificRules::new().with(b, rule));
        }
        Given::Personal => {
            sim.entity_mut(b).insert(PersonalRule(rule));
        }
        Given::Groups => {
            let mut table = sim.table();
            let (ghosts, floors) = (table.create_group(), table.create_group());
            table.set_group_rule(ghosts, floors, rule);
            sim.entity_mut(b).insert(RuleGroup(ghosts));
            sim.entity_mut(f).insert(RuleGroup(floors));
        }
    }
    let mut path = Vec::new();
    let (mut seen, mut touched) = (None, false);
    for _ in 0..FRAMES {
        sim.run(1);
        path.push(sim.at(b));
        seen = seen.max(sim.pair_rule(b, f));
        touched |= sim.touching(b, f);
    }
    (path, seen, touched)
}

fn free_fall() -> Vec<Vec3> {
    let mut sim = Sim::new();
    let b = sim.spawn(ball(0.0, 1.0));
    sim.track(b, FRAMES)
}

#[test]
fn every_rule_from_every_component_does_what_it_says() {
    let free = free_fall();
    let givens = [
        Given::BallNamesFloor,
        Given::FloorNamesBall,
        Given::Personal,
        Given::Groups,
    ];
    for given in givens {
        for rule in [Normal, NoResponse, NoContacts, NoPair] {
            let (path, seen, touched) = fall(rule, given);
            let y = path.last().unwrap().y;
            let case = format!("{rule:?} as {given:?}: y = {y}, pair {seen:?}, touched {touched}");
            if rule == Normal {
                assert!(rests(y), "{case}: the ball should rest on the floor");
                continue;
            }
            assert!(fell_through(y), "{case}: the ball should pass the floor");
            let first_apart = path.iter().zip(&free).position(|(a, b)| a != b);
            assert_eq!(
                first_apart, None,
                "{case}: the path leaves free fall at frame {first_apart:?}"
            );
            // NoResponse keeps contacts, NoContacts a pair without them,
            // NoPair no pair at all (where Rapier groups refuse it the
            // hooks never see it).
            match rule {
                NoResponse => assert!(touched, "{case}: NoResponse keeps contacts"),
                NoContacts => assert!(!touched && seen == Some(NoContacts), "{case}"),
                _ => assert!(!touched && seen.is_none_or(|s| s == NoPair), "{case}"),
            }
        }
    }
}

#[test]
fn a_sensor_sees_what_the_rule_lets_through() {
    // NoPair and NoContacts keep a sensor's intersection out; NoResponse
    // and Normal keep it.
    for (rule, expected) in [
        (Normal, true),
        (NoResponse, true),
        (NoContacts, false),
        (NoPair, false),
    ] {
        let mut sim = Sim::new();
        let zone = sim.spawn((
            Transform::default(),
            cuboid(1.0, 1.0, 1.0),
            bevy_rapier::prelude::Sensor,
        ));
        let b = sim.spawn((
            ball(0.0, 0.0),
            bevy_rapier::prelude::GravityScale(0.0),
            SpecificRules::new().with(zone, rule),
        ));
        sim.run(5);
        let context = sim.context();
        let world = sim.app.world();
        let simulation = world
            .get::<bevy_rapier::plugin::context::RapierContextSimulation>(context)
            .unwrap();
        let colliders = world
            .get::<bevy_rapier::plugin::context::RapierContextColliders>(context)
            .unwrap();
        let inside = simulation.intersection_pair(colliders, zone, b) == Some(true);
        assert_eq!(inside, expected, "{rule:?}: intersecting {inside}");
    }
}
