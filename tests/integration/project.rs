//! A project's own Rapier settings keep working beside the rules: collision
//! groups and `NoPair` both filter, solver groups and `NoResponse` both drop
//! the response, collision types are kept, runtime changes are followed, and
//! a world with layers and no rules steps bit for bit as plain Rapier.

use super::rapier::prelude::*;
use super::rules::{CollisionRule, CollisionRuleSet, OneWay, RuleHooks};
use super::{at, cuboid};

use super::scenes::Scene;
use CollisionRule::*;

fn layer(memberships: Group, filter: Group) -> InteractionGroups {
    InteractionGroups::new(memberships, filter, InteractionTestMode::And)
}

/// Bits projects name their layers with.
const PLAYER: Group = Group::GROUP_1;
const DEBRIS: Group = Group::GROUP_2;
const WORLD: Group = Group::GROUP_3;

/// Four columns of five boxes on a floor; column `i` gets `groups[i]` as
/// its project collision groups.
fn layered_pile(groups: [InteractionGroups; 4]) -> (PhysicsWorld, Vec<RigidBodyHandle>) {
    let mut world = PhysicsWorld::new();
    let ground = world.insert_body(RigidBodyBuilder::fixed().translation(at(0.0, -0.5)));
    world.insert_collider(
        cuboid(20.0, 0.5, 20.0).collision_groups(layer(WORLD, Group::ALL)),
        Some(ground),
    );
    let bodies = (0..20)
        .map(|i| {
            let (column, level) = (i / 5, i % 5);
            let body = world.insert_body(
                RigidBodyBuilder::dynamic()
                    .translation(at(column as f32 * 1.01, 0.5 + level as f32 * 1.05)),
            );
            world.insert_collider(
                cuboid(0.5, 0.5, 0.5).collision_groups(groups[column]),
                Some(body),
            );
            body
        })
        .collect();
    (world, bodies)
}

/// The rules of the group tests: columns 0 and 1 of a layered pile in two
/// groups that never pair.
fn first_columns_apart(bodies: &[RigidBodyHandle]) -> CollisionRuleSet {
    let mut rules = CollisionRuleSet::default();
    let (g0, g1) = (rules.create_group(), rules.create_group());
    rules.set_group_rule(g0, g1, NoPair);
    for &body in &bodies[0..5] {
        rules.set_group(body, Some(g0));
    }
    for &body in &bodies[5..10] {
        rules.set_group(body, Some(g1));
    }
    rules
}

fn assert_same_poses(plain: &PhysicsWorld, world: &PhysicsWorld, bodies: &[RigidBodyHandle]) {
    for &body in bodies {
        let (a, b) = (plain.bodies[body].position(), world.bodies[body].position());
        assert_eq!(a, b, "a box drifted from plain Rapier: {a:?} vs {b:?}");
    }
}

/// The project's layers of the layered pile's columns: the player (column
/// 0) ignores debris (columns 1 and 2), debris ignores debris.
fn debris_layers() -> [InteractionGroups; 4] {
    [
        layer(PLAYER, Group::ALL - DEBRIS),
        layer(DEBRIS, Group::ALL - DEBRIS - PLAYER),
        layer(DEBRIS, Group::ALL - DEBRIS - PLAYER),
        InteractionGroups::all(),
    ]
}

fn collider_of(world: &PhysicsWorld, body: RigidBodyHandle) -> ColliderHandle {
    world.bodies[body].colliders()[0]
}

#[test]
fn project_layers_without_rules_step_bit_for_bit_as_plain_rapier() {
    let groups = debris_layers();
    let (mut plain, bodies) = layered_pile(groups);
    let (mut world, _) = layered_pile(groups);
    let mut hooks = RuleHooks::default();
    for _ in 0..150 {
        plain.step();
        hooks.step(&mut world);
    }
    assert_same_poses(&plain, &world, &bodies);
    for (handle, collider) in world.colliders.iter() {
        assert_eq!(
            collider.collision_groups(),
            plain.colliders[handle].collision_groups(),
            "the project's groups of {handle:?} were changed"
        );
    }
}

#[test]
fn group_rules_share_the_bits_project_layers_leave_free() {
    // The rules: columns 0 and 1 never pair. The project: column 3 is on
    // the player layer, which the floor and everything else accept.
    let project = [
        InteractionGroups::all(),
        InteractionGroups::all(),
        InteractionGroups::all(),
        layer(PLAYER, Group::ALL),
    ];
    let (mut world, bodies) = layered_pile(project);
    let rules = first_columns_apart(&bodies);
    // The same by hand: two free bits for the rule, the player layer kept.
    let bit = |i: u32| Group::from_bits_retain(1 << i);
    let by_hand = [
        layer(bit(20), Group::ALL - bit(21)),
        layer(bit(21), Group::ALL - bit(20)),
        InteractionGroups::all(),
        layer(PLAYER, Group::ALL),
    ];
    let (mut plain, _) = layered_pile(by_hand);
    let mut hooks = RuleHooks::new(rules);
    for _ in 0..150 {
        plain.step();
        hooks.step(&mut world);
    }
    assert_eq!(
        hooks.stats().hooked_colliders,
        0,
        "the rules could share the bits: {:?}",
        hooks.stats()
    );
    assert_same_poses(&plain, &world, &bodies);
    let player = collider_of(&world, bodies[15]);
    assert_eq!(
        world.colliders[player].collision_groups(),
        layer(PLAYER, Group::ALL),
        "the player's layer was changed"
    );
}

#[test]
fn group_rules_fall_back_to_the_hook_where_project_layers_take_the_bits() {
    // Column 3 accepts only the player layer: no bit is free in its filter,
    // so the rule's groups are hooked, and stay exact. Without recycling the
    // hooked and the hand-written worlds can be compared bit for bit.
    let project = [
        InteractionGroups::all(),
        InteractionGroups::all(),
        InteractionGroups::all(),
        layer(PLAYER, PLAYER | WORLD),
    ];
    let (mut world, bodies) = layered_pile(project);
    world.integration_parameters.contact_recycling = false;
    let rules = first_columns_apart(&bodies);
    let bit = |i: u32| Group::from_bits_retain(1 << i);
    // By hand, the player layer is given every bit the rule uses.
    let by_hand = [
        layer(bit(20), Group::ALL - bit(21)),
        layer(bit(21), Group::ALL - bit(20)),
        InteractionGroups::all(),
        layer(PLAYER, PLAYER | WORLD | bit(20) | bit(21)),
    ];
    let (mut plain, _) = layered_pile(by_hand);
    plain.integration_parameters.contact_recycling = false;
    let mut hooks = RuleHooks::new(rules);
    for _ in 0..150 {
        plain.step();
        hooks.step(&mut world);
    }
    assert_eq!(
        hooks.stats().hooked_colliders,
        10,
        "the two ruled columns fall back to the hook: {:?}",
        hooks.stats()
    );
    assert_same_poses(&plain, &world, &bodies);
}

/// A cube resting on the floor and one dropped on it from 3 m: the scene,
/// the lower collider, the upper body and collider.
fn stacked() -> (Scene, ColliderHandle, (RigidBodyHandle, ColliderHandle)) {
    let mut scene = Scene::new();
    let (_, lower) = scene.cube(0.0, 0.5);
    let upper = scene.cube(0.0, 3.0);
    (scene, lower, upper)
}

/// Layers that keep debris (the lower cube) and the player (the upper
/// one) apart.
fn apart() -> [InteractionGroups; 2] {
    [
        layer(DEBRIS, Group::ALL - PLAYER),
        layer(PLAYER, Group::ALL - DEBRIS),
    ]
}

/// A cube dropped on another; the project's groups and one rule between
/// them. Returns the upper cube's height after a second.
fn dropped(project_excludes: bool, rule: Option<(CollisionRule, bool)>) -> f32 {
    let (mut scene, lower, (upper_body, upper)) = stacked();
    if project_excludes {
        let [l, u] = apart();
        scene.world.colliders[lower].set_collision_groups(l);
        scene.world.colliders[upper].set_collision_groups(u);
    }
    let mut hooks = RuleHooks::default();
    if let Some((rule, upper_names)) = rule {
        if upper_names {
            hooks.rules_mut().set_specific(upper, lower, rule);
        } else {
            hooks.rules_mut().set_specific(lower, upper, rule);
        }
    }
    for _ in 0..60 {
        hooks.step(&mut scene.world);
    }
    scene.y(upper_body)
}

#[test]
fn a_pair_interacts_only_where_both_the_project_and_the_rules_allow() {
    let rests = |y: f32| (1.3..1.7).contains(&y);
    for upper_names in [false, true] {
        // Groups forbid, the rule allows: the groups win.
        let y = dropped(true, Some((Normal, upper_names)));
        assert!(
            !rests(y),
            "project groups exclude, specific Normal (upper names: {upper_names}): y = {y}"
        );
        // Groups allow, the rule forbids: the rule wins.
        let y = dropped(false, Some((NoPair, upper_names)));
        assert!(
            !rests(y),
            "project groups allow, specific NoPair (upper names: {upper_names}): y = {y}"
        );
        // Both allow.
        let y = dropped(false, Some((Normal, upper_names)));
        assert!(rests(y), "both allow (upper names: {upper_names}): y = {y}");
    }
    let y = dropped(true, None);
    assert!(!rests(y), "project groups alone: y = {y}");
}

#[test]
fn project_solver_groups_and_a_per_pair_no_response_both_drop_the_response() {
    for (solver_excludes, rule) in [
        (true, None),
        (true, Some(Normal)),
        (false, Some(NoResponse)),
    ] {
        let (mut scene, lower, (upper_body, upper)) = stacked();
        if solver_excludes {
            let [l, u] = apart();
            scene.world.colliders[lower].set_solver_groups(l);
            scene.world.colliders[upper].set_solver_groups(u);
        }
        let mut hooks = RuleHooks::default();
        if let Some(rule) = rule {
            hooks.rules_mut().set_specific(upper, lower, rule);
        }
        let mut touched = false;
        for _ in 0..60 {
            hooks.step(&mut scene.world);
            touched |= scene.touching(upper, lower);
        }
        let y = scene.y(upper_body);
        assert!(
            touched && y < 1.0,
            "solver groups exclude: {solver_excludes}, rule {rule:?}: touched {touched}, y = {y}"
        );
    }
}

#[test]
fn project_collision_types_are_kept_and_pair_a_hooked_kinematic_with_a_wall() {
    // A kinematic sensor that the project lets see fixed colliders, and a
    // rule that hooks it (a specific entry about a fixed collider, so it
    // carries the entry). Plain Rapier pairs it with the wall; so do the rules.
    let run = |with_rule: bool, project_types: bool| {
        let mut scene = Scene::new();
        let wall_body = scene.world.insert_body(RigidBodyBuilder::fixed());
        let wall = scene
            .world
            .insert_collider(cuboid(1.0, 1.0, 1.0), Some(wall_body));
        let door = scene
            .world
            .insert_body(RigidBodyBuilder::fixed().translation(at(8.0, 1.0)));
        let door = scene
            .world
            .insert_collider(cuboid(1.0, 1.0, 1.0), Some(door));
        let body = scene
            .world
            .insert_body(RigidBodyBuilder::kinematic_position_based().translation(at(0.5, 0.0)));
        let mut sensor = ColliderBuilder::ball(0.5).sensor(true);
        if project_types {
            sensor = sensor.active_collision_types(
                ActiveCollisionTypes::default() | ActiveCollisionTypes::KINEMATIC_FIXED,
            );
        }
        let sensor = scene.world.insert_collider(sensor, Some(body));
        let mut hooks = RuleHooks::default();
        if with_rule {
            hooks.rules_mut().set_specific(sensor, door, NoPair);
        }
        for _ in 0..3 {
            hooks.step(&mut scene.world);
        }
        let sees = scene.world.narrow_phase.intersection_pair(sensor, wall) == Some(true);
        let types = scene.world.colliders[sensor].active_collision_types();
        (sees, hooks.pair_rule(&scene.world, sensor, wall), types)
    };
    let (plain_sees, _, _) = run(false, true);
    assert!(
        plain_sees,
        "the project's types let the sensor see the wall"
    );
    let (sees, rule, types) = run(true, true);
    assert!(
        sees && rule == Some(NoResponse),
        "with a rule on the sensor: sees {sees}, rule {rule:?}"
    );
    assert!(
        types.contains(ActiveCollisionTypes::KINEMATIC_FIXED),
        "the project's types were taken away: {types:?}"
    );
    // Without the project's types, the built-in entry keeps them apart.
    let (sees, rule, _) = run(true, false);
    assert!(
        !sees && rule.is_none(),
        "default types: sees {sees}, rule {rule:?}"
    );
}

#[test]
fn groups_the_project_changes_at_runtime_are_followed() {
    // The lower cube is planned (a group with a rule), the upper hooked (a
    // personal rule); the project then puts them on layers that exclude
    // each other, through Rapier, after they touched.
    let mut scene = Scene::new();
    let (_, lower) = scene.cube(0.0, 0.5);
    let (upper_body, upper) = scene.cube(0.0, 1.6);
    let mut hooks = RuleHooks::default();
    let rules = hooks.rules_mut();
    let (g, h) = (rules.create_group(), rules.create_group());
    rules.set_group(lower, Some(g));
    rules.set_group_rule(g, h, NoPair);
    rules.set_personal(upper, Normal);
    for _ in 0..30 {
        hooks.step(&mut scene.world);
    }
    let resting = scene.y(upper_body);
    assert!(
        (1.3..1.7).contains(&resting)
            && hooks.pair_rule(&scene.world, upper, lower) == Some(Normal),
        "before: y = {resting}"
    );
    scene.world.colliders[lower].set_collision_groups(layer(DEBRIS, Group::ALL - PLAYER));
    scene.world.colliders[upper].set_collision_groups(layer(PLAYER, Group::ALL - DEBRIS));
    for _ in 0..30 {
        hooks.step(&mut scene.world);
    }
    let y = scene.y(upper_body);
    assert!(y < 0.5, "the project's new layers exclude them: y = {y}");
    assert_eq!(hooks.pair_rule(&scene.world, upper, lower), None);
    assert_eq!(hooks.pair_rule(&scene.world, lower, upper), None);
    // The rules never wrote over the project's new layers.
    assert_eq!(
        scene.world.colliders[upper].collision_groups(),
        layer(PLAYER, Group::ALL - DEBRIS)
    );
}

#[test]
fn a_collider_the_rules_let_go_of_gets_the_project_settings_back() {
    let mut scene = Scene::new();
    let (body, cube) = scene.cube(0.0, 0.5);
    let own = layer(DEBRIS, Group::ALL - PLAYER);
    scene.world.colliders[cube].set_collision_groups(own);
    scene.world.colliders[cube].set_active_hooks(ActiveHooks::MODIFY_SOLVER_CONTACTS);
    let mut hooks = RuleHooks::default();
    // No group test says NoContacts: the collider is hooked.
    hooks.rules_mut().set_personal(body, NoContacts);
    hooks.step(&mut scene.world);
    let collider = &scene.world.colliders[cube];
    assert_eq!(collider.collision_groups(), own, "hooked, the groups stay");
    assert!(
        collider
            .active_hooks()
            .contains(ActiveHooks::MODIFY_SOLVER_CONTACTS | ActiveHooks::FILTER_CONTACT_PAIRS),
        "the project's hook bit is kept beside the crate's: {:?}",
        collider.active_hooks()
    );
    hooks.rules_mut().set_personal(body, Defer);
    hooks.step(&mut scene.world);
    let collider = &scene.world.colliders[cube];
    assert_eq!(
        (collider.collision_groups(), collider.active_hooks()),
        (own, ActiveHooks::MODIFY_SOLVER_CONTACTS),
        "let go, the collider has the project's settings"
    );
}

/// A project that changes one of its settings by reading it and writing
/// it back, on colliders the rules wrote to, reads it with
/// `project_settings`: the change is then exactly the project's, and once
/// the rules let the colliders go they have the project's settings and
/// nothing of the rules'. Read from the collider instead, the value carries
/// the rules' bits, which the crate takes as the project's (documented):
/// found by trying the project's settings from the docs alone, where the
/// floor kept the crate's filter bit after the rule was gone and a project
/// ball in that group fell through it (y = -9.07; plain Rapier 1.00).
#[test]
fn settings_read_with_project_settings_and_written_back_keep_only_the_projects_change() {
    let mut scene = Scene::new();
    let (ghost_body, ghost) = scene.cube(0.0, 3.0);
    let (hooked_body, hooked) = scene.cube(5.0, 0.5);
    let mut hooks = RuleHooks::default();
    // The floor and the ghost share a bit; the hooked cube is the hook's.
    hooks.rules_mut().set_specific(ghost_body, scene.ground, NoPair);
    hooks.rules_mut().set_personal(hooked_body, NoContacts);
    hooks.step(&mut scene.world);
    let floor = scene.floor;
    let wrote = [floor, ghost].map(|c| scene.world.colliders[c].collision_groups());
    assert!(
        wrote.iter().any(|&g| g != InteractionGroups::all()),
        "the rule is in Rapier's groups: {wrote:?}"
    );
    let colliders = &scene.world.colliders;
    let own = |c| hooks.project_settings(colliders, c).expect("a collider");
    let (floor_own, hooked_own) = (own(floor), own(hooked));
    assert_eq!(
        (floor_own.collision_groups, hooked_own.active_hooks),
        (InteractionGroups::all(), ActiveHooks::empty()),
        "the project's own, without the rules' bits"
    );
    // The project's read-modify-write: a layer out of the floor's
    // memberships, a hook of its own on the hooked cube.
    let groups = floor_own.collision_groups;
    scene.world.colliders[floor].set_collision_groups(InteractionGroups::new(
        groups.memberships - Group::GROUP_5,
        groups.filter,
        groups.test_mode,
    ));
    scene.world.colliders[hooked]
        .set_active_hooks(hooked_own.active_hooks | ActiveHooks::MODIFY_SOLVER_CONTACTS);
    hooks.step(&mut scene.world);
    hooks.rules_mut().remove_specific(ghost_body, scene.ground);
    hooks.rules_mut().set_personal(hooked_body, Defer);
    for _ in 0..5 {
        hooks.step(&mut scene.world);
    }
    let project_floor = layer(Group::ALL - Group::GROUP_5, Group::ALL);
    let settings = |scene: &Scene| {
        let (f, h) = (&scene.world.colliders[floor], &scene.world.colliders[hooked]);
        (f.collision_groups(), h.active_hooks())
    };
    assert_eq!(
        settings(&scene),
        (project_floor, ActiveHooks::MODIFY_SOLVER_CONTACTS),
        "the rules gone, the floor and the cube have the project's settings"
    );
    hooks.restore_project_settings(&mut scene.world.colliders);
    assert_eq!(
        settings(&scene),
        (project_floor, ActiveHooks::MODIFY_SOLVER_CONTACTS),
        "and restore gives the same back"
    );
    // What that means: a project ball in any one group lands on the floor.
    let balls: Vec<(u32, RigidBodyHandle)> = (0..32)
        .map(|i| {
            let body = scene.world.insert_body(
                RigidBodyBuilder::dynamic().translation(at(-10.0 + 0.6 * i as f32, 1.0)),
            );
            let groups = layer(Group::from_bits_retain(1 << i), Group::ALL);
            let ball = ColliderBuilder::ball(0.25).collision_groups(groups);
            scene.world.insert_collider(ball, Some(body));
            (i, body)
        })
        .collect();
    for _ in 0..90 {
        hooks.step(&mut scene.world);
    }
    for (i, body) in balls {
        let y = scene.y(body);
        assert!(y > 0.2, "the ball in group {} fell through the floor: y = {y}", i + 1);
    }
}

#[test]
fn a_ruled_collider_on_its_own_layer_is_hooked_and_keeps_the_layer() {
    // Column 0 is on the debris layer and in a group that never pairs with
    // column 1's: a group bit cannot be added to its own layer, so it is
    // hooked, keeps the layer, and the rule still holds.
    let debris = layer(DEBRIS, Group::ALL);
    let project = [
        debris,
        InteractionGroups::all(),
        InteractionGroups::all(),
        InteractionGroups::all(),
    ];
    let (mut world, bodies) = layered_pile(project);
    let rules = first_columns_apart(&bodies);
    let mut hooks = RuleHooks::new(rules);
    for _ in 0..30 {
        hooks.step(&mut world);
    }
    assert_eq!(hooks.stats().hooked_colliders, 5, "{:?}", hooks.stats());
    for i in 0..5 {
        let (a, b) = (
            collider_of(&world, bodies[i]),
            collider_of(&world, bodies[5 + i]),
        );
        assert_eq!(world.colliders[a].collision_groups(), debris);
        assert!(
            !world.colliders[a].active_hooks().is_empty(),
            "box {i} of column 0 is hooked"
        );
        assert_eq!(
            hooks.pair_rule(&world, a, b),
            None,
            "boxes {i} of columns 0 and 1 pair"
        );
    }
}

/// The project's hooks: platforms (user data 1) let bodies through from
/// below, and colliders with user data 2 are kept out of every pair. Counts
/// the filter calls per collider pair seen.
#[derive(Default)]
struct ProjectHooks {
    filtered: std::sync::Mutex<Vec<(ColliderHandle, ColliderHandle)>>,
}

impl PhysicsHooks for ProjectHooks {
    fn filter_contact_pair(&self, context: &PairFilterContext) -> Option<SolverFlags> {
        self.filtered
            .lock()
            .unwrap()
            .push((context.collider1, context.collider2));
        let banned = |c: ColliderHandle| context.colliders[c].user_data == 2;
        if banned(context.collider1) || banned(context.collider2) {
            None
        } else {
            Some(SolverFlags::COMPUTE_RIGID_IMPULSES)
        }
    }

    fn modify_solver_contacts(&self, context: &mut ContactModificationContext) {
        context.update_as_oneway_platform(Vector::Y, 0.1);
    }
}

/// A platform at height 2 with the project's one-way hook (user data 1),
/// and a ball thrown up through it from below: the world, the platform's
/// body and collider, and the ball.
fn project_platform() -> (PhysicsWorld, RigidBodyHandle, ColliderHandle, RigidBodyHandle) {
    let mut world = PhysicsWorld::new();
    let platform = world.insert_body(RigidBodyBuilder::fixed().translation(at(0.0, 2.0)));
    let deck = world.insert_collider(
        cuboid(4.0, 0.1, 4.0)
            .active_hooks(ActiveHooks::MODIFY_SOLVER_CONTACTS)
            .user_data(1),
        Some(platform),
    );
    let ball = world.insert_body(
        RigidBodyBuilder::dynamic()
            .translation(at(-1.0, 0.0))
            .linvel(at(0.0, 8.0)),
    );
    world.insert_collider(ColliderBuilder::ball(0.25), Some(ball));
    (world, platform, deck, ball)
}

#[test]
fn a_one_way_platform_of_the_project_beside_a_ghost_the_rules_let_through() {
    // The ball thrown up through the platform, and a ghost dropped onto it.
    let (mut world, platform, deck, ball) = project_platform();
    let ghost = world.insert_body(RigidBodyBuilder::dynamic().translation(at(1.0, 3.0)));
    let g = world.insert_collider(ColliderBuilder::ball(0.25), Some(ghost));
    let mut hooks = RuleHooks::default();
    hooks.rules_mut().set_specific(ghost, platform, NoResponse);
    hooks.set_user_hooks(ProjectHooks::default());
    let mut paired = false;
    for _ in 0..120 {
        hooks.step(&mut world);
        paired |= hooks.pair_rule(&world, g, deck) == Some(NoResponse);
    }
    let (yb, yg) = (
        world.bodies[ball].translation().y,
        world.bodies[ghost].translation().y,
    );
    assert!(
        (2.2..2.5).contains(&yb),
        "the ball went up through the one-way platform and rests on it: y = {yb}"
    );
    assert!(
        paired && yg < 0.0,
        "the ghost fell through the platform: y = {yg}, paired {paired}"
    );
}

/// Found by a misuse audit: a platform the project kept its own one-way
/// hook on (Rapier's `update_as_oneway_platform`) and also made a one-way
/// surface of the rules' panicked inside Rapier ("entered unreachable
/// code"): Rapier's helper met the standings the crate keeps in the top
/// bits of the manifold's `user_data`. The project's hook now sees the
/// field without them, and both surfaces apply.
#[test]
fn the_projects_one_way_hook_on_a_surface_of_the_rules_sees_only_its_own_state() {
    let (mut world, platform, _, ball) = project_platform();
    let mut hooks = RuleHooks::default();
    hooks
        .rules_mut()
        .set_one_way(platform, Some(OneWay::new(at(0.0, 1.0))));
    hooks.set_user_hooks(ProjectHooks::default());
    for _ in 0..120 {
        hooks.step(&mut world);
    }
    let y = world.bodies[ball].translation().y;
    assert!(
        (2.2..2.5).contains(&y),
        "the ball went up through both surfaces and rests on the platform: y = {y}"
    );
}

#[test]
fn the_project_filter_restricts_the_pairs_the_rules_let_through_and_never_sees_the_others() {
    for (rule, banned) in [
        (Normal, false),
        (Normal, true),
        (NoResponse, true),
        (NoPair, false),
        (NoContacts, false),
    ] {
        let mut scene = Scene::new();
        let (_, lower) = scene.cube(0.0, 0.5);
        let (upper_body, upper) = scene.cube(0.0, 3.0);
        let world = &mut scene.world;
        world.colliders[upper].set_active_hooks(ActiveHooks::FILTER_CONTACT_PAIRS);
        if banned {
            world.colliders[upper].user_data = 2;
        }
        let mut hooks = RuleHooks::default();
        hooks.rules_mut().set_specific(upper, lower, rule);
        hooks.set_user_hooks(ProjectHooks::default());
        for _ in 0..60 {
            hooks.step(&mut scene.world);
        }
        let y = scene.y(upper_body);
        assert!(hooks.remove_user_hooks().is_some(), "the hooks were set");
        let rests = (1.3..1.7).contains(&y);
        assert_eq!(
            rests,
            rule == Normal && !banned,
            "rule {rule:?}, banned by the project: {banned}: y = {y}"
        );
    }
}

#[test]
fn the_project_filter_is_asked_only_for_pairs_the_rules_let_through() {
    use std::sync::Arc;
    /// Shares its log with the test.
    struct Shared(Arc<ProjectHooks>);
    impl PhysicsHooks for Shared {
        fn filter_contact_pair(&self, context: &PairFilterContext) -> Option<SolverFlags> {
            self.0.filter_contact_pair(context)
        }
    }
    for rule in [Normal, NoResponse, NoContacts, NoPair] {
        let mut scene = Scene::new();
        let (_, lower) = scene.cube(0.0, 0.5);
        let (_, upper) = scene.cube(0.0, 1.6);
        scene.world.colliders[upper].set_active_hooks(ActiveHooks::FILTER_CONTACT_PAIRS);
        let log = Arc::new(ProjectHooks::default());
        let mut hooks = RuleHooks::default();
        hooks.rules_mut().set_specific(upper, lower, rule);
        hooks.set_user_hooks(Shared(log.clone()));
        for _ in 0..10 {
            hooks.step(&mut scene.world);
        }
        let asked = log
            .filtered
            .lock()
            .unwrap()
            .iter()
            .filter(|&&(a, b)| (a, b) == (upper, lower) || (b, a) == (upper, lower))
            .count();
        let lets_through = matches!(rule, Normal | NoResponse);
        assert_eq!(
            asked > 0,
            lets_through,
            "rule {rule:?}: the project's filter was asked {asked} times"
        );
    }
}

#[test]
fn layers_moved_into_the_rules_step_bit_for_bit_as_the_layers() {
    // Column 0 does not respond to column 3 (solver groups).
    let collision = debris_layers();
    let (mut plain, bodies) = layered_pile(collision);
    let solver_of_column = |column: usize| match column {
        0 => layer(PLAYER, Group::ALL),
        3 => layer(Group::GROUP_4, Group::ALL - PLAYER),
        _ => InteractionGroups::all(),
    };
    for (i, &body) in bodies.iter().enumerate() {
        let collider = collider_of(&plain, body);
        plain.colliders[collider].set_solver_groups(solver_of_column(i / 5));
    }
    // The same world with its layers moved into the rules.
    let (mut world, _) = layered_pile([InteractionGroups::all(); 4]);
    let floor_setting = (layer(WORLD, Group::ALL), InteractionGroups::all());
    let mut settings = vec![floor_setting];
    settings.extend((0..20).map(|i| (collision[i / 5], solver_of_column(i / 5))));
    let mut rules = CollisionRuleSet::default();
    let groups = rules.groups_from_layers(&settings);
    let floor = world
        .colliders
        .iter()
        .next()
        .map(|(h, _)| h)
        .expect("the floor");
    world.colliders[floor].set_collision_groups(InteractionGroups::all());
    // On the body: a chain whose nodes are in different groups is hooked.
    let ground = world.colliders[floor].parent().expect("on the ground");
    rules.set_group(ground, Some(groups[0]));
    for (i, &body) in bodies.iter().enumerate() {
        rules.set_group(body, Some(groups[1 + i]));
    }
    let mut hooks = RuleHooks::new(rules);
    for _ in 0..150 {
        plain.step();
        hooks.step(&mut world);
    }
    let hooked: Vec<_> = world
        .colliders
        .iter()
        .filter(|(_, c)| !c.active_hooks().is_empty())
        .map(|(h, c)| (h, c.parent().map(|b| world.bodies[b].body_type())))
        .collect();
    assert_eq!(
        hooks.stats().hooked_colliders,
        0,
        "hooked: {hooked:?}, {:?}",
        hooks.stats()
    );
    assert_same_poses(&plain, &world, &bodies);
}

/// Two boxes on the floor in groups that never pair, which the plan gives
/// bits, and one more cube made by `before` ahead of the first step; then
/// `edit` changes the world through Rapier and names the cube to watch, the
/// project says so (`told`) or not, and the world steps 60 times. Returns
/// whether the plan shared its bits with the project, and where the cube
/// came to rest.
/// Two cubes on the floor, 3 m apart, in two groups set apart (`NoPair`):
/// a plan whose groups take Rapier bits, shared with the project's
/// settings.
fn two_boxes_in_groups_apart(scene: &mut Scene) -> RuleHooks {
    let (a, _) = scene.cube(0.0, 0.5);
    let (b, _) = scene.cube(3.0, 0.5);
    let mut hooks = RuleHooks::default();
    let rules = hooks.rules_mut();
    let (g, h) = (rules.create_group(), rules.create_group());
    rules.set_group_rule(g, h, NoPair);
    rules.set_group(a, Some(g));
    rules.set_group(b, Some(h));
    hooks
}

fn boxes_apart(
    told: bool,
    before: impl Fn(&mut Scene) -> (RigidBodyHandle, ColliderHandle),
    edit: impl Fn(&mut Scene, (RigidBodyHandle, ColliderHandle)) -> RigidBodyHandle,
) -> (bool, f32) {
    let mut scene = Scene::new();
    let mut hooks = two_boxes_in_groups_apart(&mut scene);
    let extra = before(&mut scene);
    hooks.step(&mut scene.world);
    let shares = hooks.stats().shares_project_bits;
    let watched = edit(&mut scene, extra);
    if told {
        hooks.project_settings_changed();
    }
    for _ in 0..60 {
        hooks.step(&mut scene.world);
    }
    (shares, scene.y(watched))
}

#[test]
fn after_project_settings_changed_the_plan_reads_every_collider_again() {
    // A cube no rule reaches drops onto a box whose group has a bit; while
    // it falls, the project narrows the cube's filter to the player layer,
    // which leaves the group's bit out.
    let run = |told: bool| {
        boxes_apart(
            told,
            |scene| scene.cube(0.0, 3.0),
            |scene, (cube_body, cube)| {
                scene.world.colliders[cube].set_collision_groups(layer(PLAYER, PLAYER));
                cube_body
            },
        )
    };
    let (shares, y) = run(true);
    assert!(shares, "the group rule's bits are shared with the project");
    // The box's own groups are Rapier's defaults: the cube lands on it.
    assert!(
        (1.3..1.7).contains(&y),
        "told: the cube rests on the box: y = {y}"
    );
    let (_, y) = run(false);
    assert!(
        y < 1.0,
        "not told, the plan keeps bits the cube's new filter leaves out: y = {y}"
    );
}

#[test]
fn a_step_that_removes_as_many_colliders_as_it_adds_is_seen_once_told() {
    // As above, but the cube comes with its layer in the step a spare cube
    // goes: the number of colliders is unchanged, so the hooks do not read
    // the room again by themselves (`semantics.md`, "The project's own
    // settings"); `project_settings_changed` makes the next step read it.
    let run = |told: bool| {
        let (_, y) = boxes_apart(
            told,
            |scene| scene.cube(-3.0, 0.5),
            |scene, (spare, _)| {
                let count = scene.world.colliders.len();
                scene.world.remove_body(spare);
                let body = scene
                    .world
                    .insert_body(RigidBodyBuilder::dynamic().translation(at(0.0, 3.0)));
                scene.world.insert_collider(
                    cuboid(0.5, 0.5, 0.5).collision_groups(layer(PLAYER, PLAYER)),
                    Some(body),
                );
                assert_eq!(scene.world.colliders.len(), count, "as many in as out");
                body
            },
        );
        y
    };
    let y = run(true);
    assert!(
        (1.3..1.7).contains(&y),
        "told: the cube rests on the box: y = {y}"
    );
    let y = run(false);
    assert!(
        y < 1.0,
        "not told, the plan keeps bits the new cube's filter leaves out: y = {y}"
    );
}

/// Found by a large level built from the docs: a step after colliders came
/// or went read every collider's settings again, which nothing in the
/// stats said. `read_every_collider` says it, at that step only.
#[test]
fn the_stats_say_when_colliders_coming_or_going_read_every_collider() {
    let mut scene = Scene::new();
    let mut hooks = two_boxes_in_groups_apart(&mut scene);
    hooks.step(&mut scene.world);
    assert!(hooks.stats().shares_project_bits, "{:?}", hooks.stats());
    hooks.step(&mut scene.world);
    assert!(!hooks.stats().read_every_collider, "nothing came: {:?}", hooks.stats());
    let (_, added) = scene.cube(6.0, 3.0);
    hooks.step(&mut scene.world);
    assert!(hooks.stats().read_every_collider, "a cube came: {:?}", hooks.stats());
    hooks.step(&mut scene.world);
    assert!(!hooks.stats().read_every_collider, "nothing came: {:?}", hooks.stats());
    scene.world.remove_collider(added);
    hooks.step(&mut scene.world);
    assert!(hooks.stats().read_every_collider, "a cube went: {:?}", hooks.stats());
}
