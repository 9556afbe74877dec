//! A rigid box dropped on a pinned cloth (in 2D a rope pinned at both
//! ends: rapier2d's soft bodies have no cloth), for each rule and each way
//! of giving it between the box and the cloth's root body, against the box
//! without the cloth and the cloth without the box (`docs/semantics.md`,
//! "Soft bodies").

use super::rapier::prelude::*;
use super::rules::{CollisionRule, RuleHooks};
use super::{at, cube, pinned_sheet, pose_bits};

const STEPS: usize = 120;

/// How the rule between the box and the cloth is given.
#[derive(Clone, Copy, Debug)]
enum Way {
    BoxFirst,
    ClothFirst,
    PersonalOnBox,
    PersonalOnCloth,
}

/// The box's pose and the cloth's particles, bit for bit, after the drop.
fn drop_on_cloth(
    cloth: bool,
    boxed: bool,
    rule: Option<(Way, CollisionRule)>,
) -> (Vec<u32>, Vec<u32>) {
    let mut world = PhysicsWorld::new();
    let sheet = pinned_sheet();
    let sheet = world.insert_soft_body(sheet);
    let root = world.soft_bodies[sheet].root_body();
    if !cloth {
        world.remove_soft_body(sheet);
    }
    let body = world.insert_body(RigidBodyBuilder::dynamic().translation(at(0.0, 2.0)));
    if boxed {
        world.insert_collider(cube(0.15), Some(body));
    }
    let mut hooks = RuleHooks::default();
    if let Some((way, rule)) = rule {
        let rules = hooks.rules_mut();
        match way {
            Way::BoxFirst => rules.set_specific(body, root, rule),
            Way::ClothFirst => rules.set_specific(root, body, rule),
            Way::PersonalOnBox => rules.set_personal(body, rule),
            Way::PersonalOnCloth => rules.set_personal(root, rule),
        }
    }
    for _ in 0..STEPS {
        hooks.step(&mut world);
    }
    let pose = pose_bits(world.bodies[body].position());
    let particles = if cloth {
        world.soft_bodies[sheet]
            .particle_positions()
            .flat_map(|p| p.to_array())
            .map(f32::to_bits)
            .collect()
    } else {
        Vec::new()
    };
    (pose, particles)
}

#[test]
fn a_box_falls_through_a_cloth_that_does_not_respond_to_it_and_the_cloth_hangs_as_alone() {
    let (alone, _) = drop_on_cloth(false, true, None);
    let (_, hanging) = drop_on_cloth(true, false, None);
    let (held, _) = drop_on_cloth(true, true, None);
    assert!(held != alone, "with no rule the cloth holds the box");
    let y = |pose: &[u32]| f32::from_bits(pose[1]);
    assert!(
        y(&held) > 0.5,
        "the cloth holds the box at y = {}",
        y(&held)
    );
    for rule in [
        CollisionRule::NoResponse,
        CollisionRule::NoContacts,
        CollisionRule::NoPair,
    ] {
        for way in [
            Way::BoxFirst,
            Way::ClothFirst,
            Way::PersonalOnBox,
            Way::PersonalOnCloth,
        ] {
            let (rigid, cloth) = drop_on_cloth(true, true, Some((way, rule)));
            assert!(
                rigid == alone,
                "{way:?} {rule:?}: the box ends at y = {}, alone at {}",
                y(&rigid),
                y(&alone)
            );
            assert!(
                cloth == hanging,
                "{way:?} {rule:?}: the cloth moves otherwise than alone"
            );
        }
    }
}
