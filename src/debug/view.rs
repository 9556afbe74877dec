//! The debug view: what Rapier's debug rendering draws, with the shapes of
//! the colliders the rules reach tinted, then a line for each live pair the
//! rules reach in its rule's colour, with marks for overrides and ends.

use super::super::rapier::prelude::*;

use super::super::hooks::{PairReach, WorldRef};
use super::super::{CollisionRule, RuleHooks};
use super::label::label_text;
use super::tint::Tinted;
use super::{RuleDebugFilter, RuleLabelBackend, RulePalette};

/// Rapier's debug rendering with the rules drawn over it, through the
/// project's own [`DebugRenderBackend`] (feature `debug-render`).
///
/// [`render`](Self::render) draws what Rapier's own pipeline draws, in the
/// same order, and then the rules (`docs/semantics.md`, "Seeing the rules"):
///
/// - **tints**: the shape of a collider the rules reach is drawn in the
///   palette's hue for [`Reach::Planned`](super::super::Reach::Planned)
///   (teal: the planner wrote Rapier groups) or
///   [`Reach::Hooked`](super::super::Reach::Hooked) (violet: it carries a hook
///   flag the crate gave it, the hook answering its pairs or modifying
///   their contacts), keeping Rapier's lightness, so sleeping colliders stay
///   dim; an unreached collider keeps Rapier's colour;
/// - **pairs**: a line between the centres of the two colliders of each
///   live pair the rules reach, in its rule's colour (`NoContacts` and
///   `NoResponse` pairs included; a `NoPair` pair is not live and has
///   none). Pairs of two unreached colliders are plain Rapier: Rapier's
///   own contacts mode draws them;
/// - **marks**: a cross at the middle of the line of a pair whose rule is
///   an override (`set_pair_rule`, yellow, along the axes) or ends
///   ([`Until`](super::super::Until), pink, across them).
///
/// A world the rules do not reach (no rule, and no full pass: no
/// calculator, pair-created callback or `Manual` policy, and the planner
/// on; see [`StepStats::full_pass`](super::super::StepStats::full_pass),
/// under which every collider is hooked) is drawn exactly as Rapier draws
/// it.
/// Nothing is kept between frames and nothing runs while the view is not
/// drawn; drawing it costs Rapier's drawing and a pass over the live pairs.
///
/// ```
/// use rapier3d::prelude::*;
/// use rapier_collision_rules::{CollisionRule, RuleDebugRender, RuleHooks};
///
/// /// A backend that counts lines by colour (a real one draws them).
/// #[derive(Default)]
/// struct Lines(Vec<[f32; 4]>);
///
/// impl DebugRenderBackend for Lines {
///     fn draw_line(&mut self, _: DebugRenderObject, _: Vector, _: Vector, color: DebugColor) {
///         self.0.push(color);
///     }
/// }
///
/// let mut world = PhysicsWorld::new();
/// let ground = world.insert_body(RigidBodyBuilder::fixed());
/// world.insert_collider(ColliderBuilder::cuboid(10.0, 0.5, 10.0), Some(ground));
/// let ghost = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.9, 0.0)));
/// world.insert_collider(ColliderBuilder::ball(0.5), Some(ghost));
/// let mut hooks = RuleHooks::default();
/// hooks.rules_mut().set_specific(ghost, ground, CollisionRule::NoResponse);
/// hooks.step(&mut world);
///
/// let mut view = RuleDebugRender::default();
/// let mut lines = Lines::default();
/// view.render(&mut lines, &hooks, &world);
/// let orange = view.palette.no_response.hsla(1.0);
/// assert_eq!(lines.0.iter().filter(|&&c| c == orange).count(), 1, "one NoResponse pair");
/// ```
pub struct RuleDebugRender {
    /// Rapier's own pipeline, with its style and mode: what it draws is
    /// drawn first, as Rapier draws it.
    pub pipeline: DebugRenderPipeline,
    /// The colours of the rules.
    pub palette: RulePalette,
    /// Which pairs and colliders the rules are drawn for.
    pub filter: RuleDebugFilter,
    /// Whether the shapes of colliders the rules reach are tinted.
    pub tints: bool,
    /// Whether each live pair the rules reach gets a line.
    pub pairs: bool,
    /// Whether overrides and rules with an end are marked on their pair's line.
    pub marks: bool,
    /// The length of a mark's strokes, in the world's units.
    pub mark_size: Real,
}

impl Default for RuleDebugRender {
    fn default() -> RuleDebugRender {
        RuleDebugRender::new(DebugRenderPipeline::default())
    }
}

impl RuleDebugRender {
    /// The view over `pipeline` (Rapier's, with the style and mode the
    /// project chose), drawing tints, pairs and marks in the default palette.
    #[must_use]
    pub fn new(pipeline: DebugRenderPipeline) -> RuleDebugRender {
        RuleDebugRender {
            pipeline,
            palette: RulePalette::default(),
            filter: RuleDebugFilter::default(),
            tints: true,
            pairs: true,
            marks: true,
            mark_size: 0.25,
        }
    }

    /// Draws what Rapier's pipeline draws of `world` (tinted), then the
    /// rules. `world` is a `&PhysicsWorld`, or a [`WorldRef::new`] over a
    /// bare pipeline's sets: its joints and soft bodies are drawn only if it
    /// has them ([`WorldRef::with_joints`], [`WorldRef::with_soft_bodies`]),
    /// where Rapier's `DebugRenderPipeline::render` takes them always. The
    /// shapes are tinted only where the pipeline's mode draws them.
    pub fn render<'w>(
        &mut self,
        backend: &mut impl DebugRenderBackend,
        hooks: &RuleHooks,
        world: impl Into<WorldRef<'w>>,
    ) {
        let world = world.into();
        if hooks.reaches_nothing() {
            // Nothing to tint or draw: Rapier's drawing alone.
            return self.render_rapier(backend, None, world);
        }
        self.render_rapier(backend, Some(hooks).filter(|_| self.tints), world);
        self.render_rules(backend, hooks, world);
    }

    /// What Rapier's `render` draws of `world`, part by part in its order,
    /// with the shapes tinted by `tinted`'s reach.
    fn render_rapier(
        &mut self,
        backend: &mut impl DebugRenderBackend,
        tinted: Option<&RuleHooks>,
        world: WorldRef<'_>,
    ) {
        let (bodies, colliders) = (world.bodies, world.colliders);
        self.pipeline.render_rigid_bodies(backend, bodies);
        let shapes = self.pipeline.mode.contains(DebugRenderMode::COLLIDER_SHAPES);
        match tinted.filter(|_| shapes) {
            Some(hooks) => {
                let mode = self.pipeline.mode;
                self.render_shapes(backend, hooks, world, false);
                // Bounding boxes and pseudo-normals keep Rapier's colours.
                self.pipeline.mode = mode - DebugRenderMode::COLLIDER_SHAPES;
                self.pipeline.render_colliders(backend, bodies, colliders);
                self.pipeline.mode = mode;
            }
            None => self.pipeline.render_colliders(backend, bodies, colliders),
        }
        if let Some(joints) = world.joints {
            self.pipeline
                .render_joints(backend, bodies, joints.impulse, joints.multibody);
        }
        self.pipeline
            .render_contacts(backend, colliders, world.narrow_phase);
        if let Some(soft_bodies) = world.soft_bodies {
            self.pipeline.render_soft_bodies(backend, soft_bodies);
        }
    }

    /// Draws the tinted shapes of the colliders the rules reach (that the
    /// filter keeps) and nothing else: for a project whose own debug
    /// rendering draws Rapier's part (bevy_rapier's debug plugin), over
    /// which these shapes lie. Drawn whatever [`tints`](Self::tints) and
    /// the pipeline's mode say; nothing where the rules reach nothing.
    pub fn render_tints<'w>(
        &mut self,
        backend: &mut impl DebugRenderBackend,
        hooks: &RuleHooks,
        world: impl Into<WorldRef<'w>>,
    ) {
        if !hooks.reaches_nothing() {
            self.render_shapes(backend, hooks, world.into(), true);
        }
    }

    /// Rapier's drawing of the colliders' shapes, tinted: every collider's,
    /// or only those the rules reach.
    fn render_shapes(
        &mut self,
        backend: &mut impl DebugRenderBackend,
        hooks: &RuleHooks,
        world: WorldRef<'_>,
        only_reached: bool,
    ) {
        let (bodies, colliders) = (world.bodies, world.colliders);
        let mode = self.pipeline.mode;
        self.pipeline.mode = DebugRenderMode::COLLIDER_SHAPES;
        let mut tinted = Tinted {
            backend,
            hooks,
            bodies,
            colliders,
            palette: &self.palette,
            filter: &self.filter,
            only_reached,
        };
        self.pipeline
            .render_colliders(&mut tinted, bodies, colliders);
        self.pipeline.mode = mode;
    }

    /// Draws the rules alone (pairs and marks, no tints, nothing of
    /// Rapier's): for a project that draws Rapier's part itself.
    pub fn render_rules<'w>(
        &self,
        backend: &mut impl DebugRenderBackend,
        hooks: &RuleHooks,
        world: impl Into<WorldRef<'w>>,
    ) {
        if !self.pairs && !self.marks {
            return;
        }
        let world = world.into();
        self.for_each_pair(hooks, world, |object, line, reach| {
            if backend.filter_object(object) {
                self.strokes(line, reach, |stroke| {
                    backend.draw_line(object, stroke.from, stroke.to, stroke.color);
                });
            }
        });
    }

    /// Each line [`render_rules`](Self::render_rules) draws, with the pair
    /// it is drawn for, for a project that draws them its own way (the Bevy
    /// debug plugin names each pair's entities): no backend is asked.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, RuleDebugRender, RuleHooks, RuleLineKind};
    ///
    /// let mut world = PhysicsWorld::new();
    /// let ground = world.insert_body(RigidBodyBuilder::fixed());
    /// let floor = world.insert_collider(ColliderBuilder::cuboid(10.0, 0.5, 10.0), Some(ground));
    /// let body = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.9, 0.0)));
    /// let ball = world.insert_collider(ColliderBuilder::ball(0.5), Some(body));
    /// let mut hooks = RuleHooks::default();
    /// hooks.rules_mut().set_personal(body, CollisionRule::NoContacts);
    /// hooks.step(&mut world);
    ///
    /// let mut lines = Vec::new();
    /// RuleDebugRender::default().rule_lines(&hooks, &world, |line| lines.push(line));
    /// assert_eq!(lines.len(), 1);
    /// assert_eq!(lines[0].kind, RuleLineKind::Pair(CollisionRule::NoContacts));
    /// assert!([lines[0].collider1, lines[0].collider2] == [ball, floor]
    ///     || [lines[0].collider1, lines[0].collider2] == [floor, ball]);
    /// ```
    pub fn rule_lines<'w>(
        &self,
        hooks: &RuleHooks,
        world: impl Into<WorldRef<'w>>,
        mut line: impl FnMut(RuleLine),
    ) {
        if !self.pairs && !self.marks {
            return;
        }
        self.for_each_pair(hooks, world.into(), |_, segment, reach| {
            self.strokes(segment, reach, &mut line);
        });
    }

    /// The strokes of one pair: its line, then its marks.
    fn strokes(&self, line: Segment, reach: PairReach, mut stroke: impl FnMut(RuleLine)) {
        let mut emit = |from: Vector, to: Vector, kind: RuleLineKind| {
            let color = match kind {
                RuleLineKind::Pair(rule) => self.palette.rule(Some(rule)),
                RuleLineKind::Override => self.palette.overridden,
                RuleLineKind::Ending => self.palette.ending,
            };
            stroke(RuleLine {
                collider1: line.a,
                collider2: line.b,
                from,
                to,
                color: color.hsla(1.0),
                kind,
            });
        };
        if self.pairs {
            emit(line.from, line.to, RuleLineKind::Pair(reach.rule));
        }
        if !self.marks {
            return;
        }
        let middle = line.middle();
        if reach.overridden {
            for axis in 0..DIM {
                let mut half = Vector::ZERO;
                half[axis] = self.mark_size * 0.5;
                emit(middle - half, middle + half, RuleLineKind::Override);
            }
        }
        if reach.ending {
            let half = self.mark_size * 0.5 * std::f32::consts::FRAC_1_SQRT_2;
            let (mut x, mut y) = (Vector::ZERO, Vector::ZERO);
            (x[0], y[1]) = (half, half);
            for diagonal in [x + y, x - y] {
                emit(middle - diagonal, middle + diagonal, RuleLineKind::Ending);
            }
        }
    }

    /// Hands `backend` one label per pair the view draws, at the middle of
    /// its line: the rule and what decided it, as
    /// [`CollisionRuleSet::explain`](super::super::CollisionRuleSet::explain)
    /// tells (`NoResponse: specific body 2 / collider 5`), or `override`,
    /// or `calculator`; `, ends` and `, hooked` follow where they hold.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, RuleDebugRender, RuleHooks, RuleLabelBackend};
    ///
    /// #[derive(Default)]
    /// struct Labels(Vec<String>);
    ///
    /// impl RuleLabelBackend for Labels {
    ///     fn draw_label(&mut self, _at: Vector, text: &str, _color: [f32; 4]) {
    ///         self.0.push(text.to_owned());
    ///     }
    /// }
    ///
    /// let mut world = PhysicsWorld::new();
    /// let ground = world.insert_body(RigidBodyBuilder::fixed());
    /// world.insert_collider(ColliderBuilder::cuboid(10.0, 0.5, 10.0), Some(ground));
    /// let ghost = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.9, 0.0)));
    /// world.insert_collider(ColliderBuilder::ball(0.5), Some(ghost));
    /// let mut hooks = RuleHooks::default();
    /// hooks.rules_mut().set_specific(ghost, ground, CollisionRule::NoResponse);
    /// hooks.step(&mut world);
    ///
    /// let mut labels = Labels::default();
    /// RuleDebugRender::default().render_labels(&mut labels, &hooks, &world);
    /// // The nodes come in the order of the pair's colliders in Rapier's graph.
    /// let (g, b) = (ghost.into_raw_parts().0, ground.into_raw_parts().0);
    /// let one_way = format!("NoResponse: specific body {g} / body {b}");
    /// let other_way = format!("NoResponse: specific body {b} / body {g}");
    /// assert!(labels.0 == [one_way] || labels.0 == [other_way], "{:?}", labels.0);
    /// ```
    pub fn render_labels<'w>(
        &self,
        backend: &mut impl RuleLabelBackend,
        hooks: &RuleHooks,
        world: impl Into<WorldRef<'w>>,
    ) {
        let world = world.into();
        self.for_each_pair(hooks, world, |_, line, reach| {
            let why = hooks
                .rules()
                .explain(world.bodies, world.colliders, line.a, line.b);
            let text = label_text(&reach, &why, hooks.calculates());
            let color = self.palette.rule(Some(reach.rule)).hsla(1.0);
            backend.draw_label(line.middle(), &text, color);
        });
    }

    /// Each live pair the rules reach that the filter shows, with the
    /// object Rapier's backends know it by (the contact pair; the first
    /// collider for a sensor pair) and the centres of its colliders' boxes.
    fn for_each_pair<'w>(
        &self,
        hooks: &RuleHooks,
        world: WorldRef<'w>,
        mut draw: impl FnMut(DebugRenderObject<'w>, Segment, PairReach),
    ) {
        if hooks.reaches_nothing() {
            return;
        }
        let (bodies, colliders) = (world.bodies, world.colliders);
        let rules = hooks.rules();
        for (a, b, contact, pair) in hooks.reached_pairs(world) {
            if !self.filter.shows(pair.rule, pair.hooked) {
                continue;
            }
            let shown = |c| self.filter.holds(rules, bodies, colliders, c);
            if !shown(a) && !shown(b) {
                continue;
            }
            let (Some(ca), Some(cb)) = (colliders.get(a), colliders.get(b)) else {
                continue;
            };
            let object = match contact {
                Some(contact) => DebugRenderObject::ContactPair(contact, ca, cb),
                None => DebugRenderObject::Collider(a, ca),
            };
            let (from, to) = (ca.compute_aabb().center(), cb.compute_aabb().center());
            draw(object, Segment { a, b, from, to }, pair);
        }
    }
}

/// One line the rules' part of the view draws: what
/// [`RuleDebugRender::rule_lines`] hands over.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RuleLine {
    /// The pair's first collider, in Rapier's order.
    pub collider1: ColliderHandle,
    /// The pair's second collider.
    pub collider2: ColliderHandle,
    /// Where the line starts.
    pub from: Vector,
    /// Where it ends.
    pub to: Vector,
    /// Its colour, HSLA as Rapier's debug colours.
    pub color: [f32; 4],
    /// What it shows.
    pub kind: RuleLineKind,
}

/// What a [`RuleLine`] shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RuleLineKind {
    /// The pair, between its colliders' centres, in its rule's colour.
    Pair(CollisionRule),
    /// A stroke of the mark of an override, at the middle of the pair's line.
    Override,
    /// A stroke of the mark of a rule with an end.
    Ending,
}

/// A drawn pair's colliders and the centres of their boxes, where its
/// line runs.
#[derive(Clone, Copy)]
struct Segment {
    a: ColliderHandle,
    b: ColliderHandle,
    from: Vector,
    to: Vector,
}

impl Segment {
    fn middle(&self) -> Vector {
        (self.from + self.to) * 0.5
    }
}
