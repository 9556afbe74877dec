//! The soak test, ignored by default (see `docs/stability.md`): 100,000
//! steps of a 500-body world with rule churn and body turnover. The hooks'
//! pair table stays bounded by Rapier's pairs, the rule set stays clean, and
//! memory does not grow.
//!
//! `cargo test --release --test integration soak -- --ignored --nocapture`
//! (`SOAK_STEPS` shortens it).

use rapier_collision_rules::{CollisionRule, RuleHooks};
use rapier3d::prelude::*;

use crate::alloc::live_bytes;

/// A small deterministic generator (xorshift).
struct Dice(u64);

impl Dice {
    fn roll(&mut self, n: usize) -> usize {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 % n as u64) as usize
    }
}

fn spawn(world: &mut PhysicsWorld, dice: &mut Dice) -> RigidBodyHandle {
    let (x, z) = (dice.roll(20) as f32 - 10.0, dice.roll(20) as f32 - 10.0);
    let body = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(
        x * 0.9,
        2.0 + dice.roll(10) as f32,
        z * 0.9,
    )));
    world.insert_collider(ColliderBuilder::cuboid(0.4, 0.4, 0.4), Some(body));
    body
}

#[test]
#[ignore = "a long run: cargo test --release --test integration soak -- --ignored"]
fn soak_a_world_with_rule_churn_and_turnover() {
    let steps: usize = std::env::var("SOAK_STEPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(100_000);
    let mut world = PhysicsWorld::new();
    let ground =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)));
    world.insert_collider(ColliderBuilder::cuboid(12.0, 0.5, 12.0), Some(ground));
    // Walls keep the pile together.
    for (x, z, hx, hz) in [
        (12.0, 0.0, 0.5, 12.0),
        (-12.0, 0.0, 0.5, 12.0),
        (0.0, 12.0, 12.0, 0.5),
        (0.0, -12.0, 12.0, 0.5),
    ] {
        let wall = world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(x, 5.0, z)));
        world.insert_collider(ColliderBuilder::cuboid(hx, 5.0, hz), Some(wall));
    }
    let mut dice = Dice(0x50a6_5eed);
    let mut bodies: Vec<RigidBodyHandle> = (0..500).map(|_| spawn(&mut world, &mut dice)).collect();
    let mut hooks = RuleHooks::default();
    let groups: Vec<_> = (0..6).map(|_| hooks.rules_mut().create_group()).collect();
    let rules = CollisionRule::ALL;
    let (mut baseline, mut peak_ratio) = (None, 0.0f64);
    let (mut max_tracked, mut max_rapier) = (0, 0);
    for step in 0..steps {
        // Rule churn: a few edits every step.
        for _ in 0..3 {
            let body = bodies[dice.roll(bodies.len())];
            match dice.roll(4) {
                0 => hooks
                    .rules_mut()
                    .set_personal(body, rules[dice.roll(rules.len())]),
                1 => hooks
                    .rules_mut()
                    .set_group(body, Some(groups[dice.roll(groups.len())])),
                2 => {
                    let other = bodies[dice.roll(bodies.len())];
                    hooks
                        .rules_mut()
                        .set_specific(body, other, rules[dice.roll(rules.len())]);
                }
                _ => {
                    let (a, b) = (
                        groups[dice.roll(groups.len())],
                        groups[dice.roll(groups.len())],
                    );
                    hooks.rules_mut().set_group_rule(a, b, rules[dice.roll(3)]);
                }
            }
        }
        // Turnover: one body out, one in, every tenth step; and bodies whose
        // rules let them fall through the ground are replaced.
        if step % 10 == 0 {
            let i = dice.roll(bodies.len());
            world.remove_body(bodies.swap_remove(i));
            bodies.push(spawn(&mut world, &mut dice));
        }
        let mut i = 0;
        while i < bodies.len() {
            if world.bodies[bodies[i]].translation().y < -5.0 {
                world.remove_body(bodies.swap_remove(i));
                bodies.push(spawn(&mut world, &mut dice));
            } else {
                i += 1;
            }
        }
        hooks.step(&mut world);

        let rapier = world.narrow_phase.contact_pairs().count()
            + world.narrow_phase.intersection_pairs().count();
        let tracked = hooks.stats().tracked_pairs;
        assert!(
            tracked <= rapier,
            "step {step}: the hooks track {tracked} pairs, Rapier has {rapier}"
        );
        max_tracked = max_tracked.max(tracked);
        max_rapier = max_rapier.max(rapier);
        if step % 1000 == 999 {
            assert_eq!(
                hooks.rules().validate(&world.bodies, &world.colliders),
                Ok(()),
                "step {step}"
            );
            let bytes = live_bytes();
            let base = *baseline.get_or_insert(bytes);
            peak_ratio = peak_ratio.max(bytes as f64 / base as f64);
            // The rule set's share: the bytes a copy of it takes.
            let before = live_bytes();
            let copy = hooks.rules().clone();
            let rule_bytes = live_bytes() - before;
            drop(copy);
            println!(
                "step {:>6}: {} live bytes ({:.3}x the first reading), rule set {} bytes in {} records, \
                 {tracked} tracked / {rapier} Rapier pairs",
                step + 1,
                bytes,
                bytes as f64 / base as f64,
                rule_bytes,
                hooks.rules().record_count()
            );
        }
    }
    println!(
        "peak memory {peak_ratio:.3}x the first reading; at most {max_tracked} tracked pairs, {max_rapier} in Rapier"
    );
    assert!(peak_ratio < 1.5, "memory grew to {peak_ratio:.2}x");
}
