//! What each entity's rule components put into which context's rule set,
//! so that a change, a removal or a new physics object replaces exactly
//! that (`docs/bevy.md`).

use std::collections::{HashMap, HashSet};

use crate::collision_rules::{CollisionGroup, CollisionRule, Node, OneWay};
use bevy::prelude::*;

/// Where an entity's rules live: its context entity and its node there.
pub(crate) type Place = (Entity, Node);

/// The rules one entity's components gave, as last applied.
#[derive(Clone, Debug)]
pub(crate) struct Applied {
    pub(crate) place: Place,
    pub(crate) group: Option<CollisionGroup>,
    pub(crate) personal: CollisionRule,
    pub(crate) one_way: Option<OneWay>,
    /// Each entry: the entity named, its node when the entry was set, the rule.
    pub(crate) specific: Vec<(Entity, Node, CollisionRule)>,
}

/// An entity that specific rules name.
#[derive(Debug, Default)]
pub(crate) struct Named {
    /// Its place when the entries were set (`None`: it had no physics object).
    pub(crate) at: Option<Place>,
    /// The entities whose entries name it.
    pub(crate) by: HashSet<Entity>,
}

/// The plugin's book of applied rules.
#[derive(Resource, Debug, Default)]
pub(crate) struct Ledger {
    pub(crate) applied: HashMap<Entity, Applied>,
    pub(crate) named: HashMap<Entity, Named>,
    /// Entities whose rules could not all be applied yet (an entry names
    /// an entity without a physics object, or the context has no rules
    /// component yet): tried again every frame while they wait.
    pub(crate) waiting: HashSet<Entity>,
    /// Entities that lost a rule component since the last application.
    pub(crate) removed: Vec<Entity>,
    /// Entities that got or lost a parent, or got a new rigid body.
    pub(crate) moved: Vec<Entity>,
    /// Colliders that lost one of bevy_rapier's settings components.
    pub(crate) settings_removed: Vec<Entity>,
    /// Contexts that dropped their own table.
    pub(crate) table_dropped: Vec<Entity>,
}

impl Ledger {
    /// Forgets that `entity`'s entries name their targets.
    pub(crate) fn unname(&mut self, entity: Entity, applied: &Applied) {
        for &(target, _, _) in &applied.specific {
            if let Some(named) = self.named.get_mut(&target) {
                named.by.remove(&entity);
                if named.by.is_empty() {
                    self.named.remove(&target);
                }
            }
        }
    }

    /// Notes that `entity`'s entries name their targets, each at `place`.
    pub(crate) fn name(&mut self, entity: Entity, target: Entity, place: Option<Place>) {
        let named = self.named.entry(target).or_default();
        named.at = place;
        named.by.insert(entity);
    }
}
