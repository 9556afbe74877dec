//! The rules drawn with Bevy's gizmos, beside bevy_rapier's debug
//! rendering (feature `debug-render`; `docs/bevy.md`, "Seeing the rules"):
//! each context's [`RuleDebugRender`] draws into [`RuleDebugLines`] on the
//! context, and the lines go to the gizmos.

use bevy::gizmos::config::GizmoConfigStore;
use bevy::prelude::*;
use bevy_rapier::plugin::context::{
    RapierContextColliders, RapierContextJoints, RapierContextSimulation, RapierRigidBodySet,
};
use bevy_rapier::rapier::prelude::{
    ColliderHandle, DebugColor, DebugRenderBackend, DebugRenderObject, Vector,
};

use super::CollisionRules;
use crate::collision_rules::{
    CollisionRule, Node, RuleDebugFilter, RuleDebugRender, RulePalette, WorldRef,
};

/// Draws each physics context's rules with gizmos, beside bevy_rapier's
/// `RapierDebugRenderPlugin` (which draws Rapier's part): the shapes of
/// the colliders the rules reach, tinted by how (planned into Rapier's
/// groups, or hooked), a line per live pair the rules reach in its rule's
/// colour, and marks on overrides and rules with an end, in the colours of
/// [`RulePalette`] (`docs/semantics.md`, "Seeing the rules"). Add it with
/// [`CollisionRulesPlugin`](super::CollisionRulesPlugin) and Bevy's gizmos
/// (in `DefaultPlugins`). Each context gets a [`CollisionRulesDebug`],
/// which turns it on and off at runtime and filters it, and a
/// [`RuleDebugLines`] with what was drawn last. The tinted outlines are
/// drawn for every collider the rules reach, whatever bevy_rapier's own
/// debug settings say of it (this crate builds bevy_rapier without its
/// debug rendering, so it cannot read them): narrow them with the
/// filter of [`CollisionRulesDebug`].
///
/// ```
/// use bevy::prelude::*;
/// use bevy_rapier3d::prelude::*;
/// use bevy_rapier_collision_rules::prelude::*;
///
/// let mut app = App::new();
/// app.add_plugins((
///     MinimalPlugins,
///     TransformPlugin,
///     RapierPhysicsPlugin::<CollisionRulesHooks>::default(),
///     CollisionRulesPlugin::default(),
///     CollisionRulesDebugPlugin::default(),
/// ));
/// let floor = app.world_mut().spawn((Transform::default(), Collider::cuboid(5.0, 0.5, 5.0))).id();
/// app.world_mut().spawn((
///     Transform::from_xyz(0.0, 0.9, 0.0),
///     RigidBody::Dynamic,
///     Collider::ball(0.5),
///     SpecificRules::new().with(floor, CollisionRule::NoResponse),
/// ));
/// app.update();
/// app.update();
/// let lines = app.world_mut().query::<&RuleDebugLines>().single(app.world()).unwrap();
/// // One NoResponse pair: a line in the palette's orange.
/// let [h, s, l, a] = RulePalette::default().no_response.hsla(1.0);
/// assert!(lines.lines().iter().any(|line| line.color == Color::hsla(h, s, l, a)));
///
/// // Off at runtime, for this context.
/// let mut debug = app.world_mut().query::<&mut CollisionRulesDebug>();
/// debug.single_mut(app.world_mut()).unwrap().enabled = false;
/// app.update();
/// let lines = app.world_mut().query::<&RuleDebugLines>().single(app.world()).unwrap();
/// assert!(lines.lines().is_empty());
/// ```
#[derive(Default)]
pub struct CollisionRulesDebugPlugin {
    off: bool,
}

impl CollisionRulesDebugPlugin {
    /// Contexts start with the view off ([`CollisionRulesDebug::enabled`]
    /// turns it on).
    #[must_use]
    pub fn off(mut self) -> Self {
        self.off = true;
        self
    }
}

impl Plugin for CollisionRulesDebugPlugin {
    fn build(&self, app: &mut App) {
        let enabled = !self.off;
        // Every context, those made before the plugin included, gets its
        // view before it is drawn.
        let give_views =
            move |contexts: Query<Entity, (With<CollisionRules>, Without<CollisionRulesDebug>)>,
                  mut commands: Commands| {
                for context in &contexts {
                    commands.entity(context).insert((
                        CollisionRulesDebug {
                            enabled,
                            ..CollisionRulesDebug::default()
                        },
                        RuleDebugLines::default(),
                    ));
                }
            };
        // Where bevy_rapier's debug rendering draws: after the transforms
        // of the frame.
        app.add_systems(
            PostUpdate,
            (
                give_views,
                ApplyDeferred,
                collect_rule_lines,
                draw_rule_lines.run_if(resource_exists::<GizmoConfigStore>),
            )
                .chain()
                .after(TransformSystems::Propagate),
        );
    }
}

/// The debug view of one physics context: whether it is drawn and what of
/// it. The [`CollisionRulesDebugPlugin`] adds it to every context, on
/// (unless the plugin is [`off`](CollisionRulesDebugPlugin::off)), with
/// tints, pairs and marks, and no filter.
#[derive(Component, Clone, Debug, PartialEq)]
pub struct CollisionRulesDebug {
    /// Whether the context's rules are drawn.
    pub enabled: bool,
    /// The shapes of the colliders the rules reach, tinted.
    pub tints: bool,
    /// A line per live pair the rules reach.
    pub pairs: bool,
    /// Marks on overrides and rules with an end.
    pub marks: bool,
    /// Only the pairs and colliders at or under this entity (a rigid
    /// body's entity: its colliders and those of the bodies under it; a
    /// collider's entity: that collider).
    pub entity: Option<Entity>,
    /// Only the pairs with this rule.
    pub rule: Option<CollisionRule>,
    /// Only the pairs the hook answers, and the hooked colliders.
    pub hooked_only: bool,
    /// The colours.
    pub palette: RulePalette,
    /// The length of a mark's strokes, in metres (times the context's
    /// length unit: bevy_rapier2d's pixels per metre).
    pub mark_size: f32,
}

impl Default for CollisionRulesDebug {
    fn default() -> Self {
        let view = RuleDebugRender::default();
        CollisionRulesDebug {
            enabled: true,
            tints: view.tints,
            pairs: view.pairs,
            marks: view.marks,
            entity: None,
            rule: None,
            hooked_only: false,
            palette: view.palette,
            mark_size: view.mark_size,
        }
    }
}

/// What the debug view of a context drew in the last frame, as handed to
/// the gizmos.
#[derive(Component, Default)]
pub struct RuleDebugLines {
    lines: Vec<RuleDebugLine>,
    /// The core's view, kept from frame to frame (Rapier's pipeline builds
    /// its shapes' outlines when it is made).
    view: Option<RuleDebugRender>,
}

impl RuleDebugLines {
    /// The lines, in the order they were drawn: tinted shapes, then each
    /// pair's line and marks.
    #[must_use]
    pub fn lines(&self) -> &[RuleDebugLine] {
        &self.lines
    }
}

impl std::fmt::Debug for RuleDebugLines {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_tuple("RuleDebugLines").field(&self.lines).finish()
    }
}

/// One line of the debug view.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RuleDebugLine {
    /// Where it starts (z = 0 in 2D).
    pub start: Vec3,
    /// Where it ends.
    pub end: Vec3,
    /// Its colour.
    pub color: Color,
    /// What it is drawn for.
    pub object: RuleDebugObject,
}

/// What a line of the debug view is drawn for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RuleDebugObject {
    /// A collider's tinted shape.
    Collider(Entity),
    /// A live pair's line or mark: the entities of its colliders (a
    /// collider without an entity of its own, a soft body's mesh, is
    /// named by `Entity::PLACEHOLDER`).
    Pair(Entity, Entity),
}

/// Each context's view, drawn into its [`RuleDebugLines`].
fn collect_rule_lines(
    mut contexts: Query<(
        &CollisionRules,
        &CollisionRulesDebug,
        &mut RuleDebugLines,
        &RapierContextSimulation,
        &RapierContextColliders,
        &RapierContextJoints,
        &RapierRigidBodySet,
    )>,
) {
    for (rules, debug, mut lines, simulation, colliders, joints, bodies) in &mut contexts {
        let lines = &mut *lines;
        lines.lines.clear();
        if !debug.enabled {
            continue;
        }
        let node = debug.entity.and_then(|entity| {
            let body = bodies.entity2body().get(&entity).map(|&b| Node::Body(b));
            body.or_else(|| {
                colliders
                    .entity2collider()
                    .get(&entity)
                    .map(|&c| Node::Collider(c))
            })
        });
        if debug.entity.is_some() && node.is_none() {
            // The entity has no body or collider in this context.
            continue;
        }
        let view = lines.view.get_or_insert_with(RuleDebugRender::default);
        view.palette = debug.palette;
        // In the context's units (bevy_rapier2d's pixels per metre).
        view.mark_size = debug.mark_size * simulation.integration_parameters.length_unit;
        (view.pairs, view.marks) = (debug.pairs, debug.marks);
        view.filter = RuleDebugFilter {
            node,
            rule: debug.rule,
            hooked_only: debug.hooked_only,
        };
        let world = WorldRef::new(
            &simulation.narrow_phase,
            &bodies.bodies,
            &colliders.colliders,
        )
        .with_joints(&joints.impulse_joints, &joints.multibody_joints);
        let entity = |handle: ColliderHandle| {
            colliders
                .collider_entity(handle)
                .unwrap_or(Entity::PLACEHOLDER)
        };
        if debug.tints {
            let mut shapes = Shapes {
                lines: &mut lines.lines,
                entity: &entity,
            };
            view.render_tints(&mut shapes, rules.hooks(), world);
        }
        let drawn = &mut lines.lines;
        view.rule_lines(rules.hooks(), world, |line| {
            drawn.push(RuleDebugLine {
                start: vec3(line.from),
                end: vec3(line.to),
                color: hsla(line.color),
                object: RuleDebugObject::Pair(entity(line.collider1), entity(line.collider2)),
            });
        });
    }
}

/// The lines to the gizmos.
fn draw_rule_lines(contexts: Query<&RuleDebugLines>, mut gizmos: Gizmos) {
    for line in contexts.iter().flat_map(RuleDebugLines::lines) {
        gizmos.line(line.start, line.end, line.color);
    }
}

/// A `DebugRenderBackend` that keeps the tinted shapes with their
/// colliders' entities.
struct Shapes<'a, F> {
    lines: &'a mut Vec<RuleDebugLine>,
    entity: &'a F,
}

impl<F: Fn(ColliderHandle) -> Entity> DebugRenderBackend for Shapes<'_, F> {
    fn draw_line(&mut self, object: DebugRenderObject, a: Vector, b: Vector, color: DebugColor) {
        if let DebugRenderObject::Collider(handle, _) = object {
            self.lines.push(RuleDebugLine {
                start: vec3(a),
                end: vec3(b),
                color: hsla(color),
                object: RuleDebugObject::Collider((self.entity)(handle)),
            });
        }
    }
}

fn hsla(color: DebugColor) -> Color {
    Color::hsla(color[0], color[1], color[2], color[3])
}

#[cfg(feature = "dim3")]
fn vec3(v: Vector) -> Vec3 {
    Vec3::new(v.x, v.y, v.z)
}

#[cfg(feature = "dim2")]
fn vec3(v: Vector) -> Vec3 {
    Vec3::new(v.x, v.y, 0.0)
}
