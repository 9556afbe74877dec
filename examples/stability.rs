//! Where each method fails: four sweeps that push a parameter until a
//! scene breaks, each next to plain Rapier at the same point.
//!
//! - bullets from 10 to 2,000 m/s against a wall under each rule, CCD on and
//!   off, `max_ccd_substeps` 1 to 4, fixed and dynamic walls: the speed
//!   where a rule stops being free flight, or a `Normal` wall starts to
//!   tunnel;
//! - two cubes overlapping by 0 to 100%, switched from `NoResponse` to
//!   `Normal` at once or in stages: the peak separation speed, against
//!   Rapier's corrective-velocity limit;
//! - a compound 1 to 1,000 times heavier than the box it rests on, its
//!   parts under group rules (Rapier groups) or hooked rules;
//! - a 20-box stack that ghosts fall through, at time steps from 1/15 s to
//!   1/240 s: the largest step at which it stands; and a soft block that
//!   ghosts fall through, at the same steps, against the block alone;
//! - a rigid cube put into a soft block by 0 to 100%, switched from
//!   `NoResponse` to `Normal` at once or in stages, against Rapier's own
//!   switch (collision groups that let the pair in a step later).
//!
//! Writes `docs/stability_{bullets,overlap,mass,dt}.{csv,svg}`,
//! `docs/stability_soft.csv` and `docs/stability_soft_overlap.csv`, prints the
//! thresholds it found, and exits non-zero if a rule does worse than plain
//! Rapier anywhere (the shape `docs/stability.md` reports).
//!
//! `cargo run --release --example stability` (about 15 s on 2 cores).

use std::fmt::Write as _;
use std::path::Path;

use plotters::prelude::*;
use rapier_collision_rules::{CollisionRule, CollisionRuleSet, RuleHooks};
use rapier3d::prelude::*;

#[path = "../benches/common/chart.rs"]
mod chart;
#[path = "common/overlap.rs"]
mod overlap;

#[path = "common/soft_overlap.rs"]
mod soft_overlap;
#[path = "common/stack.rs"]
mod stack;

use overlap::{Switch, overlap};
use soft_overlap::{SoftSwitch, soft_overlap};
use stack::{GhostStack, ghost_stack};

type Failure = Box<dyn std::error::Error>;

/// How a scene's rule reaches Rapier.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Method {
    /// Plain Rapier: its own groups (or, for `NoContacts`, a filter hook of
    /// its own), no crate.
    Plain,
    /// The rules with the planner: Rapier groups where they are exact.
    Planned,
    /// The rules with every collider hooked (planner off): hooked pairs
    /// lose Rapier's contact recycling.
    Hooked,
    /// Plain Rapier with contact recycling off: what a hooked pair gets.
    PlainUnrecycled,
}

const METHODS: [Method; 3] = [Method::Plain, Method::Planned, Method::Hooked];
const WITH_UNRECYCLED: [Method; 4] = [
    Method::Plain,
    Method::PlainUnrecycled,
    Method::Planned,
    Method::Hooked,
];

/// Plain Rapier's own filter for `NoContacts`: a hook that refuses pairs
/// between colliders whose user data both say 1.
struct RefuseMarked;

impl PhysicsHooks for RefuseMarked {
    fn filter_contact_pair(&self, context: &PairFilterContext<'_>) -> Option<SolverFlags> {
        let marked = |c: ColliderHandle| context.colliders[c].user_data == 1;
        if marked(context.collider1) && marked(context.collider2) {
            None
        } else {
            Some(SolverFlags::COMPUTE_RIGID_IMPULSES)
        }
    }
}

/// A world stepped plainly or with the rules.
struct Run {
    world: PhysicsWorld,
    hooks: Option<RuleHooks>,
    plain_hooks: bool,
}

impl Run {
    fn new(mut world: PhysicsWorld, method: Method, rules: CollisionRuleSet) -> Run {
        if method == Method::PlainUnrecycled {
            world.integration_parameters.contact_recycling = false;
        }
        let plain = matches!(method, Method::Plain | Method::PlainUnrecycled);
        let hooks = (!plain).then(|| {
            let mut hooks = RuleHooks::new(rules);
            hooks.set_planner(method == Method::Planned);
            hooks
        });
        Run {
            world,
            hooks,
            plain_hooks: false,
        }
    }

    fn plain(&self) -> bool {
        self.hooks.is_none()
    }

    fn step(&mut self) {
        match (&mut self.hooks, self.plain_hooks) {
            (Some(hooks), _) => hooks.step(&mut self.world),
            (None, true) => self.world.step_with_events(&RefuseMarked, &()),
            (None, false) => self.world.step(),
        }
    }
}

/// Gives plain Rapier's form of `rule` between the colliders `a` and `b`.
fn plain_rule(run: &mut Run, a: ColliderHandle, b: ColliderHandle, rule: CollisionRule) {
    let bit = InteractionGroups::new(
        Group::GROUP_2,
        Group::ALL - Group::GROUP_3,
        InteractionTestMode::And,
    );
    let other = InteractionGroups::new(
        Group::GROUP_3,
        Group::ALL - Group::GROUP_2,
        InteractionTestMode::And,
    );
    let colliders = &mut run.world.colliders;
    match rule {
        CollisionRule::NoPair => {
            colliders[a].set_collision_groups(bit);
            colliders[b].set_collision_groups(other);
        }
        CollisionRule::NoResponse => {
            colliders[a].set_solver_groups(bit);
            colliders[b].set_solver_groups(other);
        }
        CollisionRule::NoContacts => {
            for c in [a, b] {
                colliders[c].user_data = 1;
                colliders[c].set_active_hooks(ActiveHooks::FILTER_CONTACT_PAIRS);
            }
            run.plain_hooks = true;
        }
        _ => {}
    }
}

// ---------------------------------------------------------------- bullets

#[derive(Clone, Copy, Debug, PartialEq)]
enum Wall {
    Fixed,
    Dynamic,
}

const SPEEDS: [f32; 13] = [
    10.0, 12.0, 14.0, 16.0, 18.0, 20.0, 50.0, 100.0, 200.0, 400.0, 700.0, 1000.0, 2000.0,
];
const WALL_X: f32 = 5.0;
const BULLET_STEPS: usize = 60;

/// Where a 0.1 m bullet and the 4 cm wall it flies at (from x = 5) end
/// after one second at `speed` (`rule` between them; `None`: no wall at
/// all).
fn bullet(
    speed: f32,
    wall: Wall,
    ccd: bool,
    substeps: usize,
    rule: Option<CollisionRule>,
    method: Method,
) -> (f32, f32) {
    let mut world = PhysicsWorld::new();
    world.gravity = Vector::ZERO;
    world.integration_parameters.max_ccd_substeps = substeps;
    let body = world.insert_body(
        RigidBodyBuilder::dynamic()
            .linvel(Vector::new(speed, 0.0, 0.0))
            .ccd_enabled(ccd),
    );
    let ball = world.insert_collider(ColliderBuilder::ball(0.1), Some(body));
    let mut rules = CollisionRuleSet::default();
    let mut run_rule = None;
    if let Some(rule) = rule {
        let builder = match wall {
            Wall::Fixed => RigidBodyBuilder::fixed(),
            Wall::Dynamic => RigidBodyBuilder::dynamic(),
        };
        let wall_body = world.insert_body(builder.translation(Vector::new(WALL_X, 0.0, 0.0)));
        let w = world.insert_collider(ColliderBuilder::cuboid(0.02, 2.0, 2.0), Some(wall_body));
        rules.set_specific(body, w, rule);
        run_rule = Some((w, rule));
    }
    let mut run = Run::new(world, method, rules);
    if let (true, Some((w, rule))) = (run.plain(), run_rule) {
        plain_rule(&mut run, ball, w, rule);
    }
    for _ in 0..BULLET_STEPS {
        run.step();
    }
    let wall_x = run_rule.and_then(|(w, _)| run.world.colliders[w].parent());
    let wall_x = wall_x.map_or(f32::MAX, |b| run.world.bodies[b].translation().x);
    (run.world.bodies[body].translation().x, wall_x)
}

struct BulletRow {
    speed: f32,
    wall: Wall,
    ccd: bool,
    substeps: usize,
    rule: CollisionRule,
    method: Method,
    x: f32,
    /// Free flight for a rule without response; tunnelled for `Normal`.
    broke: bool,
}

fn bullets() -> Vec<BulletRow> {
    let mut rows = Vec::new();
    for wall in [Wall::Fixed, Wall::Dynamic] {
        for ccd in [false, true] {
            for substeps in 1..=4 {
                for &speed in &SPEEDS {
                    let (free, _) = bullet(speed, wall, ccd, substeps, None, Method::Plain);
                    for rule in [
                        CollisionRule::Normal,
                        CollisionRule::NoResponse,
                        CollisionRule::NoContacts,
                        CollisionRule::NoPair,
                    ] {
                        for method in METHODS {
                            let (x, wall_x) =
                                bullet(speed, wall, ccd, substeps, Some(rule), method);
                            // A dynamic wall is pushed along: the bullet
                            // went through if it ends past the wall.
                            let broke = if rule == CollisionRule::Normal {
                                x > wall_x
                            } else {
                                x != free
                            };
                            rows.push(BulletRow {
                                speed,
                                wall,
                                ccd,
                                substeps,
                                rule,
                                method,
                                x,
                                broke,
                            });
                        }
                    }
                }
            }
        }
    }
    rows
}

// ---------------------------------------------------------------- overlap

const DEPTHS: [f32; 11] = [0.0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0];

// ---------------------------------------------------------------- mass

const RATIOS: [f32; 7] = [1.0, 3.0, 10.0, 30.0, 100.0, 300.0, 1000.0];

/// A compound (two boxes on one body) `ratio` times heavier than the unit
/// box it rests on, with ghosts falling through it under `NoResponse`;
/// returns how far the light box sank into the floor and how far the
/// compound slid off it, after three seconds (m).
fn mass(ratio: f32, method: Method) -> (f32, f32) {
    let mut world = PhysicsWorld::new();
    let ground =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)));
    world.insert_collider(ColliderBuilder::cuboid(20.0, 0.5, 20.0), Some(ground));
    let light =
        world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.5, 0.0)));
    world.insert_collider(ColliderBuilder::cuboid(0.5, 0.5, 0.5), Some(light));
    let heavy =
        world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 1.5, 0.0)));
    let parts: Vec<_> = [-0.3, 0.3]
        .into_iter()
        .map(|x| {
            world.insert_collider(
                ColliderBuilder::cuboid(0.3, 0.5, 0.5)
                    .translation(Vector::new(x, 0.0, 0.0))
                    .density(ratio * 1.0 / 1.2),
                Some(heavy),
            )
        })
        .collect();
    let mut rules = CollisionRuleSet::default();
    let (load, ghosts) = (rules.create_group(), rules.create_group());
    rules.set_group_rule(load, ghosts, CollisionRule::NoResponse);
    rules.set_group(heavy, Some(load));
    let mut ghost_colliders = Vec::new();
    for i in 0..3 {
        let ghost = world.insert_body(
            RigidBodyBuilder::dynamic()
                .translation(Vector::new(0.1 * i as f32, 4.0 + 2.0 * i as f32, 0.0))
                .gravity_scale(0.0)
                .linvel(Vector::new(0.0, -3.0, 0.0)),
        );
        ghost_colliders.push(world.insert_collider(ColliderBuilder::ball(0.3), Some(ghost)));
        rules.set_group(ghost, Some(ghosts));
    }
    let mut run = Run::new(world, method, rules);
    if run.plain() {
        for &part in &parts {
            for &g in &ghost_colliders {
                plain_rule(&mut run, part, g, CollisionRule::NoResponse);
            }
        }
    }
    let (mut sink, mut slide) = (0.0_f32, 0.0_f32);
    for _ in 0..180 {
        run.step();
        let (l, h) = (&run.world.bodies[light], &run.world.bodies[heavy]);
        sink = sink.max(0.5 - l.translation().y);
        slide = slide.max((h.translation() - l.translation()).with_y(0.0).length());
    }
    (sink, slide)
}

// ---------------------------------------------------------------- dt

const STEPS_PER_SECOND: [f32; 7] = [15.0, 20.0, 30.0, 45.0, 60.0, 120.0, 240.0];

/// A 20-box stack with five ghosts falling through it (`NoResponse` with
/// everything), stepped for three seconds at `1 / hz`; returns the stack's
/// largest horizontal drift.
fn stack(hz: f32, method: Method) -> f32 {
    let GhostStack {
        world,
        boxes,
        floor,
        ghosts,
        mut rules,
        spirits,
    } = ghost_stack(1.0 / hz, true);
    for &(ghost, _) in &ghosts {
        rules.set_group(ghost, Some(spirits));
    }
    let mut run = Run::new(world, method, rules);
    if run.plain() {
        for &(_, g) in &ghosts {
            for c in boxes.iter().map(|b| b.1).chain([floor]) {
                plain_rule(&mut run, g, c, CollisionRule::NoResponse);
            }
        }
    }
    let steps = (3.0 * hz) as usize;
    let mut drift: f32 = 0.0;
    for _ in 0..steps {
        run.step();
        for &(body, _) in &boxes {
            drift = drift.max(run.world.bodies[body].translation().with_y(0.0).length());
        }
    }
    drift
}

/// A soft block (4x4x4 particles) resting on a floor at `1 / hz` for
/// three seconds while three ghost balls fall through it (`NoResponse`
/// between each ghost and the block's root, which the hook says for soft
/// bodies); returns the block's lowest particle (m). Plain Rapier has no
/// form of `NoResponse` for a soft pair (its soft solver reads no solver
/// groups or solver flags), so its run is the same block without the
/// ghosts: what the rule promises.
fn soft_rest(hz: f32, method: Method) -> f32 {
    let mut world = PhysicsWorld::new();
    world.integration_parameters.dt = 1.0 / hz;
    let ground =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)));
    world.insert_collider(ColliderBuilder::cuboid(5.0, 0.5, 5.0), Some(ground));
    let block = SoftBodyBuilder::cuboid(Vector::new(0.0, 0.55, 0.0), Vector::splat(0.5), 4, 4, 4)
        .cell_model(SoftBodyCellModel::Corotational)
        .softness(SpringCoefficients::new(30.0, 1.0));
    let block = world.insert_soft_body(block);
    let root = world.soft_bodies[block].root_body();
    let mut rules = CollisionRuleSet::default();
    if method != Method::Plain {
        for i in 0..3 {
            let at = Vector::new(0.3 * i as f32 - 0.3, 2.0 + i as f32, 0.0);
            let ghost = world.insert_body(RigidBodyBuilder::dynamic().translation(at));
            world.insert_collider(ColliderBuilder::ball(0.2), Some(ghost));
            rules.set_specific(ghost, root, CollisionRule::NoResponse);
        }
    }
    let mut run = Run::new(world, method, rules);
    for _ in 0..(3.0 * hz) as usize {
        run.step();
    }
    run.world.soft_bodies[block]
        .particle_positions()
        .map(|p| p.y)
        .fold(f32::MAX, f32::min)
}

/// A labelled line of a chart: its points.
type Series = (String, Vec<(f64, f64)>);

/// Each switch measured at every depth of `DEPTHS`: the rows written to
/// `csv` and printed, one line a switch, and returned with their labels.
fn depth_sweep<S: Copy + std::fmt::Debug>(
    switches: &[S],
    csv: &mut String,
    measure: impl Fn(f32, S) -> f32,
) -> Result<Vec<Series>, Failure> {
    let mut series = Vec::new();
    for &switch in switches {
        let points: Vec<(f64, f64)> = DEPTHS
            .iter()
            .map(|&d| (f64::from(d), f64::from(measure(d, switch))))
            .collect();
        for &(d, v) in &points {
            writeln!(csv, "{d},{switch:?},{v}")?;
        }
        let row: Vec<String> = points.iter().map(|p| format!("{:.2}", p.1)).collect();
        println!("{:<12} {}", format!("{switch:?}"), row.join(" "));
        series.push((format!("{switch:?}"), points));
    }
    Ok(series)
}

// ---------------------------------------------------------------- output

fn write(name: &str, csv: &str) -> Result<(), Failure> {
    let docs = Path::new(env!("CARGO_MANIFEST_DIR")).join("docs");
    std::fs::write(docs.join(format!("stability_{name}.csv")), csv)?;
    Ok(())
}

fn svg_path(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("docs/stability_{name}.svg"))
}

const COLORS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
];

/// A chart of several series over a log x axis.
fn log_chart(
    name: &str,
    caption: &str,
    (x_label, y_label): (&str, &str),
    x_range: std::ops::Range<f64>,
    y_range: std::ops::Range<f64>,
    series: &[(String, Vec<(f64, f64)>)],
    level: Option<(f64, &str)>,
) -> Result<(), Failure> {
    let path = svg_path(name);
    let root = chart::canvas(&path, (900, 520))?;
    let mut chart =
        chart::builder(&root, caption).build_cartesian_2d(x_range.log_scale(), y_range.clone())?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .draw()?;
    for (i, (label, points)) in series.iter().enumerate() {
        chart::line(&mut chart, points, label, COLORS[i % COLORS.len()])?;
    }
    if let Some((y, label)) = level {
        let (x0, x1) = (series[0].1[0].0, series[0].1.last().map_or(1.0, |p| p.0));
        chart
            .draw_series(LineSeries::new([(x0, y), (x1, y)], BLACK.stroke_width(1)))?
            .label(label)
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], BLACK));
    }
    chart::finish(chart, &root)
}

fn main() -> Result<(), Failure> {
    let mut broken = Vec::new();

    // Bullets.
    let rows = bullets();
    let mut csv = String::from("speed_m_s,wall,ccd,max_ccd_substeps,rule,method,final_x,broke\n");
    for r in &rows {
        writeln!(
            csv,
            "{},{:?},{},{},{:?},{:?},{},{}",
            r.speed, r.wall, r.ccd, r.substeps, r.rule, r.method, r.x, r.broke
        )?;
    }
    write("bullets", &csv)?;
    println!(
        "Bullets: the lowest speed (m/s) where a rule stops being free flight, or a Normal wall lets the bullet through"
    );
    println!(
        "{:<10} {:<8} {:<4} {:<9} {:>8} {:>8} {:>8}",
        "rule", "wall", "ccd", "substeps", "plain", "planned", "hooked"
    );
    let mut series = Vec::new();
    for rule in [
        CollisionRule::Normal,
        CollisionRule::NoResponse,
        CollisionRule::NoContacts,
        CollisionRule::NoPair,
    ] {
        for wall in [Wall::Fixed, Wall::Dynamic] {
            for ccd in [false, true] {
                for substeps in 1..=4 {
                    let first = |method: Method| {
                        rows.iter()
                            .filter(|r| {
                                (r.rule, r.wall, r.ccd, r.substeps, r.method)
                                    == (rule, wall, ccd, substeps, method)
                            })
                            .find(|r| r.broke)
                            .map(|r| r.speed)
                    };
                    let [plain, planned, hooked] = METHODS.map(first);
                    let show = |s: Option<f32>| s.map_or("none".into(), |s| format!("{s}"));
                    if substeps == 1 || rule == CollisionRule::Normal {
                        println!(
                            "{:<10} {:<8} {:<4} {:<9} {:>8} {:>8} {:>8}",
                            format!("{rule:?}"),
                            format!("{wall:?}"),
                            ccd,
                            substeps,
                            show(plain),
                            show(planned),
                            show(hooked)
                        );
                    }
                    // A rule does no worse than plain Rapier: it breaks at
                    // the same speed or not at all.
                    for (method, at) in [(Method::Planned, planned), (Method::Hooked, hooked)] {
                        let worse = match (at, plain) {
                            (Some(at), Some(plain)) => at < plain,
                            (Some(_), None) => true,
                            (None, _) => false,
                        };
                        if worse {
                            broken.push(format!("bullets: {rule:?} {method:?} {wall:?} ccd {ccd} substeps {substeps} breaks at {at:?}, plain at {plain:?}"));
                        }
                    }
                }
                if rule == CollisionRule::Normal {
                    let points = SPEEDS
                        .iter()
                        .map(|&speed| {
                            let r = rows
                                .iter()
                                .find(|r| {
                                    (r.rule, r.wall, r.ccd, r.substeps, r.method, r.speed)
                                        == (rule, wall, ccd, 1, Method::Planned, speed)
                                })
                                .expect("every row was run");
                            (f64::from(speed), f64::from(r.x))
                        })
                        .collect();
                    series.push((
                        format!("{wall:?} wall, CCD {}", if ccd { "on" } else { "off" }),
                        points,
                    ));
                }
            }
        }
    }
    log_chart(
        "bullets",
        "A Normal wall at x = 5: where the bullet ends after 1 s (planned rules; plain Rapier the same)",
        ("bullet speed (m/s)", "final x (m)"),
        8.0..2500.0,
        -1.0..12.0,
        &series
            .into_iter()
            .map(|(l, p): (String, Vec<(f64, f64)>)| {
                (l, p.into_iter().map(|(s, x)| (s, x.min(12.0))).collect())
            })
            .collect::<Vec<_>>(),
        Some((f64::from(WALL_X), "the wall")),
    )?;

    // Overlap.
    let cap = f64::from(IntegrationParameters::default().max_corrective_velocity());
    let mut csv = String::from("depth,switch,peak_speed_m_s\n");
    println!(
        "\nOverlap: peak separation speed (m/s) of two unit cubes overlapping by a share of their width (Rapier's corrective-velocity limit {cap} m/s)"
    );
    let series = depth_sweep(
        &[Switch::Plain, Switch::Abrupt, Switch::Staged],
        &mut csv,
        overlap,
    )?;
    write("overlap", &csv)?;
    for (i, &depth) in DEPTHS.iter().enumerate() {
        let (plain, abrupt, staged) = (series[0].1[i].1, series[1].1[i].1, series[2].1[i].1);
        // The staged switch moves no faster than the hand (1 cm a step).
        let hand = 0.01 / f64::from(IntegrationParameters::default().dt);
        if abrupt > plain * 1.2 + 0.05 || staged > hand + 1e-3 {
            broken.push(format!(
                "overlap {depth}: plain {plain:.2}, abrupt {abrupt:.2}, staged {staged:.2} m/s"
            ));
        }
    }
    {
        let path = svg_path("overlap");
        let root = chart::canvas(&path, (900, 520))?;
        let mut chart = chart::builder(
            &root,
            "Switching an overlap to Normal: peak separation speed",
        )
        .build_cartesian_2d(0.0..1.0, 0.0..(cap * 1.4))?;
        chart
            .configure_mesh()
            .x_desc("overlap (share of the cubes' width)")
            .y_desc("peak separation speed (m/s)")
            .draw()?;
        for (i, (label, points)) in series.iter().enumerate() {
            chart::line(&mut chart, points, label, COLORS[i])?;
        }
        chart
            .draw_series(LineSeries::new(
                [(0.0, cap), (1.0, cap)],
                BLACK.stroke_width(1),
            ))?
            .label("Rapier's max corrective velocity")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], BLACK));
        chart::finish(chart, &root)?;
    }

    // A soft block and a rigid cube overlapping.
    let mut csv = String::from("depth,switch,peak_speed_m_s\n");
    println!(
        "\nOverlap, soft: peak speed (m/s) of a rigid unit cube put into a settled soft block by a share of their width"
    );
    let switches = [
        SoftSwitch::Plain,
        SoftSwitch::PlainGroups,
        SoftSwitch::Abrupt,
        SoftSwitch::Staged,
    ];
    let soft_series: Vec<Vec<(f64, f64)>> = depth_sweep(&switches, &mut csv, soft_overlap)?
        .into_iter()
        .map(|(_, points)| points)
        .collect();
    write("soft_overlap", &csv)?;
    // The staged switch against the hand; the abrupt one against Rapier's
    // own (groups that let the block in a step later), which it follows
    // (`docs/stability.md`, "A rigid cube switched into a soft block").
    for (i, &depth) in DEPTHS.iter().enumerate() {
        let (rapier, abrupt, staged) = (
            soft_series[1][i].1,
            soft_series[2][i].1,
            soft_series[3][i].1,
        );
        let hand = 0.01 / f64::from(IntegrationParameters::default().dt);
        if staged > hand + 1e-3 {
            broken.push(format!(
                "soft overlap {depth}: staged {staged:.2} m/s, faster than the hand {hand:.2}"
            ));
        }
        if abrupt > rapier * 1.2 + 0.05 {
            broken.push(format!(
                "soft overlap {depth}: the abrupt switch {abrupt:.2} m/s, Rapier's {rapier:.2} m/s"
            ));
        }
    }

    // Mass ratios.
    let mut csv = String::from("ratio,method,sink_m,slide_m\n");
    let mut series = Vec::new();
    println!(
        "\nMass: a compound resting on a unit box, ghosts through it; sink into the floor / slide off (m)"
    );
    for method in WITH_UNRECYCLED {
        let results: Vec<(f32, (f32, f32))> =
            RATIOS.iter().map(|&r| (r, mass(r, method))).collect();
        for &(r, (sink, slide)) in &results {
            writeln!(csv, "{r},{method:?},{sink},{slide}")?;
        }
        println!(
            "{:<8} {}",
            format!("{method:?}"),
            results
                .iter()
                .map(|(r, (s, d))| format!("{r}: {s:.3}/{d:.3}"))
                .collect::<Vec<_>>()
                .join("  ")
        );
        series.push((
            format!("{method:?}: sink"),
            results
                .iter()
                .map(|&(r, (s, _))| (f64::from(r), f64::from(s)))
                .collect::<Vec<_>>(),
        ));
    }
    write("mass", &csv)?;
    // Planned rules are Rapier groups: plain Rapier's numbers exactly.
    // Hooked pairs lose contact recycling: plain Rapier's without it.
    for (i, &ratio) in RATIOS.iter().enumerate() {
        let [plain, unrecycled, planned, hooked] = [0, 1, 2, 3].map(|m| series[m].1[i].1);
        if planned != plain || hooked != unrecycled {
            broken.push(format!(
                "mass {ratio}: sink plain {plain:.4}, planned {planned:.4}, unrecycled {unrecycled:.4}, hooked {hooked:.4} m"
            ));
        }
    }
    let top = series
        .iter()
        .flat_map(|s| s.1.iter().map(|p| p.1))
        .fold(0.01, f64::max);
    log_chart(
        "mass",
        "A compound on a unit box: how far the box sinks into the floor in 3 s",
        ("mass ratio (compound / box)", "sink (m)"),
        0.8..1300.0,
        0.0..top * 1.3,
        &series,
        None,
    )?;

    // Time step.
    let mut csv = String::from("steps_per_second,method,drift_m\n");
    let mut series = Vec::new();
    println!(
        "\nTime step: a 20-box stack with ghosts through it, largest drift (m) after 3 s; it stands below 0.5 m"
    );
    for method in WITH_UNRECYCLED {
        let points: Vec<(f64, f64)> = STEPS_PER_SECOND
            .iter()
            .map(|&hz| (f64::from(hz), f64::from(stack(hz, method))))
            .collect();
        for &(hz, d) in &points {
            writeln!(csv, "{hz},{method:?},{d}")?;
        }
        let stands = points
            .iter()
            .find(|p| p.1 < 0.5)
            .map(|p| format!("1/{}", p.0));
        println!(
            "{:<8} {}  (largest step that stands: {})",
            format!("{method:?}"),
            points
                .iter()
                .map(|(hz, d)| format!("1/{hz}: {d:.3}"))
                .collect::<Vec<_>>()
                .join("  "),
            stands.unwrap_or_else(|| "none".into())
        );
        series.push((format!("{method:?}"), points));
    }
    write("dt", &csv)?;
    for (i, &hz) in STEPS_PER_SECOND.iter().enumerate() {
        let [plain, unrecycled, planned, hooked] = [0, 1, 2, 3].map(|m| series[m].1[i].1);
        if planned != plain || hooked != unrecycled {
            broken.push(format!(
                "dt 1/{hz}: drift plain {plain:.3}, planned {planned:.3}, unrecycled {unrecycled:.3}, hooked {hooked:.3} m"
            ));
        }
    }
    let top = series
        .iter()
        .flat_map(|s| s.1.iter().map(|p| p.1))
        .fold(0.6, f64::max)
        .min(20.0);
    log_chart(
        "dt",
        "A 20-box stack with ghosts through it: largest drift in 3 s against the time step",
        (
            "steps per second (dt = 1 / x)",
            "largest horizontal drift (m)",
        ),
        12.0..300.0,
        0.0..top * 1.1,
        &series
            .into_iter()
            .map(|(l, p)| (l, p.into_iter().map(|(x, y)| (x, y.min(20.0))).collect()))
            .collect::<Vec<_>>(),
        Some((0.5, "collapsed above this line")),
    )?;

    // A soft block with ghosts through it.
    let mut csv = String::from("steps_per_second,method,lowest_particle_m\n");
    println!(
        "\nTime step, soft: a soft block resting on the floor with ghosts through it, its lowest particle (m) after 3 s; it rests above -0.05 m"
    );
    let mut rows = Vec::new();
    for method in METHODS {
        let points: Vec<(f32, f32)> = STEPS_PER_SECOND
            .iter()
            .map(|&hz| (hz, soft_rest(hz, method)))
            .collect();
        for &(hz, y) in &points {
            writeln!(csv, "{hz},{method:?},{y}")?;
        }
        let rests = points
            .iter()
            .find(|p| p.1 > -0.05)
            .map(|p| format!("1/{}", p.0));
        println!(
            "{:<8} {}  (largest step at which it rests: {})",
            format!("{method:?}"),
            points
                .iter()
                .map(|(hz, y)| format!("1/{hz}: {y:.3}"))
                .collect::<Vec<_>>()
                .join("  "),
            rests.unwrap_or_else(|| "none".into())
        );
        rows.push((method, points));
    }
    write("soft", &csv)?;
    // The rules rest the block as it rests without the ghosts, to the
    // particle: `NoResponse` leaves it as if they were absent.
    let plain = &rows[0].1;
    for (method, points) in &rows[1..] {
        for (&(hz, y), &(_, alone)) in points.iter().zip(plain) {
            if (y - alone).abs() > 1.0e-4 {
                broken.push(format!(
                    "soft dt 1/{hz}: {method:?} lowest particle {y:.4} m, without the ghosts {alone:.4} m"
                ));
            }
        }
    }

    if broken.is_empty() {
        println!("\nNo rule did worse than plain Rapier. CSV and SVG in docs/stability_*.");
        Ok(())
    } else {
        Err(format!("worse than plain Rapier:\n{}", broken.join("\n")).into())
    }
}
