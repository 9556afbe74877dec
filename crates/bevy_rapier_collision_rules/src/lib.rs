//! Hierarchical collision rules for [bevy_rapier3d] and [bevy_rapier2d]
//! users, as components:
//! the rules of [`rapier_collision_rules`] (per-pair specific rules,
//! personal rules and collision groups, from the most specific to the most
//! general across compound hierarchies) with bevy_rapier's world, entities
//! and hooks.
//!
//! - [`RuleGroup`], [`PersonalRule`], [`SpecificRules`] and
//!   [`OneWaySurface`] on an entity
//!   with a rigid body, a soft body or a collider give it rules (the
//!   pieces of a soft body's tear keep them); changing or removing
//!   them reaches live pairs before the next step (sleeping bodies are
//!   woken), and a despawned entity leaves no rules behind.
//! - [`RuleTable`], a resource, holds the group table and the default
//!   rule; a physics context with a [`ContextRuleTable`] uses its own.
//! - Bevy's hierarchy (`ChildOf`) between rigid bodies is the parent map:
//!   a ragdoll's limbs under its pelvis, a vehicle's wheels under its
//!   chassis.
//! - [`CollisionRules`], on each physics context, holds its rules and
//!   live pairs; [`CollisionRulesHooks`] is bevy_rapier's hooks.
//! - With [`CollisionRulesPlugin::with_rule_events`], what changes for
//!   live pairs comes as [`CollisionRuleEvent`] messages.
//! - With the feature `debug-render`, `CollisionRulesDebugPlugin` draws
//!   the rules with Bevy's gizmos, beside bevy_rapier's debug rendering.
//!
//! ```
//! use bevy::prelude::*;
//! use bevy_rapier3d::prelude::*;
//! use bevy_rapier_collision_rules::prelude::*;
//!
//! let mut app = App::new();
//! app.add_plugins((
//!     MinimalPlugins,
//!     TransformPlugin,
//!     RapierPhysicsPlugin::<CollisionRulesHooks>::default(),
//!     CollisionRulesPlugin::default(),
//! ));
//! let (player, debris) = {
//!     let mut table = app.world_mut().resource_mut::<RuleTable>();
//!     (table.create_group(), table.create_group())
//! };
//! app.world_mut()
//!     .resource_mut::<RuleTable>()
//!     .set_group_rule(player, debris, CollisionRule::NoPair);
//! app.world_mut().spawn((RigidBody::Dynamic, Collider::ball(0.5), RuleGroup(player)));
//! app.world_mut().spawn((RigidBody::Dynamic, Collider::ball(0.2), RuleGroup(debris)));
//! app.update();
//! ```
//!
//! See `docs/bevy.md` for how the components map to the rules and which
//! bevy_rapier settings the plugin combines with the project's.
//!
//! One source serves both dimensions, as bevy_rapier's does: the crate
//! `bevy_rapier_collision_rules` over bevy_rapier3d, and
//! `bevy_rapier_collision_rules2d` over bevy_rapier2d, with the same items
//! under the same names (`docs/architecture.md`, "Bevy in two
//! dimensions"). The examples here are written for 3D; in 2D they read
//! `bevy_rapier2d` and `bevy_rapier_collision_rules2d`, and the shapes
//! take two extents.
//!
//! [bevy_rapier3d]: https://docs.rs/bevy_rapier3d
//! [bevy_rapier2d]: https://docs.rs/bevy_rapier2d

#[cfg(not(any(feature = "dim2", feature = "dim3")))]
compile_error!(
    "this source needs a dimension: build it as bevy_rapier_collision_rules (3D) or \
     bevy_rapier_collision_rules2d (2D)"
);

// The dimension's bevy_rapier and the core's tree for the same Rapier, under
// one name each, so that every file is written once for both.
#[cfg(feature = "dim2")]
extern crate bevy_rapier2d as bevy_rapier;
#[cfg(feature = "dim3")]
extern crate bevy_rapier3d as bevy_rapier;
#[cfg(feature = "dim2")]
use rapier_collision_rules::dim2 as collision_rules;
#[cfg(feature = "dim3")]
use rapier_collision_rules::dim3 as collision_rules;

mod components;
#[cfg(feature = "debug-render")]
mod debug;
mod edits;
mod hierarchy;
mod hooks;
mod ledger;
mod misuse;
mod plugin;
mod project;
mod queries;
mod rule_events;
mod rules;
mod step;
mod table;

pub use components::{OneWaySurface, PersonalRule, RuleGroup, SpecificRules};
#[cfg(feature = "debug-render")]
pub use debug::{
    CollisionRulesDebug, CollisionRulesDebugPlugin, RuleDebugLine, RuleDebugLines, RuleDebugObject,
};
pub use hooks::{CollisionRulesHooks, HookedPair};
pub use plugin::{CollisionRulesPlugin, RulesSystems};
pub use queries::{ControllerFollowsRules, EntityExplanation, RuleQueries};
pub use rule_events::CollisionRuleEvent;
pub use rules::CollisionRules;
pub use table::{ContextRuleTable, RuleTable};

/// The main crate's types for this crate's dimension, so that a project
/// that depends only on this crate (and its bevy_rapier) can name
/// everything [`CollisionRules`] and its [`RuleHooks`] take and give.
pub use collision_rules::{
    CalculatorContext, CollisionGroup, CollisionRule, CollisionRuleSet, Explanation, FullPass,
    GroupTable, ManifoldUpdate, Node, OneWay, OneWayKind, PairCreated, PlanCause, Problem,
    ProjectSettings, Reach, RecalculationPolicy, RuleChange, RuleColor, RuleError, RuleEvent,
    RuleEventHandler, RuleHooks, RulePalette, Stage, StepStats, TearListener, Until, WorldRef,
};
/// The main crate, for what is not re-exported here (its dimension's
/// module, its Rapier).
pub use rapier_collision_rules;

/// The plugin, the components and the rules' own types. `Node` is left
/// out: `bevy::prelude` has a `Node` of its own (the UI's) when Bevy's UI
/// is on; it is `bevy_rapier_collision_rules::Node`.
pub mod prelude {
    pub use super::{
        CollisionGroup, CollisionRule, CollisionRuleEvent, CollisionRules, CollisionRulesHooks,
        CollisionRulesPlugin, ContextRuleTable, ControllerFollowsRules, ManifoldUpdate, OneWay,
        OneWayKind, OneWaySurface, PersonalRule, RecalculationPolicy, RuleChange, RuleEvent,
        RuleGroup, RuleHooks, RulePalette, RuleQueries, RuleTable, SpecificRules, Until, WorldRef,
    };
    #[cfg(feature = "debug-render")]
    pub use super::{
        CollisionRulesDebug, CollisionRulesDebugPlugin, RuleDebugLine, RuleDebugLines,
        RuleDebugObject,
    };
}

/// `docs/bevy.md`, whose Rust snippets `cargo test --doc` compiles and
/// runs as this crate's doc tests: the guide's code is a user's, who
/// depends on this crate, bevy and bevy_rapier3d.
#[doc = include_str!("../../../docs/bevy.md")]
#[cfg(all(doctest, feature = "dim3"))]
pub struct BevyGuide;
