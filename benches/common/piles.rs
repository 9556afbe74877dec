//! The step bench's piles and variants, written once for both dimensions
//! (`benches/step.rs`, `benches/step2d.rs`).

use std::time::Duration;

use crate::common::{Twins, pile, specific_rules};
use crate::rapier::prelude::*;
use crate::rules::{CollisionGroup, CollisionRule, CollisionRuleSet, RuleHooks};
use criterion::{BenchmarkId, Criterion, criterion_group};

/// The four groups' table: A-B `NoPair`, C-D `NoResponse`, A-C `NoResponse`,
/// B-D `NoPair`; each group with itself `Normal` (no entry).
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

/// The same table as Rapier collision and solver groups. Group `i` is bit
/// `i + 1` (bit 0 is the ground's default membership).
fn hand_written_groups(world: &mut PhysicsWorld, boxes: &[(RigidBodyHandle, usize)]) {
    let bit = |g: usize| Group::from_bits_retain(1 << (g + 1));
    // Each group's collision filter leaves out its NoPair partners, its
    // solver filter its NoResponse partners.
    let no_pair = [bit(1), bit(0) | bit(3), Group::NONE, bit(1)];
    let no_response = [bit(2), Group::NONE, bit(3) | bit(0), bit(2)];
    for &(body, column) in boxes {
        let g = column % 4;
        let collider = world.bodies[body].colliders()[0];
        let groups = |excluded: Group| {
            InteractionGroups::new(bit(g), Group::ALL - excluded, InteractionTestMode::And)
        };
        let c = &mut world.colliders[collider];
        c.set_collision_groups(groups(no_pair[g]));
        c.set_solver_groups(groups(no_response[g]));
    }
}

/// The rule sets of the variants.
pub fn variant_rules(variant: &str, boxes: &[(RigidBodyHandle, usize)]) -> CollisionRuleSet {
    let mut rules = CollisionRuleSet::default();
    match variant {
        "groups" => {
            let g = group_rules(&mut rules);
            for &(body, column) in boxes {
                rules.set_group(body, Some(g[column % 4]));
            }
        }
        "specific" => rules = specific_rules(boxes),
        _ => {}
    }
    rules
}

/// The project's layers: box `i` of column `c` is on layer `c % 3` (bits
/// 0 to 2), and every box accepts every layer but bit 7, which no box is on.
fn project_layers(world: &mut PhysicsWorld, boxes: &[(RigidBodyHandle, usize)]) {
    for &(body, column) in boxes {
        let collider = world.bodies[body].colliders()[0];
        let layer = Group::from_bits_retain(1 << (column % 3));
        let groups =
            InteractionGroups::new(layer, Group::ALL - Group::GROUP_8, InteractionTestMode::And);
        world.colliders[collider].set_collision_groups(groups);
    }
}

/// A variant's two worlds: the plain one with hand-written groups where the
/// variant needs them, and the project's layers in both where it has them.
fn twins(variant: &str, n: usize) -> Twins {
    let (layers, rules) = match variant.strip_prefix("layers") {
        Some(rest) => (true, rest.strip_prefix('+').unwrap_or("none")),
        None => (false, variant),
    };
    let (mut plain, boxes) = pile(n, false);
    if rules == "groups" {
        hand_written_groups(&mut plain, &boxes);
    }
    let (mut world, boxes) = pile(n, false);
    if layers {
        // The hand-written groups keep their own bits for collisions; the
        // layers are the plain twin's memberships only where it has none.
        if rules != "groups" {
            project_layers(&mut plain, &boxes);
        }
        project_layers(&mut world, &boxes);
    }
    let mut hooks = RuleHooks::new(variant_rules(rules, &boxes));
    hooks.set_planner(variant != "hooked");
    let mut twins = Twins {
        plain,
        world,
        hooks,
        control: variant == "control",
        churn: None,
    };
    twins.plan_alike();
    twins
}

/// Every variant, in the order they are reported.
const VARIANTS: &[&str] = &[
    "control",
    "none",
    "groups",
    "specific",
    "hooked",
    "layers",
    "layers+groups",
    "layers+specific",
];

fn step(c: &mut Criterion) {
    let mut group = c.benchmark_group("step");
    group
        .sample_size(20)
        .measurement_time(Duration::from_secs(6))
        .warm_up_time(Duration::from_secs(1));
    for n in [1000, 4000] {
        for variant in VARIANTS.iter().filter(|v| **v != "control") {
            let mut twins = twins(variant, n);
            for (name, rules) in [("plain", false), ("rules", true)] {
                let id = BenchmarkId::new(format!("{variant}/{name}"), n);
                group.bench_function(id, |b| b.iter_custom(|iters| twins.time(iters, rules)));
            }
        }
    }
    group.finish();
}

/// The cost of an edit: the next `prepare` with nothing edited, and with one
/// body moved between two groups the pile already uses (only its collider
/// is planned again), or into a group no collider uses yet (everything is).
fn edit(c: &mut Criterion) {
    let mut group = c.benchmark_group("edit");
    for n in [1000, 4000] {
        let (mut world, boxes) = pile(n, false);
        let rules = variant_rules("groups", &boxes);
        let used = [rules.group(boxes[0].0), rules.group(boxes[10].0)].map(|g| g.expect("a group"));
        let mut hooks = RuleHooks::new(rules);
        hooks.step(&mut world);
        let body = boxes[n / 2].0;
        group.bench_function(BenchmarkId::new("prepare", n), |b| {
            b.iter(|| hooks.prepare(&world.bodies, &mut world.colliders))
        });
        let mut flip = false;
        group.bench_function(BenchmarkId::new("set_group+prepare", n), |b| {
            b.iter(|| {
                flip = !flip;
                hooks
                    .rules_mut()
                    .set_group(body, Some(used[usize::from(flip)]));
                hooks.prepare(&world.bodies, &mut world.colliders);
            })
        });
        let spare = hooks.rules_mut().create_group();
        group.bench_function(BenchmarkId::new("new_group+prepare", n), |b| {
            b.iter(|| {
                flip = !flip;
                let g = if flip { spare } else { used[0] };
                hooks.rules_mut().set_group(body, Some(g));
                hooks.prepare(&world.bodies, &mut world.colliders);
            })
        });
    }
    group.finish();
}

/// Paired ratios: each variant's two worlds stepped alternately, 3 runs of
/// 100 step pairs, each step timed back to back with its twin at the same
/// point of the evolution; prints the median of the runs' ratios and their
/// range. Less exposed to the machine drifting between two criterion
/// benchmarks.
fn paired() {
    println!("paired ratios (rules / plain, median [min-max] of 3 runs of 100 step pairs):");
    for n in [1000, 4000] {
        for &variant in VARIANTS {
            // STEP_VARIANTS=none,groups limits the paired runs to those variants.
            if std::env::var("STEP_VARIANTS").is_ok_and(|v| !v.split(',').any(|x| x == variant)) {
                continue;
            }
            let mut twins = twins(variant, n);
            let mut ratios: Vec<f64> = (0..3)
                .map(|_| {
                    let (mut plain, mut rules) = (Duration::ZERO, Duration::ZERO);
                    for i in 0..100 {
                        let pair = twins.time_pair(i % 2 == 1);
                        plain += pair.plain;
                        rules += pair.rules;
                    }
                    rules.as_secs_f64() / plain.as_secs_f64()
                })
                .collect();
            ratios.sort_by(f64::total_cmp);
            let differ = if twins.identical() {
                ""
            } else {
                "  (the twins differ)"
            };
            println!(
                "  {variant:>15} {n:>5}: {:.3} [{:.3}-{:.3}]{differ}",
                ratios[1], ratios[0], ratios[2]
            );
        }
    }
}

criterion_group!(benches, step, edit);

/// The step bench: criterion, then the paired ratios.
pub fn main() {
    // STEP_PAIRED_ONLY=1 skips the criterion runs.
    // STEP_CRITERION_ONLY=1 skips the paired ratios.
    if std::env::var_os("STEP_PAIRED_ONLY").is_none() {
        benches();
    }
    if std::env::var_os("STEP_CRITERION_ONLY").is_none() {
        paired();
    }
    Criterion::default().configure_from_args().final_summary();
}
