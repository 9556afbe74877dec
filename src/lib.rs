#![doc = include_str!("../README.md")]
#![warn(missing_docs)]

mod error;
mod group;
mod hierarchy;
mod hooks;
mod integrity;
mod joints;
mod layers;
mod native;
mod node;
mod pairs;
mod project;
mod query;
mod resolve;
mod rule;
mod rule_set;
#[cfg(feature = "serde")]
mod snapshot;
mod stats;
mod tombstones;

pub use error::RuleError;
pub use group::CollisionGroup;
pub use hooks::{CalculatorContext, PairCreated, RecalculationPolicy, RuleHooks, WorldRef};
pub use integrity::Problem;
pub use node::Node;
pub use pairs::ManifoldUpdate;
pub use rapier3d;
pub use resolve::{Explanation, Stage};
pub use rule::CollisionRule;
pub use rule_set::CollisionRuleSet;
pub use stats::{FullPass, StepStats};
