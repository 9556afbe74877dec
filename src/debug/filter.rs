//! Which pairs and colliders the debug view draws the rules of.

use super::super::rapier::prelude::*;

use super::super::hooks::Reach;
use super::super::{CollisionRule, CollisionRuleSet, Node};

/// Which pairs and colliders [`RuleDebugRender`](super::RuleDebugRender)
/// draws the rules of; the default draws every pair the rules reach. What
/// Rapier itself draws is never filtered here (a
/// `DebugRenderBackend::filter_object` does that).
///
/// - `node`: only pairs with a collider at or under the node (the node
///   itself, a body's colliders, and the colliders of the bodies under it in
///   the parent map); only those colliders are tinted.
/// - `rule`: only pairs with that rule (tints are not filtered by rule).
/// - `hooked_only`: only pairs the hook answers, and only hooked colliders
///   are tinted.
///
/// ```
/// use rapier3d::prelude::*;
/// use rapier_collision_rules::{CollisionRule, RuleDebugFilter};
///
/// let mut bodies = RigidBodySet::new();
/// let player = bodies.insert(RigidBodyBuilder::dynamic());
/// let filter = RuleDebugFilter::default().node(player).rule(CollisionRule::NoResponse);
/// assert_eq!(filter.rule, Some(CollisionRule::NoResponse));
/// assert!(!filter.hooked_only);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RuleDebugFilter {
    /// Only the pairs and colliders at or under this node.
    pub node: Option<Node>,
    /// Only the pairs with this rule.
    pub rule: Option<CollisionRule>,
    /// Only the pairs the hook answers and the hooked colliders.
    pub hooked_only: bool,
}

impl RuleDebugFilter {
    /// Only the pairs and colliders at or under `node`.
    #[must_use]
    pub fn node(mut self, node: impl Into<Node>) -> RuleDebugFilter {
        self.node = Some(node.into());
        self
    }

    /// Only the pairs with `rule`.
    #[must_use]
    pub fn rule(mut self, rule: CollisionRule) -> RuleDebugFilter {
        self.rule = Some(rule);
        self
    }

    /// Only the pairs the hook answers, and the hooked colliders.
    #[must_use]
    pub fn hooked_only(mut self) -> RuleDebugFilter {
        self.hooked_only = true;
        self
    }

    /// Whether `collider` is at or under the filter's node (every collider
    /// without one).
    pub(crate) fn holds(
        &self,
        rules: &CollisionRuleSet,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        collider: ColliderHandle,
    ) -> bool {
        self.node.is_none_or(|node| {
            rules
                .hierarchy
                .chain(bodies, colliders, Node::Collider(collider))
                .any(|n| n == node)
        })
    }

    /// Whether a collider reached as `reach` is tinted.
    pub(crate) fn tints(&self, reach: Reach) -> bool {
        !self.hooked_only || reach == Reach::Hooked
    }

    /// Whether a live pair with `rule`, answered by the hook or not, is drawn.
    pub(crate) fn shows(&self, rule: CollisionRule, hooked: bool) -> bool {
        self.rule.is_none_or(|r| r == rule) && (!self.hooked_only || hooked)
    }
}
