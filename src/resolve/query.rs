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
    /// settings (groups, flags, exclusions) keep working beside it.
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
        }
    }
}
