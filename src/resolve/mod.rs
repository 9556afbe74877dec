//! **Decide**: the rule of a pair, a pure function of the rules and the
//! Rapier sets.
//!
//! [`CollisionRuleSet::resolve`](super::CollisionRuleSet::resolve) and
//! [`CollisionRuleSet::explain`](super::CollisionRuleSet::explain) build
//! each collider's chain ([`chain`]: the collider, its body, the body's
//! ancestors, each with its record and effective group), then run the
//! stages in the order of `docs/semantics.md` ([`stages`]: specific with
//! its criss-cross, personal, group, default) and the special case once
//! ([`special_case`](mod@special_case)). An [`Explanation`] ([`explanation`]) says which
//! stage, step and nodes decided. [`query`] turns the same calculation into
//! a scene-query predicate.
//!
//! The stage reads the [`model`](super::model) and nothing else of the
//! crate; the [`planner`](super::planner) and the hooks ask it.

pub(crate) mod chain;
pub(crate) mod explanation;
pub(crate) mod query;
pub(crate) mod special_case;
pub(crate) mod stages;

pub use explanation::{Explanation, Stage};
pub(crate) use chain::Alias;
pub(crate) use special_case::special_case;
