//! What a per-pair rule costs: the step time of `RuleHooks` against plain
//! Rapier as the share of hooked colliders grows from 0% to 100%, on the
//! piles of `benches/step.rs` (1,000 and 4,000 boxes), awake (never
//! sleeping) and resting (allowed to fall asleep, and asleep).
//!
//! A hooked box carries a specific `NoContacts` rule about a fixed post far
//! from the pile, which it never meets: `NoContacts` has no group form, so
//! the box's side is hooked (the post is the hub), and the physics stays
//! Rapier's. What the ratio measures is what hooking costs: the hooked
//! pairs lose Rapier's contact recycling and are answered by the hook, and
//! the named bodies are looked at before each step.
//!
//! `HOOKED_SHARE_OUT=docs cargo bench --bench hooked_share` prints the
//! paired ratios and writes `hooked_share.csv` and `hooked_share.svg` there.

use std::fmt::Write as _;
use std::time::Duration;

use plotters::prelude::*;
use rapier_collision_rules::dim3 as rules;
use rapier3d as rapier;
use rapier3d::prelude::*;
use rules::{CollisionRule, CollisionRuleSet, RuleHooks};

// What the step benchmarks share; this one uses part of it.
#[path = "common/chart.rs"]
mod chart;
#[allow(dead_code)]
mod common;
#[path = "common/space3.rs"]
mod space;

use common::{Twins, pile};

/// The shares of hooked boxes measured, in percent.
const SHARES: [usize; 6] = [0, 5, 10, 25, 50, 100];

/// A pile of `n` boxes, awake or settled asleep, with a fixed post far
/// away, and the rules that hook `share` percent of the boxes.
fn scene(n: usize, resting: bool, share: usize) -> (PhysicsWorld, CollisionRuleSet) {
    let (mut world, boxes) = pile(n, resting);
    let post =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, 0.5, -50.0)));
    world.insert_collider(ColliderBuilder::cuboid(0.5, 0.5, 0.5), Some(post));
    if resting {
        for _ in 0..1_500 {
            world.step();
            if world.islands.num_active_bodies() == 0 {
                break;
            }
        }
    }
    let mut rules = CollisionRuleSet::default();
    for (i, &(body, _)) in boxes.iter().enumerate() {
        // Exactly `share` boxes in every hundred, spread over the columns'
        // heights (37 is prime to 100 and to the columns' ten).
        if (i * 37) % 100 < share {
            rules.set_specific(body, post, CollisionRule::NoContacts);
        }
    }
    (world, rules)
}

/// One line of the chart: its label, and each share with the ratio's median,
/// min and max.
type Line = (String, Vec<(f64, [f64; 3])>);

/// One point: the median, min and max of three paired runs of 50 step
/// pairs, the time per step of each world in the median run, and the
/// hooked colliders.
struct Point {
    ratios: [f64; 3],
    plain_us: f64,
    rules_us: f64,
    hooked: usize,
}

fn measure(n: usize, resting: bool, share: usize) -> Point {
    let (plain, _) = scene(n, resting, share);
    let (world, rules) = scene(n, resting, share);
    let mut twins = Twins {
        plain,
        world,
        hooks: RuleHooks::new(rules),
        control: false,
        churn: None,
    };
    twins.plan_alike();
    twins.time(2, true);
    twins.time(2, false);
    // The hooks wake the bodies whose colliders they configured: a resting
    // pile is measured once it sleeps again, as it would in a game.
    if resting {
        for _ in 0..1_500 {
            if twins.world.islands.num_active_bodies() == 0 {
                break;
            }
            twins.time(1, true);
        }
    }
    let mut runs: Vec<(f64, f64, f64)> = (0..3)
        .map(|_| {
            let (mut plain, mut rules) = (Duration::ZERO, Duration::ZERO);
            for i in 0..50 {
                let pair = twins.time_pair(i % 2 == 1);
                plain += pair.plain;
                rules += pair.rules;
            }
            let (p, r) = (plain.as_secs_f64() / 50.0, rules.as_secs_f64() / 50.0);
            (r / p, p, r)
        })
        .collect();
    runs.sort_by(|a, b| a.0.total_cmp(&b.0));
    Point {
        ratios: [runs[1].0, runs[0].0, runs[2].0],
        plain_us: runs[1].1 * 1e6,
        rules_us: runs[1].2 * 1e6,
        hooked: twins.hooks.stats().hooked_colliders,
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    println!("hooked share (rules / plain: median [min, max] of 3 runs of 50 step pairs):");
    let mut csv = String::from(
        "pile,state,share_pct,hooked,plain_us,rules_us,ratio_median,ratio_min,ratio_max\n",
    );
    let mut lines: Vec<Line> = Vec::new();
    for n in [1_000, 4_000] {
        for resting in [false, true] {
            let state = if resting { "resting" } else { "awake" };
            let mut points = Vec::new();
            for share in SHARES {
                let p = measure(n, resting, share);
                println!(
                    "  {n:>5} {state:<7} {share:>3}%: {:.3} [{:.3}, {:.3}]  plain {:>9.1} us  rules {:>9.1} us  (hooked {})",
                    p.ratios[0], p.ratios[1], p.ratios[2], p.plain_us, p.rules_us, p.hooked
                );
                writeln!(
                    csv,
                    "{n},{state},{share},{},{:.2},{:.2},{:.4},{:.4},{:.4}",
                    p.hooked, p.plain_us, p.rules_us, p.ratios[0], p.ratios[1], p.ratios[2]
                )?;
                points.push((share as f64, p.ratios));
            }
            lines.push((format!("{n} boxes, {state}"), points));
        }
    }
    if let Ok(out) = std::env::var("HOOKED_SHARE_OUT") {
        let dir = std::path::Path::new(&out);
        std::fs::write(dir.join("hooked_share.csv"), &csv)?;
        chart(&dir.join("hooked_share.svg"), &lines)?;
        println!("wrote hooked_share.csv and hooked_share.svg in {out}");
    }
    Ok(())
}

/// The ratio against the share, one line per pile and state, with the runs'
/// min-max as bars.
fn chart(path: &std::path::Path, lines: &[Line]) -> Result<(), Box<dyn std::error::Error>> {
    let top = lines
        .iter()
        .flat_map(|(_, points)| points.iter().map(|p| p.1[2]))
        .fold(1.0f64, f64::max)
        * 1.1;
    let root = chart::canvas(path, (760, 460))?;
    let mut chart = chart::builder(
        &root,
        "Step time with RuleHooks / plain Rapier, by share of hooked colliders",
    )
    .build_cartesian_2d(0f64..100f64, (0.9f64..top).log_scale())?;
    chart
        .configure_mesh()
        .x_desc("hooked colliders (% of the pile's boxes)")
        .y_desc("step time ratio, log scale (median of 3 runs, min-max bars)")
        .draw()?;
    let colors = [BLUE, RED, GREEN, MAGENTA];
    for ((label, points), color) in lines.iter().zip(colors) {
        let median: Vec<(f64, f64)> = points.iter().map(|&(x, r)| (x, r[0])).collect();
        chart::line(&mut chart, &median, label, color)?;
        chart.draw_series(
            points
                .iter()
                .map(|&(x, r)| PathElement::new(vec![(x, r[1]), (x, r[2])], color)),
        )?;
    }
    chart::finish(chart, &root)
}
