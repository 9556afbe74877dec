//! Step cost of `RuleHooks` against plain Rapier, side by side in one run:
//! piles of 1,000 and 4,000 unit boxes (never sleeping) on a ground slab.
//!
//! - `none`: no rules, against `PhysicsWorld::step`;
//! - `groups`: four groups with group-level `NoPair` and `NoResponse` rules,
//!   against the same rules written by hand as Rapier collision and solver
//!   groups;
//! - `specific`: specific rules on 5% of the bodies, against plain Rapier;
//! - `hooked`: the planner off (every collider hooked), against plain Rapier.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use rapier_collision_rules::{CollisionGroup, CollisionRule, CollisionRuleSet, RuleHooks};
use rapier3d::prelude::*;
use std::time::Duration;

/// A settled pile of `n` boxes in columns of ten, and its body handles.
fn pile(n: usize) -> (PhysicsWorld, Vec<RigidBodyHandle>) {
    let mut world = PhysicsWorld::new();
    let ground =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)));
    world.insert_collider(ColliderBuilder::cuboid(200.0, 0.5, 200.0), Some(ground));
    let side = ((n / 10) as f32).sqrt().ceil() as usize;
    let mut bodies = Vec::with_capacity(n);
    for i in 0..n {
        let column = i / 10;
        let (cx, cz) = ((column % side) as f32 * 1.5, (column / side) as f32 * 1.5);
        let y = 0.5 + (i % 10) as f32 * 1.02;
        let body = world.insert_body(
            RigidBodyBuilder::dynamic()
                .translation(Vector::new(cx, y, cz))
                .can_sleep(false),
        );
        world.insert_collider(ColliderBuilder::cuboid(0.5, 0.5, 0.5), Some(body));
        bodies.push(body);
    }
    for _ in 0..30 {
        world.step();
    }
    (world, bodies)
}

/// The four benchmark groups and their table: A-B NoPair, C-D NoResponse,
/// A-C NoResponse, B-D NoPair; each group with itself Normal.
fn group_rules(rules: &mut CollisionRuleSet) -> [CollisionGroup; 4] {
    let g = [
        rules.create_group(),
        rules.create_group(),
        rules.create_group(),
        rules.create_group(),
    ];
    rules.set_group_rule(g[0], g[1], CollisionRule::NoPair);
    rules.set_group_rule(g[2], g[3], CollisionRule::NoResponse);
    rules.set_group_rule(g[0], g[2], CollisionRule::NoResponse);
    rules.set_group_rule(g[1], g[3], CollisionRule::NoPair);
    g
}

/// The same four groups as Rapier collision and solver groups.
fn hand_written_groups(world: &mut PhysicsWorld, bodies: &[RigidBodyHandle]) {
    let bit = |i: usize| Group::from_bits_retain(1 << i);
    // Group i's collision filter leaves out NoPair partners, its solver
    // filter NoResponse partners (the ground is in none of them: bit 4).
    let no_pair = [bit(1), bit(0), Group::NONE, Group::NONE];
    let no_pair = [no_pair[0], no_pair[1] | bit(3), no_pair[2], bit(1)];
    let no_response = [bit(2), Group::NONE, bit(3) | bit(0), bit(2)];
    for (i, &body) in bodies.iter().enumerate() {
        let g = i % 4;
        let collider = world.bodies[body].colliders()[0];
        let c = &mut world.colliders[collider];
        c.set_collision_groups(InteractionGroups::new(
            bit(g),
            Group::ALL - no_pair[g],
            InteractionTestMode::And,
        ));
        c.set_solver_groups(InteractionGroups::new(
            bit(g),
            Group::ALL - no_response[g],
            InteractionTestMode::And,
        ));
    }
}

fn step(c: &mut Criterion) {
    let mut group = c.benchmark_group("step");
    group
        .sample_size(20)
        .measurement_time(Duration::from_secs(8))
        .warm_up_time(Duration::from_secs(2));
    for n in [1000, 4000] {
        let mut plain = pile(n).0;
        group.bench_function(BenchmarkId::new("none/plain", n), |b| {
            b.iter(|| plain.step())
        });
        let (mut world, mut hooks) = (pile(n).0, RuleHooks::default());
        group.bench_function(BenchmarkId::new("none/rules", n), |b| {
            b.iter(|| hooks.step(&mut world))
        });

        let (mut plain, bodies) = pile(n);
        hand_written_groups(&mut plain, &bodies);
        group.bench_function(BenchmarkId::new("groups/plain", n), |b| {
            b.iter(|| plain.step())
        });
        let (mut world, bodies) = pile(n);
        let mut rules = CollisionRuleSet::default();
        let g = group_rules(&mut rules);
        for (i, &body) in bodies.iter().enumerate() {
            rules.set_group(body, Some(g[i % 4]));
        }
        let mut hooks = RuleHooks::new(rules);
        group.bench_function(BenchmarkId::new("groups/rules", n), |b| {
            b.iter(|| hooks.step(&mut world))
        });

        let mut plain = pile(n).0;
        group.bench_function(BenchmarkId::new("specific/plain", n), |b| {
            b.iter(|| plain.step())
        });
        let (mut world, bodies) = pile(n);
        let mut rules = CollisionRuleSet::default();
        for (i, pair) in bodies.chunks(2).enumerate().filter(|(i, _)| i % 10 == 0) {
            let rule = if i % 20 == 0 {
                CollisionRule::NoResponse
            } else {
                CollisionRule::NoContacts
            };
            rules.set_specific(pair[0], pair[1], rule);
        }
        let mut hooks = RuleHooks::new(rules);
        group.bench_function(BenchmarkId::new("specific/rules", n), |b| {
            b.iter(|| hooks.step(&mut world))
        });
    }
    group.finish();
}

criterion_group!(benches, step);
criterion_main!(benches);
