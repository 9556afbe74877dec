//! A headless app and the few shapes the tests drop on a floor.

use std::time::Duration;

use bevy::app::Plugins;
use bevy::ecs::system::SystemParamItem;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use bevy_rapier::pipeline::BevyPhysicsHooks;
use bevy_rapier::plugin::context::{
    DefaultRapierContext, RapierContextColliders, RapierContextSimulation, RapierRigidBodySet,
};
use bevy_rapier::prelude::*;
use bevy_rapier_collision_rules::prelude::*;

pub use crate::dimension::{cuboid, vect};

pub const DT: f32 = 1.0 / 60.0;

pub struct Sim {
    pub app: App,
}

impl Sim {
    /// An app with the rules as bevy_rapier's hooks.
    pub fn new() -> Sim {
        Sim::with_hooks::<CollisionRulesHooks>()
    }

    /// An app whose bevy_rapier hooks are `H`.
    pub fn with_hooks<H>() -> Sim
    where
        H: 'static + BevyPhysicsHooks,
        for<'w, 's> SystemParamItem<'w, 's, H>: BevyPhysicsHooks,
    {
        Sim::with_plugins(
            RapierPhysicsPlugin::<H>::default(),
            CollisionRulesPlugin::default(),
        )
    }

    /// An app with bevy_rapier's and the rules' plugins as given (for
    /// another schedule).
    pub fn with_plugins(rapier: impl Plugin, rules: CollisionRulesPlugin) -> Sim {
        Sim::from_plugins((rapier, rules))
    }

    /// Plain bevy_rapier without the rules, the reference of what the
    /// rules must leave alone.
    pub fn plain() -> Sim {
        Sim::from_plugins(RapierPhysicsPlugin::<()>::default())
    }

    /// An app with these plugins besides the minimal ones.
    pub fn from_plugins<M>(physics: impl Plugins<M>) -> Sim {
        let mut app = App::new();
        app.add_plugins((MinimalPlugins, TransformPlugin))
            .add_plugins(physics)
            .insert_resource(TimeUpdateStrategy::ManualDuration(Duration::from_secs_f32(
                DT,
            )));
        app.finish();
        app.cleanup();
        // Startup, and the first frame (no time has passed: no step).
        app.update();
        Sim { app }
    }

    pub fn spawn(&mut self, bundle: impl Bundle) -> Entity {
        self.app.world_mut().spawn(bundle).id()
    }

    pub fn run(&mut self, frames: usize) {
        for _ in 0..frames {
            self.app.update();
        }
    }

    /// Runs `frames` frames and returns the entity's translation after each.
    pub fn track(&mut self, entity: Entity, frames: usize) -> Vec<Vec3> {
        (0..frames)
            .map(|_| {
                self.app.update();
                self.at(entity)
            })
            .collect()
    }

    pub fn at(&self, entity: Entity) -> Vec3 {
        self.app
            .world()
            .get::<Transform>(entity)
            .unwrap()
            .translation
    }

    pub fn y(&self, entity: Entity) -> f32 {
        self.at(entity).y
    }

    /// The Rapier handle of an entity's rigid body.
    pub fn body(&self, entity: Entity) -> bevy_rapier::rapier::prelude::RigidBodyHandle {
        self.app
            .world()
            .get::<RapierRigidBodyHandle>(entity)
            .unwrap()
            .0
    }

    /// The height of an entity that may sit under another in the hierarchy.
    pub fn global_y(&self, entity: Entity) -> f32 {
        let global = self.app.world().get::<GlobalTransform>(entity).unwrap();
        global.translation().y
    }

    pub fn table(&mut self) -> Mut<'_, RuleTable> {
        self.app.world_mut().resource_mut::<RuleTable>()
    }

    pub fn entity_mut(&mut self, entity: Entity) -> EntityWorldMut<'_> {
        self.app.world_mut().entity_mut(entity)
    }

    /// The default context's entity.
    pub fn context(&mut self) -> Entity {
        self.app
            .world_mut()
            .query_filtered::<Entity, With<DefaultRapierContext>>()
            .single(self.app.world())
            .unwrap()
    }

    /// A context's rules.
    pub fn rules_of(&mut self, context: Entity) -> &CollisionRules {
        self.app.world().get::<CollisionRules>(context).unwrap()
    }

    pub fn rules(&mut self) -> &CollisionRules {
        let context = self.context();
        self.rules_of(context)
    }

    /// The rule of the live pair of two collider entities in `context`,
    /// as Rapier's graph and the rules have it (`None`: no pair).
    pub fn pair_rule_of(&mut self, context: Entity, a: Entity, b: Entity) -> Option<CollisionRule> {
        let world = self.app.world();
        let (simulation, colliders, bodies, rules) = (
            world.get::<RapierContextSimulation>(context).unwrap(),
            world.get::<RapierContextColliders>(context).unwrap(),
            world.get::<RapierRigidBodySet>(context).unwrap(),
            world.get::<CollisionRules>(context).unwrap(),
        );
        let handle = |e: Entity| colliders.entity2collider()[&e];
        let view = WorldRef::new(
            &simulation.narrow_phase,
            &bodies.bodies,
            &colliders.colliders,
        );
        rules.hooks().pair_rule(view, handle(a), handle(b))
    }

    pub fn pair_rule(&mut self, a: Entity, b: Entity) -> Option<CollisionRule> {
        let context = self.context();
        self.pair_rule_of(context, a, b)
    }

    /// Whether the two collider entities have contacts in the default context.
    pub fn touching(&mut self, a: Entity, b: Entity) -> bool {
        let context = self.context();
        let world = self.app.world();
        let (simulation, colliders, bodies) = (
            world.get::<RapierContextSimulation>(context).unwrap(),
            world.get::<RapierContextColliders>(context).unwrap(),
            world.get::<RapierRigidBodySet>(context).unwrap(),
        );
        simulation
            .contact_pair(colliders, bodies, a, b)
            .is_some_and(|pair| pair.has_any_active_contact())
    }

    /// The Rapier collider of a collider entity in the default context.
    pub fn collider<R>(
        &mut self,
        entity: Entity,
        read: impl FnOnce(&rapier_collider::Collider) -> R,
    ) -> R {
        let context = self.context();
        let colliders = self
            .app
            .world()
            .get::<RapierContextColliders>(context)
            .unwrap();
        let handle = colliders.entity2collider()[&entity];
        read(&colliders.colliders[handle])
    }
}

/// Rapier's collider type, through bevy_rapier.
pub mod rapier_collider {
    pub use bevy_rapier::rapier::prelude::Collider;
}

/// A fixed floor whose top is at y = 0.
pub fn floor() -> impl Bundle {
    (Transform::from_xyz(0.0, -0.5, 0.0), cuboid(5.0, 0.5, 5.0))
}

/// A dynamic ball of radius 0.25 at (x, y).
pub fn ball(x: f32, y: f32) -> impl Bundle {
    (
        Transform::from_xyz(x, y, 0.0),
        RigidBody::Dynamic,
        Collider::ball(0.25),
    )
}

/// Whether a ball of radius 0.25 rests on the floor.
pub fn rests(y: f32) -> bool {
    (0.2..0.3).contains(&y)
}

/// Whether a ball fell through the floor.
pub fn fell_through(y: f32) -> bool {
    y < -1.0
}
