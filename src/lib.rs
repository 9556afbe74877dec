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

        #[path = "debug/mod.rs"]
        mod debug;
        #[path = "hooks/mod.rs"]
        mod hooks;
        #[path = "model/mod.rs"]
        mod model;
        #[path = "planner/mod.rs"]
        mod planner;
        #[path = "resolve/mod.rs"]
        mod resolve;
        #[path = "world/mod.rs"]
        mod world;

        pub use debug::{RuleColor, RulePalette};
        #[cfg(feature = "debug-render")]
        pub use debug::{
            RuleDebugFilter, RuleDebugRender, RuleLabelBackend, RuleLine, RuleLineKind,
        };
        pub use hooks::{
            CalculatorContext, FullPass, ManifoldUpdate, PairCreated, PlanCause, Reach,
            RecalculationPolicy, RuleChange, RuleEvent, RuleEventHandler, RuleHooks, SplitPiece,
            StepStats, TearListener, WorldRef,
        };
        pub use model::{
            CollisionGroup, CollisionRule, CollisionRuleSet, GroupTable, Node, OneWay, OneWayKind,
            Problem, RuleError, Until,
        };
        #[cfg(feature = "serde")]
        pub use model::{LoadError, SavedRuleSet};
        pub use resolve::{Explanation, Stage};
        pub use world::ProjectSettings;
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

/// `docs/semantics.md`, whose Rust snippets `cargo test --doc` compiles and
/// runs as this crate's doc tests: the worked examples are a user's code.
#[doc = include_str!("../docs/semantics.md")]
#[cfg(all(doctest, feature = "dim3"))]
pub struct SemanticsGuide;
