//! Scene queries and character controllers that see the rules, asked with
//! entities (`docs/bevy.md`, "Queries and character controllers").
//!
//! [`RuleQueries`] borrows each context's rules and Rapier sets for one
//! system: a predicate for bevy_rapier's `QueryFilter`, and a pair's rule
//! or explanation between two entities. [`ControllerFollowsRules`] gives a
//! `KinematicCharacterController` the same predicate: bevy_rapier's
//! controller takes only a `'static` closure that cannot read the ECS, so
//! [`filter_controllers`] decides, right before bevy_rapier moves the
//! controllers, every collider within a bound of each controller's move
//! this frame, and the installed closure reads those decisions.

use std::sync::{Arc, PoisonError, RwLock};

use bevy::ecs::entity::EntityHashSet;
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy_rapier::control::{ControllerFilterPredicate, KinematicCharacterController};
use bevy_rapier::plugin::context::{
    RapierContextColliders, RapierContextSimulation, RapierRigidBodySet,
};
use bevy_rapier::prelude::{RapierColliderHandle, RapierContextEntityLink, RapierRigidBodyHandle};
use bevy_rapier::rapier::control::CharacterLength;
use bevy_rapier::rapier::math::{Real, Vector};
use bevy_rapier::rapier::parry::bounding_volume::Aabb;
use bevy_rapier::rapier::prelude::{
    Collider as RapierCollider, ColliderHandle, QueryFilter as RapierQueryFilter, QueryPipeline,
};

use crate::collision_rules::{CollisionRule, Explanation, Node, WorldRef};

use super::CollisionRules;

/// One context as the queries read it.
type ContextView = (
    &'static CollisionRules,
    &'static RapierContextSimulation,
    &'static RapierContextColliders,
    &'static RapierRigidBodySet,
);

/// The rules seen from scene queries, with entities: a predicate for
/// bevy_rapier's `QueryFilter` that leaves out what a source's rules let
/// through, and the rule or explanation of a pair of entities. A system
/// parameter that only reads, beside bevy_rapier's `ReadRapierContext`.
///
/// It reads the rules as the last step left them, as bevy_rapier's queries
/// read the colliders as the last step left them: a rule component changed
/// this frame counts from the next step on.
///
/// ```
/// use bevy::prelude::*;
/// use bevy_rapier3d::prelude::*;
/// use bevy_rapier_collision_rules::prelude::*;
///
/// #[derive(Resource)]
/// struct Eye(Entity);
///
/// /// The first collider a ray from the eye hits, as the eye's rules see it.
/// fn look(eye: Res<Eye>, context: ReadRapierContext, rules: RuleQueries) -> Option<Entity> {
///     let context = context.single().ok()?;
///     let passes = rules.predicate(eye.0)?;
///     let filter = QueryFilter::default().predicate(&passes);
///     let ray = (Vec3::ZERO, Vec3::X);
///     context.cast_ray(ray.0, ray.1, 100.0, true, filter).map(|(hit, _)| hit)
/// }
///
/// let mut app = App::new();
/// app.add_plugins((
///     MinimalPlugins,
///     TransformPlugin,
///     RapierPhysicsPlugin::<CollisionRulesHooks>::default(),
///     CollisionRulesPlugin::default(),
/// ));
/// let wall = |x: f32| (Transform::from_xyz(x, 0.0, 0.0), Collider::cuboid(0.1, 2.0, 2.0));
/// let door = app.world_mut().spawn(wall(2.0)).id();
/// let far_wall = app.world_mut().spawn(wall(6.0)).id();
/// let eye = app.world_mut().spawn((
///     Transform::default(),
///     RigidBody::KinematicPositionBased,
///     Collider::ball(0.3),
///     SpecificRules::new().with(door, CollisionRule::NoResponse),
/// ));
/// let eye = eye.id();
/// app.insert_resource(Eye(eye));
/// app.update();
/// app.update();
/// let hit = app.world_mut().run_system_cached(look).unwrap();
/// assert_eq!(hit, Some(far_wall), "the ray passes the door");
/// ```
#[derive(SystemParam)]
pub struct RuleQueries<'w, 's> {
    contexts: Query<'w, 's, ContextView>,
    links: Query<'w, 's, &'static RapierContextEntityLink>,
}

/// An [`Explanation`] with its nodes as entities: what
/// [`RuleQueries::explain`] returns.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct EntityExplanation {
    /// The rule, stage, step and nodes, as the core's `explain` gives them.
    pub explanation: Explanation,
    /// The entities of the two nodes whose comparison decided (the first
    /// from the first entity's chain): a collider's entity, or a rigid
    /// body's; `None` for the default stage, or for a node no entity holds.
    pub entities: Option<(Entity, Entity)>,
}

impl RuleQueries<'_, '_> {
    /// A predicate for bevy_rapier's `QueryFilter::predicate`: keeps a
    /// collider when the rule of its pair with `source` would have them
    /// push each other apart (`Normal`), and leaves it out otherwise (a
    /// door a character walks through, debris a player's ray passes),
    /// as the core's `CollisionRuleSet::query_predicate` does; `source`
    /// and the colliders of its body are left out. `source` is a collider
    /// entity, or a rigid body's entity, which asks for its first collider.
    /// `None` if `source` is neither, or is in no context with rules.
    #[must_use]
    pub fn predicate(
        &self,
        source: Entity,
    ) -> Option<impl Fn(Entity, &RapierCollider) -> bool + '_> {
        let (rules, _, colliders, bodies) = self.context_of(source)?;
        let handle = collider_of(colliders, bodies, source)?;
        let passes = rules
            .rules()
            .query_predicate(&bodies.bodies, &colliders.colliders, handle);
        Some(move |entity: Entity, collider: &RapierCollider| {
            // A collider without an entity of its own (a soft body's
            // meshes carry the soft body's entity) is found among its
            // body's colliders by address; one found nowhere is kept, as
            // without the rules.
            let other = colliders
                .entity2collider()
                .get(&entity)
                .copied()
                .or_else(|| {
                    let body = bodies.bodies.get(collider.parent()?)?;
                    body.colliders().iter().copied().find(|&h| {
                        colliders
                            .colliders
                            .get(h)
                            .is_some_and(|c| std::ptr::eq(c, collider))
                    })
                });
            other.is_none_or(|other| passes(other, collider))
        })
    }

    /// The rule of the live pair of two entities (colliders, or rigid
    /// bodies for their first collider), in either order, as the core's
    /// `RuleHooks::pair_rule` answers it: `None` if they form no live pair
    /// (a `NoPair` pair is not live), are not physics objects, or are in
    /// different contexts.
    #[must_use]
    pub fn pair_rule(&self, a: Entity, b: Entity) -> Option<CollisionRule> {
        let (rules, simulation, colliders, bodies) = self.context_of(a)?;
        let (ca, cb) = self.pair_in(a, b)?;
        let view = WorldRef::new(
            &simulation.narrow_phase,
            &bodies.bodies,
            &colliders.colliders,
        );
        rules.hooks().pair_rule(view, ca, cb)
    }

    /// Why two entities' pair gets its rule, from the rules alone (whether
    /// or not Rapier holds the pair now), with the deciding nodes as
    /// entities: the core's `CollisionRuleSet::explain`. `None` as for
    /// [`pair_rule`](Self::pair_rule).
    #[must_use]
    pub fn explain(&self, a: Entity, b: Entity) -> Option<EntityExplanation> {
        let (rules, _, colliders, bodies) = self.context_of(a)?;
        let (ca, cb) = self.pair_in(a, b)?;
        let explanation = rules
            .rules()
            .explain(&bodies.bodies, &colliders.colliders, ca, cb);
        let entity = |node: Node| match node {
            Node::Collider(handle) => colliders.collider_entity(handle),
            Node::Body(handle) => bodies.rigid_body_entity(handle),
        };
        let entities = explanation
            .nodes
            .and_then(|(first, second)| Some((entity(first)?, entity(second)?)));
        Some(EntityExplanation {
            explanation,
            entities,
        })
    }

    /// The collider handles of two entities of one context.
    fn pair_in(&self, a: Entity, b: Entity) -> Option<(ColliderHandle, ColliderHandle)> {
        let context = self.links.get(a).ok()?.0;
        if self.links.get(b).ok()?.0 != context {
            return None;
        }
        let (_, _, colliders, bodies) = self.contexts.get(context).ok()?;
        Some((
            collider_of(colliders, bodies, a)?,
            collider_of(colliders, bodies, b)?,
        ))
    }

    /// The context of an entity, as the queries read it.
    fn context_of(
        &self,
        entity: Entity,
    ) -> Option<(
        &CollisionRules,
        &RapierContextSimulation,
        &RapierContextColliders,
        &RapierRigidBodySet,
    )> {
        let context = self.links.get(entity).ok()?.0;
        self.contexts.get(context).ok()
    }
}

/// The collider an entity stands for: its own, or its rigid body's first.
fn collider_of(
    colliders: &RapierContextColliders,
    bodies: &RapierRigidBodySet,
    entity: Entity,
) -> Option<ColliderHandle> {
    if let Some(&handle) = colliders.entity2collider().get(&entity) {
        return Some(handle);
    }
    let body = bodies.entity2body().get(&entity)?;
    bodies.bodies.get(*body)?.colliders().first().copied()
}

/// Makes the entity's `KinematicCharacterController` see colliders as its
/// rules say: it walks through a door its rule lets it through
/// (`NoPair`, `NoContacts`, `NoResponse` with the door) and is stopped by
/// a `Normal` wall, as [`RuleQueries::predicate`] keeps and leaves out
/// colliders. The controller's own `filter_predicate` is kept and asked
/// too (a collider must pass both); set it before or after adding this
/// component, and removing or replacing the component gives it back alone.
///
/// The decisions are made each frame, right before bevy_rapier moves the
/// controllers ([`RulesSystems::Controllers`](super::RulesSystems)), for
/// every collider within a bound of the move (the character's box grown
/// by its translation, offset, snap, autostep, push out of an overlap and
/// the platform it may stand on; `docs/bevy.md`, "Queries and character
/// controllers"), with the rules as the last step left them. A collider
/// beyond the bound is kept, as without the rules.
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
/// ));
/// let door = app.world_mut().spawn((Transform::from_xyz(1.0, 0.0, 0.0), Collider::cuboid(0.1, 2.0, 2.0)));
/// let door = door.id();
/// app.world_mut().spawn((
///     Transform::default(),
///     RigidBody::KinematicPositionBased,
///     Collider::ball(0.3),
///     KinematicCharacterController::default(),
///     ControllerFollowsRules::default(),
///     SpecificRules::new().with(door, CollisionRule::NoPair),
/// ));
/// app.update();
/// ```
#[derive(Component, Default)]
pub struct ControllerFollowsRules {
    installed: Option<Installed>,
}

/// What the component put on the controller.
struct Installed {
    /// The predicate on the controller: ours, asking the project's.
    ours: ControllerFilterPredicate,
    /// The project's own predicate, asked after the rules.
    project: Option<ControllerFilterPredicate>,
    /// The colliders within reach this frame that the rules leave out.
    left_out: Arc<RwLock<EntityHashSet>>,
}

impl Installed {
    fn new(project: Option<ControllerFilterPredicate>) -> Installed {
        let left_out = Arc::new(RwLock::new(EntityHashSet::default()));
        let (seen, asked) = (Arc::clone(&left_out), project.clone());
        let ours = ControllerFilterPredicate::new(move |entity, collider| {
            let left = seen
                .read()
                .unwrap_or_else(PoisonError::into_inner)
                .contains(&entity);
            !left && asked.as_ref().is_none_or(|p| p.test(entity, collider))
        });
        Installed {
            ours,
            project,
            left_out,
        }
    }

    /// Whether `predicate` is the one installed.
    fn is_ours(&self, predicate: Option<&ControllerFilterPredicate>) -> bool {
        predicate.is_some_and(|p| Arc::ptr_eq(&p.0, &self.ours.0))
    }
}

type Controllers = (
    Entity,
    &'static RapierContextEntityLink,
    &'static mut KinematicCharacterController,
    &'static mut ControllerFollowsRules,
    Option<&'static RapierColliderHandle>,
    Option<&'static RapierRigidBodyHandle>,
    Option<&'static GlobalTransform>,
);

/// Decides, for each controller with [`ControllerFollowsRules`], the
/// colliders within its reach this frame, and installs (once, or again
/// when the project set a predicate of its own) the predicate that reads
/// them. Runs in bevy_rapier's `PhysicsSet::SyncBackend`, before its
/// controllers move.
pub(crate) fn filter_controllers(
    contexts: Query<ContextView>,
    mut controllers: Query<Controllers>,
) {
    for (entity, link, mut controller, mut follows, collider, body, global) in &mut controllers {
        let installed = match follows.installed.take() {
            Some(installed) if installed.is_ours(controller.filter_predicate.as_ref()) => installed,
            // A predicate the project set (or none, at the first frame):
            // kept, and asked after the rules.
            _ => {
                let installed = Installed::new(controller.filter_predicate.take());
                controller.filter_predicate = Some(installed.ours.clone());
                installed
            }
        };
        {
            // Last frame's decisions go first: nothing below may leave
            // them standing (a controller out of its context, or idle).
            let mut left_out = installed
                .left_out
                .write()
                .unwrap_or_else(PoisonError::into_inner);
            left_out.clear();
            // bevy_rapier moves a controller only with a translation.
            let context = contexts
                .get(link.0)
                .ok()
                .filter(|_| controller.translation.is_some());
            if let Some((rules, simulation, colliders, bodies)) = context {
                let source = collider
                    .map(|c| c.0)
                    .or_else(|| collider_of(colliders, bodies, entity));
                let shape = source.and_then(|source| {
                    character_box(&controller, colliders, bodies, source, body, global)
                });
                if let (Some(source), Some(shape)) = (source, shape) {
                    let pipeline = simulation.broad_phase.as_query_pipeline(
                        simulation.narrow_phase.query_dispatcher(),
                        &bodies.bodies,
                        &colliders.colliders,
                        RapierQueryFilter::default(),
                    );
                    let dt = simulation.integration_parameters.dt;
                    let aabb = reach(&controller, shape, &pipeline, dt);
                    let passes =
                        rules
                            .rules()
                            .query_predicate(&bodies.bodies, &colliders.colliders, source);
                    for (handle, other) in pipeline.intersect_aabb_conservative(aabb) {
                        if handle != source && !passes(handle, other) {
                            left_out.insert(RapierContextColliders::entity_from_collider(other));
                        }
                    }
                }
            }
        }
        follows.installed = Some(installed);
    }
}

/// The box of the shape the controller moves: its collider's box, or,
/// for a custom shape, a box round the shape's bounding sphere wherever
/// its offset turns it.
fn character_box(
    controller: &KinematicCharacterController,
    colliders: &RapierContextColliders,
    bodies: &RapierRigidBodySet,
    source: ColliderHandle,
    body: Option<&RapierRigidBodyHandle>,
    global: Option<&GlobalTransform>,
) -> Option<Aabb> {
    let Some((shape, translation, _)) = &controller.custom_shape else {
        return Some(colliders.colliders.get(source)?.compute_aabb());
    };
    let base = match body.and_then(|b| bodies.bodies.get(b.0)) {
        Some(body) => body.position().translation,
        None => vector_of(global?.translation()),
    };
    let sphere = shape.raw.compute_local_bounding_sphere();
    let radius = sphere.radius() + sphere.center().length() + translation.length();
    let half = Vector::splat(radius);
    Some(Aabb::new(base - half, base + half))
}

/// A Bevy translation as a vector of the dimension.
fn vector_of(translation: Vec3) -> Vector {
    #[cfg(feature = "dim3")]
    return translation;
    #[cfg(feature = "dim2")]
    translation.truncate()
}

/// The box of everything the controller's move can touch this frame: its
/// shape's box grown by a bound on the way the move can take. Rapier's
/// controller (`control/character_controller.rs`) moves by the
/// translation, keeps `offset` away, snaps down by `snap_to_ground`,
/// climbs a step of `max_height` over `min_width`, pushes the character
/// out of an overlap by at most a quarter of its height, and carries it
/// with a kinematic body it stands on by that body's velocity over `dt`.
/// Each relative length is read against the box's diagonal, which bounds
/// every extent Rapier reads it against (its height along `up`, its width
/// across), and the climb is counted four times for stairs taken in one
/// move; then a margin of half as much again. A collider beyond the box is
/// kept, as without the rules: a miss can block the character with what its
/// rules open, never let it through what they keep.
fn reach(
    controller: &KinematicCharacterController,
    shape: Aabb,
    pipeline: &QueryPipeline<'_>,
    dt: Real,
) -> Aabb {
    let diagonal = (shape.maxs - shape.mins).length();
    let length = |l: CharacterLength| match l {
        CharacterLength::Relative(x) => x * diagonal,
        CharacterLength::Absolute(x) => x,
    };
    let translation = controller.translation.map_or(0.0, |t| t.length());
    let offset = length(controller.offset);
    let snap = controller.snap_to_ground.map_or(0.0, length);
    let climb = controller
        .autostep
        .map_or(0.0, |a| 4.0 * (length(a.max_height) + length(a.min_width)));
    let push_out = 0.25 * diagonal;
    let near = translation + offset + snap + climb + push_out + controller.normal_nudge_factor;
    let carried = dt * platform_speed(pipeline, grow(shape, near + 0.1), diagonal);
    let way = near + carried;
    grow(shape, 1.5 * way + 0.1)
}

/// `aabb` grown by `by` on every side.
fn grow(aabb: Aabb, by: Real) -> Aabb {
    let by = Vector::splat(by);
    Aabb::new(aabb.mins - by, aabb.maxs + by)
}

/// The fastest a kinematic body with a collider in `near` moves any point
/// within `near` (its speed plus its spin times the farthest such point).
fn platform_speed(pipeline: &QueryPipeline<'_>, near: Aabb, diagonal: Real) -> Real {
    let center = (near.mins + near.maxs) * 0.5;
    let mut fastest: Real = 0.0;
    for (_, collider) in pipeline.intersect_aabb_conservative(near) {
        let Some(body) = collider.parent().and_then(|b| pipeline.bodies.get(b)) else {
            continue;
        };
        if !body.is_kinematic() {
            continue;
        }
        let arm = (center - body.center_of_mass()).length() + diagonal;
        fastest = fastest.max(body.linvel().length() + spin(body.angvel()) * arm);
    }
    fastest
}

/// How fast a body spins, whatever the dimension's angular velocity is.
#[cfg(feature = "dim3")]
fn spin(angvel: Vector) -> Real {
    angvel.length()
}

/// How fast a body spins, whatever the dimension's angular velocity is.
#[cfg(feature = "dim2")]
fn spin(angvel: Real) -> Real {
    angvel.abs()
}

/// Gives the controller its project's predicate back when the component
/// goes, or is replaced by a new one (which installs itself anew).
pub(crate) fn restore_controller(
    event: On<Discard<ControllerFollowsRules>>,
    mut controllers: Query<(
        &mut KinematicCharacterController,
        &mut ControllerFollowsRules,
    )>,
) {
    let Ok((mut controller, mut follows)) = controllers.get_mut(event.entity) else {
        return;
    };
    if let Some(installed) = follows.installed.take()
        && installed.is_ours(controller.filter_predicate.as_ref())
    {
        controller.filter_predicate = installed.project;
    }
}
