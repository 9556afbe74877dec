//! A parent map alone changes no pair (`docs/semantics.md`, "Effective
//! group"): random hierarchies of dynamic, kinematic and fixed bodies with no
//! rules step bit for bit as plain Rapier; a dynamic crate rides a kinematic
//! lift it is parented to, and groups given to the lift still reach it.

use proptest::prelude::*;
use proptest::test_runner::Config;

use super::rapier::prelude::*;
use super::rules::{CollisionRule, RuleHooks};
use super::{at, cube, pose_bits, slab};

const KINDS: [RigidBodyType; 4] = [
    RigidBodyType::Dynamic,
    RigidBodyType::Fixed,
    RigidBodyType::KinematicPositionBased,
    RigidBodyType::KinematicVelocityBased,
];

/// A scene: a floor, then bodies of the given kinds stacked in columns,
/// each with a parent among the bodies before it (or none).
#[derive(Clone, Debug)]
struct Scene {
    kinds: Vec<usize>,
    parents: Vec<Option<usize>>,
}

fn scene() -> impl Strategy<Value = Scene> {
    (2..10usize)
        .prop_flat_map(|n| {
            let kinds = proptest::collection::vec(0..KINDS.len(), n);
            let parents = (0..n)
                .map(|i| proptest::option::of(0..i.max(1)).prop_map(move |p| p.filter(|&p| p < i)))
                .collect::<Vec<_>>();
            (kinds, parents)
        })
        .prop_map(|(kinds, parents)| Scene { kinds, parents })
}

/// The scene's world and its bodies, the floor first.
fn build(scene: &Scene) -> (PhysicsWorld, Vec<RigidBodyHandle>) {
    let mut world = PhysicsWorld::new();
    let floor = world.insert_body(RigidBodyBuilder::fixed());
    world.insert_collider(slab(20.0, 0.5), Some(floor));
    let mut bodies = vec![floor];
    for (i, &kind) in scene.kinds.iter().enumerate() {
        // Columns of three, a little apart, so that bodies land on each other.
        let (column, row) = ((i % 3) as f32, (i / 3) as f32);
        let body = RigidBodyBuilder::new(KINDS[kind]).translation(at(column * 1.1, 1.0 + row * 1.05));
        let body = world.insert_body(body);
        world.insert_collider(cube(0.5), Some(body));
        bodies.push(body);
    }
    (world, bodies)
}

/// Moves the kinematic bodies as an elevator would (up and down).
fn drive(world: &mut PhysicsWorld, bodies: &[RigidBodyHandle], step: usize) {
    let lift = 0.02 * ((step as f32) * 0.05).sin();
    for &handle in bodies {
        let body = &mut world.bodies[handle];
        if body.body_type() == RigidBodyType::KinematicPositionBased {
            let mut next = body.translation();
            next.y += lift;
            body.set_next_kinematic_translation(next);
        } else if body.body_type() == RigidBodyType::KinematicVelocityBased {
            let mut velocity = at(0.0, 0.0);
            velocity.y = lift * 60.0;
            body.set_linvel(velocity, true);
        }
    }
}

fn config(cases: u32) -> Config {
    super::properties::props_config(cases, 0x1ff7_c0de)
}

proptest! {
    #![proptest_config(config(48))]

    /// No rules and any parent map: every pose, every step, bit for bit as
    /// plain Rapier.
    #[test]
    fn a_parent_map_alone_steps_as_plain_rapier(scene in scene()) {
        let (mut plain, bodies) = build(&scene);
        let (mut world, _) = build(&scene);
        let mut hooks = RuleHooks::default();
        for (i, parent) in scene.parents.iter().enumerate() {
            if let Some(p) = parent {
                hooks.rules_mut().set_parent(bodies[i + 1], bodies[p + 1]).expect("no cycle");
            }
        }
        for step in 0..90 {
            drive(&mut plain, &bodies, step);
            drive(&mut world, &bodies, step);
            plain.step();
            hooks.step(&mut world);
            for (i, &body) in bodies.iter().enumerate() {
                let (p, w) = (plain.bodies[body].position(), world.bodies[body].position());
                prop_assert_eq!(
                    pose_bits(p), pose_bits(w),
                    "step {}: body {} drifted from plain Rapier: {:?} vs {:?}", step, i, p, w
                );
            }
        }
    }
}

/// A lift (kinematic), a mount (fixed) and the floor; a crate parented to
/// each of the first two. Returns the world, the crates and the lift.
fn elevator() -> (PhysicsWorld, [RigidBodyHandle; 2], RigidBodyHandle, RigidBodyHandle) {
    let mut world = PhysicsWorld::new();
    let floor = world.insert_body(RigidBodyBuilder::fixed());
    world.insert_collider(slab(20.0, 0.5), Some(floor));
    let lift = world.insert_body(RigidBodyBuilder::kinematic_position_based().translation(at(-3.0, 1.0)));
    world.insert_collider(slab(1.0, 0.1), Some(lift));
    let mount = world.insert_body(RigidBodyBuilder::fixed().translation(at(3.0, 2.0)));
    world.insert_collider(slab(1.0, 0.1), Some(mount));
    let on_lift = world.insert_body(RigidBodyBuilder::dynamic().translation(at(-3.0, 1.7)));
    world.insert_collider(cube(0.5), Some(on_lift));
    let on_mount = world.insert_body(RigidBodyBuilder::dynamic().translation(at(3.0, 2.7)));
    world.insert_collider(cube(0.5), Some(on_mount));
    (world, [on_lift, on_mount], lift, mount)
}

fn ride(world: &mut PhysicsWorld, hooks: Option<&mut RuleHooks>, lift: RigidBodyHandle) {
    let mut hooks = hooks;
    for step in 0..120 {
        let body = &mut world.bodies[lift];
        let mut next = body.translation();
        next.y = 1.0 + 0.01 * step as f32;
        body.set_next_kinematic_translation(next);
        match hooks.as_deref_mut() {
            Some(hooks) => hooks.step(world),
            None => world.step(),
        }
    }
}

#[test]
fn a_crate_parented_to_a_lift_rides_it_as_in_plain_rapier() {
    let (mut plain, crates, lift, _) = elevator();
    ride(&mut plain, None, lift);
    let (mut world, _, _, mount) = elevator();
    let mut hooks = RuleHooks::default();
    hooks.rules_mut().set_parent(crates[0], lift).expect("no cycle");
    hooks.rules_mut().set_parent(crates[1], mount).expect("no cycle");
    ride(&mut world, Some(&mut hooks), lift);
    let top = 1.0 + 0.01 * 119.0 + 0.1 + 0.5;
    for (name, &body) in ["lift", "mount"].iter().zip(&crates) {
        let (p, w) = (plain.bodies[body].translation().y, world.bodies[body].translation().y);
        assert_eq!(p.to_bits(), w.to_bits(), "the crate on the {name}: y = {w}, plain Rapier {p}");
    }
    let y = world.bodies[crates[0]].translation().y;
    assert!((y - top).abs() < 0.05, "the crate did not ride the lift: y = {y}, lift top {top}");
    let y = world.bodies[crates[1]].translation().y;
    assert!((y - 2.6).abs() < 0.05, "the crate did not rest on the mount: y = {y}");
}

#[test]
fn groups_given_to_a_lift_reach_the_crate_parented_to_it() {
    let (mut world, crates, lift, _) = elevator();
    let mut hooks = RuleHooks::default();
    let rules = hooks.rules_mut();
    rules.set_parent(crates[0], lift).expect("no cycle");
    let cargo = rules.create_group();
    rules.set_group(lift, Some(cargo));
    // The lift's group passes through itself: its cargo drops through it.
    rules.set_group_rule(cargo, cargo, CollisionRule::NoPair);
    let [crate_collider] = world.bodies[crates[0]].colliders() else { panic!("one collider") };
    let [lift_collider] = world.bodies[lift].colliders() else { panic!("one collider") };
    let (crate_collider, lift_collider) = (*crate_collider, *lift_collider);
    let why = hooks.rules().explain(&world.bodies, &world.colliders, crate_collider, lift_collider);
    assert_eq!(
        (why.rule, why.groups),
        (CollisionRule::NoPair, Some((cargo, cargo))),
        "the lift's group did not reach its crate: {why:?}"
    );
    ride(&mut world, Some(&mut hooks), lift);
    let y = world.bodies[crates[0]].translation().y;
    assert!((y - 1.0).abs() < 0.05, "the crate did not drop through the lift to the floor: y = {y}");
}
