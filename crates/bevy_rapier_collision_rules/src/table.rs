//! The group table and the default rule, shared by every physics context
//! or owned by one (`docs/bevy.md`).

use crate::collision_rules::{CollisionGroup, CollisionRule, GroupTable};
use bevy::prelude::*;

/// The group table and the default rule. As a resource it is the table of
/// every physics context; a context entity that carries a
/// [`ContextRuleTable`] uses that one instead. Groups are created here and
/// given to entities with [`RuleGroup`](super::RuleGroup).
///
/// ```
/// use bevy_rapier_collision_rules::{CollisionRule, RuleTable};
///
/// let mut table = RuleTable::default();
/// let (player, debris) = (table.create_group(), table.create_group());
/// table.set_group_rule(player, debris, CollisionRule::NoPair);
/// assert_eq!(table.group_rule(debris, player), CollisionRule::NoPair);
/// assert_eq!(table.default_rule(), CollisionRule::Normal);
/// ```
#[derive(Resource, Clone, Debug)]
pub struct RuleTable {
    table: GroupTable,
    default_rule: CollisionRule,
}

impl Default for RuleTable {
    fn default() -> Self {
        RuleTable {
            table: GroupTable::default(),
            default_rule: CollisionRule::Normal,
        }
    }
}

impl RuleTable {
    /// A new group, distinct from every other group of this table.
    pub fn create_group(&mut self) -> CollisionGroup {
        self.table.create_group()
    }

    /// Sets the rule between two groups (either order); `Defer` removes it.
    ///
    /// # Panics
    ///
    /// If a group was not created by this table (nor is built in).
    pub fn set_group_rule(&mut self, a: CollisionGroup, b: CollisionGroup, rule: CollisionRule) {
        self.table.set_group_rule(a, b, rule);
    }

    /// The rule between two groups, `Defer` where there is none.
    #[must_use]
    pub fn group_rule(&self, a: CollisionGroup, b: CollisionGroup) -> CollisionRule {
        self.table.group_rule(a, b)
    }

    /// Each group of `set` with itself gets `self_rule`, each two distinct
    /// groups of it `other_rule`.
    pub fn set_group_rules_in_set(
        &mut self,
        set: &[CollisionGroup],
        self_rule: CollisionRule,
        other_rule: CollisionRule,
    ) {
        self.table
            .set_group_rules_in_set(set, self_rule, other_rule);
    }

    /// `group` gets `rule` with each group of `set`.
    pub fn set_group_rules_with_set(
        &mut self,
        group: CollisionGroup,
        set: &[CollisionGroup],
        rule: CollisionRule,
    ) {
        self.table.set_group_rules_with_set(group, set, rule);
    }

    /// Each group of `a` gets `rule` with each group of `b`.
    pub fn set_group_rules_between_sets(
        &mut self,
        a: &[CollisionGroup],
        b: &[CollisionGroup],
        rule: CollisionRule,
    ) {
        self.table.set_group_rules_between_sets(a, b, rule);
    }

    /// The rule of pairs no stage decides (`Normal` unless changed).
    pub fn set_default_rule(&mut self, rule: CollisionRule) {
        self.default_rule = rule;
    }

    /// The rule of pairs no stage decides.
    #[must_use]
    pub fn default_rule(&self) -> CollisionRule {
        self.default_rule
    }

    /// The group table, as the main crate has it.
    #[must_use]
    pub fn group_table(&self) -> &GroupTable {
        &self.table
    }
}

/// A physics context's own group table and default rule, on the context
/// entity, in place of the [`RuleTable`] resource. Removing it gives the
/// context the resource's table again.
#[derive(Component, Clone, Debug, Default)]
pub struct ContextRuleTable(pub RuleTable);
