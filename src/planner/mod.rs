//! **Translate**: which colliders Rapier decides itself, and how.
//!
//! A hooked pair costs Rapier its contact recycling, so [`plan`](mod@plan) gives each
//! collider the rules reach the cheapest mechanism that decides all of its
//! pairs exactly (`docs/architecture.md`, "The planner"): a native
//! collider's [`class`] (its effective group and whether its body is
//! dynamic) becomes collision groups, solver groups and collision types
//! through the group-level settings ([`group_settings`]), on the bits the
//! project's own settings leave ([`room`]); personal rules of dynamic
//! bodies ([`personal`]) become groups too where that is exact; each
//! specific entry keeps a decision ([`decisions`]): a bit of Rapier's
//! groups where that is exact, else its cheaper side hooked
//! ([`carriers`]), as pinned pairs are. Each collider's result is a
//! [`ColliderPlan`] ([`collider_plan`]), combined with the project's
//! settings when the hooks write it. The colliders a step's changes reach
//! are planned against the rest of the plan ([`replan`]), with the same
//! decisions a whole plan would make.
//!
//! The planner reads the [`model`](super::model) and asks the
//! [`resolve`](super::resolve) stage nothing: its classes are exact where
//! they say the same as the calculation (`tests/integration/live.rs`
//! compares them). It reads Rapier through [`world`](super::world).

pub(crate) mod carriers;
pub(crate) mod class;
pub(crate) mod collider_plan;
pub(crate) mod decisions;
pub(crate) mod group_settings;
pub(crate) mod personal;
pub(crate) mod plan;
pub(crate) mod replan;
pub(crate) mod room;

pub(crate) use collider_plan::ColliderPlan;
pub(crate) use plan::{Plan, Request, plan};
pub(crate) use replan::replan_some;
