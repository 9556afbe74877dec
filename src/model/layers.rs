//! A project's Rapier layers said as groups and table entries, for projects
//! that move their layers into the rules (more than 32 layers, rules other
//! than on and off; `docs/migration.md`).

use super::super::rapier::prelude::InteractionGroups;

use super::super::{CollisionGroup, CollisionRule, CollisionRuleSet};

impl CollisionRuleSet {
    /// One group for each distinct `(collision groups, solver groups)`
    /// setting of `layers`, with table entries that say what Rapier's tests
    /// say: `NoPair` between two settings whose collision groups fail
    /// Rapier's test, else `NoResponse` where their solver groups fail it.
    /// Returns the group of each entry of `layers`, in order. Give each
    /// collider the group of its setting and Rapier's default groups back,
    /// and the rules do what the layers did (as Rapier's own groups where 32
    /// bits suffice); from there, relations can be any rule.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, CollisionRuleSet};
    ///
    /// let layer = |m: Group, f: Group| InteractionGroups::new(m, f, InteractionTestMode::And);
    /// let (player, debris) = (Group::GROUP_1, Group::GROUP_2);
    /// let all = InteractionGroups::all();
    /// let settings = [
    ///     (layer(player, Group::ALL - debris), all),
    ///     (layer(debris, Group::ALL - player - debris), all),
    ///     (all, all),
    /// ];
    /// let mut rules = CollisionRuleSet::default();
    /// let groups = rules.groups_from_layers(&settings);
    /// assert_eq!(rules.group_rule(groups[0], groups[1]), CollisionRule::NoPair);
    /// assert_eq!(rules.group_rule(groups[1], groups[1]), CollisionRule::NoPair);
    /// assert_eq!(rules.group_rule(groups[0], groups[2]), CollisionRule::Defer);
    /// ```
    pub fn groups_from_layers(
        &mut self,
        layers: &[(InteractionGroups, InteractionGroups)],
    ) -> Vec<CollisionGroup> {
        let mut distinct: Vec<((InteractionGroups, InteractionGroups), CollisionGroup)> =
            Vec::new();
        let groups = layers
            .iter()
            .map(
                |&setting| match distinct.iter().find(|(s, _)| *s == setting) {
                    Some(&(_, group)) => group,
                    None => {
                        let group = self.create_group();
                        distinct.push((setting, group));
                        group
                    }
                },
            )
            .collect();
        for (i, &((collision1, solver1), g1)) in distinct.iter().enumerate() {
            for &((collision2, solver2), g2) in &distinct[i..] {
                let rule = if !collision1.test(collision2) {
                    CollisionRule::NoPair
                } else if !solver1.test(solver2) {
                    CollisionRule::NoResponse
                } else {
                    continue;
                };
                self.set_group_rule(g1, g2, rule);
            }
        }
        groups
    }
}
