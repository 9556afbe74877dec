//! Real `PhysicsWorld` scenes stepped with `RuleHooks`: what each rule does
//! to bodies, contacts, events, live pairs and the CCD. Every assertion
//! prints the measured value.

use approx::abs_diff_eq;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc::{Receiver, channel};

use super::rapier::prelude::*;
use super::rules::{
    CollisionGroup, CollisionRule, CollisionRuleSet, ManifoldUpdate, RecalculationPolicy,
    RuleError, RuleHooks, WorldRef,
};
use super::{at, cuboid};

use CollisionRule::*;

/// A world with a fixed ground slab whose top face is at y = 0.
pub struct Scene {
    pub world: PhysicsWorld,
    pub ground: RigidBodyHandle,
    pub floor: ColliderHandle,
}

impl Scene {
    pub fn new() -> Scene {
        let mut world = PhysicsWorld::new();
        let ground = world.insert_body(RigidBodyBuilder::fixed().translation(at(0.0, -0.5)));
        let floor = world.insert_collider(cuboid(20.0, 0.5, 20.0), Some(ground));
        Scene {
            world,
            ground,
            floor,
        }
    }

    /// A dynamic unit cube whose centre is at `(x, y, 0)`, with collision events.
    pub fn cube(&mut self, x: f32, y: f32) -> (RigidBodyHandle, ColliderHandle) {
        let body = self
            .world
            .insert_body(RigidBodyBuilder::dynamic().translation(at(x, y)));
        let collider = self.world.insert_collider(
            cuboid(0.5, 0.5, 0.5).active_events(ActiveEvents::COLLISION_EVENTS),
            Some(body),
        );
        (body, collider)
    }

    pub fn y(&self, body: RigidBodyHandle) -> f32 {
        self.world.bodies[body].translation().y
    }

    pub fn x(&self, body: RigidBodyHandle) -> f32 {
        self.world.bodies[body].translation().x
    }

    pub fn touching(&self, a: ColliderHandle, b: ColliderHandle) -> bool {
        self.world
            .narrow_phase
            .contact_pair(a, b)
            .is_some_and(|pair| pair.has_any_active_contact())
    }
}

/// Collects collision events.
pub struct Events {
    pub collector: ChannelEventCollector,
    receiver: Receiver<CollisionEvent>,
    pub started: usize,
    pub stopped: usize,
    /// Only events about this collider are counted, if set.
    pub about: Option<ColliderHandle>,
}

impl Events {
    pub fn new() -> Events {
        let (send, receiver) = channel();
        let (force, _) = channel();
        let (tear, _) = channel();
        Events {
            collector: ChannelEventCollector::new(send, force, tear),
            receiver,
            started: 0,
            stopped: 0,
            about: None,
        }
    }

    /// The events since the last call, in the order Rapier sent them.
    pub fn take(&mut self) -> Vec<CollisionEvent> {
        self.receiver.try_iter().collect()
    }

    pub fn drain(&mut self) {
        while let Ok(event) = self.receiver.try_recv() {
            if self
                .about
                .is_some_and(|c| c != event.collider1() && c != event.collider2())
            {
                continue;
            }
            if event.started() {
                self.started += 1;
            } else {
                self.stopped += 1;
            }
        }
    }
}

/// What one run of a resting cube with a rule against the ground measured.
#[derive(Debug)]
struct Outcome {
    y: f32,
    ever_touching: bool,
    started: usize,
    stopped: usize,
    ever_live: bool,
    live_rule: Option<CollisionRule>,
}

/// A cube resting on the ground (its bottom 1 cm into the slab), with `rule`
/// as its personal rule, stepped for one second.
fn resting_cube(rule: CollisionRule) -> Outcome {
    let mut scene = Scene::new();
    let (body, cube) = scene.cube(0.0, 0.49);
    let mut rules = CollisionRuleSet::default();
    rules.set_personal(body, rule);
    let mut hooks = RuleHooks::new(rules);
    let mut events = Events::new();
    let (mut ever_touching, mut ever_live, mut live_rule) = (false, false, None);
    for _ in 0..60 {
        hooks.step_with_events(&mut scene.world, &events.collector);
        events.drain();
        ever_touching |= scene.touching(cube, scene.floor);
        let live = hooks.pair_rule(&scene.world, cube, scene.floor);
        ever_live |= live.is_some();
        live_rule = live_rule.or(live);
    }
    Outcome {
        y: scene.y(body),
        ever_touching,
        started: events.started,
        stopped: events.stopped,
        ever_live,
        live_rule,
    }
}

/// What each rule promises a cube resting on the ground: whether it stays,
/// has contacts, its Started/Stopped events, and its live pair.
#[test]
fn each_rule_does_to_a_resting_cube_what_it_promises() {
    // (rule, stays, touches, (started, stopped), live rule)
    let table = [
        (Normal, true, true, (1, 0), Some(Normal)),
        (NoResponse, false, true, (1, 1), Some(NoResponse)),
        (NoContacts, false, false, (0, 0), Some(NoContacts)),
        (NoPair, false, false, (0, 0), None),
    ];
    for (rule, stays, touches, events, live) in table {
        let o = resting_cube(rule);
        let stayed = abs_diff_eq!(o.y, 0.5, epsilon = 0.05);
        assert!(
            stays == stayed && (stays || o.y < -3.0),
            "{rule:?}: cube at y = {}: {o:?}",
            o.y
        );
        assert_eq!(o.ever_touching, touches, "{rule:?}: contacts: {o:?}");
        assert_eq!((o.started, o.stopped), events, "{rule:?}: events: {o:?}");
        assert_eq!(o.live_rule, live, "{rule:?}: live pair: {o:?}");
        assert_eq!(o.ever_live, live.is_some(), "{rule:?}: ever live: {o:?}");
    }
}

#[test]
fn sensors_follow_the_rule() {
    for (rule, expect_events) in [
        (Normal, true),
        (NoResponse, true),
        (NoContacts, false),
        (NoPair, false),
    ] {
        let mut scene = Scene::new();
        let zone_body = scene
            .world
            .insert_body(RigidBodyBuilder::fixed().translation(at(0.0, 3.0)));
        let zone = scene.world.insert_collider(
            cuboid(2.0, 1.0, 2.0)
                .sensor(true)
                .active_events(ActiveEvents::COLLISION_EVENTS),
            Some(zone_body),
        );
        let (body, cube) = scene.cube(0.0, 6.0);
        let mut rules = CollisionRuleSet::default();
        rules.set_specific(zone, body, rule);
        let mut hooks = RuleHooks::new(rules);
        let mut events = Events::new();
        events.about = Some(zone);
        let mut intersected = false;
        for _ in 0..90 {
            hooks.step_with_events(&mut scene.world, &events.collector);
            events.drain();
            intersected |= scene.world.narrow_phase.intersection_pair(zone, cube) == Some(true);
        }
        assert_eq!(
            (intersected, events.started > 0),
            (expect_events, expect_events),
            "{rule:?}: intersected {intersected}, started {} stopped {}",
            events.started,
            events.stopped
        );
        assert!(
            abs_diff_eq!(scene.y(body), 0.5, epsilon = 0.05),
            "{rule:?}: cube did not land: y = {}",
            scene.y(body)
        );
    }
}

/// A bullet fired at 200 m/s along +x at a thin wall at x = 5, without
/// gravity: its x after 10 steps with `rule` between wall and bullet, in a
/// world without the wall, and with the wall in plain Rapier (no hooks).
fn bullet(rule: CollisionRule, wall_kind: RigidBodyType, ccd: bool) -> (f32, f32, f32) {
    let run = |with_wall: bool, hooked: bool| {
        let mut world = PhysicsWorld::new();
        world.gravity = Vector::ZERO;
        let body = world.insert_body(
            RigidBodyBuilder::dynamic()
                .linvel(at(200.0, 0.0))
                .ccd_enabled(ccd),
        );
        let shot = world.insert_collider(ColliderBuilder::ball(0.1), Some(body));
        let mut rules = CollisionRuleSet::default();
        if with_wall {
            let wall =
                world.insert_body(RigidBodyBuilder::new(wall_kind).translation(at(5.0, 0.0)));
            let plate = world.insert_collider(cuboid(0.02, 3.0, 3.0), Some(wall));
            rules.set_specific(plate, shot, rule);
        }
        let mut hooks = RuleHooks::new(rules);
        for _ in 0..10 {
            if hooked {
                hooks.step(&mut world);
            } else {
                world.step();
            }
        }
        world.bodies[body].translation().x
    };
    (run(true, true), run(false, true), run(true, false))
}

#[test]
fn ccd_bullets_pass_exactly_through_walls_that_do_not_respond() {
    for wall in [RigidBodyType::Fixed, RigidBodyType::Dynamic] {
        for ccd in [true, false] {
            if !ccd && wall == RigidBodyType::Dynamic {
                continue; // Without CCD nothing sweeps against a dynamic wall.
            }
            for rule in [NoResponse, NoContacts, NoPair] {
                let (x, free, _) = bullet(rule, wall, ccd);
                assert_eq!(
                    x, free,
                    "{rule:?} {wall:?} wall, ccd {ccd}: x = {x}, free flight {free}"
                );
            }
        }
    }
}

#[test]
fn ccd_bullets_stop_at_normal_walls() {
    for wall in [RigidBodyType::Fixed, RigidBodyType::Dynamic] {
        let (x, free, plain) = bullet(Normal, wall, true);
        assert!(
            x == plain && x < free - 20.0,
            "Normal {wall:?} wall: x = {x}, plain Rapier {plain}, free flight {free}"
        );
    }
}

#[test]
fn two_kinematic_bodies_with_a_normal_group_rule_touch_without_pushing() {
    let mut world = PhysicsWorld::new();
    let a = world.insert_body(RigidBodyBuilder::kinematic_velocity_based().linvel(at(1.0, 0.0)));
    let b = world.insert_body(
        RigidBodyBuilder::kinematic_velocity_based()
            .translation(at(1.5, 0.0))
            .linvel(at(-1.0, 0.0)),
    );
    let ca = world.insert_collider(cuboid(0.5, 0.5, 0.5), Some(a));
    let cb = world.insert_collider(cuboid(0.5, 0.5, 0.5), Some(b));
    let mut rules = CollisionRuleSet::default();
    let k = CollisionGroup::DEFAULT_KINEMATIC;
    rules.set_group_rule(k, k, Normal);
    let mut hooks = RuleHooks::new(rules);
    let mut touched = false;
    for _ in 0..30 {
        hooks.step(&mut world);
        touched |= world
            .narrow_phase
            .contact_pair(ca, cb)
            .is_some_and(|p| p.has_any_active_contact());
    }
    let (xa, xb) = (
        world.bodies[a].translation().x,
        world.bodies[b].translation().x,
    );
    assert!(touched, "the platforms never had contacts");
    assert!(
        abs_diff_eq!(xa, 0.5, epsilon = 1e-4) && abs_diff_eq!(xb, 1.0, epsilon = 1e-4),
        "a platform was pushed: {xa} {xb}"
    );
    assert_eq!(hooks.pair_rule(&world, ca, cb), Some(NoResponse));
}

#[test]
fn kinematic_bodies_by_default_form_no_pair() {
    let mut world = PhysicsWorld::new();
    let a = world.insert_body(RigidBodyBuilder::kinematic_position_based());
    let b =
        world.insert_body(RigidBodyBuilder::kinematic_position_based().translation(at(0.5, 0.0)));
    let ca = world.insert_collider(ColliderBuilder::ball(0.5), Some(a));
    let cb = world.insert_collider(ColliderBuilder::ball(0.5), Some(b));
    let mut hooks = RuleHooks::default();
    for _ in 0..5 {
        hooks.step(&mut world);
    }
    let touching = world
        .narrow_phase
        .contact_pair(ca, cb)
        .is_some_and(|p| p.has_any_active_contact());
    assert!(
        !touching && hooks.pair_rule(&world, ca, cb).is_none(),
        "kinematic pair: touching {touching}"
    );
}

/// A cube that has fallen asleep on the ground, and hooks with `policy`.
fn sleeping_cube(
    policy: RecalculationPolicy,
) -> (Scene, RuleHooks, RigidBodyHandle, ColliderHandle) {
    let mut scene = Scene::new();
    let (body, cube) = scene.cube(0.0, 0.5);
    let mut hooks = RuleHooks::default();
    hooks.set_policy(policy);
    for _ in 0..300 {
        hooks.step(&mut scene.world);
    }
    assert!(
        scene.world.bodies[body].is_sleeping(),
        "the cube did not fall asleep"
    );
    (scene, hooks, body, cube)
}

fn run(scene: &mut Scene, hooks: &mut RuleHooks, steps: usize) {
    for _ in 0..steps {
        hooks.step(&mut scene.world);
    }
}

#[test]
fn on_change_applies_an_edit_to_a_sleeping_pair() {
    let (mut scene, mut hooks, body, cube) = sleeping_cube(RecalculationPolicy::OnChange);
    hooks.rules_mut().set_personal(body, NoResponse);
    run(&mut scene, &mut hooks, 60);
    assert_eq!(
        hooks.pair_rule(&scene.world, cube, scene.floor),
        None,
        "the pair outlived the fall"
    );
    assert!(
        scene.y(body) < -3.0,
        "the edit did not reach the sleeping cube: y = {}",
        scene.y(body)
    );
}

#[test]
fn manual_waits_for_force_recalculation() {
    let (mut scene, mut hooks, body, cube) = sleeping_cube(RecalculationPolicy::Manual);
    hooks.rules_mut().set_personal(body, NoResponse);
    run(&mut scene, &mut hooks, 60);
    assert_eq!(hooks.pair_rule(&scene.world, cube, scene.floor), Some(Normal));
    assert!(
        abs_diff_eq!(scene.y(body), 0.5, epsilon = 0.05),
        "the edit applied without a recalculation: y = {}",
        scene.y(body)
    );
    hooks.force_recalculation(body);
    run(&mut scene, &mut hooks, 60);
    assert!(
        scene.y(body) < -3.0,
        "force_recalculation did not apply: y = {}",
        scene.y(body)
    );
}

#[test]
fn manual_gives_new_pairs_the_current_rules() {
    let mut scene = Scene::new();
    let mut hooks = RuleHooks::default();
    hooks.set_policy(RecalculationPolicy::Manual);
    let (body, _) = scene.cube(0.0, 3.0);
    hooks.rules_mut().set_personal(body, NoContacts);
    run(&mut scene, &mut hooks, 90);
    assert!(
        scene.y(body) < -3.0,
        "the new pair ignored the edit: y = {}",
        scene.y(body)
    );
}

#[test]
fn every_step_follows_a_calculator_reading_outside_state() {
    let mut scene = Scene::new();
    let (body, _) = scene.cube(0.0, 0.5);
    let open = Arc::new(AtomicBool::new(false));
    let mut hooks = RuleHooks::default();
    hooks.set_policy(RecalculationPolicy::EveryStep);
    let trapdoor = Arc::clone(&open);
    hooks.set_calculator(move |ctx| {
        if trapdoor.load(Ordering::Relaxed) {
            NoContacts
        } else {
            ctx.default_rule()
        }
    });
    run(&mut scene, &mut hooks, 30);
    let resting = scene.y(body);
    open.store(true, Ordering::Relaxed);
    run(&mut scene, &mut hooks, 60);
    assert!(
        abs_diff_eq!(resting, 0.5, epsilon = 0.05) && scene.y(body) < -3.0,
        "rested at {resting}, ended at {}",
        scene.y(body)
    );
}

#[test]
fn pair_overrides_last_until_forced() {
    let mut scene = Scene::new();
    let (body, cube) = scene.cube(0.0, 0.5);
    let (other, _) = scene.cube(3.0, 0.5);
    let mut hooks = RuleHooks::default();
    run(&mut scene, &mut hooks, 5);
    // No rule reaches the cube or the floor: Rapier decides their pair
    // alone, and the override hooks it from the next step on.
    assert!(
        hooks.set_pair_rule(&scene.world, scene.floor, cube, NoResponse),
        "the pair was not live"
    );
    assert_eq!(hooks.pair_rule(&scene.world, scene.floor, cube), Some(NoResponse));
    // An edit elsewhere does not undo the override.
    hooks.rules_mut().set_personal(other, NoResponse);
    run(&mut scene, &mut hooks, 2);
    assert_eq!(hooks.pair_rule(&scene.world, scene.floor, cube), Some(NoResponse));
    hooks.force_recalculation(body);
    run(&mut scene, &mut hooks, 1);
    assert_eq!(
        hooks.pair_rule(&scene.world, cube, scene.floor),
        Some(Normal),
        "force_recalculation kept the override"
    );
    assert!(!hooks.set_pair_rule(&scene.world, cube, ColliderHandle::invalid(), Normal));
}

#[test]
fn a_pair_override_to_no_response_lets_the_cube_fall() {
    let mut scene = Scene::new();
    let (body, cube) = scene.cube(0.0, 0.5);
    let mut hooks = RuleHooks::default();
    run(&mut scene, &mut hooks, 5);
    assert!(hooks.set_pair_rule(&scene.world, cube, scene.floor, NoResponse));
    run(&mut scene, &mut hooks, 60);
    assert!(scene.y(body) < -3.0, "y = {}", scene.y(body));
}

#[test]
fn the_created_callback_replaces_the_rule_before_any_contact() {
    let mut scene = Scene::new();
    let (body, cube) = scene.cube(0.0, 0.49);
    let calls = Arc::new(AtomicUsize::new(0));
    let counter = Arc::clone(&calls);
    let floor = scene.floor;
    let mut hooks = RuleHooks::default();
    hooks.on_pair_created(move |pair| {
        counter.fetch_add(1, Ordering::Relaxed);
        assert_eq!(pair.rule, Normal);
        let with_floor = pair.collider1 == floor || pair.collider2 == floor;
        with_floor.then_some(NoResponse)
    });
    let mut touched = false;
    for _ in 0..60 {
        hooks.step(&mut scene.world);
        touched |= scene
            .world
            .narrow_phase
            .contact_pair(cube, floor)
            .is_some_and(|p| p.has_any_active_contact());
    }
    let n = calls.load(Ordering::Relaxed);
    assert!(
        scene.y(body) < -3.0 && touched,
        "y = {}, touched {touched}",
        scene.y(body)
    );
    assert_eq!(n, 1, "the callback ran {n} times for one pair");
}

#[test]
fn a_calculator_can_replace_or_delegate() {
    let mut scene = Scene::new();
    let (a, ca) = scene.cube(0.0, 0.5);
    let (b, cb) = scene.cube(3.0, 0.5);
    let mut hooks = RuleHooks::default();
    hooks.rules_mut().set_personal(b, NoResponse);
    hooks.set_calculator(move |ctx| {
        if ctx.collider1 == ca || ctx.collider2 == ca {
            NoContacts
        } else {
            ctx.default_rule()
        }
    });
    run(&mut scene, &mut hooks, 60);
    let (ya, yb) = (scene.y(a), scene.y(b));
    assert!(ya < -3.0 && yb < -3.0, "ya = {ya}, yb = {yb}");
    assert_eq!(
        hooks
            .pairs(&scene.world)
            .filter(|&(x, y, _)| x == cb || y == cb)
            .count(),
        0
    );
}

#[test]
fn always_computes_contacts_without_response() {
    let mut scene = Scene::new();
    let (body, cube) = scene.cube(0.0, 0.49);
    let mut hooks = RuleHooks::default();
    hooks.rules_mut().set_personal(body, NoContacts);
    hooks.set_policy(RecalculationPolicy::Manual);
    run(&mut scene, &mut hooks, 1);
    assert!(hooks.set_manifold_update(&scene.world, cube, scene.floor, ManifoldUpdate::Always));
    let mut touched = false;
    for _ in 0..60 {
        hooks.step(&mut scene.world);
        touched |= scene.touching(cube, scene.floor);
    }
    assert!(
        touched && scene.y(body) < -3.0,
        "touched {touched}, y = {}",
        scene.y(body)
    );
}

#[test]
fn never_keeps_the_contacts_of_the_moment_it_was_set() {
    // Set while apart (the pair exists, no contacts yet): the cube falls through.
    let mut scene = Scene::new();
    let (body, cube) = scene.cube(0.0, 0.6);
    let mut hooks = RuleHooks::default();
    let mut frozen_apart = false;
    for _ in 0..30 {
        hooks.step(&mut scene.world);
        let live = hooks
            .pair_rule(&scene.world, cube, scene.floor)
            .is_some();
        if live && !scene.touching(cube, scene.floor) {
            frozen_apart = hooks.set_manifold_update(
                &scene.world,
                cube,
                scene.floor,
                ManifoldUpdate::Never,
            );
            break;
        }
    }
    assert!(
        frozen_apart,
        "never saw the pair live and apart: y = {}",
        scene.y(body)
    );
    run(&mut scene, &mut hooks, 60);
    assert!(
        scene.y(body) < 0.0,
        "frozen without contacts, the cube stopped: y = {}",
        scene.y(body)
    );

    // Set while resting: the cube keeps resting on the frozen contacts.
    let mut scene = Scene::new();
    let (body, cube) = scene.cube(0.0, 0.5);
    let mut hooks = RuleHooks::default();
    run(&mut scene, &mut hooks, 20);
    assert!(hooks.set_manifold_update(&scene.world, cube, scene.floor, ManifoldUpdate::Never));
    run(&mut scene, &mut hooks, 60);
    assert!(
        abs_diff_eq!(scene.y(body), 0.5, epsilon = 0.05),
        "the frozen contacts did not hold: y = {}",
        scene.y(body)
    );
    assert_eq!(
        hooks.manifold_update(&scene.world, cube, scene.floor),
        Some(ManifoldUpdate::Never)
    );
}

#[test]
fn removal_through_rapier_is_noticed_and_reused_handles_start_clean() {
    let mut scene = Scene::new();
    let (body, cube) = scene.cube(0.0, 0.5);
    let mut hooks = RuleHooks::default();
    hooks
        .rules_mut()
        .set_specific(scene.ground, body, NoResponse);
    hooks.rules_mut().set_personal(cube, NoResponse);
    run(&mut scene, &mut hooks, 2);
    scene.world.remove_body(body);
    run(&mut scene, &mut hooks, 1);
    assert_eq!(
        hooks.pairs(&scene.world).count(),
        0,
        "a pair of a removed collider survived"
    );
    assert_eq!(
        hooks.rules().specific(scene.ground, body),
        Defer,
        "an entry about a removed body survived"
    );
    assert_eq!(hooks.rules().personal(cube), Defer);
    let (new_body, new_cube) = scene.cube(0.0, 0.5);
    assert_eq!(
        new_cube.into_raw_parts().0,
        cube.into_raw_parts().0,
        "Rapier did not reuse the slot"
    );
    run(&mut scene, &mut hooks, 30);
    assert_eq!(
        hooks.pair_rule(&scene.world, new_cube, scene.floor),
        Some(Normal)
    );

    assert!(
        abs_diff_eq!(scene.y(new_body), 0.5, epsilon = 0.05),
        "y = {}",
        scene.y(new_body)
    );
}

#[test]
fn a_ragdoll_ignores_itself_and_lands_on_the_world() -> Result<(), RuleError> {
    let mut scene = Scene::new();
    // Three overlapping limbs: plain Rapier would push them apart.
    let (pelvis, p) = scene.cube(0.0, 3.0);
    let (thigh, t) = scene.cube(0.3, 3.0);
    let (shin, s) = scene.cube(0.6, 3.0);
    let mut rules = CollisionRuleSet::default();
    let ragdoll = rules.create_group();
    rules.set_group_rule(ragdoll, ragdoll, NoPair);
    rules.set_group(pelvis, Some(ragdoll));
    rules.set_parent(thigh, pelvis)?;
    rules.set_parent(shin, thigh)?;
    let mut hooks = RuleHooks::new(rules);
    run(&mut scene, &mut hooks, 120);
    for (limb, x0) in [(pelvis, 0.0), (thigh, 0.3), (shin, 0.6)] {
        let (x, y) = (scene.x(limb), scene.y(limb));
        assert!(
            abs_diff_eq!(x, x0, epsilon = 0.02) && abs_diff_eq!(y, 0.5, epsilon = 0.05),
            "limb landed at ({x}, {y})"
        );
    }
    for (a, b) in [(p, t), (t, s), (p, s)] {
        assert_eq!(
            hooks.pair_rule(&scene.world, a, b),
            None,
            "limbs formed a live pair"
        );
    }
    assert_eq!(
        hooks.pair_rule(&scene.world, s, scene.floor),
        Some(Normal)
    );
    Ok(())
}

/// A cube dropped from y = 2 through the ground and a dynamic cube lying in
/// its path; returns the cube's y after each of 90 steps.
fn dropped_cube(rule: Option<CollisionRule>) -> Vec<f32> {
    let mut scene = Scene::new();
    let (body, cube) = scene.cube(0.0, 2.0);
    let mut rules = CollisionRuleSet::default();
    if let Some(rule) = rule {
        let (_, obstacle) = scene.cube(0.2, 0.5);
        rules.set_specific(cube, scene.floor, rule);
        rules.set_specific(cube, obstacle, rule);
    } else {
        scene.world.remove_collider(scene.floor);
    }
    let mut hooks = RuleHooks::new(rules);
    (0..90)
        .map(|_| {
            hooks.step(&mut scene.world);
            scene.y(body)
        })
        .collect()
}

#[test]
fn a_body_that_does_not_respond_moves_as_if_the_others_were_absent() {
    let alone = dropped_cube(None);
    for rule in [NoResponse, NoContacts, NoPair] {
        let path = dropped_cube(Some(rule));
        assert_eq!(
            path,
            alone,
            "{rule:?}: the path differs from free fall (ends {:?} vs {:?})",
            path.last(),
            alone.last()
        );
    }
}

#[test]
fn a_bare_pipeline_with_prepare_and_after_step_matches_step() {
    let build = || {
        let mut scene = Scene::new();
        let (a, _) = scene.cube(0.0, 1.0);
        let (b, _) = scene.cube(0.3, 2.5);
        let mut rules = CollisionRuleSet::default();
        // NoContacts: the pair is the hook's (a NoResponse entry would be
        // Rapier's solver groups), so the bare pipeline's hook calls count.
        rules.set_specific(a, b, NoContacts);
        (scene, RuleHooks::new(rules), a, b)
    };
    let (mut stepped, mut hooks1, a, b) = build();
    let (mut bare, mut hooks2, _, _) = build();
    for _ in 0..60 {
        hooks1.step(&mut stepped.world);
        let w = &mut bare.world;
        hooks2.prepare(&w.bodies, &mut w.colliders);
        hooks2.wake_edited(&mut w.islands, &mut w.bodies);
        // Rapier's own step (`PhysicsPipeline::step` on the world's parts).
        w.step_with_events(&hooks2, &());
        hooks2.after_step(&w.narrow_phase, &w.bodies, &w.colliders);
    }
    for body in [a, b] {
        assert_eq!(stepped.y(body), bare.y(body), "the bare pipeline diverged");
    }
    let live = |hooks: &RuleHooks, world: WorldRef<'_>| {
        let mut pairs: Vec<_> = hooks
            .pairs(world)
            .map(|(x, y, r)| (x.into_raw_parts(), y.into_raw_parts(), r))
            .collect();
        pairs.sort();
        pairs
    };
    let w = &bare.world;
    let bare_view = WorldRef::new(&w.narrow_phase, &w.bodies, &w.colliders);
    assert_eq!(live(&hooks1, (&stepped.world).into()), live(&hooks2, bare_view));
    assert!(!live(&hooks1, (&stepped.world).into()).is_empty());
}

/// A small pile (four columns of five boxes, side by side) and its bodies.
fn small_pile() -> (PhysicsWorld, Vec<RigidBodyHandle>) {
    let mut world = PhysicsWorld::new();
    let ground = world.insert_body(RigidBodyBuilder::fixed().translation(at(0.0, -0.5)));
    world.insert_collider(cuboid(20.0, 0.5, 20.0), Some(ground));
    let bodies = (0..20)
        .map(|i| {
            let (column, level) = (i / 5, i % 5);
            let body = world.insert_body(
                RigidBodyBuilder::dynamic()
                    .translation(at(column as f32 * 1.01, 0.5 + level as f32 * 1.05)),
            );
            world.insert_collider(cuboid(0.5, 0.5, 0.5), Some(body));
            body
        })
        .collect();
    (world, bodies)
}

#[test]
fn without_rules_the_world_steps_exactly_as_plain_rapier() {
    let (mut plain, bodies) = small_pile();
    let (mut world, _) = small_pile();
    let mut hooks = RuleHooks::default();
    for _ in 0..120 {
        plain.step();
        hooks.step(&mut world);
    }
    for &body in &bodies {
        let (a, b) = (
            plain.bodies[body].translation(),
            world.bodies[body].translation(),
        );
        assert_eq!(a, b, "a box drifted from plain Rapier: {a:?} vs {b:?}");
    }
    assert_eq!(
        hooks.stats().hooked_colliders,
        0,
        "a collider without rules was hooked"
    );
}

#[test]
fn group_rules_step_exactly_as_the_same_rapier_groups() {
    // Columns 0 and 1 never pair, columns 1 and 2 do not respond to each other.
    let (mut plain, bodies) = small_pile();
    let bit = |i: u32| Group::from_bits_retain(1 << i);
    let filters = [
        (Group::ALL - bit(1), Group::ALL),
        (Group::ALL - bit(0), Group::ALL - bit(2)),
        (Group::ALL, Group::ALL - bit(1)),
        (Group::ALL, Group::ALL),
    ];
    for (i, &body) in bodies.iter().enumerate() {
        let column = i / 5;
        let collider = plain.bodies[body].colliders()[0];
        let (collision, solver) = filters[column];
        let c = &mut plain.colliders[collider];
        c.set_collision_groups(InteractionGroups::new(
            bit(column as u32),
            collision,
            InteractionTestMode::And,
        ));
        c.set_solver_groups(InteractionGroups::new(
            bit(column as u32),
            solver,
            InteractionTestMode::And,
        ));
    }
    let (mut world, _) = small_pile();
    let mut rules = CollisionRuleSet::default();
    let g: Vec<_> = (0..4).map(|_| rules.create_group()).collect();
    rules.set_group_rule(g[0], g[1], NoPair);
    rules.set_group_rule(g[1], g[2], NoResponse);
    for (i, &body) in bodies.iter().enumerate() {
        rules.set_group(body, Some(g[i / 5]));
    }
    let mut hooks = RuleHooks::new(rules);
    for _ in 0..120 {
        plain.step();
        hooks.step(&mut world);
    }
    for &body in &bodies {
        let (a, b) = (
            plain.bodies[body].translation(),
            world.bodies[body].translation(),
        );
        assert_eq!(
            a, b,
            "a box drifted from hand-written Rapier groups: {a:?} vs {b:?}"
        );
    }
    assert_eq!(hooks.stats().hooked_colliders, 0, "group rules needed the hook");
}

#[test]
fn more_groups_than_bits_fall_back_to_the_hook_and_stay_exact() {
    // 40 boxes in a row, each in its own group, each touching the next; every
    // second neighbour relation is NoPair: 40 groups with native relations,
    // more than Rapier's 32 bits.
    let mut world = PhysicsWorld::new();
    world.gravity = Vector::ZERO;
    let mut rules = CollisionRuleSet::default();
    let mut boxes = Vec::new();
    for i in 0..40 {
        let body = world.insert_body(
            RigidBodyBuilder::dynamic()
                .translation(at(i as f32 * 0.95, 0.0))
                .locked_axes(LockedAxes::all()),
        );
        let collider = world.insert_collider(cuboid(0.5, 0.5, 0.5), Some(body));
        let group = rules.create_group();
        rules.set_group(body, Some(group));
        boxes.push((collider, group));
    }
    for pair in boxes.windows(2).step_by(2) {
        rules.set_group_rule(pair[0].1, pair[1].1, NoPair);
    }
    let mut hooks = RuleHooks::new(rules);
    hooks.step(&mut world);
    hooks.step(&mut world);
    let hooked = hooks.stats().hooked_colliders;
    assert!(
        hooked >= 8,
        "40 related groups fit in 32 bits? {hooked} hooked"
    );
    for (i, pair) in boxes.windows(2).enumerate() {
        let (a, b) = (pair[0].0, pair[1].0);
        let touching = world
            .narrow_phase
            .contact_pair(a, b)
            .is_some_and(|p| p.has_any_active_contact());
        let expected = i % 2 == 1;
        assert_eq!(
            touching,
            expected,
            "boxes {i} and {}: touching {touching}",
            i + 1
        );
        assert_eq!(
            hooks.pair_rule(&world, a, b).is_some(),
            expected,
            "boxes {i} and {}",
            i + 1
        );
    }
}

#[test]
fn a_body_changing_type_updates_its_pairs_and_its_parent_changing_type_does_not()
-> Result<(), RuleError> {
    // The cube hangs under a colliderless fixed frame and rests on a
    // kinematic deck. Its pairs read its own type, never its parent's
    // (`docs/semantics.md`, "Terms", effective group): the frame made dynamic
    // changes nothing; the cube made kinematic meets the deck in the
    // built-in (DEFAULT_KINEMATIC, DEFAULT_KINEMATIC) entry, and made dynamic
    // again it is Normal with the deck again.
    let mut world = PhysicsWorld::new();
    let frame = world.insert_body(RigidBodyBuilder::fixed().translation(at(0.0, 10.0)));
    let platform = world.insert_body(RigidBodyBuilder::kinematic_position_based());
    let deck = world.insert_collider(cuboid(2.0, 0.1, 2.0), Some(platform));
    let cube = world.insert_body(RigidBodyBuilder::dynamic().translation(at(0.0, 0.6)));
    let c = world.insert_collider(cuboid(0.5, 0.5, 0.5), Some(cube));
    let mut rules = CollisionRuleSet::default();
    rules.set_parent(cube, frame)?;
    rules.set_default_rule(Defer);
    let mut hooks = RuleHooks::new(rules);
    run_world(&mut world, &mut hooks, 30);
    assert_eq!(hooks.pair_rule(&world, c, deck), Some(Defer), "under a fixed frame");
    world.bodies[frame].set_body_type(RigidBodyType::Dynamic, true);
    world.bodies[frame].set_gravity_scale(0.0, true);
    run_world(&mut world, &mut hooks, 30);
    let y = world.bodies[cube].translation().y;
    assert_eq!(hooks.pair_rule(&world, deck, c), Some(Defer), "under a dynamic frame");
    assert!(
        abs_diff_eq!(y, 0.6, epsilon = 0.05),
        "the cube did not stay on the platform: y = {y}"
    );
    world.bodies[cube].set_body_type(RigidBodyType::KinematicPositionBased, true);
    run_world(&mut world, &mut hooks, 2);
    assert_eq!(hooks.pair_rule(&world, c, deck), None, "a kinematic cube paired with the deck");
    world.bodies[cube].set_body_type(RigidBodyType::Dynamic, true);
    run_world(&mut world, &mut hooks, 30);
    let y = world.bodies[cube].translation().y;
    assert_eq!(hooks.pair_rule(&world, c, deck), Some(Defer), "dynamic again");
    assert!(
        abs_diff_eq!(y, 0.6, epsilon = 0.05),
        "the cube did not land on the platform again: y = {y}"
    );
    Ok(())
}

fn run_world(world: &mut PhysicsWorld, hooks: &mut RuleHooks, steps: usize) {
    for _ in 0..steps {
        hooks.step(world);
    }
}

/// One live-pair API for every pair (`docs/semantics.md`, "Every live
/// pair, one API"): a pair Rapier decides with the groups the planner wrote,
/// a pair the hook decides, a pair with no rule at all and a pair that does
/// not exist, each asked in both argument orders, through `pair_rule` and
/// `pairs`.
#[test]
fn pair_rule_and_pairs_answer_every_pair_however_it_is_decided() {
    let mut scene = Scene::new();
    let (planned_body, planned) = scene.cube(-3.0, 0.5);
    let (hooked_body, hooked) = scene.cube(0.0, 0.5);
    let (_, plain) = scene.cube(3.0, 0.5);
    let (_, far) = scene.cube(9.0, 5.0);
    let mut hooks = RuleHooks::default();
    // A personal NoResponse on a dynamic body is planned as solver groups;
    // a specific NoContacts needs the hook.
    hooks.rules_mut().set_personal(planned_body, NoResponse);
    hooks.rules_mut().set_specific(hooked_body, scene.ground, NoContacts);
    hooks.step(&mut scene.world);
    let stats = hooks.stats();
    assert_eq!(stats.hooked_colliders, 1, "one collider is hooked: {stats:?}");
    let floor = scene.floor;
    let world = &scene.world;
    let listed: Vec<_> = hooks.pairs(world).collect();
    let cases = [
        ("planned", planned, Some(NoResponse)),
        ("hooked", hooked, Some(NoContacts)),
        ("no rule", plain, Some(Normal)),
        ("no pair", far, None),
    ];
    for (what, cube, expected) in cases {
        assert_eq!(hooks.pair_rule(world, cube, floor), expected, "{what}: cube first");
        assert_eq!(hooks.pair_rule(world, floor, cube), expected, "{what}: floor first");
        let found: Vec<_> = listed
            .iter()
            .filter(|&&(a, b, _)| (a, b) == (cube, floor) || (a, b) == (floor, cube))
            .map(|&(.., rule)| rule)
            .collect();
        assert_eq!(found, Vec::from_iter(expected), "{what}: pairs lists {listed:?}");
    }
    assert_eq!(listed.len(), 3, "pairs lists exactly the three: {listed:?}");
}

/// The first body put into a group whose table entry Rapier's groups decide
/// changes only its own collider: the boxes asleep on the shared floor stay
/// asleep (`docs/architecture.md`, "The planner": a group the table relates
/// has its bit before its first member).
#[test]
fn the_first_member_of_a_group_wakes_only_its_own_body() {
    let mut scene = Scene::new();
    let boxes: Vec<_> = (0..10).map(|i| scene.cube(i as f32 * 3.0 - 15.0, 0.5).0).collect();
    let mut hooks = RuleHooks::default();
    let ghosts = hooks.rules_mut().create_group();
    hooks
        .rules_mut()
        .set_group_rule(ghosts, CollisionGroup::DEFAULT_KINEMATIC, NoResponse);
    run(&mut scene, &mut hooks, 300);
    let asleep = |scene: &Scene| boxes.iter().filter(|&&b| scene.world.bodies[b].is_sleeping()).count();
    assert_eq!(asleep(&scene), 10, "the boxes fell asleep");
    for (member, x) in [("first", -13.5), ("second", -10.5)] {
        let (ghost, _) = scene.cube(x, 3.0);
        hooks.rules_mut().set_group(ghost, Some(ghosts));
        run(&mut scene, &mut hooks, 1);
        let stats = hooks.stats();
        assert_eq!(
            asleep(&scene),
            10,
            "the {member} member woke the boxes on the floor: {stats:?}"
        );
        run(&mut scene, &mut hooks, 90);
        let y = scene.y(ghost);
        assert!(y < -1.0, "the {member} member did not pass the floor: y = {y}");
    }
}
