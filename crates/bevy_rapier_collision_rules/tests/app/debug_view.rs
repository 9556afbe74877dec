//! The debug plugin's output (the lines it hands to the gizmos) for the
//! scene of the core's debug-view tests: one line per live pair the rules
//! reach in its rule's colour naming the pair's entities, tinted shapes of
//! the reached colliders, toggled per context at runtime, filtered.

use CollisionRule::*;
use bevy::prelude::*;
use bevy_rapier::prelude::*;
use bevy_rapier_collision_rules::prelude::*;

use super::scene::{Sim, ball, floor};

fn color(c: RuleColor) -> Color {
    let [h, s, l, a] = c.hsla(1.0);
    Color::hsla(h, s, l, a)
}

use bevy_rapier_collision_rules::{Reach, RuleColor};

fn debug_sim() -> Sim {
    Sim::from_plugins((
        RapierPhysicsPlugin::<CollisionRulesHooks>::default(),
        CollisionRulesPlugin::default(),
        CollisionRulesDebugPlugin::default(),
    ))
}

/// A floor, four balls resting on it each with one rule about it, and a
/// ball no rule names.
struct Scene {
    sim: Sim,
    floor: Entity,
    balls: Vec<(CollisionRule, Entity)>,
    plain: Entity,
}

fn scene() -> Scene {
    let mut sim = debug_sim();
    let floor = sim.spawn(floor());
    let balls = [Normal, NoResponse, NoContacts, NoPair]
        .into_iter()
        .enumerate()
        .map(|(i, rule)| {
            let ball = sim.spawn((
                ball(-3.0 + 1.5 * i as f32, 0.24),
                SpecificRules::new().with(floor, rule),
            ));
            (rule, ball)
        })
        .collect();
    let plain = sim.spawn(ball(3.0, 0.24));
    sim.run(2);
    Scene {
        sim,
        floor,
        balls,
        plain,
    }
}

fn lines(sim: &mut Sim, context: Entity) -> Vec<RuleDebugLine> {
    sim.app
        .world()
        .get::<RuleDebugLines>(context)
        .expect("the plugin gives every context its lines")
        .lines()
        .to_vec()
}

/// A context's view settings, to change at runtime.
fn view(sim: &mut Sim, context: Entity) -> Mut<'_, CollisionRulesDebug> {
    sim.app
        .world_mut()
        .get_mut::<CollisionRulesDebug>(context)
        .expect("the plugin gives every context its view")
}

fn pair_lines(lines: &[RuleDebugLine], a: Entity, b: Entity) -> Vec<RuleDebugLine> {
    lines
        .iter()
        .filter(|l| {
            l.object == RuleDebugObject::Pair(a, b) || l.object == RuleDebugObject::Pair(b, a)
        })
        .copied()
        .collect()
}

#[test]
fn each_live_pair_the_rules_reach_is_a_line_in_its_rules_colour() {
    let mut s = scene();
    let context = s.sim.context();
    let palette = RulePalette::default();
    let drawn = lines(&mut s.sim, context);
    for &(rule, ball) in &s.balls {
        let of_pair = pair_lines(&drawn, ball, s.floor);
        let live = s.sim.pair_rule(ball, s.floor);
        if rule == NoPair {
            assert_eq!(live, None);
            assert!(
                of_pair.is_empty(),
                "a NoPair pair draws nothing: {of_pair:?}"
            );
        } else {
            assert_eq!(live, Some(rule));
            assert_eq!(of_pair.len(), 1, "{rule:?}: {of_pair:?}");
            assert_eq!(
                of_pair[0].color,
                color(palette.rule(Some(rule))),
                "{rule:?}"
            );
        }
    }
    // The floor is reached: its pair with the plain ball is drawn (Normal).
    let plain = pair_lines(&drawn, s.plain, s.floor);
    assert_eq!(plain.len(), 1, "{plain:?}");
    assert_eq!(plain[0].color, color(palette.normal));
    // Tints: the floor's shape, and the NoContacts ball's (hooked); the
    // plain ball keeps bevy_rapier's own drawing.
    let tinted = |e: Entity| {
        drawn
            .iter()
            .filter(|l| l.object == RuleDebugObject::Collider(e))
            .count()
    };
    assert!(tinted(s.floor) > 0 && tinted(s.balls[2].1) > 0);
    assert_eq!(tinted(s.plain), 0);
    let hooked = palette.hooked.hsla(1.0);
    let no_contacts_ball = drawn
        .iter()
        .find(|l| l.object == RuleDebugObject::Collider(s.balls[2].1))
        .unwrap();
    let hsla = Hsla::from(no_contacts_ball.color);
    assert!(
        (hsla.hue - hooked[0]).abs() < 1e-3 && (hsla.saturation - hooked[1]).abs() < 1e-3,
        "the hooked ball's tint: {hsla:?}"
    );
}

#[test]
fn the_view_is_toggled_and_filtered_per_context_at_runtime() {
    let mut s = scene();
    let first = s.sim.context();
    let second = s.sim.spawn((
        RapierContextSimulation::default(),
        RapierConfiguration::new(1.0),
    ));
    let link = RapierContextEntityLink(second);
    let floor2 = s.sim.spawn((floor(), link));
    s.sim.spawn((
        ball(0.0, 0.24),
        link,
        SpecificRules::new().with(floor2, NoResponse),
    ));
    s.sim.run(2);
    assert!(!lines(&mut s.sim, first).is_empty());
    assert!(!lines(&mut s.sim, second).is_empty());

    view(&mut s.sim, first).enabled = false;
    s.sim.run(1);
    assert!(
        lines(&mut s.sim, first).is_empty(),
        "off in the first context"
    );
    assert!(
        !lines(&mut s.sim, second).is_empty(),
        "still on in the second"
    );

    // Back on, for one ball only, pairs without tints.
    {
        let mut debug = view(&mut s.sim, first);
        debug.enabled = true;
        debug.entity = Some(s.balls[1].1);
        debug.tints = false;
    }
    s.sim.run(1);
    let drawn = lines(&mut s.sim, first);
    assert_eq!(drawn.len(), 1, "{drawn:?}");
    assert_eq!(drawn[0].color, color(RulePalette::default().no_response));

    // The pairs the hook answers: the NoContacts ball's (it carries the
    // hook), with its tint.
    {
        let mut debug = view(&mut s.sim, first);
        debug.entity = None;
        debug.tints = true;
        debug.hooked_only = true;
    }
    s.sim.run(1);
    let drawn = lines(&mut s.sim, first);
    let pairs: Vec<_> = drawn
        .iter()
        .filter(|l| matches!(l.object, RuleDebugObject::Pair(..)))
        .collect();
    // The NoContacts ball carries the hook; every pair drawn has a hooked
    // collider, and only hooked colliders are tinted.
    let hooked = |sim: &mut Sim, e: Entity| {
        let handle = sim.app.world().get::<RapierColliderHandle>(e).unwrap().0;
        sim.rules().hooks().reach(handle) == Reach::Hooked
    };
    assert!(
        pair_lines(&drawn, s.balls[2].1, s.floor)
            .iter()
            .any(|l| l.color == color(RulePalette::default().no_contacts)),
        "{pairs:?}"
    );
    for line in &drawn {
        match line.object {
            RuleDebugObject::Pair(a, b) => {
                assert!(hooked(&mut s.sim, a) || hooked(&mut s.sim, b), "{line:?}")
            }
            RuleDebugObject::Collider(c) => assert!(hooked(&mut s.sim, c), "{line:?}"),
        }
    }
    view(&mut s.sim, first).hooked_only = false;

    // One rule.
    {
        let mut debug = view(&mut s.sim, first);
        debug.tints = false;
        debug.rule = Some(Normal);
    }
    s.sim.run(1);
    let drawn = lines(&mut s.sim, first);
    assert_eq!(
        drawn.len(),
        2,
        "the Normal ball's and the plain ball's pairs: {drawn:?}"
    );
}

#[test]
fn a_plugin_that_starts_off_draws_nothing_until_turned_on() {
    let mut sim = Sim::from_plugins((
        RapierPhysicsPlugin::<CollisionRulesHooks>::default(),
        CollisionRulesPlugin::default(),
        CollisionRulesDebugPlugin::default().off(),
    ));
    let floor = sim.spawn(floor());
    sim.spawn((ball(0.0, 0.24), PersonalRule(NoResponse)));
    sim.run(2);
    let context = sim.context();
    assert!(lines(&mut sim, context).is_empty());
    assert_eq!(
        sim.app
            .world()
            .get::<CollisionRulesDebug>(context)
            .map(|d| d.enabled),
        Some(false)
    );
    view(&mut sim, context).enabled = true;
    sim.run(1);
    let drawn = lines(&mut sim, context);
    assert!(
        drawn
            .iter()
            .any(|l| matches!(l.object, RuleDebugObject::Pair(a, b) if a == floor || b == floor))
    );
}

/// Bevy's gizmo storage without its render-side plugins (which a headless
/// app does not have).
struct HeadlessGizmos;

impl Plugin for HeadlessGizmos {
    fn build(&self, app: &mut App) {
        use bevy::gizmos::{AppGizmoBuilder, GizmoAsset};
        app.add_plugins(bevy::asset::AssetPlugin::default())
            .init_asset::<GizmoAsset>()
            .init_gizmo_group::<DefaultGizmoConfigGroup>();
    }
}

#[test]
fn the_lines_reach_bevys_gizmos() {
    let mut sim = Sim::from_plugins((
        HeadlessGizmos,
        RapierPhysicsPlugin::<CollisionRulesHooks>::default(),
        CollisionRulesPlugin::default(),
        CollisionRulesDebugPlugin::default(),
    ));
    sim.spawn(floor());
    sim.spawn((ball(0.0, 0.24), PersonalRule(NoResponse)));
    sim.run(2);
    let context = sim.context();
    let drawn = lines(&mut sim, context);
    assert!(!drawn.is_empty());
    // Each line's two ends, in the frame's gizmo buffer.
    let assets = sim
        .app
        .world()
        .resource::<Assets<bevy::gizmos::GizmoAsset>>();
    let positions: usize = assets
        .iter()
        .map(|(_, a)| a.buffer().list_positions.len())
        .sum();
    assert_eq!(positions, 2 * drawn.len());
}

#[test]
fn the_view_draws_every_frame_whatever_schedule_the_physics_steps_in() {
    let mut sim = Sim::from_plugins((
        RapierPhysicsPlugin::<CollisionRulesHooks>::default().in_fixed_schedule(),
        CollisionRulesPlugin::default().in_fixed_schedule(),
        CollisionRulesDebugPlugin::default(),
    ));
    let floor = sim.spawn(floor());
    let ball = sim.spawn((
        ball(0.0, 0.24),
        SpecificRules::new().with(floor, NoResponse),
    ));
    sim.run(5);
    let context = sim.context();
    let drawn = lines(&mut sim, context);
    let pair = pair_lines(&drawn, ball, floor);
    assert_eq!(pair.len(), 1, "{drawn:?}");
    assert_eq!(pair[0].color, color(RulePalette::default().no_response));
}
