//! The rules an entity carries, as components (`docs/bevy.md`).

use crate::collision_rules::{CollisionGroup, CollisionRule, OneWay, Until};
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
/// An entry can have an end ([`Until`]): the hooks count it from the frame
/// it is applied in, and when it ends the plugin removes it from the
/// component too, in the frame it ends (`docs/bevy.md`, "Rules with an
/// end"). Changing the component's other entries does not restart it;
/// setting the entry again does.
///
/// ```
/// use bevy::prelude::*;
/// use bevy_rapier_collision_rules::{CollisionRule, SpecificRules, Until};
///
/// let mut world = World::new();
/// let (wall, shooter) = (world.spawn_empty().id(), world.spawn_empty().id());
/// let mut rules = SpecificRules::new()
///     .with(wall, CollisionRule::NoResponse)
///     .with_until(shooter, CollisionRule::NoContacts, Until::apart());
/// assert_eq!(rules.get(wall), CollisionRule::NoResponse);
/// assert_eq!(rules.until(shooter), Some(Until::apart()));
/// assert_eq!(rules.until(wall), None, "an entry without an end");
/// rules.set(wall, CollisionRule::Defer);
/// assert_eq!(rules.get(wall), CollisionRule::Defer, "Defer removes the entry");
/// assert_eq!(rules.iter().count(), 1);
/// ```
#[derive(Component, Clone, Debug, Default, PartialEq)]
pub struct SpecificRules {
    entries: Vec<SpecificEntry>,
    /// Counts the settings, so that an entry set again with the same rule
    /// and end is told from the one before (and its end restarts).
    settings: u32,
}

/// One entry of [`SpecificRules`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SpecificEntry {
    pub(crate) other: Entity,
    pub(crate) rule: CollisionRule,
    pub(crate) until: Option<Until>,
    /// Which setting of the component made it.
    pub(crate) setting: u32,
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

    /// These rules, with `rule` about `other` until `until` comes.
    #[must_use]
    pub fn with_until(mut self, other: Entity, rule: CollisionRule, until: Until) -> SpecificRules {
        self.set_until(other, rule, until);
        self
    }

    /// Sets the rule about `other`, without an end; `Defer` removes the
    /// entry.
    pub fn set(&mut self, other: Entity, rule: CollisionRule) {
        self.put(other, rule, None);
    }

    /// Sets the rule about `other` until `until` comes (as
    /// `CollisionRuleSet::set_specific_until`); `Defer` removes the entry.
    pub fn set_until(&mut self, other: Entity, rule: CollisionRule, until: Until) {
        self.put(other, rule, Some(until));
    }

    fn put(&mut self, other: Entity, rule: CollisionRule, until: Option<Until>) {
        let at = self.entries.iter().position(|e| e.other == other);
        self.settings = self.settings.wrapping_add(1);
        let entry = SpecificEntry {
            other,
            rule,
            until,
            setting: self.settings,
        };
        match (at, rule) {
            (Some(i), CollisionRule::Defer) => {
                self.entries.swap_remove(i);
            }
            (Some(i), _) => self.entries[i] = entry,
            (None, CollisionRule::Defer) => {}
            (None, _) => self.entries.push(entry),
        }
    }

    /// The rule about `other`, `Defer` if none.
    #[must_use]
    pub fn get(&self, other: Entity) -> CollisionRule {
        self.entry(other).map_or(CollisionRule::Defer, |e| e.rule)
    }

    /// The end of the entry about `other` as it was given (the count
    /// itself runs in the rule set: `CollisionRuleSet::specific_until`),
    /// `None` for an entry without an end or no entry.
    #[must_use]
    pub fn until(&self, other: Entity) -> Option<Until> {
        self.entry(other).and_then(|e| e.until)
    }

    /// The setting that made the entry about `other`.
    pub(crate) fn setting_of(&self, other: Entity) -> Option<u32> {
        self.entry(other).map(|e| e.setting)
    }

    fn entry(&self, other: Entity) -> Option<&SpecificEntry> {
        self.entries.iter().find(|e| e.other == other)
    }

    /// Every entry (the entity named and the rule), in no particular order.
    pub fn iter(&self) -> impl Iterator<Item = (Entity, CollisionRule)> + '_ {
        self.entries.iter().map(|e| (e.other, e.rule))
    }

    /// Gives `to` a copy of the entry about `from` (the same setting: the
    /// end the rule set copied for a piece of a tear runs on), unless `to`
    /// has one.
    pub(crate) fn copy_entry(&mut self, from: Entity, to: Entity) {
        if self.entry(to).is_some() {
            return;
        }
        if let Some(&entry) = self.entry(from) {
            self.entries.push(SpecificEntry { other: to, ..entry });
        }
    }

    /// Every entry with its end, for the plugin.
    pub(crate) fn entries(&self) -> impl Iterator<Item = SpecificEntry> + '_ {
        self.entries.iter().copied()
    }

    /// Whether there is no entry.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }
}
