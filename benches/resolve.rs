//! Nanoseconds per `resolve` for chains of depth 1, 2, 4 and 8 (bodies above
//! the collider), with no rules at all and with every node carrying specific
//! entries that do not match the pair (the specific stage's worst case).
//!
//! Tables: 64 created groups, both chains in the same one (inherited from
//! the root), the group table holding 2,017 entries (every two distinct
//! groups, plus the built-in one), none about the pair; in the `specific`
//! variant every node of both chains holds 16 entries about other bodies.

use criterion::{BenchmarkId, Criterion, black_box, criterion_group, criterion_main};
use rapier_collision_rules::{CollisionRule, CollisionRuleSet};
use rapier3d::prelude::*;

struct Setup {
    bodies: RigidBodySet,
    colliders: ColliderSet,
    rules: CollisionRuleSet,
    pair: (ColliderHandle, ColliderHandle),
}

/// Two colliders, each on a chain of `depth` bodies.
fn setup(depth: usize, specific: bool) -> Setup {
    let mut bodies = RigidBodySet::new();
    let mut colliders = ColliderSet::new();
    let mut rules = CollisionRuleSet::default();
    let groups: Vec<_> = (0..64).map(|_| rules.create_group()).collect();
    rules.set_group_rules_in_set(&groups, CollisionRule::Defer, CollisionRule::NoResponse);
    let strangers: Vec<_> = (0..16)
        .map(|_| bodies.insert(RigidBodyBuilder::dynamic()))
        .collect();
    let mut leaves = Vec::new();
    for _ in 0..2 {
        let chain: Vec<_> = (0..depth)
            .map(|_| bodies.insert(RigidBodyBuilder::dynamic()))
            .collect();
        for pair in chain.windows(2) {
            rules
                .set_parent(pair[0], pair[1])
                .expect("a chain has no cycle");
        }
        let leaf = colliders.insert_with_parent(ColliderBuilder::ball(0.5), chain[0], &mut bodies);
        // Both chains in one group: the pair falls through every stage.
        rules.set_group(chain[depth - 1], Some(groups[0]));
        if specific {
            for &body in &chain {
                for &stranger in &strangers {
                    rules.set_specific(body, stranger, CollisionRule::NoPair);
                }
            }
            for &stranger in &strangers {
                rules.set_specific(leaf, stranger, CollisionRule::NoPair);
            }
        }
        leaves.push(leaf);
    }
    Setup {
        bodies,
        colliders,
        rules,
        pair: (leaves[0], leaves[1]),
    }
}

fn resolve(c: &mut Criterion) {
    let mut group = c.benchmark_group("resolve");
    for variant in ["none", "specific"] {
        for depth in [1, 2, 4, 8] {
            let s = setup(depth, variant == "specific");
            let expected = s.rules.resolve(&s.bodies, &s.colliders, s.pair.0, s.pair.1);
            assert_eq!(expected, CollisionRule::Normal, "the pair falls through");
            group.bench_with_input(BenchmarkId::new(variant, depth), &s, |b, s| {
                b.iter(|| {
                    s.rules.resolve(
                        black_box(&s.bodies),
                        black_box(&s.colliders),
                        black_box(s.pair.0),
                        black_box(s.pair.1),
                    )
                })
            });
        }
    }
    group.finish();
}

criterion_group!(benches, resolve);
criterion_main!(benches);
