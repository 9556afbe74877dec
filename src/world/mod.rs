//! What the crate reads and writes in Rapier: look-ups in Rapier's pair
//! graphs ([`graph`]), the body types of a pair ([`kinds`]), the shapes that
//! are made of parts ([`shapes`]), and each collider's settings as the
//! project set them and as the crate wrote them ([`settings`]), the
//! crate's [`mark`] on the colliders it wrote, which a saved world carries,
//! and whether two sides of a rule with an end are [`apart`](mod@apart).
//!
//! The [`planner`](super::planner) and the [`hooks`](super::hooks) stand on
//! it; it knows nothing of rules.

pub(crate) mod apart;
pub(crate) mod graph;
pub(crate) mod kinds;
pub(crate) mod mark;
pub(crate) mod pair_key;
pub(crate) mod settings;
pub(crate) mod shapes;

pub(crate) use apart::apart;
pub(crate) use graph::{Census, Joints, census, filters_pass, pair_exists, partners_of, same_body};
pub(crate) use kinds::body_types;
pub(crate) use mark::Mark;
pub(crate) use pair_key::PairKey;
pub use settings::ProjectSettings;
pub(crate) use settings::{Settings, Written};
pub(crate) use shapes::made_of_parts;
