//! The step boundary: CCD substeps, several pipeline steps between
//! `prepare` and `after_step` (what bevy_rapier does with substeps), the
//! one-call bare pipeline, the calls a bare-pipeline user can forget or
//! make twice, and a rule set put in place of the hooks' one.

use super::rapier::prelude::*;
use super::rules::{CollisionRule, ManifoldUpdate, OneWay, RuleHooks, WorldRef};
use super::{at, cuboid};

use super::scenes::Events;
use super::world::panic_message;

/// A fast CCD ball crossing a thick slab, then stopped by a thin wall just
/// past it: the wall's impact makes the CCD split the step into substeps
/// while the ball is inside the slab.
struct Crossing {
    world: PhysicsWorld,
    ball: RigidBodyHandle,
    shot: ColliderHandle,
    slab: ColliderHandle,
}

/// How the slab lets the ball through.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Pass {
    /// Rapier's own solver groups, without the rules.
    Rapier,
    /// A specific `NoResponse` rule, which the planner gives to Rapier's
    /// solver groups (a bit of the ball's own).
    Bits,
    /// The same rule, with the slab hooked by a personal `Normal`, so that
    /// the hook decides the pair at each of the CCD's questions.
    Hook,
}

impl Crossing {
    fn new(substeps: usize, pass: Pass) -> (Crossing, Option<RuleHooks>) {
        let hooked = pass != Pass::Rapier;
        let mut world = PhysicsWorld::new();
        world.gravity = Vector::ZERO;
        world.integration_parameters.max_ccd_substeps = substeps;
        let fixed = world.insert_body(RigidBodyBuilder::fixed());
        let events = ActiveEvents::COLLISION_EVENTS;
        let slab = cuboid(1.5, 2.0, 2.0)
            .translation(at(4.0, 0.0))
            .active_events(events);
        let slab = if hooked {
            slab
        } else {
            slab.solver_groups(InteractionGroups::none())
        };
        let slab = world.insert_collider(slab, Some(fixed));
        world.insert_collider(
            cuboid(0.05, 2.0, 2.0).translation(at(6.0, 0.0)),
            Some(fixed),
        );
        let ball = world.insert_body(
            RigidBodyBuilder::dynamic()
                .linvel(at(70.0, 0.0))
                .ccd_enabled(true),
        );
        let shot = world.insert_collider(
            ColliderBuilder::ball(0.25).active_events(events),
            Some(ball),
        );
        let hooks = hooked.then(|| {
            let mut hooks = RuleHooks::default();
            hooks
                .rules_mut()
                .set_specific(slab, shot, CollisionRule::NoResponse);
            if pass == Pass::Hook {
                hooks.rules_mut().set_personal(slab, CollisionRule::Normal);
            }
            hooks
        });
        let crossing = Crossing {
            world,
            ball,
            shot,
            slab,
        };
        (crossing, hooks)
    }

    /// One Rapier step with the hooks (or none).
    fn pipeline_step(&mut self, hooks: Option<&RuleHooks>, events: &Events) {
        let hooks: &dyn PhysicsHooks = match hooks {
            Some(hooks) => hooks,
            None => &(),
        };
        self.world.step_with_events(hooks, &events.collector);
    }

    /// What one run saw, step by step: the ball's position (bits), whether
    /// the ball and the slab touched, and the events.
    fn run(substeps: usize, per_bracket: usize, pass: Pass) -> Vec<String> {
        let (mut scene, mut hooks) = Crossing::new(substeps, pass);
        let mut events = Events::new();
        let mut seen = Vec::new();
        for _ in 0..6 {
            if let Some(hooks) = &mut hooks {
                let w = &mut scene.world;
                hooks.prepare(&w.bodies, &mut w.colliders);
                hooks.freeze_manifolds(&w.narrow_phase);
                hooks.wake_edited(&mut w.islands, &mut w.bodies);
            }
            for _ in 0..per_bracket {
                scene.pipeline_step(hooks.as_ref(), &events);
                let x = scene.world.bodies[scene.ball].translation().x;
                let touching = scene
                    .world
                    .narrow_phase
                    .contact_pair(scene.shot, scene.slab)
                    .is_some_and(|pair| pair.has_any_active_contact());
                seen.push(format!(
                    "x {x} ({:#x}), touching {touching}, events {:?}",
                    x.to_bits(),
                    events.take()
                ));
            }
            if let Some(hooks) = &mut hooks {
                let w = &scene.world;
                hooks.after_step(&w.narrow_phase, &w.bodies, &w.colliders);
                assert_eq!(
                    hooks.stats().hooked_colliders > 0,
                    pass == Pass::Hook,
                    "{pass:?}: hooked colliders {}",
                    hooks.stats().hooked_colliders
                );
            }
        }
        seen
    }
}

/// A `NoResponse` pair's contacts and events, hooked or given to Rapier's
/// solver groups by the planner, equal those of the same pair excluded by
/// hand-written solver groups, step by step, with 1 to 4 CCD substeps and 1
/// or 3 Rapier steps between `prepare` and `after_step`.
#[test]
fn no_response_holds_across_ccd_substeps_and_pipeline_steps() {
    for substeps in 1..=4 {
        for per_bracket in [1, 3] {
            let plain = Crossing::run(substeps, per_bracket, Pass::Rapier);
            assert!(
                plain.iter().any(|s| s.contains("touching true")),
                "the ball passes through the slab: {plain:#?}"
            );
            for pass in [Pass::Bits, Pass::Hook] {
                let ruled = Crossing::run(substeps, per_bracket, pass);
                for (step, (plain, ruled)) in plain.iter().zip(&ruled).enumerate() {
                    assert_eq!(
                        ruled, plain,
                        "{substeps} CCD substeps, {per_bracket} steps per bracket, step {step}: \
                         {pass:?} against solver groups"
                    );
                }
            }
        }
    }
}

/// `step_pipeline` on bare sets steps exactly as `step` on a `PhysicsWorld`.
#[test]
fn step_pipeline_is_step_on_bare_sets() {
    let (mut stepped, hooks1) = Crossing::new(2, Pass::Hook);
    let (mut bare, hooks2) = Crossing::new(2, Pass::Hook);
    let (mut hooks1, mut hooks2) = (hooks1.expect("hooks"), hooks2.expect("hooks"));
    for step in 0..8 {
        hooks1.step(&mut stepped.world);
        let w = &mut bare.world;
        hooks2.step_pipeline(
            &mut w.physics_pipeline,
            w.gravity,
            &w.integration_parameters,
            &mut w.islands,
            &mut w.broad_phase,
            &mut w.narrow_phase,
            &mut w.bodies,
            &mut w.colliders,
            &mut w.impulse_joints,
            &mut w.multibody_joints,
            &mut w.soft_bodies,
            &mut w.ccd_solver,
            &(),
        );
        let x = |s: &Crossing| s.world.bodies[s.ball].translation().x.to_bits();
        assert_eq!(x(&stepped), x(&bare), "step {step}: the ball's x diverged");
        assert_eq!(
            hooks1.pair_rule(&stepped.world, stepped.shot, stepped.slab),
            hooks2.pair_rule(
                WorldRef::new(&bare.world.narrow_phase, &bare.world.bodies, &bare.world.colliders),
                bare.slab,
                bare.shot,
            ),
            "step {step}: the live pair"
        );
    }
}

/// What a bare-pipeline user can leave out, and the call the panic names.
#[test]
fn a_forgotten_call_fails_loudly_and_names_it() {
    // (what the user does, the call the message names)
    type Misuse = fn(&mut Crossing, &mut RuleHooks);
    let table: [(&str, Misuse, &str); 5] = [
        (
            "after_step without prepare",
            |s, hooks| {
                s.pipeline_step(Some(hooks), &Events::new());
                let w = &s.world;
                hooks.after_step(&w.narrow_phase, &w.bodies, &w.colliders);
            },
            "RuleHooks::prepare",
        ),
        (
            "prepare twice around a step",
            |s, hooks| {
                let w = &mut s.world;
                hooks.prepare(&w.bodies, &mut w.colliders);
                hooks.wake_edited(&mut w.islands, &mut w.bodies);
                s.pipeline_step(Some(hooks), &Events::new());
                let w = &mut s.world;
                hooks.prepare(&w.bodies, &mut w.colliders);
            },
            "RuleHooks::after_step",
        ),
        (
            "a pair override, without wake_edited",
            |s, hooks| {
                assert!(hooks.set_pair_rule(&s.world, s.shot, s.slab, CollisionRule::Normal));
                let w = &mut s.world;
                hooks.prepare(&w.bodies, &mut w.colliders);
                s.pipeline_step(Some(hooks), &Events::new());
                let w = &s.world;
                hooks.after_step(&w.narrow_phase, &w.bodies, &w.colliders);
            },
            "RuleHooks::wake_edited",
        ),
        (
            "a Never setting without freeze_manifolds",
            |s, hooks| {
                assert!(hooks.set_manifold_update(&s.world, s.shot, s.slab, ManifoldUpdate::Never));
                let w = &mut s.world;
                hooks.prepare(&w.bodies, &mut w.colliders);
                hooks.wake_edited(&mut w.islands, &mut w.bodies);
                s.pipeline_step(Some(hooks), &Events::new());
                let w = &s.world;
                hooks.after_step(&w.narrow_phase, &w.bodies, &w.colliders);
            },
            "RuleHooks::freeze_manifolds",
        ),
        // Found by a misuse audit: one step of a NaN timestep left every
        // `Until::seconds` counting NaN for good.
        (
            "a timestep that is not a number",
            |s, hooks| {
                s.world.integration_parameters.dt = f32::NAN;
                hooks.step(&mut s.world);
            },
            "IntegrationParameters::dt is NaN",
        ),
    ];
    for (misuse, act, names) in table {
        let (mut scene, hooks) = Crossing::new(1, Pass::Hook);
        let mut hooks = hooks.expect("hooks");
        // Three good steps: the ball is inside the slab, the pair live.
        for _ in 0..3 {
            hooks.step(&mut scene.world);
        }
        let message = panic_message(|| {
            act(&mut scene, &mut hooks);
        })
            .unwrap_or_else(|| panic!("{misuse}: no panic"));
        assert!(
            message.contains(names),
            "{misuse}: the message names {names}: {message}"
        );
    }
}

/// Rapier stepping the world without the hooks inside their own bracket:
/// `prepare`, `freeze_manifolds`, `wake_edited`, then `world.step()` where
/// the hooks should have been passed, then `after_step`. Found by trying
/// the bare-pipeline calls from the docs alone: `after_step` forgot the
/// witness, since nothing was answered, and the next `freeze_manifolds`
/// had nothing to look up; the ghost then rested on the floor while
/// `pair_rule` said `NoContacts`. A debug build panics at that
/// `after_step`, naming what happened and the fix; a release build warns
/// once and says so in that step's stats. A ghost held still in the floor
/// falls asleep, and a step with the hooks then asks them nothing: that
/// step is not mistaken for one without them (`docs/semantics.md`,
/// "Stepping without the hooks").
#[test]
fn stepping_rapier_without_the_hooks_inside_their_bracket_is_caught_at_after_step() {
    use super::{cube, slab};
    use CollisionRule::{NoContacts, NoResponse};
    /// One bracket of the bare-pipeline calls; `hooked`: the hooks are
    /// given to Rapier's step.
    fn bracket(world: &mut PhysicsWorld, hooks: &mut RuleHooks, hooked: bool) {
        hooks.prepare(&world.bodies, &mut world.colliders);
        hooks.freeze_manifolds(&world.narrow_phase);
        hooks.wake_edited(&mut world.islands, &mut world.bodies);
        if hooked {
            world.step_with_events(&*hooks, &());
        } else {
            world.step();
        }
        hooks.after_step(&world.narrow_phase, &world.bodies, &world.colliders);
    }
    // The ghost sunk into the floor (`held`: without gravity, so that it
    // falls asleep there), and its hooks deciding `rule` with every
    // collider hooked.
    let build = |rule: CollisionRule, held: bool| {
        let mut world = PhysicsWorld::new();
        let ground = world.insert_body(RigidBodyBuilder::fixed());
        world.insert_collider(slab(10.0, 0.5), Some(ground));
        let ghost = world.insert_body(
            RigidBodyBuilder::dynamic()
                .translation(at(0.0, 0.9))
                .gravity_scale(if held { 0.0 } else { 1.0 }),
        );
        world.insert_collider(cube(0.5), Some(ghost));
        let mut hooks = RuleHooks::default();
        hooks.set_planner(false);
        hooks.rules_mut().set_specific(ghost, ground, rule);
        (world, hooks, ghost)
    };

    // With the hooks throughout, until the held ghost sleeps and long after.
    let (mut world, mut hooks, ghost) = build(NoContacts, true);
    for step in 0..300 {
        bracket(&mut world, &mut hooks, true);
        assert!(
            !hooks.stats().stepped_without_hooks,
            "step {step}: stepped with the hooks, said without: {:?}",
            hooks.stats()
        );
    }
    assert!(
        world.bodies[ghost].is_sleeping(),
        "the held ghost fell asleep, so that the last steps asked the hooks nothing"
    );

    for rule in [NoContacts, NoResponse] {
        let (mut world, mut hooks, _) = build(rule, false);
        for _ in 0..3 {
            bracket(&mut world, &mut hooks, true);
        }
        if !cfg!(debug_assertions) {
            bracket(&mut world, &mut hooks, false);
            assert!(
                hooks.stats().stepped_without_hooks,
                "{rule:?}: went unnoticed: {:?}",
                hooks.stats()
            );
            bracket(&mut world, &mut hooks, true);
            assert!(!hooks.stats().stepped_without_hooks, "{rule:?}: said for its step only");
            continue;
        }
        let message = panic_message(|| {
            bracket(&mut world, &mut hooks, false);
        })
            .unwrap_or_else(|| panic!("{rule:?}: went unnoticed"));
        assert!(
            message.contains("between their `prepare` and `after_step`")
                && message.contains("never `world.step()`"),
            "{rule:?}: the message names what happened and the fix: {message}"
        );
    }
}

/// Rapier stepping the world between two steps of the hooks: without them
/// (`world.step()`: every rule the hook decides is dropped for that step),
/// or with them but without their `prepare` (`world.step_with_events(&hooks,
/// ..)`: the hook answers, so no rule looks broken to the witness, but
/// nothing that changed was planned). A debug build panics at the next step
/// of the hooks, naming what happened and the fix; a release build warns
/// once and says so in the stats of that step (`docs/semantics.md`,
/// "Stepping without the hooks"). Stepping with the hooks throughout, with
/// the same scene, says nothing.
#[test]
fn stepping_rapier_without_the_hooks_or_their_prepare_is_caught_at_the_next_step() {
    use super::{cube, slab};
    use CollisionRule::{NoContacts, NoPair, NoResponse};
    type Misstep = fn(&mut PhysicsWorld, &RuleHooks);
    // (what happened, the rule (`None`: a one-way ground, the world's only
    // rule), the step, what the message says)
    let cases: [(&str, Option<CollisionRule>, Misstep, &str); 5] = [
        // Found by a robot arm built from the docs: a hooked NoPair pair
        // (a link and its neighbour) was never the witness, and one
        // `world.step()` threw the arm apart unseen.
        ("world.step(), NoPair", Some(NoPair), |w, _| w.step(), "never `world.step()`"),
        ("world.step(), NoContacts", Some(NoContacts), |w, _| w.step(), "never `world.step()`"),
        ("world.step(), NoResponse", Some(NoResponse), |w, _| w.step(), "never `world.step()`"),
        (
            "the hooks given to Rapier without prepare",
            Some(NoContacts),
            |w, hooks| w.step_with_events(hooks, &()),
            "without their `prepare`",
        ),
        // Found by trying one-way platforms from the docs alone: the one-way
        // answers did not count as the hooks' answers.
        (
            "the hooks given to Rapier without prepare, a one-way ground",
            None,
            |w, hooks| w.step_with_events(hooks, &()),
            "without their `prepare`",
        ),
    ];
    for (name, rule, misstep, says) in cases {
        let build = || {
            let mut world = PhysicsWorld::new();
            let ground = world.insert_body(RigidBodyBuilder::fixed());
            world.insert_collider(slab(10.0, 0.5), Some(ground));
            let ghost = world.insert_body(RigidBodyBuilder::dynamic().translation(at(0.0, 1.0)));
            world.insert_collider(cube(0.5), Some(ghost));
            let mut hooks = RuleHooks::default();
            match rule {
                Some(rule) => {
                    // Every collider hooked: the rule is the hook's alone,
                    // and Rapier asks the hook about the pair.
                    hooks.set_planner(false);
                    hooks.rules_mut().set_specific(ghost, ground, rule);
                }
                None => hooks.rules_mut().set_one_way(ground, Some(OneWay::new(at(0.0, 1.0)))),
            }
            (world, hooks)
        };
        let (mut world, mut hooks) = build();
        for _ in 0..40 {
            hooks.step(&mut world);
            assert!(!hooks.stats().stepped_without_hooks, "{name}: stepped with the hooks");
        }
        let (mut world, mut hooks) = build();
        for _ in 0..3 {
            hooks.step(&mut world);
        }
        misstep(&mut world, &hooks);
        if !cfg!(debug_assertions) {
            hooks.step(&mut world);
            assert!(
                hooks.stats().stepped_without_hooks,
                "{name}: went unnoticed: {:?}",
                hooks.stats()
            );
            hooks.step(&mut world);
            assert!(!hooks.stats().stepped_without_hooks, "{name}: said for its step only");
            continue;
        }
        let message = panic_message(|| {
            hooks.step(&mut world);
        })
            .unwrap_or_else(|| panic!("{name}: went unnoticed"));
        assert!(
            message.contains(says) && message.contains("hooks.step(&mut world)"),
            "{name}: the message names what happened and the fix: {message}"
        );
    }
}

/// A floor and a ball above it, the same handles in every copy.
fn ball_over_floor() -> (PhysicsWorld, ColliderHandle, RigidBodyHandle, ColliderHandle) {
    let mut world = PhysicsWorld::new();
    let floor = world.insert_body(RigidBodyBuilder::fixed());
    let deck = world.insert_collider(cuboid(10.0, 0.5, 10.0), Some(floor));
    let ball = world.insert_body(RigidBodyBuilder::dynamic().translation(at(0.0, 3.0)));
    let shot = world.insert_collider(ColliderBuilder::ball(0.5), Some(ball));
    (world, deck, ball, shot)
}

/// Found by a misuse audit: a rule set put in place of the hooks' one was
/// followed only where its change log held edits. A fresh set, or a copy
/// taken after its edits were read, left the colliders with the old set's
/// settings: a ball fell through a floor no rule named any more. Every set
/// is now another to the hooks, copies included (`docs/semantics.md`,
/// "Saving and loading").
#[test]
fn a_rule_set_put_in_place_of_the_hooks_one_is_followed_whole() {
    use super::rules::{CollisionRuleSet, PlanCause};
    // How the set that lets the ball through the floor is replaced by one
    // under which it rests; `other` holds such a set, stepped.
    type Replace = fn(&mut RuleHooks, &mut RuleHooks);
    let ways: [(&str, Replace); 3] = [
        ("a new set", |hooks, _| *hooks.rules_mut() = CollisionRuleSet::default()),
        ("a copy of another's set", |hooks, other| {
            *hooks.rules_mut() = other.rules().clone();
        }),
        ("two hooks' sets swapped", |hooks, other| {
            std::mem::swap(hooks.rules_mut(), other.rules_mut());
        }),
    ];
    for (way, replace) in ways {
        let (mut world, deck, ball, shot) = ball_over_floor();
        let (mut resting, _, other_ball, _) = ball_over_floor();
        let mut hooks = RuleHooks::default();
        hooks.rules_mut().set_specific(shot, deck, CollisionRule::NoResponse);
        let mut other = RuleHooks::default();
        other.rules_mut().set_personal(other_ball, CollisionRule::Normal);
        for _ in 0..10 {
            hooks.step(&mut world);
            other.step(&mut resting);
        }
        replace(&mut hooks, &mut other);
        hooks.step(&mut world);
        other.step(&mut resting);
        assert_eq!(hooks.stats().full_plan, Some(PlanCause::GlobalEdit), "{way}: {:?}", hooks.stats());
        for _ in 0..120 {
            hooks.step(&mut world);
            other.step(&mut resting);
        }
        let y = world.bodies[ball].translation().y;
        assert!((0.9..1.1).contains(&y), "{way}: the ball rests on the floor: y = {y}");
        if way == "two hooks' sets swapped" {
            let y = resting.bodies[other_ball].translation().y;
            assert!(y < 0.0, "{way}: the other world's ball fell through its floor: y = {y}");
        }
    }
}

/// Found by a misuse audit: `manifold_update` panicked in debug builds on
/// a live pair whose rule is `Defer` (the default rule set to `Defer`),
/// which `pair_rule` reports as it is.
#[test]
fn a_live_pair_whose_rule_is_defer_has_a_manifold_setting() {
    let (mut world, deck, _, shot) = ball_over_floor();
    let mut hooks = RuleHooks::default();
    hooks.rules_mut().set_default_rule(CollisionRule::Defer);
    for _ in 0..60 {
        hooks.step(&mut world);
    }
    assert_eq!(hooks.pair_rule(&world, shot, deck), Some(CollisionRule::Defer));
    assert_eq!(hooks.manifold_update(&world, shot, deck), Some(ManifoldUpdate::ByRule));
}

/// Found by a misuse audit: a `prepare` the project called before the
/// hooks' own step (to read the stats or a pair's rule first; the paired
/// benches did it to plan each step's changes untimed) counted the step
/// again against every rule with an end: `Until::steps(6)` held 3 steps.
/// The step's brackets count once, however many `prepare` calls they hold.
#[test]
fn a_prepare_before_the_hooks_own_step_counts_with_it_once() {
    use super::rules::Until;
    for prepares in 0..3 {
        let (mut world, deck, _, shot) = ball_over_floor();
        let mut hooks = RuleHooks::default();
        hooks.rules_mut().set_specific_until(
            shot,
            deck,
            CollisionRule::NoResponse,
            Until::steps(6).even_if_overlapping(),
        );
        let mut held = 0;
        for _ in 0..12 {
            for _ in 0..prepares {
                hooks.prepare(&world.bodies, &mut world.colliders);
            }
            hooks.step(&mut world);
            held += usize::from(hooks.rules().specific(shot, deck) == CollisionRule::NoResponse);
        }
        assert_eq!(held, 6, "{prepares} prepare calls before each step: steps after which the rule held");
    }
}

/// The look reads only what Rapier's change flags show changed since the
/// hooks' last step (`docs/architecture.md`, "Rapier's change flags"), and
/// any step of Rapier's clears them. A change the project made before a
/// `world.step()` that no witness sees (no pair is hooked), or before
/// collision detection run between the hooks' steps, is read all the same:
/// at the next step in a debug build (which stops there, naming the fixes),
/// within 32 steps in a release build, after which an edit of the object's
/// rules keeps it; at the next step after `project_settings_changed`.
#[test]
fn a_change_a_step_without_the_hooks_hid_is_read_all_the_same() {
    type Between = fn(&mut PhysicsWorld, &mut RuleHooks);
    // (what came between, whether the project says so, what a debug
    // build's message names)
    let cases: [(&str, Between, bool, &str); 3] = [
        ("world.step()", |w, _| w.step(), false, "never `world.step()`"),
        (
            "collision detection",
            |w, _| w.detect_collisions(&(), &()),
            false,
            "hooks.project_settings_changed()",
        ),
        (
            "collision detection, then project_settings_changed",
            |w, hooks| {
                w.detect_collisions(&(), &());
                hooks.project_settings_changed();
            },
            true,
            "",
        ),
    ];
    for (name, between, said, names) in cases {
        let (mut world, _, ball, shot) = ball_over_floor();
        let marker = world.insert_body(RigidBodyBuilder::fixed().translation(at(50.0, 0.5)));
        world.insert_collider(cuboid(0.5, 0.5, 0.5), Some(marker));
        let mut hooks = RuleHooks::default();
        hooks.rules_mut().set_specific(ball, marker, CollisionRule::NoPair);
        for _ in 0..5 {
            hooks.step(&mut world);
        }
        let written = world.colliders[shot].collision_groups();
        // The project's own change: the ball collides with nothing.
        let own = InteractionGroups::new(Group::GROUP_1, Group::NONE, InteractionTestMode::And);
        assert_ne!(written, own, "{name}: the crate wrote the ball's groups");
        world.colliders[shot].set_collision_groups(own);
        between(&mut world, &mut hooks);
        if cfg!(debug_assertions) && !said {
            let message = panic_message(|| {
                hooks.step(&mut world);
            })
            .unwrap_or_else(|| panic!("{name}: a debug build stops at the change the flags hid"));
            assert!(
                message.contains(names)
                    && message.contains("hooks.step(&mut world)")
                    && message.contains("hooks.world_replaced()"),
                "{name}: the message names what happened and the fixes: {message}"
            );
            continue;
        }
        let read = (1..=32).find(|_| {
            hooks.step(&mut world);
            hooks.stats().planned_colliders > 0
        });
        match read {
            Some(1) => {}
            Some(_) if !said => {}
            _ => panic!("{name}: the change was read at step {read:?}"),
        }
        hooks.rules_mut().set_specific(ball, marker, CollisionRule::NoContacts);
        for _ in 0..60 {
            hooks.step(&mut world);
        }
        let filter = world.colliders[shot].collision_groups().filter;
        let y = world.bodies[ball].translation().y;
        assert!(
            filter == Group::NONE && y < -1.0,
            "{name}: the project's filter kept (read at step {read:?}): filter {filter:?}, the ball at y = {y}"
        );
    }
}

/// A `world.step()` the witness sees makes the same step's look read every
/// object the rules reach: the change the project made before it is read at
/// once, not a step later (`docs/architecture.md`, "Rapier's change
/// flags"). A ghost held inside the floor, hooked for a `NoContacts` with
/// it, keeps the witness every step.
#[test]
fn a_change_before_a_step_the_witness_saw_is_read_at_once() {
    let mut world = PhysicsWorld::new();
    let floor = world.insert_body(RigidBodyBuilder::fixed());
    world.insert_collider(cuboid(10.0, 0.5, 10.0), Some(floor));
    let ghost = world.insert_body(RigidBodyBuilder::dynamic().gravity_scale(0.0));
    // Layers of its own: the planner hooks it rather than give it a bit.
    let layers = InteractionGroups::new(Group::GROUP_3, Group::ALL, InteractionTestMode::And);
    let shape = world.insert_collider(cuboid(0.5, 0.5, 0.5).collision_groups(layers), Some(ghost));
    let mut hooks = RuleHooks::default();
    hooks.rules_mut().set_specific(ghost, floor, CollisionRule::NoContacts);
    for _ in 0..5 {
        hooks.step(&mut world);
    }
    assert!(hooks.stats().hooked_colliders > 0, "the ghost is hooked: {:?}", hooks.stats());
    // The project's own change: other solver groups for the ghost.
    let solver = InteractionGroups::new(Group::GROUP_4, Group::ALL, InteractionTestMode::And);
    world.colliders[shape].set_solver_groups(solver);
    world.step();
    if cfg!(debug_assertions) {
        let message = panic_message(|| {
            hooks.step(&mut world);
        })
        .expect("a debug build stops at the step without the hooks");
        assert!(message.contains("never `world.step()`"), "the witness says it: {message}");
        return;
    }
    hooks.step(&mut world);
    let stats = hooks.stats();
    assert!(
        stats.stepped_without_hooks && stats.planned_colliders > 0,
        "the step without the hooks seen and the change read at once: {stats:?}"
    );
}
