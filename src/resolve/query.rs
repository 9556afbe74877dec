//! Scene queries that follow the rules: a predicate for Rapier's
//! `QueryFilter` (`docs/semantics.md`, "The project's own settings").

use super::super::rapier::prelude::*;

use super::super::{CollisionRule, CollisionRuleSet};

impl CollisionRuleSet {
    /// A predicate for [`QueryFilter::predicate`]: keeps a collider when the
    /// rule of its pair with `source` would have them push each other apart
    /// (`Normal`), and leaves it out otherwise (a door a character may walk
    /// through, debris a player's ray passes). The rule is read before the
    /// special case of two non-dynamic bodies, which only says such bodies
    /// cannot respond: a kinematic character is stopped by a `Normal` wall.
    /// For the same reason the `(DEFAULT_KINEMATIC, DEFAULT_KINEMATIC)`
    /// entry, which stands for Rapier's default collision types, does not
    /// keep a kinematic character's query from its walls: such a pair
    /// takes the default rule. A final `Defer` counts as `Normal`, as in a
    /// step. `source` itself and
    /// the colliders of its body are left out. Rapier's own `QueryFilter`
    /// settings (groups, flags, exclusions) keep working beside it. A
    /// one-way surface ([`set_one_way`](Self::set_one_way)) is left out
    /// while `source` is not wholly on its blocking side, so that a
    /// character controller jumps up through it and stands on it.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, CollisionRuleSet};
    ///
    /// let mut world = PhysicsWorld::new();
    /// let wall = |x: f32| RigidBodyBuilder::fixed().translation(Vector::new(x, 0.0, 0.0));
    /// let door = world.insert_body(wall(2.0));
    /// world.insert_collider(ColliderBuilder::cuboid(0.1, 2.0, 2.0), Some(door));
    /// let far = world.insert_body(wall(6.0));
    /// let far_wall = world.insert_collider(ColliderBuilder::cuboid(0.1, 2.0, 2.0), Some(far));
    /// let player = world.insert_body(RigidBodyBuilder::kinematic_position_based());
    /// let eye = world.insert_collider(ColliderBuilder::ball(0.3), Some(player));
    /// world.step();
    ///
    /// let mut rules = CollisionRuleSet::default();
    /// rules.set_specific(player, door, CollisionRule::NoResponse);
    /// let passes = rules.query_predicate(&world.bodies, &world.colliders, eye);
    /// let ray = Ray::new(Vector::ZERO, Vector::X);
    /// let hit = world
    ///     .query_pipeline_with_filter(QueryFilter::default().predicate(&passes))
    ///     .cast_ray(&ray, 100.0, true);
    /// assert_eq!(hit.map(|(collider, _)| collider), Some(far_wall), "the ray passes the door");
    /// ```
    pub fn query_predicate<'a>(
        &'a self,
        bodies: &'a RigidBodySet,
        colliders: &'a ColliderSet,
        source: ColliderHandle,
    ) -> impl Fn(ColliderHandle, &Collider) -> bool + 'a {
        let body = colliders.get(source).and_then(|c| c.parent());
        move |handle, collider| {
            if handle == source || (body.is_some() && collider.parent() == body) {
                return false;
            }
            let why = self.explain(bodies, colliders, source, handle);
            let decided = if why.by_kinematic_entry() {
                self.default_rule()
            } else {
                why.decided
            };
            matches!(decided, CollisionRule::Normal | CollisionRule::Defer)
                && !self.one_way_lets_query_through(bodies, colliders, source, handle, collider)
        }
    }

    /// Whether `collider`'s one-way surface, if it has one, lets a query
    /// from `source` through: `source` is not wholly on its blocking side.
    /// Along the surface's normal, the lowest point of `source` (of its
    /// bounding box for a shape that is not convex) lies below the
    /// surface's top (its extent along the
    /// normal in its own frame, so that a rotated platform is measured as
    /// it stands; for a surface of parts, its top under the source) by more than [`ONE_WAY_QUERY_SLACK`] (1 cm). A character
    /// controller given the predicate then walks or jumps through from
    /// below and stands on top, as a body does in a step.
    pub(crate) fn one_way_lets_query_through(
        &self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        source: ColliderHandle,
        handle: ColliderHandle,
        collider: &Collider,
    ) -> bool {
        let Some((node, one_way)) = self.one_way_of(bodies, colliders, handle) else {
            return false;
        };
        let normal = one_way.world_normal(bodies, colliders, node);
        let pose = collider.position();
        let local = pose.inverse_transform_vector(normal);
        let aabb = collider.shape().compute_local_aabb();
        let top = pose.translation.dot(normal) + extent(aabb.center(), aabb.half_extents(), local);
        let Some(source) = colliders.get(source) else {
            return false;
        };
        let top = match collider.shape().as_support_map() {
            Some(_) => top,
            // A surface of parts (a mesh, a height field, a compound, a
            // polyline) is measured where the source is: the first part
            // under the source's centre, along the normal (the centre
            // itself when it is inside a part; the whole box's top where
            // no part is under it), so that a part above the source (a
            // higher platform of the same mesh) does not count.
            None => {
                let bottom = pose.translation.dot(normal) - extent(aabb.center(), aabb.half_extents(), -local);
                let centre = source.position().translation;
                let ray = Ray::new(centre, -normal);
                let reach = (centre.dot(normal) - bottom).max(0.0) + 1.0;
                collider
                    .shape()
                    .cast_ray(pose, &ray, reach, true)
                    .map_or(top, |toi| centre.dot(normal) - toi)
            }
        };
        // The source's lowest point along the normal: exact for a convex
        // shape (a capsule on a tilted platform), its bounding box's
        // otherwise.
        let pose = source.position();
        let low = match source.shape().as_support_map() {
            Some(support) => {
                let deepest = support.local_support_point(pose.inverse_transform_vector(-normal));
                pose.transform_point(deepest).dot(normal)
            }
            None => {
                let aabb = source.compute_aabb();
                aabb.center().dot(normal) - extent(Vector::ZERO, aabb.half_extents(), normal)
            }
        };
        low < top - ONE_WAY_QUERY_SLACK
    }
}

/// How far below a one-way surface's top a query's source may reach and
/// still be on its blocking side (a resting body's contact skin, a
/// character controller's offset).
pub(crate) const ONE_WAY_QUERY_SLACK: Real = 0.01;

/// How far a box of `center` and `half` extents reaches along `direction`.
fn extent(center: Vector, half: Vector, direction: Vector) -> Real {
    center.dot(direction) + (half * direction).abs().element_sum()
}
