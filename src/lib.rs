#![doc = include_str!("../README.md")]
#![warn(missing_docs)]

#[cfg(not(any(feature = "dim2", feature = "dim3")))]
compile_error!("rapier-collision-rules needs a dimension: feature `dim3` (the default) or `dim2`");

/// The crate's module tree, mounted once per dimension over that
/// dimension's Rapier: the rules are written once, and each file names
/// Rapier as `rapier` and its siblings relative to the tree's root
/// (`docs/architecture.md`, "One source, two dimensions").
macro_rules! dimension {
    ($rapier:ident) => {
        pub use $rapier;
        use $rapier as rapier;

        #[path = "error.rs"]
        mod error;
        #[path = "group.rs"]
        mod group;
        #[path = "hierarchy.rs"]
        mod hierarchy;
        #[path = "hooks/mod.rs"]
        mod hooks;
        #[path = "integrity.rs"]
        mod integrity;
        #[path = "joints.rs"]
        mod joints;
        #[path = "layers.rs"]
        mod layers;
        #[path = "native.rs"]
        mod native;
        #[path = "node.rs"]
        mod node;
        #[path = "pairs.rs"]
        mod pairs;
        #[path = "project.rs"]
        mod project;
        #[path = "query.rs"]
        mod query;
        #[path = "resolve.rs"]
        mod resolve;
        #[path = "rule.rs"]
        mod rule;
        #[path = "rule_set.rs"]
        mod rule_set;
        #[cfg(feature = "serde")]
        #[path = "snapshot.rs"]
        mod snapshot;
        #[path = "stats.rs"]
        mod stats;
        #[path = "tombstones.rs"]
        mod tombstones;

        pub use error::RuleError;
        pub use group::CollisionGroup;
        pub use hooks::{CalculatorContext, PairCreated, RecalculationPolicy, RuleHooks, WorldRef};
        pub use integrity::Problem;
        pub use node::Node;
        pub use pairs::ManifoldUpdate;
        pub use resolve::{Explanation, Stage};
        pub use rule::CollisionRule;
        pub use rule_set::CollisionRuleSet;
        pub use stats::{FullPass, StepStats};
    };
}

// Each dimension mounts the same files on purpose: one source, two Rapiers.
#[cfg(feature = "dim3")]
#[allow(clippy::duplicate_mod)]
pub mod dim3;

// The 2D tree's doc examples are the 3D tree's text: with both dimensions
// on they are run once, at the crate's root.
#[cfg(all(feature = "dim2", any(not(doctest), not(feature = "dim3"))))]
#[allow(clippy::duplicate_mod)]
pub mod dim2;

#[cfg(feature = "dim3")]
pub use dim3::*;
