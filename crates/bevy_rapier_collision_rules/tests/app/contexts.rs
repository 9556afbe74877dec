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
