//! Rule events as Bevy messages (`docs/bevy.md`, "Rule events"): with
//! [`CollisionRulesPlugin::with_rule_events`](super::CollisionRulesPlugin::with_rule_events),
//! each context records its rule events, and after its step each becomes a
//! [`CollisionRuleEvent`] naming the colliders' entities.

use bevy::platform::collections::HashMap;
use bevy::prelude::*;
use bevy_rapier::plugin::context::RapierContextColliders;
use bevy_rapier::rapier::prelude::ColliderHandle;

use super::CollisionRules;
use crate::collision_rules::RuleEvent;

/// What changed for a live pair of a physics context in its last step
/// (see [`RuleEvent`]), with the entities of the pair's colliders: those of
/// `event`'s `collider1` and `collider2`, in that order. A collider
/// despawned in the step that ended its pair is still named.
#[derive(Message, Clone, Copy, Debug, PartialEq)]
pub struct CollisionRuleEvent {
    /// The physics context.
    pub context: Entity,
    /// The entity of the event's `collider1`.
    pub entity1: Entity,
    /// The entity of the event's `collider2`.
    pub entity2: Entity,
    /// The event, with Rapier's handles.
    pub event: RuleEvent,
}

/// The entities of the colliders a context's rule events have named, so
/// that a pair ended by a despawn still names its entities.
#[derive(Default)]
pub(crate) struct EventEntities(HashMap<ColliderHandle, Entity>);

/// Before the first step of a context: its rules record rule events.
pub(crate) fn record_rule_events(mut contexts: Query<&mut CollisionRules, Added<CollisionRules>>) {
    for mut rules in &mut contexts {
        rules.hooks_mut().record_rule_events(true);
    }
}

/// After the step: each context's rule events, in their order, as messages.
pub(crate) fn send_rule_events(
    mut contexts: Query<(Entity, &mut CollisionRules, &RapierContextColliders)>,
    mut messages: MessageWriter<CollisionRuleEvent>,
) {
    for (context, mut rules, colliders) in &mut contexts {
        let rules = &mut *rules;
        let known = &mut rules.event_entities.0;
        for event in rules.hooks.drain_rule_events() {
            let (RuleEvent::PairStarted {
                collider1,
                collider2,
                ..
            }
            | RuleEvent::RuleChanged {
                collider1,
                collider2,
                ..
            }
            | RuleEvent::PairEnded {
                collider1,
                collider2,
                ..
            }) = event
            else {
                continue;
            };
            let mut entity = |handle: ColliderHandle| {
                let entity = colliders
                    .collider_entity(handle)
                    .or_else(|| known.get(&handle).copied());
                if let Some(entity) = entity {
                    known.insert(handle, entity);
                }
                entity
            };
            // OK since a pair's colliders were in the set when its first
            // event named them, and were noted then.
            let (Some(entity1), Some(entity2)) = (entity(collider1), entity(collider2)) else {
                continue;
            };
            messages.write(CollisionRuleEvent {
                context,
                entity1,
                entity2,
                event,
            });
        }
        // Colliders gone have no pair left to end.
        known.retain(|&handle, _| colliders.colliders.contains(handle));
    }
}
