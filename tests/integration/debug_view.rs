//! The debug view (`RuleDebugRender`, feature `debug-render`) drawn into a
//! recording backend: one line per live pair the rules reach in its rule's
//! colour, tints by how the rules reach each collider, marks, the filter,
//! labels, and a world without rules drawn exactly as Rapier draws it.

use super::rapier::prelude::*;
use super::rules::{
    CollisionRule, Reach, RuleDebugFilter, RuleDebugRender, RuleHooks, RuleLabelBackend,
    RulePalette, Until, WorldRef,
};

use super::scenes::Scene;
use super::{at, ball_joint, cuboid, soft_block};
use CollisionRule::*;

/// What a drawn line was about.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Object {
    Body(RigidBodyHandle),
    Collider(ColliderHandle),
    Aabb(ColliderHandle),
    Contact(ColliderHandle, ColliderHandle),
    Other,
}

/// One line, bit for bit.
#[derive(Clone, Debug, PartialEq)]
struct Line {
    object: Object,
    from: Vec<u32>,
    to: Vec<u32>,
    color: [u32; 4],
}

impl Line {
    fn hsla(&self) -> [f32; 4] {
        self.color.map(f32::from_bits)
    }
}

/// Records every line, and labels.
#[derive(Default)]
struct Recorder {
    lines: Vec<Line>,
    labels: Vec<(ColliderHandle, String)>,
    /// Objects the backend refuses.
    refuse: Option<Object>,
}

fn object_of(object: DebugRenderObject) -> Object {
    match object {
        DebugRenderObject::RigidBody(h, _) => Object::Body(h),
        DebugRenderObject::Collider(h, _) => Object::Collider(h),
        DebugRenderObject::ColliderAabb(h, _, _) => Object::Aabb(h),
        DebugRenderObject::ContactPair(pair, _, _) => {
            Object::Contact(pair.collider1, pair.collider2)
        }
        _ => Object::Other,
    }
}

fn bits(v: Vector) -> Vec<u32> {
    v.to_array().into_iter().map(f32::to_bits).collect()
}

impl DebugRenderBackend for Recorder {
    fn filter_object(&self, object: DebugRenderObject) -> bool {
        self.refuse != Some(object_of(object))
    }

    fn draw_line(&mut self, object: DebugRenderObject, a: Vector, b: Vector, color: DebugColor) {
        self.lines.push(Line {
            object: object_of(object),
            from: bits(a),
            to: bits(b),
            color: color.map(f32::to_bits),
        });
    }
}

impl RuleLabelBackend for Recorder {
    fn draw_label(&mut self, _at: Vector, text: &str, _color: [f32; 4]) {
        self.labels
            .push((ColliderHandle::invalid(), text.to_owned()));
    }
}

impl Recorder {
    /// The lines drawn in `color`.
    fn in_color(&self, color: [f32; 4]) -> Vec<&Line> {
        self.lines.iter().filter(|l| l.hsla() == color).collect()
    }

    /// The lines of a pair of colliders, in either order.
    fn of_pair(&self, a: ColliderHandle, b: ColliderHandle) -> Vec<&Line> {
        self.lines
            .iter()
            .filter(|l| l.object == Object::Contact(a, b) || l.object == Object::Contact(b, a))
            .collect()
    }
}

/// A floor with four cubes resting on it, each with one rule about the
/// floor, a sensor around the `Normal` cube that ignores its response, and
/// two cubes no rule reaches, one on the other.
struct RuledScene {
    scene: Scene,
    hooks: RuleHooks,
    cubes: Vec<(CollisionRule, RigidBodyHandle, ColliderHandle)>,
    sensor: ColliderHandle,
    plain: [ColliderHandle; 2],
}

fn ruled_scene() -> RuledScene {
    let mut scene = Scene::new();
    let mut hooks = RuleHooks::default();
    let mut cubes = Vec::new();
    for (i, rule) in [Normal, NoResponse, NoContacts, NoPair]
        .into_iter()
        .enumerate()
    {
        let (body, collider) = scene.cube(-6.0 + 3.0 * i as f32, 0.5);
        hooks.rules_mut().set_specific(body, scene.ground, rule);
        cubes.push((rule, body, collider));
    }
    let holder = scene
        .world
        .insert_body(RigidBodyBuilder::fixed().translation(at(-6.0, 0.5)));
    let sensor = scene
        .world
        .insert_collider(ColliderBuilder::ball(1.0).sensor(true), Some(holder));
    hooks
        .rules_mut()
        .set_specific(holder, cubes[0].1, NoResponse);
    let plain = [scene.cube(8.0, 0.5).1, scene.cube(8.0, 1.5).1];
    hooks.step(&mut scene.world);
    RuledScene {
        scene,
        hooks,
        cubes,
        sensor,
        plain,
    }
}

fn drawn(view: &mut RuleDebugRender, s: &RuledScene) -> Recorder {
    let mut recorder = Recorder::default();
    view.render(&mut recorder, &s.hooks, &s.scene.world);
    recorder
}

#[test]
fn each_live_pair_the_rules_reach_is_one_line_in_its_rules_colour() {
    let s = ruled_scene();
    let palette = RulePalette::default();
    let floor = s.scene.floor;
    let recorder = drawn(&mut RuleDebugRender::default(), &s);
    for &(rule, _, cube) in &s.cubes {
        let lines = recorder.of_pair(cube, floor);
        let live = s.hooks.pair_rule(&s.scene.world, cube, floor);
        if rule == NoPair {
            assert_eq!(live, None);
            assert!(lines.is_empty(), "a NoPair pair draws nothing: {lines:?}");
        } else {
            assert_eq!(live, Some(rule));
            let color = palette.rule(Some(rule)).hsla(1.0);
            assert_eq!(lines.len(), 1, "{rule:?}: {lines:?}");
            assert_eq!(lines[0].hsla(), color, "{rule:?}");
        }
    }
    // The sensor's pair with the Normal cube is an intersection pair: its
    // line names the first collider.
    let orange = palette.no_response.hsla(1.0);
    let no_response = recorder.in_color(orange);
    assert_eq!(
        no_response.len(),
        2,
        "the NoResponse cube and the sensor: {no_response:?}"
    );
    assert!(
        no_response
            .iter()
            .any(|l| l.object == Object::Collider(s.sensor)
                || l.object == Object::Collider(s.cubes[0].2)),
        "{no_response:?}"
    );
    // The floor is reached (it names the cubes), so its pair with a cube no
    // rule names is drawn with the rule it gets; a pair of two unreached
    // colliders is Rapier's alone.
    let [plain, on_it] = s.plain;
    assert_eq!(s.hooks.reach(plain), Reach::Unreached);
    let lines = recorder.of_pair(plain, floor);
    assert_eq!(lines.len(), 1, "{lines:?}");
    assert_eq!(lines[0].hsla(), palette.normal.hsla(1.0));
    assert!(s.scene.touching(plain, on_it), "the plain cubes touch");
    assert!(recorder.of_pair(plain, on_it).is_empty());
    for rule in [NoPair, Defer] {
        let color = palette.rule(Some(rule)).hsla(1.0);
        assert!(recorder.in_color(color).is_empty(), "{rule:?}");
    }
}

#[test]
fn colliders_are_tinted_by_how_the_rules_reach_them() {
    let s = ruled_scene();
    let palette = RulePalette::default();
    let style = DebugRenderStyle::default();
    let recorder = drawn(&mut RuleDebugRender::default(), &s);
    let hue_and_saturation = |c: [f32; 4]| [c[0], c[1]];
    let reach = |c| s.hooks.reach(c);
    // NoContacts has no group form: its cube carries the hook; the other
    // entries are Rapier groups.
    // The sensor's NoResponse with the Normal cube has no group form that
    // leaves the cube's Normal pairs alone: the cube carries the hook too.
    assert_eq!(reach(s.cubes[2].2), Reach::Hooked);
    assert_eq!(reach(s.cubes[1].2), Reach::Planned);
    assert_eq!(reach(s.scene.floor), Reach::Planned);
    assert_eq!(reach(s.plain[0]), Reach::Unreached);
    // A sensor pair's line names its first collider: the shapes are the
    // lines not in a rule's colour.
    let rules = CollisionRule::ALL.map(|r| palette.rule(Some(r)).hsla(1.0));
    let mut colliders: Vec<ColliderHandle> = s.cubes.iter().map(|c| c.2).collect();
    colliders.extend([s.scene.floor, s.sensor, s.plain[0], s.plain[1]]);
    let mut tints = std::collections::HashSet::new();
    for collider in colliders {
        let shape: Vec<_> = recorder
            .lines
            .iter()
            .filter(|l| l.object == Object::Collider(collider) && !rules.contains(&l.hsla()))
            .collect();
        tints.insert(reach(collider));
        assert!(!shape.is_empty());
        for line in shape {
            let color = line.hsla();
            match palette.reach(reach(collider)) {
                Some(tint) => assert_eq!(
                    hue_and_saturation(color),
                    hue_and_saturation(tint.hsla(1.0)),
                    "{:?}",
                    reach(collider)
                ),
                None => assert_eq!(
                    color, style.collider_dynamic_color,
                    "unreached: Rapier's colour"
                ),
            }
        }
    }
    assert_eq!(
        tints.len(),
        3,
        "every way of being reached is in the scene: {tints:?}"
    );
    // Without tints, every shape has Rapier's colour.
    let mut view = RuleDebugRender {
        tints: false,
        ..RuleDebugRender::default()
    };
    let plain = drawn(&mut view, &s);
    let cube = s.cubes[2].2;
    assert!(
        plain
            .lines
            .iter()
            .filter(|l| l.object == Object::Collider(cube))
            .all(|l| l.hsla() == style.collider_dynamic_color)
    );
}

#[test]
fn the_filter_keeps_one_node_one_rule_or_the_hooked_pairs() {
    let s = ruled_scene();
    let palette = RulePalette::default();
    let pair_lines = |r: &Recorder| -> Vec<[f32; 4]> {
        let rules = [Normal, NoResponse, NoContacts].map(|r| palette.rule(Some(r)).hsla(1.0));
        r.lines
            .iter()
            .map(Line::hsla)
            .filter(|c| rules.contains(c))
            .collect()
    };
    let mut view = RuleDebugRender::default();
    let all = s.hooks.pairs(&s.scene.world).count();
    // Every live pair but the plain cubes' one.
    assert_eq!(pair_lines(&drawn(&mut view, &s)).len(), all - 1);
    assert_eq!(all, 6);

    view.filter = RuleDebugFilter::default().rule(NoResponse);
    let lines = pair_lines(&drawn(&mut view, &s));
    assert_eq!(lines, [palette.no_response.hsla(1.0); 2]);

    // The Normal cube's body: its floor pair and the sensor's pair.
    view.filter = RuleDebugFilter::default().node(s.cubes[0].1);
    let mut lines = pair_lines(&drawn(&mut view, &s));
    lines.sort_by(|a, b| a[0].total_cmp(&b[0]));
    assert_eq!(
        lines,
        [palette.no_response.hsla(1.0), palette.normal.hsla(1.0)]
    );

    // The pairs of the hooked cubes: the Normal cube's two, the NoContacts one.
    view.filter = RuleDebugFilter::default().hooked_only();
    let recorder = drawn(&mut view, &s);
    let mut lines = pair_lines(&recorder);
    lines.sort_by(|a, b| a[0].total_cmp(&b[0]));
    let expected = [palette.no_response, palette.no_contacts, palette.normal].map(|c| c.hsla(1.0));
    assert_eq!(lines, expected);
    // Only hooked colliders are tinted.
    let planned = palette.planned.hsla(1.0);
    assert!(recorder.lines.iter().all(|l| l.hsla()[..2] != planned[..2]));

    // The backend's own filter refuses the pair's object.
    let mut view = RuleDebugRender::default();
    let mut recorder = Recorder {
        refuse: Some(Object::Contact(s.cubes[1].2, s.scene.floor)),
        ..Recorder::default()
    };
    view.render(&mut recorder, &s.hooks, &s.scene.world);
    let refused = Recorder {
        refuse: Some(Object::Contact(s.scene.floor, s.cubes[1].2)),
        ..Recorder::default()
    };
    let mut recorder2 = refused;
    view.render(&mut recorder2, &s.hooks, &s.scene.world);
    let orange = palette.no_response.hsla(1.0);
    assert_eq!(
        recorder
            .in_color(orange)
            .len()
            .min(recorder2.in_color(orange).len()),
        1,
        "the refused pair is not drawn, the sensor's is"
    );
}

#[test]
fn overrides_and_rules_with_an_end_are_marked() {
    let mut s = ruled_scene();
    let palette = RulePalette::default();
    let (normal_cube, floor) = (s.cubes[0].2, s.scene.floor);
    assert!(
        s.hooks
            .set_pair_rule(&s.scene.world, normal_cube, floor, NoContacts)
    );
    let ending = s.cubes[1].1;
    s.hooks
        .rules_mut()
        .set_specific_until(ending, s.scene.ground, NoResponse, Until::steps(100));
    s.hooks.step(&mut s.scene.world);
    let recorder = drawn(&mut RuleDebugRender::default(), &s);
    let yellow = recorder.in_color(palette.overridden.hsla(1.0));
    assert_eq!(yellow.len(), DIM, "a cross along the axes: {yellow:?}");
    assert!(
        yellow
            .iter()
            .all(|l| matches!(l.object, Object::Contact(..)))
    );
    let pink = recorder.in_color(palette.ending.hsla(1.0));
    assert_eq!(pink.len(), 2, "a cross across the axes: {pink:?}");
    // The mark sits at the middle of its pair's line.
    let line = &recorder.of_pair(normal_cube, floor)[0];
    let middle: Vec<f32> = line
        .from
        .iter()
        .zip(&line.to)
        .map(|(a, b)| (f32::from_bits(*a) + f32::from_bits(*b)) * 0.5)
        .collect();
    let mark: Vec<f32> = yellow[0]
        .from
        .iter()
        .zip(&yellow[0].to)
        .map(|(a, b)| (f32::from_bits(*a) + f32::from_bits(*b)) * 0.5)
        .collect();
    for (m, k) in middle.iter().zip(&mark) {
        assert!(
            (m - k).abs() < 1e-5,
            "mark at {mark:?}, line's middle {middle:?}"
        );
    }
    let mut view = RuleDebugRender {
        marks: false,
        ..RuleDebugRender::default()
    };
    assert!(
        drawn(&mut view, &s)
            .in_color(palette.overridden.hsla(1.0))
            .is_empty()
    );
}

#[test]
fn labels_say_what_explain_says() {
    let mut s = ruled_scene();
    let (normal_cube, floor) = (s.cubes[0].2, s.scene.floor);
    assert!(
        s.hooks
            .set_pair_rule(&s.scene.world, normal_cube, floor, NoContacts)
    );
    s.hooks.step(&mut s.scene.world);
    let mut recorder = Recorder::default();
    RuleDebugRender::default().render_labels(&mut recorder, &s.hooks, &s.scene.world);
    // Each label as its rule, what decided, and the two nodes in either
    // order; `, hooked` counted apart.
    let hooked_labels = recorder
        .labels
        .iter()
        .filter(|(_, t)| t.ends_with(", hooked"))
        .count();
    let mut labels: Vec<(String, String, Vec<String>)> = recorder
        .labels
        .iter()
        .map(|(_, text)| {
            let text = text.trim_end_matches(", hooked");
            let (rule, why) = text.split_once(": ").expect("rule: why");
            let (stage, nodes) = why.split_once(' ').unwrap_or((why, ""));
            let mut nodes: Vec<String> = nodes
                .split(" / ")
                .filter(|n| !n.is_empty())
                .map(str::to_owned)
                .collect();
            nodes.sort();
            (rule.to_owned(), stage.to_owned(), nodes)
        })
        .collect();
    labels.sort();
    let name = |b: RigidBodyHandle| format!("body {}", b.into_raw_parts().0);
    let holder = s.scene.world.colliders[s.sensor].parent().unwrap();
    let ground = s.scene.ground;
    let entry = |rule: &str, a: RigidBodyHandle, b: RigidBodyHandle| {
        let mut nodes = vec![name(a), name(b)];
        nodes.sort();
        (rule.to_owned(), "specific".to_owned(), nodes)
    };
    let mut expected = vec![
        ("NoContacts".to_owned(), "override".to_owned(), vec![]),
        entry("NoResponse", s.cubes[1].1, ground),
        entry("NoContacts", s.cubes[2].1, ground),
        entry("NoResponse", holder, s.cubes[0].1),
        // The plain cube on the reached floor.
        (
            "Normal".to_owned(),
            "default".to_owned(),
            vec!["rule".to_owned()],
        ),
    ];
    expected.sort();
    assert_eq!(labels, expected);
    let hooked_pairs = s
        .hooks
        .pairs(&s.scene.world)
        .filter(|&(a, b, _)| [a, b].iter().any(|&c| s.hooks.reach(c) == Reach::Hooked))
        .count();
    assert_eq!(hooked_labels, hooked_pairs, "{:?}", recorder.labels);
}

/// Bodies of every type, joints, a sensor, contacts and a soft body; the
/// boxes' bodies.
fn every_kind_world() -> (PhysicsWorld, Vec<RigidBodyHandle>) {
    let mut world = PhysicsWorld::new();
    let ground = world.insert_body(RigidBodyBuilder::fixed().translation(at(0.0, -0.5)));
    world.insert_collider(cuboid(20.0, 0.5, 20.0), Some(ground));
    let mut boxes: Vec<RigidBodyHandle> = Vec::new();
    for i in 0..4 {
        let body = world
            .insert_body(RigidBodyBuilder::dynamic().translation(at(-3.0 + 2.0 * i as f32, 1.0)));
        world.insert_collider(cuboid(0.5, 0.5, 0.5), Some(body));
        if let Some(&previous) = boxes.last() {
            world.insert_impulse_joint(previous, body, ball_joint(at(-2.0, 0.0)));
        }
        boxes.push(body);
    }
    let platform =
        world.insert_body(RigidBodyBuilder::kinematic_velocity_based().translation(at(6.0, 2.0)));
    world.insert_collider(cuboid(1.0, 0.2, 1.0), Some(platform));
    world.insert_collider(
        ColliderBuilder::ball(1.5)
            .sensor(true)
            .translation(at(-3.0, 1.0)),
        None,
    );
    world.insert_soft_body(soft_block(at(10.0, 0.8), 0.5));
    (world, boxes)
}

#[test]
fn a_world_without_rules_is_drawn_exactly_as_rapier_draws_it() {
    // Every mode of Rapier's drawing, at several instants.
    let (mut world, _) = every_kind_world();
    let mut hooks = RuleHooks::default();
    let mut view =
        RuleDebugRender::new(DebugRenderPipeline::render_all(DebugRenderStyle::default()));
    let mut rapiers = DebugRenderPipeline::render_all(DebugRenderStyle::default());
    for step in 0..40 {
        hooks.step(&mut world);
        if step % 13 != 0 {
            continue;
        }
        let mut ours = Recorder::default();
        view.render(&mut ours, &hooks, &world);
        let mut theirs = Recorder::default();
        world.debug_render(&mut rapiers, &mut theirs);
        assert!(
            theirs.lines.len() > 100,
            "Rapier drew {} lines",
            theirs.lines.len()
        );
        assert!(
            ours.lines == theirs.lines,
            "step {step}: {} lines drawn, Rapier drew {}",
            ours.lines.len(),
            theirs.lines.len()
        );
    }
}

#[test]
fn rapiers_part_is_drawn_as_rapier_draws_it_in_every_mode_where_rules_reach_some_colliders() {
    let (mut world, boxes) = every_kind_world();
    let mut hooks = RuleHooks::default();
    hooks
        .rules_mut()
        .set_specific(boxes[0], boxes[1], CollisionRule::NoContacts);
    hooks
        .rules_mut()
        .set_personal(boxes[3], CollisionRule::NoResponse);
    for _ in 0..20 {
        hooks.step(&mut world);
    }
    let reached: Vec<ColliderHandle> = world
        .colliders
        .iter()
        .map(|(h, _)| h)
        .filter(|&h| hooks.reach(h) != Reach::Unreached)
        .collect();
    assert!(reached.len() >= 3 && reached.len() < world.colliders.len());
    let mut modes: Vec<DebugRenderMode> = DebugRenderMode::all().iter().collect();
    modes.push(DebugRenderMode::all());
    modes.push(DebugRenderMode::default());
    for mode in modes {
        let style = DebugRenderStyle::default();
        // A bare pipeline's sets, with the joints and soft bodies.
        let bare = WorldRef::new(&world.narrow_phase, &world.bodies, &world.colliders)
            .with_joints(&world.impulse_joints, &world.multibody_joints)
            .with_soft_bodies(&world.soft_bodies);
        let mut theirs = Recorder::default();
        DebugRenderPipeline::new(style, mode).render(
            &mut theirs,
            &world.bodies,
            &world.colliders,
            &world.impulse_joints,
            &world.multibody_joints,
            &world.narrow_phase,
            &world.soft_bodies,
        );
        for tints in [false, true] {
            let mut view = RuleDebugRender {
                tints,
                ..RuleDebugRender::new(DebugRenderPipeline::new(style, mode))
            };
            let mut ours = Recorder::default();
            view.render(&mut ours, &hooks, bare);
            assert!(ours.lines.len() >= theirs.lines.len(), "{mode:?}");
            let rapiers_part = &ours.lines[..theirs.lines.len()];
            for (o, t) in rapiers_part.iter().zip(&theirs.lines) {
                let tinted =
                    tints && matches!(o.object, Object::Collider(c) if reached.contains(&c));
                if tinted {
                    // Only the hue and saturation differ.
                    let same = (&o.object, &o.from, &o.to, &o.color[2..])
                        == (&t.object, &t.from, &t.to, &t.color[2..]);
                    assert!(same, "{mode:?}, tinted: {o:?} against Rapier's {t:?}");
                } else {
                    assert_eq!(o, t, "{mode:?}, tints {tints}");
                }
            }
            // What follows is the rules' lines: pairs and marks.
            assert!(
                ours.lines[theirs.lines.len()..]
                    .iter()
                    .all(|l| !matches!(l.object, Object::Body(_) | Object::Aabb(_))),
                "{mode:?}"
            );
        }
    }
}

#[test]
fn render_tints_draws_only_the_shapes_the_rules_reach() {
    let s = ruled_scene();
    let palette = RulePalette::default();
    let mut view = RuleDebugRender::default();
    let mut tints = Recorder::default();
    view.render_tints(&mut tints, &s.hooks, &s.scene.world);
    let mut full = Recorder::default();
    view.render(&mut full, &s.hooks, &s.scene.world);
    let rules = CollisionRule::ALL.map(|r| palette.rule(Some(r)).hsla(1.0));
    // The same shape lines as the full view's, for the reached colliders.
    let expected: Vec<&Line> = full
        .lines
        .iter()
        .filter(|l| match l.object {
            Object::Collider(c) => {
                s.hooks.reach(c) != Reach::Unreached && !rules.contains(&l.hsla())
            }
            _ => false,
        })
        .collect();
    assert!(!expected.is_empty());
    assert_eq!(tints.lines.iter().collect::<Vec<_>>(), expected);
    assert!(
        tints
            .lines
            .iter()
            .all(|l| l.object != Object::Collider(s.plain[0]))
    );
}
