//! Collision groups: small ids whose relations live in the group table.

/// A collision group: a small copyable id whose relations to other groups
/// live in the rule set's group table.
///
/// Groups are made by [`CollisionRuleSet::create_group`](super::super::CollisionRuleSet::create_group);
/// two are built in. A node with no explicit group (and none up its chain)
/// is in [`DEFAULT_DYNAMIC`](Self::DEFAULT_DYNAMIC) when its rigid body is
/// dynamic, and in [`DEFAULT_KINEMATIC`](Self::DEFAULT_KINEMATIC) otherwise.
///
/// ```
/// use rapier_collision_rules::{CollisionGroup, CollisionRule, CollisionRuleSet};
///
/// let mut rules = CollisionRuleSet::default();
/// let debris = rules.create_group();
/// rules.set_group_rule(debris, CollisionGroup::DEFAULT_DYNAMIC, CollisionRule::NoPair);
/// assert_eq!(
///     rules.group_rule(CollisionGroup::DEFAULT_DYNAMIC, debris),
///     CollisionRule::NoPair,
/// );
/// ```
#[doc(alias = "layer")]
#[doc(alias = "mask")]
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct CollisionGroup(pub(super) u32);

impl CollisionGroup {
    /// The default group of colliders on dynamic bodies.
    pub const DEFAULT_DYNAMIC: CollisionGroup = CollisionGroup(0);
    /// The default group of colliders on kinematic or fixed bodies, and of
    /// colliders without a body.
    pub const DEFAULT_KINEMATIC: CollisionGroup = CollisionGroup(1);

    /// The default group of a body: [`DEFAULT_DYNAMIC`](Self::DEFAULT_DYNAMIC)
    /// when it is dynamic, [`DEFAULT_KINEMATIC`](Self::DEFAULT_KINEMATIC)
    /// when it is kinematic or fixed, or for a collider without a body.
    #[inline]
    pub(crate) fn default_for(dynamic: bool) -> CollisionGroup {
        if dynamic {
            CollisionGroup::DEFAULT_DYNAMIC
        } else {
            CollisionGroup::DEFAULT_KINEMATIC
        }
    }

    /// The group's number: 0 and 1 are the built-in groups, created groups
    /// count up from 2 in the order they were created.
    #[must_use]
    pub fn id(self) -> u32 {
        self.0
    }
}
