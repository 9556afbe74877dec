//! Rule components into the context's rule set: each entity's components
//! are compared with what they gave last (the [`Ledger`]), and only the
//! difference is edited, so that `OnChange` recalculates just the pairs an
//! edit can affect (`docs/bevy.md`).

use bevy::prelude::*;
use bevy_rapier3d::prelude::{
    RapierColliderHandle, RapierContextEntityLink, RapierRigidBodyHandle,
};
use rapier_collision_rules::{CollisionRule, CollisionRuleSet, Node};

use super::ledger::{Applied, Ledger, Place};
use super::{CollisionRules, PersonalRule, RuleGroup, SpecificRules};

/// Every entity's physics object, if it has one: its body, its collider,
/// its context.
pub(crate) type Objects<'w, 's> = Query<
    'w,
    's,
    (
        Option<&'static RapierRigidBodyHandle>,
        Option<&'static RapierColliderHandle>,
        Option<&'static RapierContextEntityLink>,
    ),
>;

/// Where an entity's rules live: the body of an entity with a rigid body
/// (its colliders inherit them), else its collider.
pub(crate) fn place_of(objects: &Objects, entity: Entity) -> Option<Place> {
    let (body, collider, link) = objects.get(entity).ok()?;
    let node = match (body, collider) {
        (Some(body), _) => Node::from(body.0),
        (None, Some(collider)) => Node::from(collider.0),
        (None, None) => return None,
    };
    Some((link?.0, node))
}

type Carried = (
    Option<&'static RuleGroup>,
    Option<&'static PersonalRule>,
    Option<&'static SpecificRules>,
);

type Edited = (
    Or<(With<RuleGroup>, With<PersonalRule>, With<SpecificRules>)>,
    Or<(
        Changed<RuleGroup>,
        Changed<PersonalRule>,
        Changed<SpecificRules>,
        Changed<RapierRigidBodyHandle>,
        Changed<RapierColliderHandle>,
        Changed<RapierContextEntityLink>,
    )>,
);

/// Applies the rule components that changed, were removed, or whose
/// entity (or an entity they name) got a new physics object. Only entities
/// that carry rule components are looked at.
pub(crate) fn apply_rule_components(
    mut ledger: ResMut<Ledger>,
    mut contexts: Query<&mut CollisionRules>,
    objects: Objects,
    carried: Query<Carried>,
    edited: Query<Entity, Edited>,
) {
    let ledger = &mut *ledger;
    let mut dirty: Vec<Entity> = edited.iter().collect();
    dirty.append(&mut ledger.removed);
    dirty.extend(ledger.waiting.drain());
    // A named entity that moved (a new object, another context, despawned):
    // the entries about it are set again.
    for (&target, named) in &ledger.named {
        if place_of(&objects, target) != named.at {
            dirty.extend(named.by.iter().copied());
        }
    }
    if dirty.is_empty() {
        return;
    }
    dirty.sort_unstable();
    dirty.dedup();
    for entity in dirty {
        let components = carried.get(entity).unwrap_or((None, None, None));
        apply(ledger, &mut contexts, &objects, entity, components);
    }
}

/// Brings `entity`'s rules in its context's rule set to what its
/// components say.
fn apply(
    ledger: &mut Ledger,
    contexts: &mut Query<&mut CollisionRules>,
    objects: &Objects,
    entity: Entity,
    (group, personal, specific): (
        Option<&RuleGroup>,
        Option<&PersonalRule>,
        Option<&SpecificRules>,
    ),
) {
    let place = place_of(objects, entity);
    let wants = group.is_some() || personal.is_some() || specific.is_some();
    let old = ledger.applied.remove(&entity);
    if let Some(old) = &old {
        ledger.unname(entity, old);
    }
    // What the rule set holds from this entity at its place now.
    let before = match old {
        Some(old) if wants && place == Some(old.place) => Some(old),
        Some(old) => {
            if let Ok(mut rules) = contexts.get_mut(old.place.0) {
                clear(rules.rules_mut(), &old);
            }
            None
        }
        None => None,
    };
    let Some(place) = place.filter(|_| wants) else {
        return;
    };
    let Ok(mut rules) = contexts.get_mut(place.0) else {
        // The context gets its rules component with the next commands.
        ledger.waiting.insert(entity);
        return;
    };
    let before = before.unwrap_or(Applied {
        place,
        group: None,
        personal: CollisionRule::Defer,
        specific: Vec::new(),
    });
    let (context, node) = place;
    let set = rules.rules_mut();
    let group = group.map(|g| g.0);
    if before.group != group {
        set.set_group(node, group);
    }
    let personal = personal.map_or(CollisionRule::Defer, |p| p.0);
    if before.personal != personal {
        set.set_personal(node, personal);
    }
    let mut entries = Vec::new();
    for (target, rule) in specific.into_iter().flat_map(SpecificRules::iter) {
        if objects.get(target).is_err() {
            // Despawned: its entries went with it.
            continue;
        }
        let at = place_of(objects, target);
        ledger.name(entity, target, at);
        match at {
            Some((c, target_node)) if c == context => entries.push((target, target_node, rule)),
            // Another context's object means nothing here.
            Some(_) => {}
            None => {
                ledger.waiting.insert(entity);
            }
        }
    }
    for &(_, target_node, _) in &before.specific {
        if !entries.iter().any(|&(_, n, _)| n == target_node) {
            set.remove_specific(node, target_node);
        }
    }
    for &entry in &entries {
        if !before.specific.contains(&entry) {
            set.set_specific(node, entry.1, entry.2);
        }
    }
    ledger.applied.insert(
        entity,
        Applied {
            place,
            group,
            personal,
            specific: entries,
        },
    );
}

/// Takes back what `applied` gave.
fn clear(set: &mut CollisionRuleSet, applied: &Applied) {
    let node = applied.place.1;
    set.set_group(node, None);
    set.set_personal(node, CollisionRule::Defer);
    for &(_, target, _) in &applied.specific {
        set.remove_specific(node, target);
    }
}
