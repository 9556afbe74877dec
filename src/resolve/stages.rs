//! The default calculation, stage by stage in the order of
//! `docs/semantics.md` ("The stages"), and its special case.

use super::super::rapier::prelude::{ColliderHandle, ColliderSet, RigidBodySet};

use super::chain::{Alias, Chain, Link};
use super::special_case::special_case;
use super::super::model::{BodyKinds, soft_rigid};
use super::super::{CollisionRule, CollisionRuleSet, Explanation, Node, Stage};

impl CollisionRuleSet {
    /// The rule of the pair of colliders `a` and `b`: the default
    /// calculation of the specification (specific, personal, group, default)
    /// followed by its special cases. Symmetric: `resolve(a, b) ==
    /// resolve(b, a)`.
    ///
    /// A collider missing from `colliders` is a one-node chain with no rules
    /// and no body; a body missing from `bodies` ends the chain below it.
    /// Chains of up to sixteen nodes resolve without allocating.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionGroup, CollisionRule, CollisionRuleSet};
    ///
    /// let mut bodies = RigidBodySet::new();
    /// let mut colliders = ColliderSet::new();
    /// let platform_a = bodies.insert(RigidBodyBuilder::kinematic_position_based());
    /// let platform_b = bodies.insert(RigidBodyBuilder::kinematic_position_based());
    /// let a = colliders.insert_with_parent(ColliderBuilder::cuboid(1.0, 0.1, 1.0), platform_a, &mut bodies);
    /// let b = colliders.insert_with_parent(ColliderBuilder::cuboid(1.0, 0.1, 1.0), platform_b, &mut bodies);
    ///
    /// let mut rules = CollisionRuleSet::default();
    /// // Kinematic bodies do not pair by default (the built-in group entry).
    /// assert_eq!(rules.resolve(&bodies, &colliders, a, b), CollisionRule::NoPair);
    /// // Allowed to collide, two non-dynamic bodies get contacts without response.
    /// let k = CollisionGroup::DEFAULT_KINEMATIC;
    /// rules.set_group_rule(k, k, CollisionRule::Normal);
    /// assert_eq!(rules.resolve(&bodies, &colliders, a, b), CollisionRule::NoResponse);
    /// ```
    #[must_use]
    pub fn resolve(
        &self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        a: ColliderHandle,
        b: ColliderHandle,
    ) -> CollisionRule {
        self.explain_rule(bodies, colliders, a, b).rule
    }

    /// [`resolve`](Self::resolve), with the stage, step and nodes that
    /// decided, and whether Rapier keeps the contacts the rule keeps (see
    /// [`Explanation::without_contacts`]).
    #[must_use]
    pub fn explain(
        &self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        a: ColliderHandle,
        b: ColliderHandle,
    ) -> Explanation {
        let mut explanation = self.explain_rule(bodies, colliders, a, b);
        explanation.without_contacts =
            explanation.rule == CollisionRule::NoResponse && soft_rigid(colliders, a, b);
        explanation.one_way = self
            .one_way_of(bodies, colliders, a)
            .or_else(|| self.one_way_of(bodies, colliders, b))
            .map(|(node, _)| node);
        explanation
    }

    /// The rule of a pair and what decided it, without asking Rapier
    /// about its contacts: the hook's path.
    #[inline]
    pub(crate) fn explain_rule(
        &self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        a: ColliderHandle,
        b: ColliderHandle,
    ) -> Explanation {
        self.explain_rule_as(bodies, colliders, a, b, None)
    }

    /// [`explain_rule`](Self::explain_rule), with bodies that stand for
    /// others (the hook's path while a tear is not yet followed).
    pub(crate) fn explain_rule_as(
        &self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        a: ColliderHandle,
        b: ColliderHandle,
        alias: Option<Alias<'_>>,
    ) -> Explanation {
        let a = self.chain(bodies, colliders, a, alias);
        let b = self.chain(bodies, colliders, b, alias);
        let mut explanation = self.calculate(&a, &b);
        let kinds = BodyKinds {
            first: a.dynamic,
            second: b.dynamic,
        };
        explanation.rule = special_case(kinds, explanation.rule);
        explanation
    }

    /// The default calculation, stages 1 to 4 of `docs/semantics.md`.
    fn calculate(&self, a: &Chain<'_>, b: &Chain<'_>) -> Explanation {
        let (a, a_flags) = (&a.links[..], (a.any_specific, a.any_personal));
        let (b, b_flags) = (&b.links[..], (b.any_specific, b.any_personal));
        let (m, n) = (a.len() - 1, b.len() - 1);
        // At step k the chains stand at a[min(k, m)] and b[min(k, n)]: a chain
        // that reached its root stays there.
        let steps = (0..=m.max(n)).map(|k| (k, k.min(m), k.min(n)));

        // 1. Specific stage: direct comparison, then criss-cross by distance.
        if a_flags.0 || b_flags.0 {
            for (k, i, j) in steps.clone() {
                let direct = spec(&a[i], &b[j]);
                if direct.is_decided() {
                    return decided(Stage::Specific, k, 0, (a[i].node, b[j].node), direct);
                }
                for t in 1.. {
                    let up_b = b.get(j + t).map(|bt| spec(&a[i], bt));
                    let up_a = a.get(i + t).map(|at| spec(at, &b[j]));
                    if up_a.is_none() && up_b.is_none() {
                        break;
                    }
                    let (ra, rb) = (up_a.unwrap_or_default(), up_b.unwrap_or_default());
                    let rule = ra.most_restrictive(rb);
                    if rule.is_decided() {
                        let nodes = if rb >= ra {
                            (a[i].node, b[j + t].node)
                        } else {
                            (a[i + t].node, b[j].node)
                        };
                        return decided(Stage::Specific, k, t, nodes, rule);
                    }
                }
            }
        }

        // 2. Personal stage: no criss-cross.
        if a_flags.1 || b_flags.1 {
            for (k, i, j) in steps.clone() {
                let rule = personal(&a[i]).most_restrictive(personal(&b[j]));
                if rule.is_decided() {
                    return decided(Stage::Personal, k, 0, (a[i].node, b[j].node), rule);
                }
            }
        }

        // 3. Group stage, on effective groups. A step whose two groups equal
        // the previous step's gives the same table answer, so it is skipped.
        let mut previous = None;
        for (k, i, j) in steps {
            let groups = (a[i].group, b[j].group);
            if previous == Some(groups) {
                continue;
            }
            previous = Some(groups);
            let rule = self.groups.get(groups.0, groups.1);
            if rule.is_decided() {
                return Explanation {
                    groups: Some(groups),
                    ..decided(Stage::Group, k, 0, (a[i].node, b[j].node), rule)
                };
            }
        }

        // 4. Default.
        Explanation {
            rule: self.default_rule,
            stage: Stage::Default,
            step: 0,
            distance: 0,
            nodes: None,
            groups: None,
            decided: self.default_rule,
            without_contacts: false,
            one_way: None,
        }
    }

}

/// `spec(x, y)`: both nodes' entries about each other, the most restrictive.
#[inline]
fn spec(x: &Link<'_>, y: &Link<'_>) -> CollisionRule {
    entry(x, y.node).most_restrictive(entry(y, x.node))
}

#[inline]
fn entry(x: &Link<'_>, other: Node) -> CollisionRule {
    match x.record {
        Some(record) if !record.specific.is_empty() => {
            record.specific.get(&other).copied().unwrap_or_default()
        }
        _ => CollisionRule::Defer,
    }
}

#[inline]
fn personal(x: &Link<'_>) -> CollisionRule {
    x.record
        .map_or(CollisionRule::Defer, |record| record.personal)
}

fn decided(
    stage: Stage,
    step: usize,
    distance: usize,
    nodes: (Node, Node),
    rule: CollisionRule,
) -> Explanation {
    Explanation {
        rule,
        stage,
        step,
        distance,
        nodes: Some(nodes),
        groups: None,
        decided: rule,
        without_contacts: false,
        one_way: None,
    }
}
