//! Half of the set-up is loud: the rules need both `CollisionRulesPlugin`
//! and bevy_rapier stepping with `CollisionRulesHooks` (directly or inside
//! a project's own hooks), and each without the other fails silently. Each
//! case is warned about once per app, through the `log` facade that Bevy's
//! `LogPlugin` (and bevy_rapier's own messages) go through (`docs/bevy.md`,
//! "Half a set-up").

use bevy::ecs::intern::Interned;
use bevy::ecs::schedule::ScheduleLabel;
use bevy::prelude::*;

use super::ledger::Ledger;

/// A `Local` of `CollisionRulesHooks`: Bevy makes it from the world when it
/// initializes the system that takes the hooks, which is when bevy_rapier's
/// step is set up (at the first run of its schedule, after every plugin was
/// built). That is the one moment the hooks can see the world: they note
/// in the plugin's [`Ledger`] that they are in use, or warn that
/// `CollisionRulesPlugin` is missing.
///
/// It inserts nothing: Bevy keeps each resource in an entity of its own,
/// and one spawned here, between the project's spawns, changes the order in
/// which bevy_rapier gives its colliders their handles, and with it the
/// physics of a world without rules (`docs/bevy.md`, "Without rules").
#[doc(hidden)]
pub struct HooksProbe;

impl FromWorld for HooksProbe {
    fn from_world(world: &mut World) -> Self {
        match world.get_resource_mut::<Ledger>() {
            Some(mut ledger) => ledger.bypass_change_detection().hooks_in_use = true,
            // Once per system that takes the hooks: bevy_rapier's step.
            None => log::warn!("{}", without_plugin()),
        }
        HooksProbe
    }
}

/// The warning for `CollisionRulesHooks` stepping without the plugin.
pub(crate) fn without_plugin() -> &'static str {
    "CollisionRulesHooks is in use (bevy_rapier steps with it), but \
     CollisionRulesPlugin was not added: no physics context has rules, so every RuleGroup, \
     PersonalRule, SpecificRules and the RuleTable are ignored. Fix: add \
     CollisionRulesPlugin::default() to the app, in bevy_rapier's schedule \
     (`.in_fixed_schedule()` or `.in_schedule(label)` if bevy_rapier runs \
     in another one)."
}

/// The warning for the plugin without `CollisionRulesHooks` in bevy_rapier's
/// step in the plugin's schedule: other hooks, or another schedule.
pub(crate) fn without_hooks(schedule: Interned<dyn ScheduleLabel>) -> String {
    format!(
        "CollisionRulesPlugin runs in {schedule:?}, but bevy_rapier does not \
         step with CollisionRulesHooks there. If it steps with other hooks \
         (RapierPhysicsPlugin::<()>, or a project's hooks without \
         CollisionRulesHooks), the rules the plugin turns into Rapier's \
         collision and solver groups still hold and every rule left to the \
         hooks (NoContacts, most NoResponse and specific rules, \
         ManifoldUpdate, live-pair overrides) is silently dropped; if it \
         steps in another schedule, the rules are prepared out of step with \
         its steps. Fix: RapierPhysicsPlugin::<CollisionRulesHooks>, or a \
         project's own hooks with a CollisionRulesHooks field that they ask \
         first, in the same schedule as CollisionRulesPlugin."
    )
}

/// The warning for a rule component on an entity without a physics object.
pub(crate) fn bare_carrier(entity: Entity) -> String {
    format!(
        "{entity} has a rule component (RuleGroup, PersonalRule, SpecificRules or \
         OneWaySurface) but no RigidBody, Collider or SoftBody: its rules reach nothing, not even \
         its children, until it has one (later entities like it are not reported). Rules pass \
         down from a rigid body to its colliders and, through ChildOf, to the rigid bodies below \
         it; a plain entity in between passes nothing. Fix: put the component on the rigid body \
         entity (or on each collider)."
    )
}

/// The warning for a `ContextRuleTable` on an entity that is not a physics
/// context.
pub(crate) fn table_off_context(entity: Entity) -> String {
    format!(
        "{entity} has a ContextRuleTable but is not a physics context (no \
         RapierContextSimulation): no context reads it, and its groups and default rule reach \
         nothing. Fix: insert it on the context's entity (the one with \
         RapierContextSimulation; DefaultRapierContext for the default one), or change the \
         shared RuleTable resource."
    )
}

/// Runs once, at the first run of the plugin's systems: by then Bevy has
/// initialized every system of the schedule, so if bevy_rapier steps there
/// with hooks that include `CollisionRulesHooks`, the [`HooksProbe`] has
/// noted them in the [`Ledger`].
pub(crate) fn check_hooks(schedule: Interned<dyn ScheduleLabel>) -> impl FnMut(Res<Ledger>) {
    move |ledger| {
        if !ledger.hooks_in_use {
            log::warn!("{}", without_hooks(schedule));
        }
    }
}
