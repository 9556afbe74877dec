//! What drawing the rules costs (feature `debug-render`): the debug view
//! (`RuleDebugRender::render`) against Rapier's own debug rendering of the
//! same world, and the rules' part alone (`render_rules`) against one pass
//! over the live pairs (`RuleHooks::pairs`), on the awake pile of
//! `benches/step.rs` (1,000 boxes on a floor) with no rules, and with every
//! box in a group (a `NoPair` rule with a group nobody is in: every pair is
//! reached, planned into Rapier's groups, and drawn).
//!
//! `cargo bench --features debug-render --bench debug_view` prints, for
//! each, the median [min, max] over five repeats of the ratio of summed
//! times, the two measured back to back, alternating which goes first.

use std::hint::black_box;
use std::time::{Duration, Instant};

use rapier_collision_rules::dim3 as rules;
use rapier3d as rapier;
use rapier3d::prelude::*;
use rules::{CollisionRule, RuleDebugRender, RuleHooks};

#[allow(dead_code)]
mod common;
#[path = "common/space3.rs"]
mod space;

/// A backend that only adds up what it is given.
#[derive(Default)]
struct Sum(f32);

impl DebugRenderBackend for Sum {
    fn draw_line(&mut self, _: DebugRenderObject, a: Vector, b: Vector, color: DebugColor) {
        self.0 += a.x + b.y + color[0];
    }
}

const DRAWS: usize = 100;
const REPEATS: usize = 5;

/// The ratio of the summed times of `b` to `a`, each drawn `DRAWS` times
/// a repeat, back to back, alternating which goes first.
fn ratio(mut a: impl FnMut() -> f32, mut b: impl FnMut() -> f32) -> (f64, f64, f64, Duration) {
    let mut ratios = Vec::new();
    let mut a_time = Duration::ZERO;
    for repeat in 0..REPEATS {
        let (mut ta, mut tb) = (Duration::ZERO, Duration::ZERO);
        for draw in 0..DRAWS {
            let a_first = (repeat + draw) % 2 == 0;
            for turn in 0..2 {
                let start = Instant::now();
                if (turn == 0) == a_first {
                    black_box(a());
                    ta += start.elapsed();
                } else {
                    black_box(b());
                    tb += start.elapsed();
                }
            }
        }
        a_time += ta;
        ratios.push(tb.as_secs_f64() / ta.as_secs_f64());
    }
    ratios.sort_by(f64::total_cmp);
    let per_draw = a_time / (REPEATS * DRAWS) as u32;
    (
        ratios[REPEATS / 2],
        ratios[0],
        ratios[REPEATS - 1],
        per_draw,
    )
}

fn main() {
    for variant in ["none", "groups"] {
        let (mut world, boxes) = common::pile(1000, false);
        let mut hooks = RuleHooks::default();
        if variant == "groups" {
            let rules = hooks.rules_mut();
            let (boxes_group, nobody) = (rules.create_group(), rules.create_group());
            rules.set_group_rule(boxes_group, nobody, CollisionRule::NoPair);
            for &(body, _) in &boxes {
                rules.set_group(body, Some(boxes_group));
            }
        }
        for _ in 0..5 {
            hooks.step(&mut world);
        }
        let live = hooks.pairs(&world).count();
        let mut rapiers = DebugRenderPipeline::default();
        let mut view = RuleDebugRender::default();
        let (m, lo, hi, rapier_time) = ratio(
            || {
                let mut sum = Sum::default();
                world.debug_render(&mut rapiers, &mut sum);
                sum.0
            },
            || {
                let mut sum = Sum::default();
                view.render(&mut sum, &hooks, &world);
                sum.0
            },
        );
        println!(
            "debug_view/{variant}: view / Rapier's drawing {m:.3} [{lo:.3}, {hi:.3}] \
             (Rapier's {rapier_time:?} a draw, {live} live pairs)"
        );
        let view = RuleDebugRender::default();
        let (m, lo, hi, pass_time) = ratio(
            || hooks.pairs(&world).count() as f32,
            || {
                let mut sum = Sum::default();
                view.render_rules(&mut sum, &hooks, &world);
                sum.0
            },
        );
        println!(
            "debug_view/{variant}: rules' part / a pass over the live pairs {m:.3} [{lo:.3}, {hi:.3}] \
             (the pass {pass_time:?})"
        );
    }
}
