//! The rules an entity carries, as components (`docs/bevy.md`).

use crate::collision_rules::{CollisionGroup, CollisionRule, OneWay};
use bevy::prelude::*;

/// The entity's collision group, from the [`RuleTable`](super::RuleTable)
/// its physics context uses. On a rigid body it is the body's group (its
/// colliders inherit it unless they carry their own); on a collider
/// without a body of its own, the collider's.
///
/// Removing the component clears the group.
///
/// # Panics
///
/// The plugin panics when it applies a group that the entity's context's
/// table did not create (a group of a [`ContextRuleTable`](super::ContextRuleTable)
/// with more groups than the context uses, say): a caller bug, as with
/// `CollisionRuleSet::set_group`.
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct RuleGroup(pub CollisionGroup);

/// The entity's personal rule: the rule of all its pairs that no specific
/// rule decides, before any group. Removing the component clears it.
#[derive(Component, Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct PersonalRule(pub CollisionRule);

/// The entity's colliders (a rigid body's, and those of the bodies below
/// it in the hierarchy) are a one-way surface: in a `Normal` pair they
/// block only from the side the normal points to, in the body's frame
/// (`docs/semantics.md`, "One-way surfaces"). Removing the component takes
/// it away.
///
/// ```
/// use bevy::prelude::*;
/// use bevy_rapier_collision_rules::{OneWay, OneWaySurface};
///
/// let platform = OneWaySurface(OneWay::new(Vec3::Y));
/// assert_eq!(platform.0.normal(), Vec3::Y);
/// ```
#[derive(Component, Clone, Copy, Debug, PartialEq)]
pub struct OneWaySurface(pub OneWay);

/// What the entity says about other entities: the most specific rules.
/// An entry about an entity of another physics context means nothing and
/// is left out; an entry about an entity that has no physics object yet
/// takes effect once it has one. Removing the component, or an entry,
/// clears what it said.
///
/// ```
/// use bevy::prelude::*;
/// use bevy_rapier_collision_rules::{CollisionRule, SpecificRules};
///
/// let mut world = World::new();
/// let wall = world.spawn_empty().id();
/// let mut rules = SpecificRules::new().with(wall, CollisionRule::NoResponse);
/// assert_eq!(rules.get(wall), CollisionRule::NoResponse);
/// rules.set(wall, CollisionRule::Defer);
/// assert_eq!(rules.get(wall), CollisionRule::Defer, "Defer removes the entry");
/// assert!(rules.is_empty());
/// ```
#[derive(Component, Clone, Debug, Default, PartialEq, Eq)]
pub struct SpecificRules {
    entries: Vec<(Entity, CollisionRule)>,
}

impl SpecificRules {
    /// No entries.
    #[must_use]
    pub fn new() -> SpecificRules {
        SpecificRules::default()
    }

    /// These rules, with `rule` about `other`.
    #[must_use]
    pub fn with(mut self, other: Entity, rule: CollisionRule) -> SpecificRules {
        self.set(other, rule);
        self
    }

    /// Sets the rule about `other`; `Defer` removes the entry.
    pub fn set(&mut self, other: Entity, rule: CollisionRule) {
        let at = self.entries.iter().position(|&(e, _)| e == other);
        match (at, rule) {
            (Some(i), CollisionRule::Defer) => {
                self.entries.swap_remove(i);
            }
            (Some(i), _) => self.entries[i].1 = rule,
            (None, CollisionRule::Defer) => {}
            (None, _) => self.entries.push((other, rule)),
        }
    }

    /// The rule about `other`, `Defer` if none.
    #[must_use]
    pub fn get(&self, other: Entity) -> CollisionRule {
        self.entries
            .iter()
            .find(|&&(e, _)| e == other)
            .map_or(CollisionRule::Defer, |&(_, rule)| rule)
    }

    /// Every entry, in no particular order.
    pub fn iter(&self) -> impl Iterator<Item = (Entity, CollisionRule)> + '_ {
        self.entries.iter().copied()
    }

    /// Whether there is no entry.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }
}
