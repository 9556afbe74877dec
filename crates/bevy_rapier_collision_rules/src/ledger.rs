//! What each entity's rule components put into which context's rule set,
//! so that a change, a removal or a new physics object replaces exactly
//! that (`docs/bevy.md`).

use std::collections::{HashMap, HashSet};

use crate::collision_rules::{CollisionGroup, CollisionRule, Node, OneWay, Until};
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
    pub(crate) specific: Vec<AppliedEntry>,
}

/// A specific entry as applied.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct AppliedEntry {
    /// The entity named.
    pub(crate) target: Entity,
    /// Its node when the entry was set.
    pub(crate) node: Node,
    pub(crate) rule: CollisionRule,
    /// The end as the component gave it (the count runs in the rule set).
    pub(crate) until: Option<Until>,
    /// The component's setting that made it: an entry set again is applied
    /// again, and its end restarts.
    pub(crate) setting: u32,
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
    /// Pieces of cuts and tears holding their source's rules in the book
    /// until bevy_rapier gives them their components: applied again, with
    /// the entities naming them, once they have them (a component the
    /// source lost in the frame of the split is not copied onto the piece).
    pub(crate) pieces: HashSet<Entity>,
    /// Entities that lost a rule component since the last application.
    pub(crate) removed: Vec<Entity>,
    /// Entities that got or lost a parent, or got a new rigid body.
    pub(crate) moved: Vec<Entity>,
    /// Colliders that lost one of bevy_rapier's settings components.
    pub(crate) settings_removed: Vec<Entity>,
    /// Contexts that dropped their own table.
    pub(crate) table_dropped: Vec<Entity>,
    /// Entities whose applied entries may include one with an end (some
    /// may have ended or gone since): looked at after each step.
    pub(crate) ending: HashSet<Entity>,
    /// How many rule components (and contexts' own tables) the world
    /// holds: counted as they come and go.
    pub(crate) carriers: usize,
    /// Some context's hooks watched, tracked or hooked something in their
    /// last step, or planned with bits from the project's room: changes of
    /// the project's settings must reach them.
    pub(crate) hooks_reach: bool,
}

impl Ledger {
    /// Whether the edits have nothing to follow or apply this frame: no
    /// rule component in the world, nothing held in the book or noted by
    /// the observers, and no context whose hooks read the project's
    /// settings (`docs/bevy.md`, "Cost").
    pub(crate) fn at_rest(&self) -> bool {
        self.carriers == 0
            && !self.hooks_reach
            && self.applied.is_empty()
            && self.named.is_empty()
            && self.waiting.is_empty()
            && self.pieces.is_empty()
            && self.removed.is_empty()
            && self.moved.is_empty()
            && self.settings_removed.is_empty()
            && self.table_dropped.is_empty()
            && self.ending.is_empty()
    }

    /// Forgets that `entity`'s entries name their targets.
    pub(crate) fn unname(&mut self, entity: Entity, applied: &Applied) {
        for entry in &applied.specific {
            self.unname_target(entity, entry.target);
        }
    }

    /// Forgets that an entry of `entity` names `target`.
    pub(crate) fn unname_target(&mut self, entity: Entity, target: Entity) {
        if let Some(named) = self.named.get_mut(&target) {
            named.by.remove(&entity);
            if named.by.is_empty() {
                self.named.remove(&target);
            }
        }
    }

    /// Notes `applied` as what `entity`'s components gave now.
    pub(crate) fn note_applied(&mut self, entity: Entity, applied: Applied) {
        if applied.specific.iter().any(|e| e.until.is_some()) {
            self.ending.insert(entity);
        }
        self.applied.insert(entity, applied);
    }

    /// Notes that `entity`'s entries name their targets, each at `place`.
    pub(crate) fn name(&mut self, entity: Entity, target: Entity, place: Option<Place>) {
        let named = self.named.entry(target).or_default();
        named.at = place;
        named.by.insert(entity);
    }
}
