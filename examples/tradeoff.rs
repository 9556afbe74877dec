//! Speed against accuracy, in the style of Erez, Tassa and Todorov (ICRA
//! 2015, "Simulation tools for model-based robotics"): for three scenes and
//! five ways of stepping them, the wall-clock time per simulated second
//! against the error from a converged reference, over time steps from 1/15
//! s to 1/960 s, with the step at which each way fails marked. Writes
//! `docs/tradeoff.svg` and `docs/tradeoff.csv`; then the recalculation
//! policies' cost and staleness over the number of edits per step, to
//! `docs/freshness.csv` (a table in `docs/performance.md`).
//!
//! Scenes (each over its own horizon, see `SCENES`):
//! - **stack**: five `NoResponse` ghosts walk down through a 20-box stack;
//! - **ragdolls**: four ragdolls of six jointed, overlapping limbs fall in a
//!   pile; the limbs of one ragdoll ignore each other (`NoPair`);
//! - **debris**: 30 boxes fall through a standing player (`NoPair`) onto a
//!   thin floor and pile up.
//!
//! Ways of stepping (the same rules each time):
//! - plain Rapier with the rules written as Rapier groups, with contact
//!   recycling (Rapier's default) and without it;
//! - `RuleHooks` with the rules as group rules (the planner compiles them
//!   to Rapier groups);
//! - `RuleHooks` with the rules as specific rules between the objects
//!   (per-pair, answered by the hook);
//! - `RuleHooks` with group rules and the planner off (every collider hooked).
//!
//! The reference is plain Rapier without recycling at 1/1920 s; its own
//! convergence is shown against 1/3840 s, and that difference is the
//! tolerance the checks below use.
//!
//! `cargo run --release --example tradeoff` (about ten seconds on 2 cores)

use approx::abs_diff_eq;
use std::fmt::Write as _;
use std::time::Instant;

use plotters::prelude::*;
use rapier_collision_rules::{
    CollisionGroup, CollisionRule, CollisionRuleSet, RecalculationPolicy, RuleHooks,
};
use rapier3d::prelude::*;

/// A way of stepping a scene.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Method {
    Recycling,
    NoRecycling,
    Groups,
    PerPair,
    AllHooked,
}

const METHODS: [(Method, &str, RGBColor); 5] = [
    (
        Method::Recycling,
        "plain Rapier, recycling",
        RGBColor(76, 120, 168),
    ),
    (
        Method::NoRecycling,
        "plain Rapier, no recycling",
        RGBColor(114, 183, 178),
    ),
    (
        Method::Groups,
        "RuleHooks, group rules (planner)",
        RGBColor(245, 133, 24),
    ),
    (
        Method::PerPair,
        "RuleHooks, per-pair rules (hook)",
        RGBColor(228, 26, 28),
    ),
    (
        Method::AllHooked,
        "RuleHooks, every collider hooked",
        RGBColor(84, 162, 75),
    ),
];

const RATES: [u32; 7] = [15, 30, 60, 120, 240, 480, 960];

/// A scene built for one method and time step.
struct Built {
    world: PhysicsWorld,
    hooks: Option<RuleHooks>,
    /// The bodies whose final positions are compared.
    tracked: Vec<RigidBodyHandle>,
    /// Names what went wrong at the end of a run, if anything did.
    failed: fn(&Built, f32) -> Option<&'static str>,
    /// Bodies a check reads (ghosts, the player).
    others: Vec<RigidBodyHandle>,
}

/// A Rapier world stepping at `dt`, recycling contacts unless the method
/// says not to.
fn world(method: Method, dt: f32) -> PhysicsWorld {
    let mut world = PhysicsWorld::new();
    world.integration_parameters.dt = dt;
    world.integration_parameters.contact_recycling = method != Method::NoRecycling;
    world
}

/// The hooks for `rules`, or none for the plain methods.
fn hooks_for(method: Method, rules: CollisionRuleSet) -> Option<RuleHooks> {
    match method {
        Method::Recycling | Method::NoRecycling => None,
        _ => {
            let mut hooks = RuleHooks::new(rules);
            hooks.set_planner(method != Method::AllHooked);
            Some(hooks)
        }
    }
}

fn plain(method: Method) -> bool {
    matches!(method, Method::Recycling | Method::NoRecycling)
}

/// Boxes in the stack; the ghosts start this high above the ground.
const STACK: usize = 20;
const GHOSTS_FROM: f32 = 22.0;

/// Five ghosts walk down through a 20-box stack and the ground.
fn stack(method: Method, dt: f32) -> Built {
    let mut world = world(method, dt);
    let ground =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)));
    let floor = world.insert_collider(ColliderBuilder::cuboid(20.0, 0.5, 20.0), Some(ground));
    let boxes: Vec<_> = (0..STACK)
        .map(|i| {
            let body = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(
                0.0,
                0.5 + i as f32,
                0.0,
            )));
            world.insert_collider(ColliderBuilder::cuboid(0.5, 0.5, 0.5), Some(body));
            body
        })
        .collect();
    let mut rules = CollisionRuleSet::default();
    let ghosts_group = rules.create_group();
    let mut ghosts = Vec::new();
    for i in 0..5 {
        let ghost = world.insert_body(
            RigidBodyBuilder::dynamic()
                .translation(Vector::new(0.1, GHOSTS_FROM + 2.0 * i as f32, 0.0))
                .gravity_scale(0.0)
                .linvel(Vector::new(0.0, -4.0, 0.0)),
        );
        let mut collider = ColliderBuilder::ball(0.6);
        if plain(method) {
            collider = collider.solver_groups(InteractionGroups::none());
        }
        world.insert_collider(collider, Some(ghost));
        ghosts.push(ghost);
    }
    match method {
        Method::Groups | Method::AllHooked => {
            for other in [
                CollisionGroup::DEFAULT_DYNAMIC,
                CollisionGroup::DEFAULT_KINEMATIC,
                ghosts_group,
            ] {
                rules.set_group_rule(ghosts_group, other, CollisionRule::NoResponse);
            }
            for &ghost in &ghosts {
                rules.set_group(ghost, Some(ghosts_group));
            }
        }
        Method::PerPair => {
            for (i, &ghost) in ghosts.iter().enumerate() {
                rules.set_specific(ghost, floor, CollisionRule::NoResponse);
                for &b in boxes.iter().chain(&ghosts[i + 1..]) {
                    rules.set_specific(ghost, b, CollisionRule::NoResponse);
                }
            }
        }
        _ => {}
    }
    Built {
        world,
        hooks: hooks_for(method, rules),
        tracked: boxes,
        others: ghosts,
        failed: |built, seconds| {
            let fallen = built.tracked.iter().enumerate().any(|(i, &b)| {
                let p = built.world.bodies[b].translation();
                p.x.hypot(p.z) > 0.25 || p.y < 0.5 + i as f32 - 0.25
            });
            let stuck = built.others.iter().enumerate().any(|(i, &g)| {
                let free = GHOSTS_FROM + 2.0 * i as f32 - 4.0 * seconds;
                built.world.bodies[g].translation().y > free + 0.1
            });
            match (fallen, stuck) {
                (true, _) => Some("stack collapses"),
                (_, true) => Some("ghost stuck"),
                _ => None,
            }
        },
    }
}

/// Four ragdolls of six overlapping, jointed limbs fall in a pile; the
/// limbs of one ragdoll ignore each other.
fn ragdolls(method: Method, dt: f32) -> Built {
    let mut world = world(method, dt);
    let ground =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)));
    world.insert_collider(ColliderBuilder::cuboid(20.0, 0.5, 20.0), Some(ground));
    // (offset from the torso, half extents, joint on the torso)
    let limbs: [(Vector, Vector, Vector); 5] = [
        (
            Vector::new(0.0, 0.45, 0.0),
            Vector::new(0.12, 0.12, 0.12),
            Vector::new(0.0, 0.3, 0.0),
        ),
        (
            Vector::new(0.4, 0.15, 0.0),
            Vector::new(0.25, 0.07, 0.07),
            Vector::new(0.2, 0.15, 0.0),
        ),
        (
            Vector::new(-0.4, 0.15, 0.0),
            Vector::new(0.25, 0.07, 0.07),
            Vector::new(-0.2, 0.15, 0.0),
        ),
        (
            Vector::new(0.1, -0.55, 0.0),
            Vector::new(0.08, 0.3, 0.08),
            Vector::new(0.1, -0.3, 0.0),
        ),
        (
            Vector::new(-0.1, -0.55, 0.0),
            Vector::new(0.08, 0.3, 0.08),
            Vector::new(-0.1, -0.3, 0.0),
        ),
    ];
    let mut rules = CollisionRuleSet::default();
    let mut tracked = Vec::new();
    for k in 0..4 {
        let origin = Vector::new(2.0 * k as f32, 1.2 + 0.2 * k as f32, 0.0);
        let bit = Group::from_bits_truncate(1 << k);
        let groups = InteractionGroups::new(bit, Group::ALL - bit, InteractionTestMode::And);
        let collider = |half: Vector| {
            let c = ColliderBuilder::cuboid(half.x, half.y, half.z);
            if plain(method) {
                c.collision_groups(groups)
            } else {
                c
            }
        };
        let torso = world.insert_body(RigidBodyBuilder::dynamic().translation(origin));
        world.insert_collider(collider(Vector::new(0.2, 0.3, 0.1)), Some(torso));
        let mut parts = vec![torso];
        for (offset, half, anchor) in limbs {
            let body = world.insert_body(RigidBodyBuilder::dynamic().translation(origin + offset));
            world.insert_collider(collider(half), Some(body));
            let joint = SphericalJointBuilder::new()
                .local_anchor1(anchor)
                .local_anchor2(anchor - offset);
            world.insert_impulse_joint(torso, body, joint);
            parts.push(body);
        }
        match method {
            Method::Groups | Method::AllHooked => {
                let group = rules.create_group();
                rules.set_group_rule(group, group, CollisionRule::NoPair);
                for &part in &parts {
                    rules.set_group(part, Some(group));
                }
            }
            Method::PerPair => {
                for (i, &a) in parts.iter().enumerate() {
                    for &b in &parts[i + 1..] {
                        rules.set_specific(a, b, CollisionRule::NoPair);
                    }
                }
            }
            _ => {}
        }
        tracked.extend(parts);
    }
    Built {
        world,
        hooks: hooks_for(method, rules),
        tracked,
        others: Vec::new(),
        failed: |built, _| {
            let bad = built.tracked.iter().any(|&b| {
                let body = &built.world.bodies[b];
                body.linvel().length() > 20.0 || body.translation().y < -0.1
            });
            bad.then_some("ragdoll explodes")
        },
    }
}

/// 30 boxes fall through a standing player onto a thin floor.
fn debris(method: Method, dt: f32) -> Built {
    let mut world = world(method, dt);
    let ground = world.insert_body(RigidBodyBuilder::fixed());
    world.insert_collider(
        ColliderBuilder::cuboid(20.0, 0.02, 20.0).translation(Vector::new(0.0, -0.02, 0.0)),
        Some(ground),
    );
    let player = world.insert_body(
        RigidBodyBuilder::dynamic()
            .translation(Vector::new(0.0, 0.9, 0.0))
            .lock_rotations(),
    );
    let player_groups = InteractionGroups::new(
        Group::GROUP_2,
        Group::ALL - Group::GROUP_3,
        InteractionTestMode::And,
    );
    let debris_groups = InteractionGroups::new(
        Group::GROUP_3,
        Group::ALL - Group::GROUP_2,
        InteractionTestMode::And,
    );
    let mut shape = ColliderBuilder::capsule_y(0.5, 0.4);
    if plain(method) {
        shape = shape.collision_groups(player_groups);
    }
    world.insert_collider(shape, Some(player));
    let mut rules = CollisionRuleSet::default();
    let (players, rocks) = (rules.create_group(), rules.create_group());
    rules.set_group(player, Some(players));
    let mut pieces = Vec::new();
    for i in 0..30 {
        let (x, z) = ((i % 5) as f32 * 0.3 - 0.6, ((i / 5) % 3) as f32 * 0.3 - 0.3);
        let body = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(
            x,
            3.0 + 0.4 * (i / 15) as f32,
            z,
        )));
        let mut shape = ColliderBuilder::cuboid(0.1, 0.1, 0.1);
        if plain(method) {
            shape = shape.collision_groups(debris_groups);
        }
        world.insert_collider(shape, Some(body));
        match method {
            Method::Groups | Method::AllHooked => rules.set_group(body, Some(rocks)),
            Method::PerPair => rules.set_specific(player, body, CollisionRule::NoPair),
            _ => {}
        }
        pieces.push(body);
    }
    if matches!(method, Method::Groups | Method::AllHooked) {
        rules.set_group_rule(players, rocks, CollisionRule::NoPair);
    }
    let mut tracked = pieces;
    tracked.push(player);
    Built {
        world,
        hooks: hooks_for(method, rules),
        tracked,
        others: vec![player],
        failed: |built, _| {
            let p = built.world.bodies[built.others[0]].translation();
            let tunneled = built
                .tracked
                .iter()
                .any(|&b| built.world.bodies[b].translation().y < -0.05);
            match (tunneled, p.x.hypot(p.z) > 0.05) {
                (true, _) => Some("debris tunnels"),
                (_, true) => Some("player pushed"),
                _ => None,
            }
        },
    }
}

type Scene = fn(Method, f32) -> Built;

/// (id, title, scene, simulated seconds). The horizons end where the
/// reference still converges. A pile of ragdolls or debris diverges at any
/// time step once its bodies tumble over each other (the ragdolls' landing
/// differed by 4.8 cm between 1/1920 s and 1/3840 s), so the ragdolls are
/// measured while they fall with their limbs overlapping at the joints,
/// before they land, and the debris while it passes the player. The stack
/// is measured with the ghosts halfway down; its rest compression shrinks
/// slowly with the step (Rapier's contact softness), which the stated
/// tolerance of that scene shows.
const SCENES: [(&str, &str, Scene, f32); 3] = [
    ("stack", "stack with NoResponse ghosts", stack, 3.0),
    (
        "ragdolls",
        "ragdolls whose limbs ignore each other",
        ragdolls,
        0.25,
    ),
    ("debris", "debris passing a player", debris, 0.6),
];

/// What one run measured.
struct Run {
    positions: Vec<Vector>,
    /// Wall-clock seconds per simulated second.
    cost: f64,
    failure: Option<&'static str>,
}

fn run(scene: Scene, method: Method, dt: f32, seconds: f32) -> Run {
    let mut built = scene(method, dt);
    let steps = (seconds / dt).round() as usize;
    let start = Instant::now();
    for _ in 0..steps {
        match built.hooks.as_mut() {
            Some(hooks) => hooks.step(&mut built.world),
            None => built.world.step(),
        }
    }
    let wall = start.elapsed().as_secs_f64();
    Run {
        positions: built
            .tracked
            .iter()
            .map(|&b| built.world.bodies[b].translation())
            .collect(),
        cost: wall / f64::from(seconds),
        // The time simulated: a whole number of steps.
        failure: (built.failed)(&built, steps as f32 * dt),
    }
}

/// The mean distance between two runs' tracked bodies.
fn error(a: &[Vector], b: &[Vector]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| f64::from((*p - *q).length()))
        .sum::<f64>()
        / a.len() as f64
}

/// One point of a curve: its rate, median and min-max cost, error, failure.
struct Point {
    hz: u32,
    cost: [f64; 3],
    error: f64,
    failure: Option<&'static str>,
}

fn median_min_max(mut values: Vec<f64>) -> [f64; 3] {
    values.sort_by(f64::total_cmp);
    [
        values[values.len() / 2],
        values[0],
        values[values.len() - 1],
    ]
}

/// The measurements of one scene: the reference's tolerance and each
/// method's curve.
struct Measured {
    tolerance: f64,
    curves: Vec<(Method, Vec<Point>)>,
}

fn measure(scene: Scene, seconds: f32, rates: &[u32], repeats: usize) -> Measured {
    let reference = run(scene, Method::NoRecycling, 1.0 / 1920.0, seconds).positions;
    let finer = run(scene, Method::NoRecycling, 1.0 / 3840.0, seconds).positions;
    let tolerance = error(&reference, &finer).max(1e-6);
    let curves = METHODS
        .iter()
        .map(|&(method, _, _)| {
            let points = rates
                .iter()
                .map(|&hz| {
                    let runs: Vec<Run> = (0..repeats)
                        .map(|_| run(scene, method, 1.0 / hz as f32, seconds))
                        .collect();
                    Point {
                        hz,
                        cost: median_min_max(runs.iter().map(|r| r.cost).collect()),
                        error: error(&runs[0].positions, &reference).max(1e-6),
                        failure: runs[0].failure,
                    }
                })
                .collect();
            (method, points)
        })
        .collect();
    Measured { tolerance, curves }
}

/// Which plain run each `RuleHooks` run steps as: a hooked pair loses
/// Rapier's contact recycling, and only it. The planner's groups and the
/// per-pair rules (which hook one side of each entry: the ghosts, the
/// player, the limbs of a ragdoll) leave the pairs that carry the scene's
/// contacts recycled, so they step as plain Rapier with recycling; with
/// every collider hooked, as plain Rapier without it. At every time step
/// their errors agree within the reference's tolerance.
fn check(name: &str, measured: &Measured) -> Result<(), String> {
    let curve = |m: Method| {
        &measured
            .curves
            .iter()
            .find(|(c, _)| *c == m)
            .expect("measured")
            .1
    };
    for (a, b) in [
        (Method::Groups, Method::Recycling),
        (Method::PerPair, Method::Recycling),
        (Method::AllHooked, Method::NoRecycling),
    ] {
        for (p, q) in curve(a).iter().zip(curve(b)) {
            if !abs_diff_eq!(p.error, q.error, epsilon = measured.tolerance) {
                return Err(format!(
                    "{name} at 1/{} s: {a:?} error {:.3e} m against {b:?} {:.3e} m (tolerance {:.1e} m)",
                    p.hz, p.error, q.error, measured.tolerance
                ));
            }
        }
    }
    Ok(())
}

fn chart(
    path: &std::path::Path,
    scenes: &[(&str, &Measured)],
) -> Result<(), Box<dyn std::error::Error>> {
    let root = SVGBackend::new(path, (960, 420 * scenes.len() as u32)).into_drawing_area();
    root.fill(&WHITE)?;
    for (area, (title, measured)) in root.split_evenly((scenes.len(), 1)).iter().zip(scenes) {
        let points = measured.curves.iter().flat_map(|(_, p)| p);
        let (x0, x1) = points.clone().fold((f64::MAX, 0f64), |(a, b), p| {
            (a.min(p.cost[1]), b.max(p.cost[2]))
        });
        let (y0, y1) = points.fold((f64::MAX, 0f64), |(a, b), p| {
            (a.min(p.error), b.max(p.error))
        });
        let y0 = y0.min(measured.tolerance);
        let mut chart = ChartBuilder::on(area)
            .caption(
                format!(
                    "{title}: error against cost (reference tolerance {:.1e} m)",
                    measured.tolerance
                ),
                ("sans-serif", 16),
            )
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(
                (x0 / 1.5..x1 * 1.5).log_scale(),
                (y0 / 2.0..y1 * 4.0).log_scale(),
            )?;
        chart
            .configure_mesh()
            .x_desc("wall-clock seconds per simulated second (median of repeats, min-max bars)")
            .y_desc("mean position error (m)")
            .draw()?;
        chart.draw_series(LineSeries::new(
            [
                (x0 / 1.5, measured.tolerance),
                (x1 * 1.5, measured.tolerance),
            ],
            BLACK.mix(0.4).stroke_width(1),
        ))?;
        for (method, points) in &measured.curves {
            let &(_, name, color) = METHODS
                .iter()
                .find(|(m, _, _)| m == method)
                .expect("a method");
            let line: Vec<(f64, f64)> = points.iter().map(|p| (p.cost[0], p.error)).collect();
            chart
                .draw_series(LineSeries::new(line, color.stroke_width(2)))?
                .label(name)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], color));
            chart.draw_series(points.iter().map(|p| {
                ErrorBar::new_horizontal(p.error, p.cost[1], p.cost[0], p.cost[2], color, 6)
            }))?;
            chart.draw_series(
                points
                    .iter()
                    .map(|p| Circle::new((p.cost[0], p.error), 3, color.filled())),
            )?;
            chart.draw_series(points.iter().map(|p| {
                Text::new(
                    format!("1/{}", p.hz),
                    (p.cost[0], p.error * 1.25),
                    ("sans-serif", 10).into_font().color(&color),
                )
            }))?;
            chart.draw_series(points.iter().filter_map(|p| {
                p.failure.map(|f| {
                    EmptyElement::at((p.cost[0], p.error))
                        + Cross::new((0, 0), 7, RED.stroke_width(2))
                        + Text::new(f, (8, 4), ("sans-serif", 11).into_font().color(&RED))
                })
            }))?;
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(SeriesLabelPosition::UpperRight)
            .draw()?;
    }
    root.present()?;
    Ok(())
}

/// Recalculation policies over the number of edits per step: time per step
/// and the share of live pairs whose rule is stale right after the step.
fn freshness(policy: RecalculationPolicy, edits: usize, steps: usize) -> (f64, f64) {
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
    let (mut stale, mut total, mut time) = (0usize, 0usize, 0.0f64);
    for _ in 0..steps {
        for _ in 0..edits {
            let body = bodies[next(bodies.len())];
            hooks
                .rules_mut()
                .set_personal(body, rules[next(rules.len())]);
        }
        let start = Instant::now();
        hooks.step(&mut world);
        time += start.elapsed().as_secs_f64();
        for (a, b, rule) in hooks.pairs(&world) {
            total += 1;
            stale +=
                usize::from(rule != hooks.rules().resolve(&world.bodies, &world.colliders, a, b));
        }
    }
    (
        time / steps as f64 * 1000.0,
        stale as f64 / total.max(1) as f64,
    )
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let repeats = std::env::var("TRADEOFF_REPEATS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(5);
    generate(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs"),
        1.0,
        &RATES,
        repeats,
        60,
    )
}

/// Measures every scene (over its horizon times `scale`) and policy and
/// writes the chart and the tables into `docs`; fails if a check does.
fn generate(
    docs: &std::path::Path,
    scale: f32,
    rates: &[u32],
    repeats: usize,
    edit_steps: usize,
) -> Result<(), Box<dyn std::error::Error>> {
    std::fs::create_dir_all(docs)?;
    let mut csv = String::from(
        "scene,method,dt,cost_median_s_per_s,cost_min,cost_max,error_m,failure,reference_tolerance_m\n",
    );
    let mut all = Vec::new();
    for (id, title, scene, horizon) in SCENES {
        let measured = measure(scene, horizon * scale, rates, repeats);
        println!(
            "{title}: reference (1/1920 s) against 1/3840 s: {:.2e} m",
            measured.tolerance
        );
        for (method, points) in &measured.curves {
            for p in points {
                let failure = p.failure.unwrap_or("");
                let _ = writeln!(
                    csv,
                    "{id},{method:?},1/{},{:.5},{:.5},{:.5},{:.3e},{failure},{:.2e}",
                    p.hz, p.cost[0], p.cost[1], p.cost[2], p.error, measured.tolerance
                );
                println!(
                    "  {:<12} 1/{:<4} {:>9.4} s/s [{:.4}, {:.4}]  error {:.3e} m  {failure}",
                    format!("{method:?}"),
                    p.hz,
                    p.cost[0],
                    p.cost[1],
                    p.cost[2],
                    p.error
                );
            }
        }
        check(id, &measured)?;
        all.push((title, measured));
    }
    std::fs::write(docs.join("tradeoff.csv"), csv)?;
    let scenes: Vec<(&str, &Measured)> = all.iter().map(|(t, m)| (*t, m)).collect();
    chart(&docs.join("tradeoff.svg"), &scenes)?;

    let mut csv =
        String::from("policy,edits_per_step,ms_per_step_median,ms_min,ms_max,stale_share\n");
    for policy in [
        RecalculationPolicy::Manual,
        RecalculationPolicy::OnChange,
        RecalculationPolicy::EveryStep,
    ] {
        for edits in [1, 4, 16, 64] {
            // The same edits each repeat: the share of stale pairs is one
            // number, the time a median of the repeats.
            let runs: Vec<(f64, f64)> = (0..repeats)
                .map(|_| freshness(policy, edits, edit_steps))
                .collect();
            let [ms, low, high] = median_min_max(runs.iter().map(|r| r.0).collect());
            let stale = runs[0].1;
            let _ = writeln!(
                csv,
                "{policy:?},{edits},{ms:.3},{low:.3},{high:.3},{stale:.4}"
            );
            println!(
                "{:>10}, {edits:>2} edits a step: {ms:.3} ms a step [{low:.3}, {high:.3}], {:.2}% of live pairs stale",
                format!("{policy:?}"),
                stale * 100.0
            );
            if policy != RecalculationPolicy::Manual && stale > 0.0 {
                return Err(format!("{policy:?} left stale pairs: {stale}").into());
            }
        }
    }
    std::fs::write(docs.join("freshness.csv"), csv)?;
    println!(
        "wrote tradeoff.svg, tradeoff.csv and freshness.csv in {}",
        docs.display()
    );
    Ok(())
}

#[test]
fn the_hook_steps_as_plain_rapier_and_every_policy_but_manual_stays_fresh() {
    // Written under target/: the committed chart comes from a release run.
    let out = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target/tradeoff");
    generate(&out, 0.5, &[30, 120], 1, 5).expect("the example's own checks");
    assert!(out.join("tradeoff.svg").exists());
}
