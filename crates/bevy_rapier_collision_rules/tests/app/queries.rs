//! Queries and character controllers that see the rules: a controller
//! walks through a door its rule opens and is stopped by a `Normal` wall
//! behind it, a ray passes the door and hits the wall, and the pair
//! questions answer with entities.

use CollisionRule::*;
use std::sync::Arc;

use bevy::prelude::*;
use bevy_rapier::control::{ControllerFilterPredicate, KinematicCharacterController};
use bevy_rapier::prelude::*;
use bevy_rapier_collision_rules::prelude::*;
use bevy_rapier_collision_rules::{EntityExplanation, Stage};

use super::scene::{Sim, ball, cuboid, floor, vect};

/// The door's and the wall's x; the character starts at 0.
const DOOR_X: f32 = 2.0;
const WALL_X: f32 = 6.0;
/// The character's radius and its step each frame.
const RADIUS: f32 = 0.3;
const STEP: f32 = 0.1;

/// A thin fixed slab across the x axis.
fn slab(x: f32) -> impl Bundle {
    (Transform::from_xyz(x, 1.0, 0.0), cuboid(0.1, 1.0, 1.0))
}

/// Moves every controller along +x each frame.
fn push(mut controllers: Query<&mut KinematicCharacterController>) {
    for mut controller in &mut controllers {
        controller.translation = Some(vect(STEP, 0.0, 0.0));
    }
}

struct Corridor {
    sim: Sim,
    door: Entity,
    wall: Entity,
    character: Entity,
}

/// A character at x = 0 facing a door and a wall behind it, with `rule`
/// between it and the door (`None`: no rule), following the rules or not.
fn corridor(rule: Option<CollisionRule>, follows: bool) -> Corridor {
    let mut sim = Sim::new();
    sim.app.add_systems(Update, push);
    let door = sim.spawn(slab(DOOR_X));
    let wall = sim.spawn(slab(WALL_X));
    let character = sim.spawn((
        Transform::from_xyz(0.0, 1.0, 0.0),
        RigidBody::KinematicPositionBased,
        Collider::ball(RADIUS),
        KinematicCharacterController::default(),
    ));
    if let Some(rule) = rule {
        sim.entity_mut(character)
            .insert(SpecificRules::new().with(door, rule));
    }
    if follows {
        sim.entity_mut(character)
            .insert(ControllerFollowsRules::default());
    }
    Corridor {
        sim,
        door,
        wall,
        character,
    }
}

/// Where the character stops in front of a slab at `x` (its face at
/// `x - 0.1`, the controller's offset between).
fn stopped_before(at: f32, x: f32) -> bool {
    let face = x - 0.1 - RADIUS;
    (face - 0.1..=face + 1e-3).contains(&at)
}

const FRAMES: usize = 90;

/// The height of a second character, which walks into a `Normal` wall
/// right above the door, within the reach of the same rules.
const ABOVE_Y: f32 = 3.0;

#[test]
fn a_controller_walks_through_the_door_its_rule_opens_and_is_stopped_by_the_wall() {
    for rule in [NoPair, NoContacts, NoResponse] {
        let mut c = corridor(Some(rule), true);
        // A wall on the door (y 2 to 4), and a second character with the
        // same rule walking into it: the door is within its reach, the
        // wall stops it.
        c.sim.spawn((
            Transform::from_xyz(DOOR_X, ABOVE_Y, 0.0),
            cuboid(0.1, 1.0, 1.0),
        ));
        let second = c.sim.spawn((
            Transform::from_xyz(0.0, ABOVE_Y, 0.0),
            RigidBody::KinematicPositionBased,
            Collider::ball(RADIUS),
            KinematicCharacterController::default(),
            ControllerFollowsRules::default(),
            SpecificRules::new().with(c.door, rule),
        ));
        c.sim.run(FRAMES);
        let x = c.sim.at(c.character).x;
        assert!(
            stopped_before(x, WALL_X),
            "{rule:?} with the door: the character passes it and stops at the wall, x = {x}"
        );
        let x = c.sim.at(second).x;
        assert!(
            stopped_before(x, DOOR_X),
            "{rule:?} with the door: the wall on it stops the second character, x = {x}"
        );
    }
    // A Normal rule, no rule, and the rules not followed: the door stops it.
    for (rule, follows) in [(Some(Normal), true), (None, true), (Some(NoPair), false)] {
        let mut c = corridor(rule, follows);
        c.sim.run(FRAMES);
        let x = c.sim.at(c.character).x;
        assert!(
            stopped_before(x, DOOR_X),
            "{rule:?}, following the rules: {follows}: the door stops the character, x = {x}"
        );
    }
}

/// The predicate on the character's controller.
fn predicate_of(sim: &Sim, character: Entity) -> ControllerFilterPredicate {
    let controller = sim
        .app
        .world()
        .get::<KinematicCharacterController>(character);
    controller
        .unwrap()
        .filter_predicate
        .clone()
        .expect("a predicate")
}

#[test]
fn a_controllers_own_predicate_is_asked_too_and_comes_back_alone() {
    let mut c = corridor(Some(NoPair), true);
    c.sim.run(5);
    // The project sets a predicate of its own after the rules installed
    // theirs: both are asked.
    let wall = c.wall;
    let own = ControllerFilterPredicate::new(move |e, _| e != wall);
    c.sim
        .entity_mut(c.character)
        .get_mut::<KinematicCharacterController>()
        .unwrap()
        .filter_predicate = Some(own.clone());
    c.sim.run(FRAMES);
    let x = c.sim.at(c.character).x;
    assert!(
        x > WALL_X + 1.0,
        "the rules open the door, the project's predicate the wall: x = {x}"
    );
    // Back in front of the door, within reach: the rules leave it out
    // (the move reaches Rapier in the first frame, the decisions are made
    // there in the second).
    c.sim
        .entity_mut(c.character)
        .insert(Transform::from_xyz(DOOR_X - 0.8, 1.0, 0.0));
    c.sim.run(2);
    let ball = rapier_ball();
    let both = predicate_of(&c.sim, c.character);
    assert!(!Arc::ptr_eq(&both.0, &own.0), "the rules' predicate is on");
    assert!(!both.test(c.door, &ball) && !both.test(c.wall, &ball));
    // A new component in place of the old one gives the project's
    // predicate back and installs itself anew, asking it.
    c.sim
        .entity_mut(c.character)
        .insert(ControllerFollowsRules::default());
    c.sim.run(1);
    let again = predicate_of(&c.sim, c.character);
    assert!(!Arc::ptr_eq(&again.0, &both.0), "installed anew");
    assert!(!again.test(c.door, &ball) && !again.test(c.wall, &ball));
    // Without the component, the project's predicate alone, while the
    // door is still within reach.
    c.sim
        .entity_mut(c.character)
        .remove::<ControllerFollowsRules>();
    let alone = predicate_of(&c.sim, c.character);
    assert!(
        Arc::ptr_eq(&alone.0, &own.0),
        "the project's own predicate is back"
    );
    c.sim
        .entity_mut(c.character)
        .insert(Transform::from_xyz(0.0, 1.0, 0.0));
    c.sim.run(FRAMES);
    let x = c.sim.at(c.character).x;
    assert!(
        stopped_before(x, DOOR_X),
        "the door stops it again: x = {x}"
    );
}

/// A Rapier collider to hand a predicate (it reads only the entity).
fn rapier_ball() -> bevy_rapier::rapier::prelude::Collider {
    bevy_rapier::rapier::prelude::ColliderBuilder::ball(0.1).build()
}

/// The first collider hit by a ray along +x from the character's start,
/// with the character's rules as the filter (`None` when the character is
/// not in a context with rules).
fn first_hit(
    source: In<Entity>,
    context: bevy_rapier::plugin::ReadRapierContext,
    rules: RuleQueries,
) -> Option<Entity> {
    let context = context.single().ok()?;
    let passes = rules.predicate(*source)?;
    let filter = QueryFilter::default().predicate(&passes);
    context
        .cast_ray(
            vect(0.0, 1.0, 0.0),
            vect(1.0, 0.0, 0.0),
            100.0,
            true,
            filter,
        )
        .map(|(hit, _)| hit)
}

impl Corridor {
    /// What the character's ray hits first: "wall", `name` for `other`, or
    /// "nothing".
    fn ray_hits(&mut self, other: Entity, name: &'static str) -> &'static str {
        let world = self.sim.app.world_mut();
        match world
            .run_system_cached_with(first_hit, self.character)
            .unwrap()
        {
            Some(e) if e == other => name,
            Some(e) if e == self.wall => "wall",
            _ => "nothing",
        }
    }
}

#[test]
fn a_ray_with_the_rules_passes_the_door_and_hits_the_wall() {
    for (rule, expected) in [
        (Some(NoPair), "wall"),
        (Some(NoContacts), "wall"),
        (Some(NoResponse), "wall"),
        (Some(Normal), "door"),
        (None, "door"),
    ] {
        let mut c = corridor(rule, false);
        c.sim.run(2);
        let door = c.door;
        assert_eq!(c.ray_hits(door, "door"), expected, "{rule:?} with the door");
    }
}

/// The rule and the explanation of a pair of entities.
fn pair_of(
    pair: In<(Entity, Entity)>,
    rules: RuleQueries,
) -> (Option<CollisionRule>, Option<EntityExplanation>) {
    let (a, b) = *pair;
    (rules.pair_rule(a, b), rules.explain(a, b))
}

#[test]
fn pair_questions_take_and_give_entities() {
    let mut sim = Sim::new();
    let f = sim.spawn(floor());
    let resting = sim.spawn(ball(-1.0, 0.3));
    let ghost = sim.spawn((ball(1.0, 0.3), SpecificRules::new().with(f, NoResponse)));
    sim.run(10);
    let mut ask = |a, b| {
        sim.app
            .world_mut()
            .run_system_cached_with(pair_of, (a, b))
            .unwrap()
    };
    let (rule, why) = ask(resting, f);
    assert_eq!(rule, Some(Normal), "a ball resting on the floor");
    assert_eq!(why.map(|w| w.explanation.stage), Some(Stage::Default));
    assert_eq!(why.and_then(|w| w.entities), None);
    for (a, b) in [(ghost, f), (f, ghost)] {
        let (rule, why) = ask(a, b);
        assert_eq!(
            rule,
            Some(NoResponse),
            "the ghost's live pair with the floor"
        );
        let why = why.unwrap();
        assert_eq!(why.explanation.stage, Stage::Specific);
        assert_eq!(
            why.entities,
            Some((a, b)),
            "the entry is between the two entities"
        );
    }
    // Two balls far apart form no pair, and an entity without physics is
    // no answer.
    let (rule, _) = ask(resting, ghost);
    assert_eq!(rule, None);
    let nothing = sim.spawn(Transform::default());
    let mut ask = |a, b| {
        sim.app
            .world_mut()
            .run_system_cached_with(pair_of, (a, b))
            .unwrap()
    };
    assert_eq!(ask(nothing, f), (None, None));
}

/// A soft body's meshes carry the soft body's entity, not one of their
/// own: the ray still asks their rule.
#[cfg(feature = "dim3")]
#[test]
fn a_ray_with_the_rules_passes_a_soft_body_its_rule_opens() {
    for (rule, expected) in [
        (Some(NoPair), "wall"),
        (Some(NoResponse), "wall"),
        (None, "jelly"),
    ] {
        let mut c = corridor(None, false);
        let jelly = c.sim.spawn((
            Transform::from_xyz(DOOR_X + 1.0, 1.0, 0.0),
            SoftBody::cuboid(Vec3::splat(0.5), 3, 3, 3),
        ));
        c.sim.entity_mut(c.door).despawn();
        if let Some(rule) = rule {
            c.sim
                .entity_mut(c.character)
                .insert(SpecificRules::new().with(jelly, rule));
        }
        c.sim.run(2);
        assert_eq!(
            c.ray_hits(jelly, "jelly"),
            expected,
            "{rule:?} with the jelly"
        );
    }
}
