//! Several physics contexts, each with its own rules.

use CollisionRule::*;
use bevy_rapier::plugin::context::RapierContextSimulation;
use bevy_rapier::prelude::*;
use bevy_rapier_collision_rules::prelude::*;

use super::scene::{Sim, ball, fell_through, floor, rests};

#[test]
fn each_context_has_its_own_rules_and_table() {
    let mut sim = Sim::new();
    let first = sim.context();
    let second = sim.spawn((
        RapierContextSimulation::default(),
        RapierConfiguration::new(1.0),
    ));
    let link = RapierContextEntityLink(second);
    // The same groups mean NoResponse in the first context (the shared
    // table) and Normal in the second (its own table).
    let (ghosts, floors) = {
        let mut table = sim.table();
        (table.create_group(), table.create_group())
    };
    sim.table().set_group_rule(ghosts, floors, NoResponse);
    let mut own = sim.app.world().resource::<RuleTable>().clone();
    own.set_group_rule(ghosts, floors, Normal);
    sim.entity_mut(second).insert(ContextRuleTable(own));

    let f1 = sim.spawn((floor(), RuleGroup(floors)));
    let g1 = sim.spawn((ball(0.0, 1.0), RuleGroup(ghosts)));
    let f2 = sim.spawn((floor(), RuleGroup(floors), link));
    let g2 = sim.spawn((ball(0.0, 1.0), RuleGroup(ghosts), link));
    // An entry about an entity of the other context means nothing.
    let b2 = sim.spawn((ball(1.0, 1.0), link, SpecificRules::new().with(f1, NoPair)));
    sim.run(120);
    assert!(
        fell_through(sim.y(g1)),
        "first context, NoResponse: y = {}",
        sim.y(g1)
    );
    assert!(
        rests(sim.y(g2)),
        "second context, its own table says Normal: y = {}",
        sim.y(g2)
    );
    assert!(
        rests(sim.y(b2)),
        "an entry across contexts is left out: y = {}",
        sim.y(b2)
    );
    assert_eq!(
        sim.pair_rule_of(second, g2, f2),
        Some(Normal),
        "the second context's pair"
    );
    assert_eq!(sim.rules_of(first).rules().nodes().count(), 2);
    assert_eq!(
        sim.rules_of(second).rules().nodes().count(),
        2,
        "b2's entry was left out"
    );

    // Removing the context's own table gives it the shared one.
    sim.entity_mut(second).remove::<ContextRuleTable>();
    let g3 = sim.spawn((ball(-2.0, 1.0), RuleGroup(ghosts), link));
    sim.run(90);
    assert!(
        fell_through(sim.y(g3)),
        "the shared table again: y = {}",
        sim.y(g3)
    );
}

/// A group created with another table than the one its entity's context
/// uses is a caller bug: the frame that applies it panics, naming the
/// entity, its context and the fix. Found by trying the 2D adapter from its
/// docs alone: the core's message named neither.
#[test]
fn a_group_from_another_table_panics_naming_the_entity_and_the_fix() {
    let mut sim = Sim::new();
    let context = sim.context();
    let mut other = RuleTable::default();
    let foreign = [(); 3].map(|_| other.create_group())[2];
    let ghost = sim.spawn((ball(0.0, 1.0), RuleGroup(foreign)));
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| sim.run(1)));
    let message = outcome
        .err()
        .and_then(|panic| {
            panic
                .downcast::<String>()
                .map(|m| *m)
                .or_else(|panic| panic.downcast::<&str>().map(|m| m.to_string()))
                .ok()
        })
        .expect("a panic with a message");
    assert!(
        message.contains(&ghost.to_string())
            && message.contains(&context.to_string())
            && message.contains("Fix: create the group with the table that context uses"),
        "names the entity ({ghost}), its context ({context}) and the fix: {message}"
    );
}
