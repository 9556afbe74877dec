//! Speed against accuracy, charted in the style of Erez, Tassa and Todorov
//! (ICRA 2015), and rule freshness against cost for the three
//! recalculation policies. Writes `docs/tradeoff.svg`, `docs/tradeoff.csv`,
//! `docs/freshness.svg` and `docs/freshness.csv`.
//!
//! Chart 1: a 10-box stack that five `NoResponse` ghosts pass through while
//! `NoPair` debris rains on it, simulated for 2 s at time steps from 1/30 s
//! to 1/960 s. X: real-time factor (simulated seconds per wall-clock second);
//! Y: the stack's mean position error against the same engine at 1/1920 s.
//! One curve each for plain Rapier (the same rules as hand-written collision
//! and solver groups), `RuleHooks` with the planner on, and with it off.
//!
//! Chart 2: 300 boxes, random rule edits before every step; the share of
//! live pairs whose rule equals a fresh `resolve` right after each step,
//! against milliseconds per step, for `Manual`, `OnChange` and `EveryStep`.
//!
//! `cargo run --release --example tradeoff`

use std::fmt::Write as _;
use std::time::Instant;

use rapier_collision_rules::{
    CollisionGroup, CollisionRule, CollisionRuleSet, RecalculationPolicy, RuleHooks,
};
use rapier3d::prelude::*;

#[derive(Clone, Copy, PartialEq)]
enum Engine {
    Plain,
    PlannerOn,
    PlannerOff,
}

const ENGINES: [(Engine, &str, &str); 3] = [
    (Engine::Plain, "plain Rapier", "#4c78a8"),
    (Engine::PlannerOn, "RuleHooks, planner on", "#f58518"),
    (Engine::PlannerOff, "RuleHooks, planner off", "#54a24b"),
];

/// The stack scene; returns the stack's bodies.
fn stack_scene(engine: Engine, dt: f32) -> (PhysicsWorld, Option<RuleHooks>, Vec<RigidBodyHandle>) {
    let mut world = PhysicsWorld::new();
    world.integration_parameters.dt = dt;
    let ground =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)));
    world.insert_collider(ColliderBuilder::cuboid(20.0, 0.5, 20.0), Some(ground));
    let stack: Vec<_> = (0..10)
        .map(|i| {
            let body = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(
                0.0,
                0.5 + i as f32 * 1.01,
                0.0,
            )));
            world.insert_collider(ColliderBuilder::cuboid(0.5, 0.5, 0.5), Some(body));
            body
        })
        .collect();
    let mut rules = CollisionRuleSet::default();
    let (ghosts, debris) = (rules.create_group(), rules.create_group());
    for g in [
        CollisionGroup::DEFAULT_DYNAMIC,
        CollisionGroup::DEFAULT_KINEMATIC,
    ] {
        rules.set_group_rule(ghosts, g, CollisionRule::NoResponse);
    }
    rules.set_group_rule(
        debris,
        CollisionGroup::DEFAULT_DYNAMIC,
        CollisionRule::NoPair,
    );
    rules.set_group_rule(debris, debris, CollisionRule::NoPair);
    for i in 0..5 {
        let ghost = world.insert_body(
            RigidBodyBuilder::dynamic()
                .translation(Vector::new(0.1, 14.0 + 2.0 * i as f32, 0.0))
                .gravity_scale(0.0)
                .linvel(Vector::new(0.0, -6.0, 0.0)),
        );
        let c = world.insert_collider(ColliderBuilder::ball(0.6), Some(ghost));
        rules.set_group(ghost, Some(ghosts));
        if engine == Engine::Plain {
            world.colliders[c].set_solver_groups(InteractionGroups::new(
                Group::GROUP_2,
                Group::NONE,
                InteractionTestMode::And,
            ));
        }
        let rock = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(
            -0.2 + 0.1 * i as f32,
            12.0 + i as f32,
            0.2,
        )));
        let c = world.insert_collider(ColliderBuilder::cuboid(0.15, 0.15, 0.15), Some(rock));
        rules.set_group(rock, Some(debris));
        if engine == Engine::Plain {
            // Debris meets only the ground (the ground keeps every bit).
            world.colliders[c].set_collision_groups(InteractionGroups::new(
                Group::GROUP_3,
                Group::GROUP_1,
                InteractionTestMode::And,
            ));
        }
    }
    if engine == Engine::Plain {
        for &b in &stack {
            let c = world.bodies[b].colliders()[0];
            world.colliders[c].set_collision_groups(InteractionGroups::new(
                Group::GROUP_1,
                Group::ALL - Group::GROUP_3,
                InteractionTestMode::And,
            ));
        }
    }
    let hooks = (engine != Engine::Plain).then(|| {
        let mut hooks = RuleHooks::new(rules);
        hooks.set_planner(engine == Engine::PlannerOn);
        hooks
    });
    (world, hooks, stack)
}

/// Runs `seconds` at `dt`; returns the stack's final positions and the
/// real-time factor.
fn run(engine: Engine, dt: f32, seconds: f32) -> (Vec<Vector>, f64) {
    let (mut world, mut hooks, stack) = stack_scene(engine, dt);
    let steps = (seconds / dt).round() as usize;
    let start = Instant::now();
    for _ in 0..steps {
        match hooks.as_mut() {
            Some(hooks) => hooks.step(&mut world),
            None => world.step(),
        }
    }
    let wall = start.elapsed().as_secs_f64();
    let positions = stack
        .iter()
        .map(|&b| world.bodies[b].translation())
        .collect();
    (positions, steps as f64 * dt as f64 / wall)
}

fn freshness(policy: RecalculationPolicy, steps: usize) -> (f64, f64) {
    let mut world = PhysicsWorld::new();
    let ground =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)));
    world.insert_collider(ColliderBuilder::cuboid(40.0, 0.5, 40.0), Some(ground));
    let bodies: Vec<_> = (0..300)
        .map(|i| {
            let (x, z) = ((i % 10) as f32 * 1.02, ((i / 10) % 10) as f32 * 1.02);
            let body = world.insert_body(
                RigidBodyBuilder::dynamic()
                    .translation(Vector::new(x, 0.5 + (i / 100) as f32 * 1.02, z))
                    .can_sleep(false),
            );
            world.insert_collider(ColliderBuilder::cuboid(0.5, 0.5, 0.5), Some(body));
            body
        })
        .collect();
    let mut hooks = RuleHooks::default();
    hooks.set_policy(policy);
    let rules = [
        CollisionRule::Defer,
        CollisionRule::Normal,
        CollisionRule::NoResponse,
        CollisionRule::NoContacts,
    ];
    let mut seed: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut next = move |n: usize| {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed % n as u64) as usize
    };
    for _ in 0..10 {
        hooks.step(&mut world);
    }
    let (mut fresh, mut total, mut time) = (0usize, 0usize, 0.0f64);
    for _ in 0..steps {
        for _ in 0..5 {
            let body = bodies[next(bodies.len())];
            hooks
                .rules_mut()
                .set_personal(body, rules[next(rules.len())]);
        }
        let start = Instant::now();
        hooks.step(&mut world);
        time += start.elapsed().as_secs_f64();
        for (a, b, rule) in hooks.pairs() {
            total += 1;
            fresh +=
                usize::from(rule == hooks.rules().resolve(&world.bodies, &world.colliders, a, b));
        }
    }
    (fresh as f64 / total as f64, time / steps as f64 * 1000.0)
}

/// One curve: its name, its colour and its points.
type Series<'a> = (&'a str, &'a str, Vec<(f64, f64)>);

/// A log-log (or lin-y) line chart as SVG.
fn chart(title: &str, x_label: &str, y_label: &str, log_y: bool, series: &[Series<'_>]) -> String {
    let (w, h, m) = (640.0, 420.0, 60.0);
    let all: Vec<(f64, f64)> = series.iter().flat_map(|s| s.2.iter().copied()).collect();
    let tx = |v: f64| v.log10();
    let ty = |v: f64| if log_y { v.max(1e-9).log10() } else { v };
    let (mut x0, mut x1) = all.iter().fold((f64::MAX, f64::MIN), |(a, b), p| {
        (a.min(tx(p.0)), b.max(tx(p.0)))
    });
    let (mut y0, mut y1) = all.iter().fold((f64::MAX, f64::MIN), |(a, b), p| {
        (a.min(ty(p.1)), b.max(ty(p.1)))
    });
    if log_y {
        (y0, y1) = (y0.floor(), y1.ceil());
    } else {
        (y0, y1) = (y0 - 0.05, y1.max(y0 + 0.1) + 0.05);
    }
    (x0, x1) = (x0.floor(), x1.ceil());
    let px = |v: f64| m + (tx(v) - x0) / (x1 - x0) * (w - 2.0 * m);
    let py = |v: f64| h - m - (ty(v) - y0) / (y1 - y0) * (h - 2.0 * m);
    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(
        svg,
        r##"<rect width="100%" height="100%" fill="#fff"/><text x="{}" y="24" text-anchor="middle" font-size="14">{title}</text>"##,
        w / 2.0
    );
    let _ = writeln!(
        svg,
        r##"<rect x="{m}" y="{m}" width="{}" height="{}" fill="none" stroke="#333"/>"##,
        w - 2.0 * m,
        h - 2.0 * m
    );
    for d in (x0 as i32)..=(x1 as i32) {
        let x = m + (d as f64 - x0) / (x1 - x0) * (w - 2.0 * m);
        let _ = writeln!(
            svg,
            r##"<line x1="{x}" y1="{m}" x2="{x}" y2="{}" stroke="#eee"/><text x="{x}" y="{}" text-anchor="middle">1e{d}</text>"##,
            h - m,
            h - m + 16.0
        );
    }
    let ticks: Vec<f64> = if log_y {
        ((y0 as i32)..=(y1 as i32)).map(f64::from).collect()
    } else {
        (0..=4).map(|i| y0 + (y1 - y0) * i as f64 / 4.0).collect()
    };
    for t in ticks {
        let y = h - m - (t - y0) / (y1 - y0) * (h - 2.0 * m);
        let label = if log_y {
            format!("1e{t}")
        } else {
            format!("{t:.2}")
        };
        let _ = writeln!(
            svg,
            r##"<line x1="{m}" y1="{y}" x2="{}" y2="{y}" stroke="#eee"/><text x="{}" y="{}" text-anchor="end">{label}</text>"##,
            w - m,
            m - 6.0,
            y + 4.0
        );
    }
    let _ = writeln!(
        svg,
        r#"<text x="{}" y="{}" text-anchor="middle">{x_label}</text>"#,
        w / 2.0,
        h - 16.0
    );
    let _ = writeln!(
        svg,
        r#"<text x="16" y="{}" text-anchor="middle" transform="rotate(-90 16 {})">{y_label}</text>"#,
        h / 2.0,
        h / 2.0
    );
    for (i, (name, color, points)) in series.iter().enumerate() {
        let path: Vec<String> = points
            .iter()
            .map(|p| format!("{:.1},{:.1}", px(p.0), py(p.1)))
            .collect();
        let _ = writeln!(
            svg,
            r#"<polyline points="{}" fill="none" stroke="{color}" stroke-width="2"/>"#,
            path.join(" ")
        );
        for p in points {
            let _ = writeln!(
                svg,
                r#"<circle cx="{:.1}" cy="{:.1}" r="3.5" fill="{color}"/>"#,
                px(p.0),
                py(p.1)
            );
        }
        let ly = m + 16.0 + i as f64 * 16.0;
        let _ = writeln!(
            svg,
            r#"<rect x="{}" y="{}" width="12" height="3" fill="{color}"/><text x="{}" y="{}">{name}</text>"#,
            w - m - 190.0,
            ly - 4.0,
            w - m - 172.0,
            ly
        );
    }
    svg.push_str("</svg>\n");
    svg
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    generate(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs"),
        2.0,
        120,
    )
}

/// Measures both charts over `seconds` of simulation and `edit_steps` edited
/// steps, and writes them, with their data, into `docs`.
fn generate(
    docs: &std::path::Path,
    seconds: f32,
    edit_steps: usize,
) -> Result<(), Box<dyn std::error::Error>> {
    std::fs::create_dir_all(docs)?;
    let reference = run(Engine::Plain, 1.0 / 1920.0, seconds).0;
    let mut csv = String::from("engine,dt,real_time_factor,mean_error_m\n");
    let mut series = Vec::new();
    for (engine, name, color) in ENGINES {
        let mut points = Vec::new();
        for hz in [30.0, 60.0, 120.0, 240.0, 480.0, 960.0] {
            let (positions, rtf) = run(engine, 1.0 / hz, seconds);
            let error = positions
                .iter()
                .zip(&reference)
                .map(|(p, r)| (*p - *r).length() as f64)
                .sum::<f64>()
                / positions.len() as f64;
            let id = name.replace(", ", " ");
            let _ = writeln!(csv, "{id},1/{hz},{rtf:.1},{error:.3e}");
            println!("{name:>24} dt 1/{hz:<4} real-time factor {rtf:>8.1}  error {error:.3e} m");
            points.push((rtf, error.max(1e-7)));
        }
        series.push((name, color, points));
    }
    std::fs::write(docs.join("tradeoff.csv"), csv)?;
    std::fs::write(
        docs.join("tradeoff.svg"),
        chart(
            "Speed against accuracy: stack, NoResponse ghosts, NoPair debris",
            "real-time factor (simulated s per wall-clock s)",
            "mean position error (m)",
            true,
            &series,
        ),
    )?;

    let mut csv = String::from("policy,ms_per_step,fresh_share\n");
    let mut series = Vec::new();
    let colors = ["#4c78a8", "#f58518", "#54a24b"];
    for (i, policy) in [
        RecalculationPolicy::Manual,
        RecalculationPolicy::OnChange,
        RecalculationPolicy::EveryStep,
    ]
    .into_iter()
    .enumerate()
    {
        let (share, ms) = freshness(policy, edit_steps);
        let _ = writeln!(csv, "{policy:?},{ms:.3},{share:.4}");
        println!(
            "{:>10}: {ms:.3} ms per step, {:.1}% of live pairs fresh",
            format!("{policy:?}"),
            share * 100.0
        );
        if policy != RecalculationPolicy::Manual && share < 0.999 {
            return Err(format!("{policy:?} left stale pairs: {share}").into());
        }
        series.push((
            ["Manual", "OnChange", "EveryStep"][i],
            colors[i],
            vec![(ms, share)],
        ));
    }
    std::fs::write(docs.join("freshness.csv"), csv)?;
    std::fs::write(
        docs.join("freshness.svg"),
        chart(
            "Rule freshness against cost (300 boxes, 5 edits per step)",
            "ms per step",
            "share of live pairs equal to a fresh resolve",
            false,
            &series,
        ),
    )?;
    println!(
        "wrote tradeoff.svg, tradeoff.csv, freshness.svg and freshness.csv in {}",
        docs.display()
    );
    Ok(())
}

#[test]
fn the_charts_are_drawn_and_every_policy_but_manual_stays_fresh() {
    // Written under target/: the committed charts come from release runs.
    let out = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target/tradeoff");
    generate(&out, 0.25, 20).expect("the example's own checks");
    assert!(out.join("tradeoff.svg").exists() && out.join("freshness.svg").exists());
}
