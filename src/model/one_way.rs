//! One-way surfaces (`docs/semantics.md`, "One-way surfaces"): a node
//! whose colliders block other bodies only from one side, carried in its
//! record beside its other rules.

use super::super::rapier::prelude::{ColliderHandle, ColliderSet, Real, RigidBodySet, Vector};

use super::super::{CollisionRuleSet, Node};
use super::body_of;

/// Which bodies a [`OneWay`] surface blocks.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum OneWayKind {
    /// Rapier's one-way platform (`ContactModificationContext::update_as_oneway_platform`):
    /// a contact whose normal points out of the surface's allowed side
    /// (within the angle) is kept; any other is dropped, and stays dropped
    /// until the two no longer penetrate.
    #[default]
    Rapier,
    /// Godot's: as `Rapier`, and a body moving away from the surface along
    /// its normal (arriving from behind it) is let through too, so that a
    /// body rising through a platform is never caught by its top.
    Godot,
}

/// A one-way surface: the side its colliders block from, as a normal in the
/// frame of the node's body (a rotated platform's normal turns with it),
/// the largest angle between a contact's normal and it that still blocks,
/// and the semantics. Given with [`CollisionRuleSet::set_one_way`].
///
/// ```
/// use rapier3d::prelude::*;
/// use rapier_collision_rules::{OneWay, OneWayKind};
///
/// let up = OneWay::new(Vector::Y).with_max_angle(0.5).with_kind(OneWayKind::Godot);
/// assert_eq!(up.normal(), Vector::Y);
/// assert_eq!(up.max_angle(), 0.5);
/// assert_eq!(OneWay::new(Vector::Y * 3.0).normal(), Vector::Y, "the normal is normalized");
/// assert_eq!(OneWay::new(Vector::Y * 1e30).normal(), Vector::Y, "however long it is");
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct OneWay {
    normal: Vector,
    angle: Real,
    kind: OneWayKind,
}

impl OneWay {
    /// A surface that blocks from the side `normal` points to (in the frame
    /// of the node's body; the world's for a collider without a body),
    /// within 45 degrees, with Rapier's semantics.
    ///
    /// # Panics
    ///
    /// If `normal` is not finite or shorter than `1e-6`: it names no side.
    #[must_use]
    #[track_caller]
    pub fn new(normal: Vector) -> OneWay {
        // Scaled by its largest component first, so that the length of a
        // finite vector never overflows (`1e30 * Y` is a direction too).
        let largest = normal.abs().max_element();
        let scaled = normal / largest;
        assert!(
            largest.is_finite() && largest * scaled.length() > 1e-6,
            "OneWay::new({normal:?}): the normal must be a direction (not zero, finite)"
        );
        OneWay {
            normal: scaled / scaled.length(),
            angle: std::f32::consts::FRAC_PI_4,
            kind: OneWayKind::Rapier,
        }
    }

    /// The largest angle (radians) between a contact's normal and the
    /// surface's normal that still blocks.
    ///
    /// # Panics
    ///
    /// If `angle` is not between 0 and pi.
    #[must_use]
    #[track_caller]
    pub fn with_max_angle(self, angle: Real) -> OneWay {
        assert!(
            (0.0..=std::f32::consts::PI).contains(&angle),
            "OneWay::with_max_angle({angle}): an angle between 0 and pi radians"
        );
        OneWay { angle, ..self }
    }

    /// The semantics.
    #[must_use]
    pub fn with_kind(self, kind: OneWayKind) -> OneWay {
        OneWay { kind, ..self }
    }

    /// The normal, of length 1, in the frame of the node's body.
    #[must_use]
    pub fn normal(&self) -> Vector {
        self.normal
    }

    /// The largest blocking angle, in radians ([`with_max_angle`](Self::with_max_angle)).
    #[must_use]
    pub fn max_angle(&self) -> Real {
        self.angle
    }

    /// The semantics ([`with_kind`](Self::with_kind)).
    #[must_use]
    pub fn kind(&self) -> OneWayKind {
        self.kind
    }

    /// The normal in the world, for the setting carried by `node`: in the
    /// frame of `node`'s body (a collider's own body; the world's for a
    /// collider without one), whichever collider below it the surface is.
    #[must_use]
    pub fn world_normal(&self, bodies: &RigidBodySet, colliders: &ColliderSet, node: Node) -> Vector {
        let body = match node {
            Node::Body(body) => bodies.get(body),
            Node::Collider(collider) => body_of(bodies, colliders, collider),
        };
        match body {
            Some(body) => body.position().transform_vector(self.normal),
            None => self.normal,
        }
    }

    /// What the constructors let through (a save may hold anything).
    #[cfg(feature = "serde")]
    pub(crate) fn is_valid(&self) -> bool {
        (self.normal.length() - 1.0).abs() < 1e-3 && (0.0..=std::f32::consts::PI).contains(&self.angle)
    }
}

/// One-way surfaces.
impl CollisionRuleSet {
    /// Makes `node`'s colliders, and those of every body below it in the
    /// parent map, a one-way surface (`None`: no longer). A pair with such
    /// a collider whose rule is `Normal` has its contacts kept only from
    /// the allowed side; the rules decide everything else as before (a
    /// `NoResponse` ghost passes either way). The nearest node up a
    /// collider's chain with a one-way setting decides.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{OneWay, RuleHooks};
    ///
    /// let mut world = PhysicsWorld::new();
    /// let platform = world.insert_body(RigidBodyBuilder::fixed());
    /// world.insert_collider(ColliderBuilder::cuboid(3.0, 0.1, 3.0), Some(platform));
    /// // Thrown up from under the platform: it passes, and lands on top.
    /// let crate_ = world.insert_body(
    ///     RigidBodyBuilder::dynamic().translation(Vector::new(0.0, -1.0, 0.0)).linvel(Vector::new(0.0, 8.0, 0.0)),
    /// );
    /// world.insert_collider(ColliderBuilder::cuboid(0.3, 0.3, 0.3), Some(crate_));
    /// let mut hooks = RuleHooks::default();
    /// hooks.rules_mut().set_one_way(platform, Some(OneWay::new(Vector::Y)));
    /// for _ in 0..180 {
    ///     hooks.step(&mut world);
    /// }
    /// let y = world.bodies[crate_].translation().y;
    /// assert!((y - 0.4).abs() < 0.02, "the crate rests on top of the platform: y = {y}");
    /// ```
    pub fn set_one_way(&mut self, node: impl Into<Node>, one_way: Option<OneWay>) {
        let node = node.into();
        if (one_way.is_none() && self.record_id(node).is_none()) || self.is_removed(node) {
            return;
        }
        if let Some(record) = self.record_mut(node) {
            record.one_way = one_way;
        }
        self.one_ways_used |= one_way.is_some();
        self.tidy(node);
    }

    /// The node's own one-way setting (not one up its chain).
    #[must_use]
    pub fn one_way(&self, node: impl Into<Node>) -> Option<OneWay> {
        self.record(node.into()).and_then(|record| record.one_way)
    }

    /// The one-way setting that applies to `collider`: the nearest up its
    /// chain, with the node that carries it.
    #[must_use]
    pub fn one_way_of(
        &self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        collider: ColliderHandle,
    ) -> Option<(Node, OneWay)> {
        if !self.one_ways_used {
            return None;
        }
        let mut current = Some(Node::Collider(collider));
        while let Some(node) = current {
            if let Some(one_way) = self.one_way(node) {
                return Some((node, one_way));
            }
            current = self.hierarchy.next(bodies, colliders, node);
        }
        None
    }

    /// Whether any node was ever given a one-way setting: until then, no
    /// chain is walked for one.
    pub(crate) fn uses_one_ways(&self) -> bool {
        self.one_ways_used
    }
}
