//! **Edit**: what the user edits, and the invariants every edit keeps.
//!
//! A [`CollisionRuleSet`] holds all the rules of one world: the group table
//! ([`group_table`]) relating [`CollisionGroup`]s by [`CollisionRule`]s, the
//! default rule, and for each [`Node`] (a collider or a rigid body) a
//! record ([`records`]) with its group, personal rule and specific entries,
//! which several nodes may share. The crate's own parent map
//! ([`hierarchy`], edited through [`parents`]) makes chains of bodies.
//!
//! Every verb validates on write and trusts on read: a parent cycle is
//! refused with a [`RuleError`], a group of another rule set panics, a dead
//! handle ([`tombstones`]) is ignored, and a removed object leaves no rule
//! behind ([`removal`]). Entries with an end keep it against a clock
//! ([`endings`]), so that a step counts only the ends that come. Each edit is logged ([`changes`]) so that the hooks
//! recalculate just what it can affect. [`integrity`] checks a rule set
//! against its world, [`snapshot`] saves and loads one, and [`joints`] and
//! [`layers`] build rules from what a Rapier project already has, and
//! [`pieces`] gives the pieces of a cut or torn soft body the rules of the
//! body they came from.
//!
//! The next stage, [`resolve`](super::resolve), reads the model and never
//! edits it.

pub(crate) mod body_kinds;
pub(crate) mod changes;
pub(crate) mod decision;
pub(crate) mod ending;
pub(crate) mod endings;
pub(crate) mod error;
pub(crate) mod group;
pub(crate) mod group_table;
pub(crate) mod hierarchy;
pub(crate) mod identity;
pub(crate) mod integrity;
pub(crate) mod joints;
pub(crate) mod layers;
pub(crate) mod node;
pub(crate) mod node_map;
pub(crate) mod node_rules;
pub(crate) mod one_way;
pub(crate) mod parents;
pub(crate) mod pieces;
pub(crate) mod records;
pub(crate) mod removal;
pub(crate) mod rule;
pub(crate) mod rule_set;
pub(crate) mod small_set;
#[cfg(feature = "serde")]
pub(crate) mod snapshot;
pub(crate) mod tombstones;
pub(crate) mod written;

pub use ending::Until;
pub use error::RuleError;
pub(crate) use error::Named;
pub use one_way::{OneWay, OneWayKind};
pub use group::CollisionGroup;
pub use group_table::GroupTable;
pub use integrity::Problem;
pub use node::Node;
pub use rule::CollisionRule;
pub use rule_set::CollisionRuleSet;
#[cfg(feature = "serde")]
pub use snapshot::{LoadError, SavedRuleSet};
pub(crate) use ending::{Countdown, Due, DueEnd};
pub(crate) use body_kinds::{BodyKinds, body_of, dynamic_body, is_dynamic, soft_rigid, soft_surface};
pub(crate) use pieces::Heir;
pub(crate) use node::{Handle, HandleMap};
pub(crate) use node_map::NodeMap;
pub(crate) use node_rules::CollidersUnder;
pub(crate) use records::Record;
pub(crate) use small_set::SmallSet;
pub(crate) use decision::Decision;
pub(crate) use written::{Settings, Written};
