//! What decides a live pair besides the rule set, with soft bodies
//! (`docs/semantics.md`, "Soft bodies"): the calculator, the pair-created
//! callback, overrides, manifold settings and scene queries, each against
//! the same scene without the other object.

use std::sync::Arc;
use std::sync::atomic::{AtomicUsize, Ordering};

use super::rapier::prelude::*;
use super::rules::{CollisionRule, ManifoldUpdate, RuleHooks};
use super::{at, cube, slab, soft_block};

use CollisionRule::*;

const STEPS: usize = 90;

/// A soft block over a fixed ground (top at y = 0), or over nothing.
struct Scene {
    world: PhysicsWorld,
    ground: ColliderHandle,
    block: SoftBodyHandle,
}

impl Scene {
    fn new(ground: bool, block_y: f32) -> Scene {
        let mut world = PhysicsWorld::new();
        let floor = world.insert_body(RigidBodyBuilder::fixed().translation(at(0.0, -0.5)));
        let shape = slab(5.0, 0.5);
        let ground = if ground {
            world.insert_collider(shape, Some(floor))
        } else {
            ColliderHandle::invalid()
        };
        let block = world.insert_soft_body(soft_block(at(0.0, block_y), 0.5));
        Scene { world, ground, block }
    }

    /// The block's particles, bit for bit.
    fn particles(&self) -> Vec<u32> {
        self.world.soft_bodies[self.block]
            .particle_positions()
            .flat_map(|p| p.to_array())
            .map(f32::to_bits)
            .collect()
    }

    fn lowest(&self) -> f32 {
        self.world.soft_bodies[self.block]
            .particle_positions()
            .map(|p| p.y)
            .fold(f32::MAX, f32::min)
    }

    fn run(&mut self, hooks: &mut RuleHooks, steps: usize) {
        for _ in 0..steps {
            hooks.step(&mut self.world);
        }
    }

    /// The live pairs between the ground and the block's colliders.
    fn ground_pairs(&self, hooks: &RuleHooks) -> Vec<(ColliderHandle, ColliderHandle)> {
        let mut pairs: Vec<_> = hooks
            .pairs(&self.world)
            .map(|(a, b, _)| (a, b))
            .filter(|&(a, b)| a == self.ground || b == self.ground)
            .collect();
        pairs.sort_unstable_by_key(|&(a, b)| (a.into_raw_parts(), b.into_raw_parts()));
        pairs
    }
}

/// Whether a collider belongs to a soft body.
fn soft(colliders: &ColliderSet, c: ColliderHandle) -> bool {
    colliders.get(c).is_some_and(|c| c.deformable_mesh_ref().is_some())
}

/// The block's fall with no ground, and the same fall over the ground when
/// `hooks` decide.
fn fall_against_no_ground(hooks: RuleHooks) -> (Vec<u32>, Vec<u32>, f32) {
    let mut alone = Scene::new(false, 0.8);
    alone.run(&mut RuleHooks::default(), STEPS);
    let mut scene = Scene::new(true, 0.8);
    let mut hooks = hooks;
    scene.run(&mut hooks, STEPS);
    (alone.particles(), scene.particles(), scene.lowest())
}

#[test]
fn a_calculator_decides_soft_rigid_pairs_as_the_rule_set_does() {
    for rule in [Normal, NoResponse, NoContacts, NoPair] {
        let mut hooks = RuleHooks::default();
        hooks.set_calculator(move |pair| {
            if soft(pair.colliders, pair.collider1) != soft(pair.colliders, pair.collider2) {
                rule
            } else {
                pair.default_rule()
            }
        });
        let (alone, over, lowest) = fall_against_no_ground(hooks);
        if rule == Normal {
            assert!(lowest > -0.1, "{rule:?}: the block should rest: lowest at {lowest}");
        } else {
            assert_eq!(over, alone, "{rule:?}: the block should fall as with no ground (lowest at {lowest})");
        }
    }
}

#[test]
fn the_pair_created_callback_sees_soft_pairs_and_its_answer_holds() {
    for rule in [Normal, NoResponse, NoContacts, NoPair] {
        let seen = Arc::new(AtomicUsize::new(0));
        let mut hooks = RuleHooks::default();
        let count = Arc::clone(&seen);
        hooks.on_pair_created(move |pair| {
            let soft_pair = soft(pair.colliders, pair.collider1) != soft(pair.colliders, pair.collider2);
            if soft_pair {
                count.fetch_add(1, Ordering::Relaxed);
                assert_eq!(pair.rule, Normal, "no rule set: the calculation says Normal");
            }
            soft_pair.then_some(rule)
        });
        let (alone, over, lowest) = fall_against_no_ground(hooks);
        let seen = seen.load(Ordering::Relaxed);
        assert!(seen > 0, "{rule:?}: the callback never saw a soft pair");
        if rule == Normal {
            assert!(lowest > -0.1, "{rule:?}: the block should rest: lowest at {lowest}");
        } else {
            assert_eq!(over, alone, "{rule:?}: the block should fall as with no ground (lowest at {lowest}, {seen} pairs seen)");
        }
    }
}

/// A block resting on the ground, then from step `REST` on either with an
/// override on its ground pairs or with the ground removed.
const REST: usize = 60;

/// The block after `REST` steps on the ground: the scene, its hooks and
/// its live pairs with the ground.
fn resting() -> (Scene, RuleHooks, Vec<(ColliderHandle, ColliderHandle)>) {
    let mut scene = Scene::new(true, 0.6);
    let mut hooks = RuleHooks::default();
    scene.run(&mut hooks, REST);
    let pairs = scene.ground_pairs(&hooks);
    assert!(!pairs.is_empty(), "the resting block has live pairs with the ground");
    (scene, hooks, pairs)
}

/// The twin: the block rests for `REST` steps, then the ground is removed
/// and it falls for `STEPS`.
fn ground_removed() -> Scene {
    let mut gone = Scene::new(true, 0.6);
    let mut plain = RuleHooks::default();
    gone.run(&mut plain, REST);
    let rested = gone.lowest();
    assert!(rested > -0.1, "the block rests before the ground goes: lowest at {rested}");
    let ground = gone.ground;
    gone.world.remove_collider(ground);
    gone.run(&mut plain, STEPS);
    gone
}

#[test]
fn an_override_of_a_resting_soft_pair_acts_as_if_the_ground_were_gone() {
    // The twin: the ground is removed when the override would be set.
    let gone = ground_removed();
    for rule in [Normal, NoResponse, NoContacts, NoPair] {
        let (mut scene, mut hooks, pairs) = resting();
        for &(a, b) in &pairs {
            assert!(hooks.set_pair_rule(&scene.world, a, b, rule), "{rule:?}: refused on a live pair");
        }
        for &(a, b) in &pairs {
            // A `NoPair` pair is not live.
            let expected = (rule != NoPair).then_some(rule);
            assert_eq!(hooks.pair_rule(&scene.world, b, a), expected, "{rule:?}: the override, read the other way");
        }
        scene.run(&mut hooks, STEPS);
        let lowest = scene.lowest();
        if rule == Normal {
            assert!(lowest > -0.1, "{rule:?}: the block should still rest: lowest at {lowest}");
        } else {
            assert_eq!(
                scene.particles(),
                gone.particles(),
                "{rule:?}: the block should fall as when the ground is removed (lowest at {lowest}, twin's at {})",
                gone.lowest()
            );
        }
        // Taking the override back gives the pairs the rule set's answer
        // again (no rule here: Normal).
        if rule != NoPair {
            for &(a, b) in &scene.ground_pairs(&hooks) {
                hooks.set_pair_rule(&scene.world, a, b, Defer);
                assert_eq!(hooks.pair_rule(&scene.world, a, b), Some(Normal), "{rule:?}: the override taken back");
            }
        }
    }
}

#[test]
fn soft_pairs_take_every_manifold_setting_but_never() {
    let (mut scene, mut hooks, pairs) = resting();
    for &(a, b) in &pairs {
        // A soft surface is made of parts: frozen contacts could not be kept
        // (Rapier's soft-body solver builds its contacts from the particles).
        assert!(!hooks.set_manifold_update(&scene.world, a, b, ManifoldUpdate::Never), "Never was taken on a soft pair");
        assert_eq!(hooks.manifold_update(&scene.world, a, b), Some(ManifoldUpdate::ByRule), "a refused setting changed the pair");
        assert!(hooks.set_manifold_update(&scene.world, b, a, ManifoldUpdate::Always), "Always was refused on a live soft pair");
        assert_eq!(hooks.manifold_update(&scene.world, a, b), Some(ManifoldUpdate::Always));
    }
    // `Always` on a pair whose rule computes no contacts: a soft-rigid pair
    // cannot have contacts without response, so it keeps none and the block
    // falls as with no ground (`docs/semantics.md`, "Soft bodies").
    for &(a, b) in &pairs {
        hooks.set_pair_rule(&scene.world, a, b, NoContacts);
    }
    let gone = ground_removed();
    scene.run(&mut hooks, STEPS);
    assert_eq!(
        scene.particles(),
        gone.particles(),
        "NoContacts with Always: the block should fall as when the ground is removed (lowest at {}, twin's at {})",
        scene.lowest(),
        gone.lowest()
    );
}

#[test]
fn a_ray_passes_a_soft_body_the_rules_let_through() {
    for (rule, passes) in [(None, false), (Some(Normal), false), (Some(NoResponse), true), (Some(NoContacts), true), (Some(NoPair), true)] {
        let mut world = PhysicsWorld::new();
        let shooter = world.insert_body(RigidBodyBuilder::kinematic_position_based().translation(at(-3.0, 0.0)));
        let eye = world.insert_collider(cube(0.1), Some(shooter));
        let wall = world.insert_body(RigidBodyBuilder::fixed().translation(at(3.0, 0.0)));
        let wall = world.insert_collider(cube(0.5), Some(wall));
        let block = world.insert_soft_body(soft_block(at(0.0, 0.0), 0.5).gravity_scale(0.0));
        let root = world.soft_bodies[block].root_body();
        let mut hooks = RuleHooks::default();
        if let Some(rule) = rule {
            hooks.rules_mut().set_specific(shooter, root, rule);
        }
        hooks.step(&mut world);
        let passes_by = hooks.rules().query_predicate(&world.bodies, &world.colliders, eye);
        let ray = Ray::new(at(-3.0, 0.0), at(1.0, 0.0));
        let hit = world
            .query_pipeline_with_filter(QueryFilter::default().predicate(&passes_by))
            .cast_ray(&ray, 100.0, true)
            .map(|(collider, _)| collider);
        let soft_hit = hit.is_some_and(|c| soft(&world.colliders, c));
        let expected = if passes { Some(wall) } else { hit.filter(|_| soft_hit) };
        assert_eq!(hit, expected, "{rule:?}: the ray hit {hit:?} (a soft surface: {soft_hit})");
        assert!(passes || soft_hit, "{rule:?}: the ray should stop at the block, hit {hit:?}");
    }
}
