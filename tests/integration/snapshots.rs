//! Rapier's own snapshot round trip (rapier3d 0.36.1,
//! `tests/snapshot_roundtrip.rs`), stepped through the rules: a world
//! saved mid-run and loaded into a fresh world and fresh hooks must go on
//! exactly as the run that was not interrupted, and the proof is the
//! snapshot itself: after every step the loaded world serializes to the
//! same bytes as the uninterrupted one. The scenes are Rapier's (an awake
//! pile, a sleeping pile, CCD bodies, a joint chain and a sensor, a
//! multibody articulation, structural changes), with rules that the
//! planner turns into Rapier's groups and rules it hooks, loaded both ways
//! a game loads them: the world with its rule set, and the world alone with
//! the same rules given by code (`docs/semantics.md`, "Saving and loading").

use rapier_collision_rules::{CollisionRule, CollisionRuleSet, RuleHooks};
use rapier3d::prelude::*;

/// The structures of a snapshot, each serialized: their names say which
/// differs when the bytes do.
fn parts(world: &PhysicsWorld) -> Vec<(&'static str, String)> {
    let json = |value: Result<String, serde_json::Error>| value.expect("a snapshot serializes");
    vec![
        ("islands", json(serde_json::to_string(&world.islands))),
        (
            "broad_phase",
            json(serde_json::to_string(&world.broad_phase)),
        ),
        (
            "narrow_phase",
            json(serde_json::to_string(&world.narrow_phase)),
        ),
        ("bodies", json(serde_json::to_string(&world.bodies))),
        ("colliders", json(serde_json::to_string(&world.colliders))),
        (
            "impulse_joints",
            json(serde_json::to_string(&world.impulse_joints)),
        ),
        (
            "multibody_joints",
            json(serde_json::to_string(&world.multibody_joints)),
        ),
    ]
}

/// The first body whose pose differs, for the message.
fn first_moved(a: &PhysicsWorld, b: &PhysicsWorld) -> String {
    a.bodies
        .iter()
        .zip(b.bodies.iter())
        .find(|((_, x), (_, y))| x.position() != y.position())
        .map_or(
            "none: the layout moved without the simulation".into(),
            |((h, x), (_, y))| format!("{h:?}: {:?} vs {:?}", x.position(), y.position()),
        )
}

/// A scene: a world and its rules, built alike every time.
type Scene = fn() -> (PhysicsWorld, CollisionRuleSet);

/// Panics, naming the structures that differ and the first body that
/// moved, unless `loaded` serializes to the same bytes as `uninterrupted`
/// `step + 1` steps after loading.
fn assert_same(uninterrupted: &PhysicsWorld, loaded: &PhysicsWorld, what: &str, step: usize) {
    let (want, got) = (parts(uninterrupted), parts(loaded));
    let differing: Vec<_> = want
        .iter()
        .zip(&got)
        .filter(|(a, b)| a.1 != b.1)
        .map(|(a, _)| a.0)
        .collect();
    assert!(
        differing.is_empty(),
        "{what}: the snapshot differs {} step(s) after loading in {differing:?}; first moved \
         body: {}",
        step + 1,
        first_moved(uninterrupted, loaded)
    );
}

/// An edit made before each step, in both runs alike: the step's index and
/// the bodies spawned so far.
type Edit = fn(&mut PhysicsWorld, &mut CollisionRuleSet, usize, &mut Vec<RigidBodyHandle>);

/// The rules a game gives again by code to the bodies its edits spawned
/// that are alive when it loads.
type GiveAgain = fn(&mut CollisionRuleSet, &PhysicsWorld, &[RigidBodyHandle]);

fn no_edits(
    _: &mut PhysicsWorld,
    _: &mut CollisionRuleSet,
    _: usize,
    _: &mut Vec<RigidBodyHandle>,
) {
}

fn nothing_spawned(_: &mut CollisionRuleSet, _: &PhysicsWorld, _: &[RigidBodyHandle]) {}

/// Steps `scene` `before` steps through the rules, saves it (with its rule
/// set, or alone), loads it into a fresh world and fresh hooks (the saved
/// rule set, or `scene`'s rules again), and steps both `after` steps,
/// requiring byte-identical snapshots after every step.
fn check_roundtrip(
    what: &str,
    scene: Scene,
    before: usize,
    after: usize,
    (edit, give_again): (Edit, GiveAgain),
) {
    for with_rule_set in [true, false] {
        let how = if with_rule_set {
            "with its rule set"
        } else {
            "alone, rules by code"
        };
        let (mut world, rules) = scene();
        let mut hooks = RuleHooks::new(rules);
        let mut spawned = Vec::new();
        for step in 0..before {
            edit(&mut world, hooks.rules_mut(), step, &mut spawned);
            hooks.step(&mut world);
        }
        let saved = serde_json::to_string(&world).expect("the world saves");
        let mut loaded: PhysicsWorld = serde_json::from_str(&saved).expect("the world loads");
        let rules = if with_rule_set {
            let saved = serde_json::to_string(hooks.rules()).expect("the rule set saves");
            serde_json::from_str(&saved).expect("the rule set loads")
        } else {
            let mut rules = scene().1;
            give_again(&mut rules, &loaded, &spawned);
            rules
        };
        let mut loaded_hooks = RuleHooks::new(rules);
        let mut loaded_spawned = spawned.clone();
        for step in 0..after {
            edit(&mut world, hooks.rules_mut(), before + step, &mut spawned);
            hooks.step(&mut world);
            edit(
                &mut loaded,
                loaded_hooks.rules_mut(),
                before + step,
                &mut loaded_spawned,
            );
            loaded_hooks.step(&mut loaded);
            if step == 0 {
                let stats = loaded_hooks.stats();
                assert_eq!(
                    (stats.loaded_writes_given_back, stats.loaded_writes_changed),
                    (0, 0),
                    "{what}, saved {how}: the first step parts from the saved run"
                );
            }
            assert_same(&world, &loaded, &format!("{what}, saved {how}"), step);
        }
    }
}

/// Rapier's pile of 192 boxes on a ground (`sleepy`: it settles and sleeps,
/// with four movers that never do), with rules: the harmless one (a
/// box and a ball 5 km away never pair), a group pair that does not
/// respond, a personal `NoPair`, a box that does not respond to the ground,
/// and a pair without contacts, which is hooked.
fn pile(sleepy: bool) -> (PhysicsWorld, CollisionRuleSet) {
    let mut world = PhysicsWorld::new();
    let ground =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)));
    world.insert_collider(ColliderBuilder::cuboid(20.0, 0.5, 20.0), Some(ground));
    let mut boxes = Vec::new();
    for i in 0..8 {
        for j in 0..3 {
            for k in 0..8 {
                let jitter = (i as Real * 0.013 + k as Real * 0.017) % 0.05;
                let body = world.insert_body(
                    RigidBodyBuilder::dynamic()
                        .translation(Vector::new(
                            i as Real * 1.05 - 4.0 + jitter,
                            j as Real * 1.05 + 0.55,
                            k as Real * 1.05 - 4.0 - jitter,
                        ))
                        .can_sleep(sleepy),
                );
                world.insert_collider(ColliderBuilder::cuboid(0.5, 0.5, 0.5), Some(body));
                boxes.push(body);
            }
        }
    }
    if sleepy {
        for i in 0..4 {
            let body = world.insert_body(
                RigidBodyBuilder::dynamic()
                    .translation(Vector::new(-9.0 + i as Real * 0.7, 3.4, -3.0 + i as Real))
                    .linvel(Vector::new(4.0, 0.0, 0.3 * i as Real))
                    .can_sleep(false),
            );
            world.insert_collider(ColliderBuilder::ball(0.4), Some(body));
        }
    }
    let far =
        world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(5000.0, 0.0, 0.0)));
    world.insert_collider(ColliderBuilder::ball(0.5), Some(far));
    let mut rules = CollisionRuleSet::default();
    rules.set_specific(boxes[0], far, CollisionRule::NoPair);
    let (red, blue) = (rules.create_group(), rules.create_group());
    rules.set_group_rule(red, blue, CollisionRule::NoResponse);
    for (i, &body) in boxes.iter().enumerate().skip(1) {
        match i % 11 {
            3 => rules.set_group(body, Some(red)),
            7 => rules.set_group(body, Some(blue)),
            _ => {}
        }
    }
    rules.set_personal(boxes[50], CollisionRule::NoPair);
    rules.set_specific(boxes[100], ground, CollisionRule::NoResponse);
    rules.set_specific(boxes[120], boxes[121], CollisionRule::NoContacts);
    (world, rules)
}

fn awake_pile() -> (PhysicsWorld, CollisionRuleSet) {
    pile(false)
}

fn sleeping_pile() -> (PhysicsWorld, CollisionRuleSet) {
    pile(true)
}

/// Rapier's fast CCD balls over the sleeping pile, every third of them
/// not responding to anything (a personal rule that reaches CCD).
fn ccd_bodies() -> (PhysicsWorld, CollisionRuleSet) {
    let (mut world, mut rules) = pile(true);
    for i in 0..8 {
        let body = world.insert_body(
            RigidBodyBuilder::dynamic()
                .translation(Vector::new(
                    -6.0 + i as Real * 1.5,
                    4.0 + i as Real * 0.3,
                    0.0,
                ))
                .linvel(Vector::new(90.0, -45.0, 3.0 * i as Real))
                .ccd_enabled(true)
                .can_sleep(false),
        );
        world.insert_collider(ColliderBuilder::ball(0.15), Some(body));
        if i % 3 == 0 {
            rules.set_personal(body, CollisionRule::NoResponse);
        }
    }
    (world, rules)
}

/// Rapier's hanging chain of spherical joints and the sensor it swings
/// through, the chain's links in a group whose members never pair and its
/// last link without contacts with the sensor.
fn with_joints_and_sensor(world: &mut PhysicsWorld, rules: &mut CollisionRuleSet) {
    let anchor =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, 7.0, 0.0)));
    let chain = rules.create_group();
    rules.set_group_rule(chain, chain, CollisionRule::NoPair);
    let mut prev = anchor;
    for i in 0..4 {
        let body = world.insert_body(
            RigidBodyBuilder::dynamic()
                .translation(Vector::new(0.6 * (i + 1) as Real, 7.0, 0.0))
                .can_sleep(false),
        );
        world.insert_collider(ColliderBuilder::ball(0.25), Some(body));
        world.insert_impulse_joint(
            prev,
            body,
            SphericalJointBuilder::new()
                .local_anchor1(Vector::X * 0.3)
                .local_anchor2(Vector::X * -0.3),
        );
        rules.set_group(body, Some(chain));
        prev = body;
    }
    let sensor = world.insert_collider(
        ColliderBuilder::cuboid(3.0, 0.5, 3.0)
            .translation(Vector::new(0.0, 4.0, 0.0))
            .sensor(true),
        None,
    );
    rules.set_specific(prev, sensor, CollisionRule::NoContacts);
}

fn joints_and_sensor() -> (PhysicsWorld, CollisionRuleSet) {
    let (mut world, mut rules) = pile(true);
    with_joints_and_sensor(&mut world, &mut rules);
    (world, rules)
}

/// Rapier's articulation of ten multibody links over the sleeping pile,
/// the links parented along the chain and the whole arm ignoring the pile
/// in response (a personal rule at its root).
fn multibody_articulation() -> (PhysicsWorld, CollisionRuleSet) {
    let (mut world, mut rules) = pile(true);
    let root = world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(6.0, 4.0, 0.0)));
    let mut last = root;
    let mut links = Vec::new();
    for i in 0..10 {
        let size = 0.4;
        let body = world.insert_body(RigidBodyBuilder::dynamic().can_sleep(false));
        world.insert_collider(
            ColliderBuilder::cuboid(size / 8.0, size / 2.0, size / 8.0).density(1.0),
            Some(body),
        );
        let joint = SphericalJointBuilder::new()
            .local_anchor1(Vector::new(
                0.0,
                size / 2.0 * (i != 0) as usize as Real,
                0.0,
            ))
            .local_anchor2(Vector::new(0.0, -size / 2.0, 0.0))
            .build()
            .data;
        world.insert_multibody_joint(last, body, joint);
        links.push(body);
        last = body;
    }
    rules
        .set_parents_from_multibody(&world.multibody_joints, links[0])
        .expect("the links form a tree");
    rules.set_personal(links[0], CollisionRule::NoResponse);
    (world, rules)
}

/// Rapier's structural churn with the joint chain and the sensor: a ball
/// spawned every 17 steps, which ignores the ground until it is removed,
/// and the oldest removed every 23.
fn structural(
    world: &mut PhysicsWorld,
    rules: &mut CollisionRuleSet,
    step: usize,
    spawned: &mut Vec<RigidBodyHandle>,
) {
    if step % 17 == 0 {
        let body = world.insert_body(
            RigidBodyBuilder::dynamic()
                .translation(Vector::new(
                    (step % 5) as Real - 2.0,
                    6.0 + (step % 3) as Real,
                    (step % 7) as Real - 3.0,
                ))
                .can_sleep(false),
        );
        world.insert_collider(ColliderBuilder::ball(0.45), Some(body));
        spawned.push(body);
        spawned_rules(rules, world, &[body]);
    }
    if step % 23 == 0 && !spawned.is_empty() {
        let body = spawned.remove(0);
        world.remove_body(body);
    }
}

/// The rule of each spawned ball: it does not respond to the ground.
fn spawned_rules(rules: &mut CollisionRuleSet, world: &PhysicsWorld, spawned: &[RigidBodyHandle]) {
    let ground = world
        .bodies
        .iter()
        .next()
        .map(|(h, _)| h)
        .expect("the ground");
    for &body in spawned {
        rules.set_specific(body, ground, CollisionRule::NoResponse);
    }
}

#[test]
fn an_awake_pile_reloads_byte_for_byte() {
    check_roundtrip(
        "awake pile",
        awake_pile,
        60,
        30,
        (no_edits, nothing_spawned),
    );
}

#[test]
fn a_sleeping_pile_reloads_byte_for_byte() {
    check_roundtrip(
        "sleeping pile",
        sleeping_pile,
        100,
        30,
        (no_edits, nothing_spawned),
    );
}

#[test]
fn ccd_bodies_reload_byte_for_byte() {
    check_roundtrip("ccd", ccd_bodies, 40, 20, (no_edits, nothing_spawned));
}

#[test]
fn joints_and_a_sensor_reload_byte_for_byte() {
    check_roundtrip(
        "joints",
        joints_and_sensor,
        60,
        30,
        (no_edits, nothing_spawned),
    );
}

#[test]
fn a_multibody_reloads_byte_for_byte() {
    check_roundtrip(
        "multibody",
        multibody_articulation,
        60,
        30,
        (no_edits, nothing_spawned),
    );
}

#[test]
fn structural_changes_reload_byte_for_byte() {
    check_roundtrip(
        "structural",
        joints_and_sensor,
        60,
        40,
        (structural, spawned_rules),
    );
}

/// Six boxes in a row on a ground (the fifth and sixth squeeze the first
/// between them), for the layouts of specific entries below.
fn row() -> (PhysicsWorld, Vec<RigidBodyHandle>, RigidBodyHandle) {
    let mut world = PhysicsWorld::new();
    let ground =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)));
    world.insert_collider(ColliderBuilder::cuboid(20.0, 0.5, 20.0), Some(ground));
    let boxes = [
        (0.0, 0.5),
        (5.0, 0.5),
        (10.0, 0.5),
        (-0.98, 0.5),
        (0.98, 0.5),
        (0.0, 1.6),
    ]
    .into_iter()
    .map(|(x, y)| {
        let body =
            world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(x, y, 0.0)));
        world.insert_collider(ColliderBuilder::cuboid(0.5, 0.5, 0.5), Some(body));
        body
    })
    .collect();
    (world, boxes, ground)
}

/// Layouts where one node is in several specific entries, decided each
/// its own way (a bit, a hooked side): the loaded world shows each only
/// through the others.
const LAYOUTS: [(&str, Scene); 6] = [
    ("a bit and a hooked side on one box", || {
        let (world, b, _) = row();
        let mut rules = CollisionRuleSet::default();
        rules.set_specific(b[0], b[1], CollisionRule::NoPair);
        rules.set_specific(b[0], b[2], CollisionRule::NoContacts);
        (world, rules)
    }),
    ("a box hooked against the ground, with a bit", || {
        let (world, b, ground) = row();
        let mut rules = CollisionRuleSet::default();
        rules.set_specific(b[0], ground, CollisionRule::NoContacts);
        rules.set_specific(b[0], b[1], CollisionRule::NoPair);
        (world, rules)
    }),
    ("bits and hooked sides in two clusters", || {
        let (world, b, ground) = row();
        let mut rules = CollisionRuleSet::default();
        rules.set_specific(b[1], b[0], CollisionRule::NoPair);
        rules.set_specific(ground, b[0], CollisionRule::NoContacts);
        rules.set_specific(b[3], b[4], CollisionRule::NoResponse);
        rules.set_specific(b[4], b[5], CollisionRule::NoContacts);
        (world, rules)
    }),
    ("a star of bits and a hooked link", || {
        let (world, b, ground) = row();
        let mut rules = CollisionRuleSet::default();
        rules.set_specific(b[2], ground, CollisionRule::NoPair);
        rules.set_specific(b[2], b[3], CollisionRule::NoContacts);
        rules.set_specific(b[3], b[4], CollisionRule::NoPair);
        rules.set_specific(b[5], b[4], CollisionRule::NoPair);
        (world, rules)
    }),
    ("a chain of hooked links", || {
        let (world, b, _) = row();
        let mut rules = CollisionRuleSet::default();
        rules.set_specific(b[0], b[1], CollisionRule::NoContacts);
        rules.set_specific(b[1], b[2], CollisionRule::NoContacts);
        rules.set_specific(b[2], b[3], CollisionRule::NoContacts);
        (world, rules)
    }),
    ("a chain of hooked links through the ground", || {
        let (world, b, ground) = row();
        let mut rules = CollisionRuleSet::default();
        rules.set_specific(ground, b[0], CollisionRule::NoContacts);
        rules.set_specific(b[0], b[1], CollisionRule::NoContacts);
        rules.set_specific(b[2], ground, CollisionRule::NoContacts);
        rules.set_specific(b[1], b[2], CollisionRule::NoContacts);
        (world, rules)
    }),
];

#[test]
fn layouts_of_entries_that_share_a_node_reload_byte_for_byte() {
    for (what, scene) in LAYOUTS {
        for before in [1, 2, 20] {
            check_roundtrip(what, scene, before, 30, (no_edits, nothing_spawned));
        }
    }
}

/// Rapier's `restoring_into_a_live_pipeline`, as a quickload: the running
/// world goes on past the save (a rule taken away and given back meanwhile),
/// then the saved world is put in its place,
/// keeping the live pipeline, and the same hooks go on after
/// `world_replaced`; after every step it serializes to the same bytes as a
/// twin run that never saved.
#[test]
fn a_quickload_into_the_live_pipeline_reloads_byte_for_byte() {
    for (what, scene) in [
        ("sleeping pile", sleeping_pile as Scene),
        ("joints", joints_and_sensor),
    ] {
        let (mut world, rules) = scene();
        let mut hooks = RuleHooks::new(rules);
        let (mut twin, twin_rules) = scene();
        let mut twin_hooks = RuleHooks::new(twin_rules);
        for _ in 0..40 {
            hooks.step(&mut world);
            twin_hooks.step(&mut twin);
        }
        let saved = serde_json::to_string(&world).expect("the world saves");
        // The pile's `NoPair` box loses its rule and gets it back before the
        // quickload: what the hooks wrote meanwhile is not what the save
        // holds.
        let (ghost, _) = world.bodies.iter().nth(51).expect("the pile's NoPair box");
        assert_eq!(hooks.rules().personal(ghost), CollisionRule::NoPair);
        hooks.rules_mut().set_personal(ghost, CollisionRule::Defer);
        for _ in 0..10 {
            hooks.step(&mut world);
        }
        hooks.rules_mut().set_personal(ghost, CollisionRule::NoPair);
        let mut restored: PhysicsWorld = serde_json::from_str(&saved).expect("the world loads");
        restored.physics_pipeline = std::mem::take(&mut world.physics_pipeline);
        restored.ccd_solver = std::mem::take(&mut world.ccd_solver);
        let mut world = restored;
        hooks.world_replaced();
        for step in 0..20 {
            hooks.step(&mut world);
            twin_hooks.step(&mut twin);
            assert_same(&twin, &world, &format!("{what}, quickloaded"), step);
        }
    }
}
