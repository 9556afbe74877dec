//! Edits through components reach live pairs before the next step, wake
//! sleeping bodies, and leave nothing behind when taken back or despawned.

use CollisionRule::*;
use bevy::prelude::*;
use bevy_rapier::prelude::Sleeping;
use bevy_rapier_collision_rules::prelude::*;

use super::scene::{Sim, ball, cuboid, fell_through, floor, rests};

fn asleep(sim: &Sim, entity: Entity) -> bool {
    sim.app
        .world()
        .get::<Sleeping>(entity)
        .is_some_and(|s| s.sleeping)
}

#[test]
fn a_rule_inserted_on_a_sleeping_ball_wakes_it_and_it_falls() {
    let mut sim = Sim::new();
    let f = sim.spawn(floor());
    let b = sim.spawn((ball(0.0, 0.3), Sleeping::default()));
    sim.run(240);
    assert!(
        rests(sim.y(b)) && asleep(&sim, b),
        "resting and asleep: y = {}",
        sim.y(b)
    );
    sim.entity_mut(b)
        .insert(SpecificRules::new().with(f, NoResponse));
    sim.run(60);
    let y = sim.y(b);
    assert!(
        fell_through(y),
        "woken by the edit, through the floor: y = {y}"
    );
}

#[test]
fn a_changed_and_then_removed_rule_is_taken_back() {
    let mut sim = Sim::new();
    let f = sim.spawn(floor());
    let b = sim.spawn((ball(0.0, 3.0), SpecificRules::new().with(f, NoContacts)));
    sim.run(2);
    // Changed in place before it reaches the floor: now Normal.
    sim.app
        .world_mut()
        .get_mut::<SpecificRules>(b)
        .unwrap()
        .set(f, Normal);
    sim.run(120);
    assert!(
        rests(sim.y(b)),
        "the changed rule lets it land: y = {}",
        sim.y(b)
    );
    // A personal rule, then its removal.
    sim.entity_mut(b)
        .remove::<SpecificRules>()
        .insert(PersonalRule(NoPair));
    sim.run(60);
    assert!(fell_through(sim.y(b)), "personal NoPair: y = {}", sim.y(b));
    let second = sim.spawn((ball(1.0, 2.0), PersonalRule(NoPair)));
    sim.run(1);
    sim.entity_mut(second).remove::<PersonalRule>();
    sim.run(120);
    assert!(
        rests(sim.y(second)),
        "removed before it landed: y = {}",
        sim.y(second)
    );
    sim.entity_mut(b).remove::<PersonalRule>();
    sim.run(1);
    let rules = sim.rules().rules();
    assert_eq!(
        rules.record_count(),
        0,
        "no rule is left: {:?}",
        rules.nodes().collect::<Vec<_>>()
    );
}

#[test]
fn a_despawned_entity_leaves_no_rules_behind() {
    let mut sim = Sim::new();
    let f = sim.spawn(floor());
    let wall = sim.spawn((Transform::from_xyz(3.0, 1.0, 0.0), cuboid(0.1, 1.0, 1.0)));
    let ghost = sim.spawn((
        ball(0.0, 2.0),
        SpecificRules::new()
            .with(wall, NoResponse)
            .with(f, NoContacts),
    ));
    let named = sim.spawn((ball(1.0, 2.0), SpecificRules::new().with(ghost, NoPair)));
    sim.run(10);
    assert!(sim.rules().rules().record_count() > 0, "rules were given");
    sim.app.world_mut().despawn(ghost);
    sim.run(2);
    let rules = sim.rules().rules();
    assert_eq!(
        rules.nodes().count(),
        0,
        "the ghost's rules and the entry naming it are gone: {:?}",
        rules.nodes().collect::<Vec<_>>()
    );
    sim.app.world_mut().despawn(wall);
    sim.run(120);
    // The entry about the despawned ghost stays in the component; it names nothing.
    assert_eq!(
        sim.app
            .world()
            .get::<SpecificRules>(named)
            .unwrap()
            .get(ghost),
        NoPair
    );
    assert!(
        rests(sim.y(named)),
        "the other ball lands: y = {}",
        sim.y(named)
    );
}

#[test]
fn an_entry_about_an_entity_spawned_later_takes_effect_once_it_exists() {
    let mut sim = Sim::new();
    let later = sim.app.world_mut().spawn_empty().id();
    let b = sim.spawn((ball(0.0, 2.0), SpecificRules::new().with(later, NoPair)));
    sim.run(3);
    // The named entity becomes the floor.
    sim.entity_mut(later).insert(floor());
    sim.run(90);
    assert!(
        fell_through(sim.y(b)),
        "the entry reached the floor: y = {}",
        sim.y(b)
    );
}

/// A world without rules skips the edits (`docs/bevy.md`, "Cost"): after
/// idle frames, a change of the shared table alone, a rule component, and
/// a context's own table each still reach the rules the frame they come.
#[test]
fn rules_that_come_after_idle_frames_are_followed() {
    // The shared table's default rule.
    let mut sim = Sim::new();
    sim.spawn(floor());
    let resting = sim.spawn(ball(0.0, 0.3));
    sim.run(30);
    assert!(rests(sim.y(resting)), "y = {}", sim.y(resting));
    sim.table().set_default_rule(NoPair);
    sim.run(60);
    assert!(
        fell_through(sim.y(resting)),
        "the table's default NoPair: y = {}",
        sim.y(resting)
    );

    // A component on an entity that had none.
    let mut sim = Sim::new();
    sim.spawn(floor());
    let resting = sim.spawn(ball(0.0, 0.3));
    sim.run(30);
    sim.entity_mut(resting).insert(PersonalRule(NoPair));
    sim.run(60);
    assert!(
        fell_through(sim.y(resting)),
        "a personal NoPair: y = {}",
        sim.y(resting)
    );

    // A context's own table, added and then changed in place.
    let mut sim = Sim::new();
    sim.spawn(floor());
    let resting = sim.spawn(ball(0.0, 0.3));
    sim.run(30);
    let context = sim.context();
    sim.entity_mut(context).insert(ContextRuleTable::default());
    sim.run(5);
    assert!(rests(sim.y(resting)), "y = {}", sim.y(resting));
    sim.app
        .world_mut()
        .get_mut::<ContextRuleTable>(context)
        .unwrap()
        .0
        .set_default_rule(NoPair);
    sim.run(60);
    assert!(
        fell_through(sim.y(resting)),
        "the context's own default NoPair: y = {}",
        sim.y(resting)
    );
}
