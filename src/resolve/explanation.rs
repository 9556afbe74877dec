//! What `explain` tells: the rule, the stage, step and nodes that decided,
//! and the groups that met.

use super::super::{CollisionGroup, CollisionRule, Node};

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

/// Why a pair got its rule: what [`CollisionRuleSet::explain`](super::super::CollisionRuleSet::explain) returns.
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
    /// The pair's rule: what [`CollisionRuleSet::resolve`](super::super::CollisionRuleSet::resolve) returns.
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
    /// The rule keeps the pair's contacts but Rapier cannot: a `NoResponse`
    /// pair of a soft body's surface and a rigid collider has no contacts
    /// and no collision events, since Rapier 0.36.1's soft-body solver
    /// solves every contact of such a pair (`docs/semantics.md`, "Soft
    /// bodies"). Each side still moves as if the other were absent.
    pub without_contacts: bool,
    /// The node whose one-way setting the pair's contacts follow when its
    /// rule is `Normal` (the first collider's, else the second's; see
    /// [`CollisionRuleSet::set_one_way`](super::super::CollisionRuleSet::set_one_way)):
    /// contacts from the other side are dropped.
    pub one_way: Option<Node>,
}

impl Explanation {
    /// Whether this is a `NoPair` given by the `(DEFAULT_KINEMATIC,
    /// DEFAULT_KINEMATIC)` table entry: the rules' word for Rapier's default
    /// collision types, which gives way where those types do not apply (a
    /// project's wider types, scene queries; `docs/semantics.md`, "The
    /// project's own settings"). Both chains are then in `DEFAULT_KINEMATIC` from the deciding step
    /// up, so no later step of the group stage decides either: the pair
    /// gets the default rule.
    pub(crate) fn by_kinematic_entry(&self) -> bool {
        let kinematic = CollisionGroup::DEFAULT_KINEMATIC;
        self.decided == CollisionRule::NoPair && self.groups == Some((kinematic, kinematic))
    }

}
