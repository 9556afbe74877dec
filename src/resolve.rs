//! The default calculation and its special case, stage by stage in the
//! order of `docs/semantics.md`, section 2.

use super::rapier::prelude::{ColliderHandle, ColliderSet, RigidBodySet};
use smallvec::SmallVec;

use super::rule_set::Record;
use super::{CollisionGroup, CollisionRule, CollisionRuleSet, Node};

/// The stage of the default calculation that decided a pair.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Stage {
    /// Stage 1: a specific entry, direct or criss-cross.
    Specific,
    /// Stage 2: the personal rules.
    Personal,
    /// Stage 3: the group table, on effective groups.
    Group,
    /// Stage 4: no stage decided; the default rule.
    Default,
}

/// Why a pair got its rule: what [`CollisionRuleSet::explain`] returns.
///
/// ```
/// use rapier3d::prelude::*;
/// use rapier_collision_rules::{CollisionRule, CollisionRuleSet, Node, Stage};
///
/// let mut bodies = RigidBodySet::new();
/// let mut colliders = ColliderSet::new();
/// let (a, b) = (bodies.insert(RigidBodyBuilder::dynamic()), bodies.insert(RigidBodyBuilder::dynamic()));
/// let ca = colliders.insert_with_parent(ColliderBuilder::ball(0.5), a, &mut bodies);
/// let cb = colliders.insert_with_parent(ColliderBuilder::ball(0.5), b, &mut bodies);
/// let mut rules = CollisionRuleSet::default();
/// rules.set_specific(b, a, CollisionRule::NoResponse);
///
/// let why = rules.explain(&bodies, &colliders, ca, cb);
/// assert_eq!(why.rule, CollisionRule::NoResponse);
/// assert_eq!(why.stage, Stage::Specific);
/// assert_eq!((why.step, why.distance), (1, 0), "body against body, the second step");
/// assert_eq!(why.nodes, Some((Node::Body(a), Node::Body(b))));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Explanation {
    /// The pair's rule: what [`CollisionRuleSet::resolve`] returns.
    pub rule: CollisionRule,
    /// The stage that decided it.
    pub stage: Stage,
    /// The step of that stage (0 compares the two colliders, 1 their bodies
    /// or a collider with a body, and so on up the chains); 0 for `Default`.
    pub step: usize,
    /// For the specific stage, the criss-cross distance (0: the direct
    /// comparison); 0 for the other stages.
    pub distance: usize,
    /// The two nodes whose comparison decided, the first from the first
    /// collider's chain; `None` for `Default`.
    pub nodes: Option<(Node, Node)>,
    /// For the group stage, the effective groups of the two nodes, whose
    /// table entry decided (the first from the first collider's chain);
    /// `None` for the other stages.
    pub groups: Option<(CollisionGroup, CollisionGroup)>,
    /// The rule the stage gave before the special case of `docs/semantics.md` (two
    /// non-dynamic colliders with `Normal` get `NoResponse`).
    pub decided: CollisionRule,
}

/// One node of a chain, with what the stages need of it.
#[derive(Clone, Copy)]
struct Link<'a> {
    node: Node,
    record: Option<&'a Record>,
    /// The node's effective group (`docs/semantics.md`, section 1).
    group: CollisionGroup,
}

/// Chains of up to this many nodes are resolved without allocating.
const INLINE_CHAIN: usize = 16;

struct Chain<'a> {
    links: SmallVec<[Link<'a>; INLINE_CHAIN]>,
    /// Whether the leaf collider's body is dynamic.
    dynamic: bool,
    any_specific: bool,
    any_personal: bool,
}

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
        self.explain(bodies, colliders, a, b).rule
    }

    /// [`resolve`](Self::resolve), with the stage, step and nodes that decided.
    #[must_use]
    pub fn explain(
        &self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        a: ColliderHandle,
        b: ColliderHandle,
    ) -> Explanation {
        let a = self.chain(bodies, colliders, a);
        let b = self.chain(bodies, colliders, b);
        let mut explanation = self.calculate(&a, &b);
        // The special case: non-dynamic bodies cannot respond, whatever the rule says.
        if !a.dynamic && !b.dynamic && explanation.rule == CollisionRule::Normal {
            explanation.rule = CollisionRule::NoResponse;
        }
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
        }
    }

    /// The chain of collider `leaf` with each node's record and effective group.
    fn chain<'a>(
        &'a self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        leaf: ColliderHandle,
    ) -> Chain<'a> {
        let present = colliders.contains(leaf);
        // A node with no group at or above it counts as the colliding body's
        // default group, whatever its ancestors' types (`docs/semantics.md`,
        // "Effective group"): a parent map alone changes no pair.
        let fallback = default_group(bodies, colliders, Node::Collider(leaf));
        let mut links: SmallVec<[Link<'a>; INLINE_CHAIN]> = SmallVec::new();
        let mut node = Some(Node::Collider(leaf));
        while let Some(current) = node {
            links.push(Link {
                node: current,
                // A stale collider handle is a node with no rules.
                record: if present { self.record(current) } else { None },
                group: fallback,
            });
            node = self.hierarchy.next(bodies, colliders, current);
        }
        // Effective groups: own group, else the nearest explicit one above,
        // else the fallback already stored. Walk from the root down.
        let mut above: Option<CollisionGroup> = None;
        let (mut any_specific, mut any_personal) = (false, false);
        for link in links.iter_mut().rev() {
            if let Some(record) = link.record {
                above = record.group.or(above);
                any_specific |= !record.specific.is_empty();
                any_personal |= record.personal.is_decided();
            }
            if let Some(group) = above {
                link.group = group;
            }
        }
        Chain {
            dynamic: fallback == CollisionGroup::DEFAULT_DYNAMIC,
            links,
            any_specific,
            any_personal,
        }
    }

    /// Whether `why` is a `NoPair` given by the `(DEFAULT_KINEMATIC,
    /// DEFAULT_KINEMATIC)` table entry: the rules' word for Rapier's default
    /// collision types, which gives way where those types do not apply (a
    /// project's wider types, scene queries; `docs/semantics.md`, section
    /// 6). Both chains are then in `DEFAULT_KINEMATIC` from the deciding step
    /// up, so no later step of the group stage decides either: the pair
    /// gets the default rule.
    pub(crate) fn by_kinematic_entry(why: &Explanation) -> bool {
        let kinematic = CollisionGroup::DEFAULT_KINEMATIC;
        why.decided == CollisionRule::NoPair && why.groups == Some((kinematic, kinematic))
    }

    /// The effective group of `node` (`docs/semantics.md`, "Effective
    /// group"): its own group, else the nearest explicit group up its chain,
    /// else the default group of the colliding body, which is `node`'s own
    /// body (a collider's body, or the body itself), whatever the types of
    /// its ancestors. A node further up another collider's chain may count
    /// differently in that collider's pairs:
    /// [`explain`](Self::explain)'s `groups` tells what met in the table.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionGroup, CollisionRuleSet, RuleError};
    ///
    /// let mut bodies = RigidBodySet::new();
    /// let mut colliders = ColliderSet::new();
    /// let pelvis = bodies.insert(RigidBodyBuilder::dynamic());
    /// let thigh = bodies.insert(RigidBodyBuilder::dynamic());
    /// let leg = colliders.insert_with_parent(ColliderBuilder::capsule_y(0.3, 0.1), thigh, &mut bodies);
    /// let mut rules = CollisionRuleSet::default();
    /// assert_eq!(rules.effective_group(&bodies, &colliders, leg), CollisionGroup::DEFAULT_DYNAMIC);
    /// let ragdoll = rules.create_group();
    /// rules.set_group(pelvis, Some(ragdoll));
    /// rules.set_parent(thigh, pelvis)?;
    /// assert_eq!(rules.effective_group(&bodies, &colliders, leg), ragdoll);
    /// # Ok::<(), RuleError>(())
    /// ```
    #[must_use]
    pub fn effective_group(
        &self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        node: impl Into<Node>,
    ) -> CollisionGroup {
        let start = node.into();
        // An object Rapier has removed takes no part in any pair: like
        // `resolve`, read none of its rules (`docs/semantics.md`).
        let present = match start {
            Node::Collider(c) => colliders.contains(c),
            Node::Body(b) => bodies.contains(b),
        };
        let mut node = present.then_some(start);
        while let Some(current) = node {
            if let Some(group) = self.group(current) {
                return group;
            }
            node = self.hierarchy.next(bodies, colliders, current);
        }
        default_group(bodies, colliders, start)
    }
}

/// The special case of `docs/semantics.md`: two colliders neither of whose own
/// bodies is dynamic cannot respond, so `Normal` becomes `NoResponse`.
pub(crate) fn special_case(
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    a: ColliderHandle,
    b: ColliderHandle,
    rule: CollisionRule,
) -> CollisionRule {
    let dynamic =
        |c| default_group(bodies, colliders, Node::Collider(c)) == CollisionGroup::DEFAULT_DYNAMIC;
    if rule == CollisionRule::Normal && !dynamic(a) && !dynamic(b) {
        CollisionRule::NoResponse
    } else {
        rule
    }
}

/// `DEFAULT_DYNAMIC` for a node of a dynamic body, `DEFAULT_KINEMATIC` for
/// one of a kinematic or fixed body and for a collider without a body.
#[inline]
fn default_group(bodies: &RigidBodySet, colliders: &ColliderSet, node: Node) -> CollisionGroup {
    let body = match node {
        Node::Collider(handle) => colliders.get(handle).and_then(|c| c.parent()),
        Node::Body(handle) => Some(handle),
    };
    match body.and_then(|handle| bodies.get(handle)) {
        Some(body) if body.is_dynamic() => CollisionGroup::DEFAULT_DYNAMIC,
        _ => CollisionGroup::DEFAULT_KINEMATIC,
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
    }
}
