//! Parent maps filled from Rapier's joints equal the same maps written by
//! hand, and a refused one changes nothing.

use super::rapier::prelude::*;
use super::rules::{CollisionGroup, CollisionRule, CollisionRuleSet, RuleError, RuleHooks};
use super::{at, ball_joint, cuboid};

/// A ragdoll: pelvis, torso, head, two arms of two links, two legs of two
/// links; `(child, parent)` in the order they are jointed.
fn ragdoll(world: &mut PhysicsWorld) -> (RigidBodyHandle, Vec<(RigidBodyHandle, RigidBodyHandle)>) {
    let mut body = |y: f32| {
        let body = world.insert_body(RigidBodyBuilder::dynamic().translation(at(0.0, y)));
        world.insert_collider(ColliderBuilder::capsule_y(0.2, 0.1), Some(body));
        body
    };
    let pelvis = body(1.0);
    let torso = body(1.5);
    let head = body(2.0);
    let mut links = vec![(torso, pelvis), (head, torso)];
    for _ in 0..2 {
        let upper = body(1.5);
        let lower = body(1.2);
        links.extend([(upper, torso), (lower, upper)]);
        let thigh = body(0.6);
        let shin = body(0.2);
        links.extend([(thigh, pelvis), (shin, thigh)]);
    }
    (pelvis, links)
}

fn joint() -> GenericJoint {
    ball_joint(at(0.0, 0.3))
}

fn sorted(rules: &CollisionRuleSet) -> Vec<((u32, u32), (u32, u32))> {
    let mut links: Vec<_> = rules
        .parents()
        .map(|(c, p)| (c.into_raw_parts(), p.into_raw_parts()))
        .collect();
    links.sort();
    links
}

/// The rule set a ragdoll gets: one group whose members ignore each other.
fn rules_with(
    group_of: impl Fn(&mut CollisionRuleSet) -> Result<(), RuleError>,
    root: RigidBodyHandle,
) -> Result<CollisionRuleSet, RuleError> {
    let mut rules = CollisionRuleSet::default();
    let g = rules.create_group();
    rules.set_group_rule(g, g, CollisionRule::NoPair);
    rules.set_group(root, Some(g));
    group_of(&mut rules)?;
    Ok(rules)
}

fn assert_same_resolution(world: &PhysicsWorld, a: &CollisionRuleSet, b: &CollisionRuleSet) {
    for (c1, _) in world.colliders.iter() {
        for (c2, _) in world.colliders.iter() {
            assert_eq!(
                a.resolve(&world.bodies, &world.colliders, c1, c2),
                b.resolve(&world.bodies, &world.colliders, c1, c2),
                "({c1:?}, {c2:?})"
            );
        }
    }
}

#[test]
fn a_multibody_ragdoll_gets_the_parent_map_written_by_hand() -> Result<(), RuleError> {
    let mut world = PhysicsWorld::new();
    let (pelvis, links) = ragdoll(&mut world);
    for &(child, parent) in &links {
        world.multibody_joints.insert(parent, child, joint(), true);
    }
    let by_hand = rules_with(
        |rules| links.iter().try_for_each(|&(c, p)| rules.set_parent(c, p)),
        pelvis,
    )?;
    // From any link of the multibody.
    let from_joints = rules_with(
        |rules| {
            let set = rules.set_parents_from_multibody(&world.multibody_joints, links[5].0)?;
            assert_eq!(set, links.len());
            Ok(())
        },
        pelvis,
    )?;
    assert_eq!(sorted(&from_joints), sorted(&by_hand));
    assert_same_resolution(&world, &from_joints, &by_hand);
    let (head, torso) = (links[1].0, links[0].0);
    assert_eq!(
        from_joints.effective_group(&world.bodies, &world.colliders, head),
        by_hand.effective_group(&world.bodies, &world.colliders, torso),
    );
    assert_ne!(
        from_joints.effective_group(&world.bodies, &world.colliders, head),
        CollisionGroup::DEFAULT_DYNAMIC,
        "the head inherits the ragdoll's group"
    );
    Ok(())
}

#[test]
fn impulse_joints_from_a_root_give_the_parent_map_written_by_hand() -> Result<(), RuleError> {
    let mut world = PhysicsWorld::new();
    let (pelvis, links) = ragdoll(&mut world);
    // Joints in either direction: the walk follows them both ways.
    for (i, &(child, parent)) in links.iter().enumerate() {
        if i % 2 == 0 {
            world.impulse_joints.insert(parent, child, joint(), true);
        } else {
            world.impulse_joints.insert(child, parent, joint(), true);
        }
    }
    // A loop: the hands joined to each other. The walk enters it once.
    let (left_hand, right_hand) = (links[3].0, links[7].0);
    world
        .impulse_joints
        .insert(left_hand, right_hand, joint(), true);
    let by_hand = rules_with(
        |rules| links.iter().try_for_each(|&(c, p)| rules.set_parent(c, p)),
        pelvis,
    )?;
    let from_joints = rules_with(
        |rules| {
            let set = rules.set_parents_from_impulse_joints(&world.impulse_joints, &world.bodies, pelvis)?;
            assert_eq!(set, links.len());
            Ok(())
        },
        pelvis,
    )?;
    assert_eq!(sorted(&from_joints), sorted(&by_hand));
    assert_same_resolution(&world, &from_joints, &by_hand);
    Ok(())
}

#[test]
fn a_joint_map_that_would_close_a_cycle_is_refused_and_changes_nothing() {
    let mut world = PhysicsWorld::new();
    let (pelvis, links) = ragdoll(&mut world);
    for &(child, parent) in &links {
        world.impulse_joints.insert(parent, child, joint(), true);
    }
    let mut rules = CollisionRuleSet::default();
    // The pelvis already hangs under a shin: walking from the pelvis makes
    // that shin its descendant.
    let shin = links[5].0;
    rules.set_parent(pelvis, shin).expect("a root under a body");
    let before = sorted(&rules);
    let refused = rules.set_parents_from_impulse_joints(&world.impulse_joints, &world.bodies, pelvis);
    assert!(
        matches!(refused, Err(RuleError::Cycle { .. })),
        "a cycle through the existing link: {refused:?}"
    );
    assert_eq!(sorted(&rules), before, "the refused call changed the map");
}

/// Two robot arms bolted to one fixed ground, and a crate hanging from the
/// ground on a rope: reading arm A's hierarchy from its joints parents
/// A's links and stops at the ground, which is an anchor, not a link. Found
/// by trying hierarchies from joints from the docs alone: the walk went
/// through the ground, made it and arm B children of A's base, and A's
/// group rule then let the crate fall through the floor (y = -2.5, 0.3
/// without reading the joints).
#[test]
fn the_walk_of_impulse_joints_stops_at_bodies_that_are_not_dynamic() -> Result<(), RuleError> {
    let mut world = PhysicsWorld::new();
    let ground = world.insert_body(RigidBodyBuilder::fixed());
    world.insert_collider(cuboid(10.0, 0.5, 10.0), Some(ground));
    let mut arm = |x: f32| {
        let links: Vec<RigidBodyHandle> = (0..3)
            .map(|i| {
                let body = world.insert_body(
                    RigidBodyBuilder::dynamic().translation(at(x, 1.0 + 0.6 * i as f32)),
                );
                world.insert_collider(ColliderBuilder::capsule_y(0.2, 0.1), Some(body));
                body
            })
            .collect();
        world
            .impulse_joints
            .insert(ground, links[0], FixedJointBuilder::new(), true);
        for pair in links.windows(2) {
            world.impulse_joints.insert(pair[0], pair[1], joint(), true);
        }
        links
    };
    let (a, b) = (arm(-3.0), arm(3.0));
    let hanging = world.insert_body(RigidBodyBuilder::dynamic().translation(at(0.0, 0.8)));
    world.insert_collider(cuboid(0.25, 0.25, 0.25), Some(hanging));
    let rope = RopeJointBuilder::new(2.0);
    world.impulse_joints.insert(ground, hanging, rope, true);

    let mut rules = CollisionRuleSet::default();
    let arms = rules.create_group();
    rules.set_group_rule(arms, arms, CollisionRule::NoPair);
    rules.set_group(a[0], Some(arms));
    let set = rules.set_parents_from_impulse_joints(&world.impulse_joints, &world.bodies, a[0])?;
    let parents: Vec<Option<RigidBodyHandle>> =
        [ground, b[0], hanging].iter().map(|&body| rules.parent(body)).collect();
    assert_eq!(
        (set, rules.parent(a[1]), rules.parent(a[2]), parents),
        (2, Some(a[0]), Some(a[1]), vec![None; 3]),
        "A's two links under its base; the ground, B and the crate untouched"
    );
    let mut hooks = RuleHooks::new(rules);
    for _ in 0..90 {
        hooks.step(&mut world);
    }
    let y = world.bodies[hanging].translation().y;
    assert!(y > 0.2, "the crate rests on the ground: y = {y}");
    Ok(())
}

/// The two robot recipes of `docs/semantics.md` (stage 3), found by a
/// robot arm built from the docs: an entry about the base's collider sets
/// the fixed base apart from the table and no link; entries about the
/// links' colliders set apart neighbouring links only, with the parent map
/// in place. Resolved for every pair, in both orders.
#[test]
fn robot_recipes_name_colliders_to_reach_one_pair_only() -> Result<(), RuleError> {
    let mut world = PhysicsWorld::new();
    let table = world.insert_body(RigidBodyBuilder::fixed());
    let table_collider = world.insert_collider(cuboid(2.0, 0.05, 2.0), Some(table));
    let base = world.insert_body(RigidBodyBuilder::fixed().translation(at(0.0, 0.1)));
    let base_collider = world.insert_collider(cuboid(0.1, 0.1, 0.1), Some(base));
    let mut parent = base;
    let mut links = Vec::new();
    for i in 1..=4 {
        let link =
            world.insert_body(RigidBodyBuilder::dynamic().translation(at(0.0, 0.1 + 0.3 * i as f32)));
        let collider = world.insert_collider(cuboid(0.05, 0.2, 0.05), Some(link));
        world.multibody_joints.insert(parent, link, joint(), true);
        links.push(collider);
        parent = link;
    }
    let last = world.colliders[links[3]].parent().expect("a link body");
    let mut rules = CollisionRuleSet::default();
    assert_eq!(rules.set_parents_from_multibody(&world.multibody_joints, last)?, 4);
    let arm = rules.create_group();
    rules.set_group(base, Some(arm));
    rules.set_specific(base_collider, table_collider, CollisionRule::NoPair);
    for pair in links.windows(2) {
        rules.set_specific(pair[0], pair[1], CollisionRule::NoPair);
    }
    let resolve = |a, b| {
        let (ab, ba) = (
            rules.resolve(&world.bodies, &world.colliders, a, b),
            rules.resolve(&world.bodies, &world.colliders, b, a),
        );
        assert_eq!(ab, ba, "both orders");
        ab
    };
    assert_eq!(resolve(base_collider, table_collider), CollisionRule::NoPair);
    for (i, &link) in links.iter().enumerate() {
        assert_eq!(
            resolve(link, table_collider),
            CollisionRule::Normal,
            "link {i} meets the table"
        );
        for (j, &other) in links.iter().enumerate().skip(i + 1) {
            let expected = if j == i + 1 {
                CollisionRule::NoPair
            } else {
                CollisionRule::Normal
            };
            assert_eq!(resolve(link, other), expected, "links {i} and {j}");
        }
    }
    Ok(())
}
