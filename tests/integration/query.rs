//! Scene queries that follow the rules: `query_predicate` with a ray cast
//! and with Rapier's kinematic character controller, beside Rapier's own
//! query filter groups.

use super::rapier::control::KinematicCharacterController;
use super::rapier::prelude::*;
use super::rules::{CollisionRule, CollisionRuleSet};
use super::{at, cuboid};

/// A corridor along +x: a door at x = 2 and a wall at x = 6, and a
/// kinematic character (a ball) at the origin.
struct Corridor {
    world: PhysicsWorld,
    door: (RigidBodyHandle, ColliderHandle),
    wall: ColliderHandle,
    character: (RigidBodyHandle, ColliderHandle),
}

fn corridor() -> Corridor {
    let mut world = PhysicsWorld::new();
    let slab = |x: f32| RigidBodyBuilder::fixed().translation(at(x, 0.0));
    let shape = || {
        cuboid(0.1, 2.0, 2.0).collision_groups(InteractionGroups::new(
            Group::GROUP_2,
            Group::ALL,
            InteractionTestMode::And,
        ))
    };
    let door_body = world.insert_body(slab(2.0));
    let door = world.insert_collider(shape(), Some(door_body));
    let wall_body = world.insert_body(slab(6.0));
    let wall = world.insert_collider(shape(), Some(wall_body));
    let body = world.insert_body(RigidBodyBuilder::kinematic_position_based());
    let ball = world.insert_collider(ColliderBuilder::ball(0.3), Some(body));
    world.step();
    Corridor {
        world,
        door: (door_body, door),
        wall,
        character: (body, ball),
    }
}

fn first_hit(
    corridor: &Corridor,
    rules: &CollisionRuleSet,
    filter: QueryFilter,
) -> Option<ColliderHandle> {
    let world = &corridor.world;
    let passes = rules.query_predicate(&world.bodies, &world.colliders, corridor.character.1);
    let ray = Ray::new(Vector::ZERO, Vector::X);
    world
        .query_pipeline_with_filter(filter.predicate(&passes))
        .cast_ray(&ray, 100.0, true)
        .map(|(collider, _)| collider)
}

#[test]
fn a_ray_passes_what_the_rules_let_through_and_stops_at_the_rest() {
    let c = corridor();
    let (door_body, door) = c.door;
    for (rule, stops_at) in [
        (None, Some(door)),
        (Some(CollisionRule::Normal), Some(door)),
        (Some(CollisionRule::NoResponse), Some(c.wall)),
        (Some(CollisionRule::NoContacts), Some(c.wall)),
        (Some(CollisionRule::NoPair), Some(c.wall)),
    ] {
        let mut rules = CollisionRuleSet::default();
        if let Some(rule) = rule {
            rules.set_specific(c.character.0, door_body, rule);
        }
        let hit = first_hit(&c, &rules, QueryFilter::default());
        assert_eq!(hit, stops_at, "the door says {rule:?}: the ray hit {hit:?}");
    }
}

#[test]
fn rapier_query_groups_keep_working_beside_the_predicate() {
    let c = corridor();
    let mut rules = CollisionRuleSet::default();
    rules.set_specific(c.character.0, c.door.0, CollisionRule::NoResponse);
    // The query's own groups leave out both slabs (they are on GROUP_2).
    let groups = InteractionGroups::new(Group::ALL, Group::GROUP_1, InteractionTestMode::And);
    let hit = first_hit(&c, &rules, QueryFilter::default().groups(groups));
    assert_eq!(
        hit, None,
        "the query's groups leave out the wall too: {hit:?}"
    );
    // Excluding the wall's body by Rapier's own filter: nothing is left.
    let wall_body = c.world.colliders[c.wall].parent().expect("on a body");
    let hit = first_hit(
        &c,
        &rules,
        QueryFilter::default().exclude_rigid_body(wall_body),
    );
    assert_eq!(hit, None, "the door passes, the wall is excluded: {hit:?}");
}

/// Walks the character 8 m along +x with Rapier's controller; returns
/// where it stopped.
fn walk(rules: &CollisionRuleSet) -> f32 {
    let mut c = corridor();
    let controller = KinematicCharacterController {
        snap_to_ground: None,
        ..KinematicCharacterController::default()
    };
    let (body, ball) = c.character;
    let dt = 1.0 / 60.0;
    for _ in 0..240 {
        let next = {
            let world = &c.world;
            let passes = rules.query_predicate(&world.bodies, &world.colliders, ball);
            let filter = QueryFilter::default()
                .exclude_rigid_body(body)
                .predicate(&passes);
            let queries = world.query_pipeline_with_filter(filter);
            let collider = &world.colliders[ball];
            let movement = controller.move_shape(
                dt,
                &queries,
                collider.shape(),
                collider.position(),
                at(2.0 * dt, 0.0),
                |_| {},
            );
            world.bodies[body].translation() + movement.translation
        };
        c.world.bodies[body].set_next_kinematic_translation(next);
        c.world.step();
    }
    c.world.bodies[body].translation().x
}

#[test]
fn the_character_controller_walks_through_the_door_the_rules_open_and_stops_at_the_wall() {
    let closed = walk(&CollisionRuleSet::default());
    assert!(
        (1.4..1.7).contains(&closed),
        "no rule: the door stops the character at x = {closed}"
    );
    let c = corridor();
    let mut rules = CollisionRuleSet::default();
    rules.set_specific(c.character.0, c.door.0, CollisionRule::NoResponse);
    let open = walk(&rules);
    assert!(
        (5.4..5.7).contains(&open),
        "the rule opens the door; the wall stops the character at x = {open}"
    );
}
