//! Rule events as messages (`docs/bevy.md`, "Rule events"): a pair made,
//! its rule changed by a component, the pair ended, and a pair ended by a
//! despawn naming the despawned entity; none when the plugin was not
//! asked.

use bevy::ecs::message::MessageCursor;
use bevy::prelude::*;
use bevy_rapier::prelude::*;
use bevy_rapier_collision_rules::prelude::*;

use crate::scene::{self, Sim, floor};

/// The events of the messages sent since the cursor last read that name
/// `ball`.
fn read(
    sim: &mut Sim,
    cursor: &mut MessageCursor<CollisionRuleEvent>,
    ball: Entity,
) -> Vec<RuleEvent> {
    let messages = sim.app.world().resource::<Messages<CollisionRuleEvent>>();
    cursor
        .read(messages)
        .filter(|m| m.entity1 == ball || m.entity2 == ball)
        .map(|m| m.event)
        .collect()
}

fn sim_with_events() -> Sim {
    Sim::with_plugins(
        RapierPhysicsPlugin::<CollisionRulesHooks>::default(),
        CollisionRulesPlugin::default().with_rule_events(),
    )
}

#[test]
fn a_pair_made_changed_and_ended_comes_as_messages_naming_its_entities() {
    let mut sim = sim_with_events();
    let floor = sim.spawn(floor());
    let ball = sim.spawn(scene::ball(0.0, 0.25));
    let mut cursor = MessageCursor::default();
    let mut events = Vec::new();
    for _ in 0..10 {
        sim.run(1);
        events.extend(read(&mut sim, &mut cursor, ball));
    }
    assert!(
        matches!(
            events[..],
            [RuleEvent::PairStarted {
                rule: CollisionRule::Normal,
                ..
            }]
        ),
        "the ball landed on the floor: {events:?}"
    );
    sim.entity_mut(ball)
        .insert(PersonalRule(CollisionRule::NoResponse));
    let mut events = Vec::new();
    for _ in 0..60 {
        sim.run(1);
        events.extend(read(&mut sim, &mut cursor, ball));
    }
    assert!(
        matches!(
            events[..],
            [
                RuleEvent::RuleChanged {
                    from: CollisionRule::Normal,
                    to: CollisionRule::NoResponse,
                    cause: RuleChange::Edit,
                    ..
                },
                RuleEvent::PairEnded {
                    rule: CollisionRule::NoResponse,
                    ..
                },
            ]
        ),
        "the component changed the rule, and the ball fell through: {events:?}"
    );
    // A second ball, despawned while it rests: its pair's end names it.
    let second = sim.spawn(scene::ball(1.0, 0.25));
    sim.run(10);
    let _ = read(&mut sim, &mut cursor, second);
    sim.app.world_mut().despawn(second);
    sim.run(2);
    let messages = sim.app.world().resource::<Messages<CollisionRuleEvent>>();
    let ended: Vec<_> = cursor
        .read(messages)
        .filter(|m| matches!(m.event, RuleEvent::PairEnded { .. }))
        .map(|m| (m.entity1, m.entity2))
        .collect();
    assert!(
        ended
            .iter()
            .any(|&(a, b)| [a, b].contains(&second) && [a, b].contains(&floor)),
        "the despawned ball's pair ended naming it and the floor: {ended:?}"
    );
}

#[test]
fn without_asking_there_are_no_messages_and_nothing_is_recorded() {
    let mut sim = Sim::new();
    sim.spawn(floor());
    sim.spawn((
        scene::ball(0.0, 0.25),
        PersonalRule(CollisionRule::NoResponse),
    ));
    sim.run(10);
    assert!(
        sim.app
            .world()
            .get_resource::<Messages<CollisionRuleEvent>>()
            .is_none()
    );
    let context = sim.context();
    let mut rules = sim
        .app
        .world_mut()
        .get_mut::<CollisionRules>(context)
        .expect("the context's rules");
    assert_eq!(
        rules.hooks_mut().drain_rule_events().count(),
        0,
        "nothing was recorded"
    );
}
