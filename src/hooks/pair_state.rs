//! Live pairs (`docs/semantics.md`, "Decisions about live pairs"): each pair's rule, kept from the pair's creation to
//! its end, its override, its manifold setting, and the contacts frozen by
//! `ManifoldUpdate::Never`.

use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};

use hashbrown::HashMap;
use super::super::rapier::prelude::{
    ColliderHandle, Pose, RigidBodyHandle, RigidBodySet, SolverContact, Vector,
};

use super::super::CollisionRule;
use super::super::model::BodyKinds;
use super::super::resolve::special_case;
use super::super::world::PairKey;

/// How a live pair's contacts are updated (the BEPU design's `ManifoldUpdateSetting`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum ManifoldUpdate {
    /// Contacts are computed when the rule allows them (`Normal`,
    /// `NoResponse`).
    #[default]
    ByRule,
    /// Contacts are computed whatever the rule (collision events included),
    /// and solved only if the rule allows a response.
    Always,
    /// The solver keeps seeing the contacts the pair had when the setting
    /// took effect, fixed in each body's frame, until the setting changes.
    Never,
}

/// Solver contacts frozen in each body's frame.
#[derive(Clone, Debug)]
pub(crate) struct FrozenContact {
    anchor1: Vector,
    anchor2: Vector,
    dist: f32,
    contact: SolverContact,
}

/// One manifold's frozen contacts, keyed by the manifold's sub-shapes.
#[derive(Clone, Debug)]
pub(crate) struct FrozenManifold {
    subshapes: (u32, u32),
    /// The normal in the first body's frame.
    normal: Vector,
    contacts: Vec<FrozenContact>,
}

/// Whether a pinned pair left the table with a removed collider: its
/// other side may still be hooked for it, and only a plan gives it back.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[must_use]
pub(crate) struct PinnedGone(pub(crate) bool);

/// What the crate keeps about one live pair.
#[derive(Debug)]
pub(crate) struct PairState {
    /// The rule the calculation (and the created callback) gave.
    pub(crate) computed: CollisionRule,
    /// A rule set with `set_pair_rule`, kept for the pair's life.
    pub(crate) overridden: Option<CollisionRule>,
    pub(crate) manifold: ManifoldUpdate,
    /// The step in which the hook last answered for this pair: a second
    /// answer in one step comes from the CCD (see `RuleHooks`).
    pub(crate) last_answer: AtomicU64,
    /// Where the pair's bodies were at the hook's last answer, for a pair
    /// whose contacts get no response (see `answer.rs`, `poses`): the CCD
    /// asks at the poses of the narrow phase's last pass.
    pub(crate) poses: AtomicU64,
    /// The contacts frozen by `ManifoldUpdate::Never`, with the step they
    /// were frozen in; `None` until the first contact update after the
    /// setting took effect.
    pub(crate) frozen: Mutex<Option<(u64, Vec<FrozenManifold>)>>,
    /// Rapier dropped the pair when its collider was regrouped, and may find
    /// it again: the state is kept for one step, but the pair is not live.
    pub(crate) absent: bool,
    /// Whether each collider's body (in key order) was dynamic when the rule
    /// was computed: the default groups follow the body types, which may
    /// change on a body the hooks do not watch.
    pub(crate) kinds: BodyKinds,
    /// A collider of the pair is made of parts (see [`PairKey::made_of_parts`]):
    /// `ManifoldUpdate::Never` is refused for it.
    pub(crate) parts: bool,
}

impl PairState {
    pub(crate) fn new(
        computed: CollisionRule,
        step: u64,
        kinds: BodyKinds,
        parts: bool,
    ) -> PairState {
        PairState {
            computed,
            overridden: None,
            manifold: ManifoldUpdate::ByRule,
            last_answer: AtomicU64::new(step),
            poses: AtomicU64::new(0),
            frozen: Mutex::new(None),
            absent: false,
            kinds,
            parts,
        }
    }

    /// Whether an override or a manifold setting keeps the pair hooked (a
    /// pinned pair): the plan hooks a side of it while it lives.
    #[inline]
    pub(crate) fn is_pinned(&self) -> bool {
        self.overridden.is_some() || self.manifold != ManifoldUpdate::ByRule
    }

    /// The pair's rule: its override if it has one, else the computed rule.
    #[inline]
    pub(crate) fn rule(&self) -> CollisionRule {
        self.rule_for(self.kinds)
    }

    /// The pair's rule while its bodies are dynamic as `kinds` says. An
    /// override takes the special case like every other answer: two
    /// non-dynamic bodies cannot respond, so `Normal` is `NoResponse`
    /// (`docs/semantics.md`). The computed rule has it already.
    #[inline]
    pub(crate) fn rule_for(&self, kinds: BodyKinds) -> CollisionRule {
        match self.overridden {
            Some(rule) => special_case(kinds, rule),
            None => self.computed,
        }
    }

    /// Whether the hook answered for this pair in `step`.
    #[inline]
    pub(crate) fn answered_in(&self, step: u64) -> bool {
        self.last_answer.load(Ordering::Relaxed) == step
    }

    /// Records an answer in `step`; `true` if the hook already answered for
    /// this pair in the same step.
    #[inline]
    pub(crate) fn answered_again(&self, step: u64) -> bool {
        self.last_answer.swap(step, Ordering::Relaxed) == step
    }

    /// Records an answer in `step` with the bodies at `poses`; `true` if it
    /// is the CCD's: the hook already answered in this step and no body
    /// moved since. The narrow phase asks again only after the bodies moved
    /// (a CCD substep or another pipeline step between the hooks'
    /// `prepare` and `after_step`), the CCD at the poses of the narrow
    /// phase's last pass (`docs/architecture.md`, "The CCD").
    #[inline]
    pub(crate) fn answered_by_ccd(&self, step: u64, poses: u64) -> bool {
        let again = self.answered_again(step);
        let moved = self.poses.swap(poses, Ordering::Relaxed) != poses;
        again && !moved
    }
}

/// The live-pair table. Pairs whose rule is `NoPair` stay in it (so that the
/// hook keeps refusing them) but are not live for the user. Each collider's
/// pairs are indexed, so that an edit or a removal costs the pairs of the
/// colliders it reaches, not a pass over the table (`docs/architecture.md`,
/// "Cost per step").
#[derive(Debug, Default)]
pub(crate) struct PairTable {
    pairs: HashMap<PairKey, PairState>,
    /// Each collider's pairs in the table (a few each: a hooked collider's
    /// neighbours).
    by_collider: HashMap<ColliderHandle, Vec<PairKey>>,
}

impl PairTable {
    #[inline]
    pub(crate) fn get(&self, key: PairKey) -> Option<&PairState> {
        self.pairs.get(&key)
    }

    pub(crate) fn get_mut(&mut self, key: PairKey) -> Option<&mut PairState> {
        self.pairs.get_mut(&key)
    }

    pub(crate) fn insert(&mut self, key: PairKey, state: PairState) {
        if self.pairs.insert(key, state).is_none() {
            let (a, b) = key.colliders();
            self.by_collider.entry(a).or_default().push(key);
            self.by_collider.entry(b).or_default().push(key);
        }
    }

    pub(crate) fn retain(&mut self, mut keep: impl FnMut(PairKey, &mut PairState) -> bool) {
        let mut dropped = Vec::new();
        self.pairs.retain(|key, state| {
            let kept = keep(*key, state);
            if !kept {
                dropped.push(*key);
            }
            kept
        });
        for key in dropped {
            self.unindex(key);
        }
    }

    /// Forgets every pair of `collider`.
    pub(crate) fn remove_collider(&mut self, collider: ColliderHandle) -> PinnedGone {
        let mut pinned = PinnedGone(false);
        for key in self.by_collider.remove(&collider).unwrap_or_default() {
            pinned.0 |= self.pairs.remove(&key).is_some_and(|state| state.is_pinned());
            let (a, b) = key.colliders();
            let other = if a == collider { b } else { a };
            self.unlink(other, key);
        }
        pinned
    }

    /// The pairs of `collider` in the table.
    pub(crate) fn keys_of(&self, collider: ColliderHandle) -> &[PairKey] {
        self.by_collider.get(&collider).map_or(&[], Vec::as_slice)
    }

    fn unindex(&mut self, key: PairKey) {
        let (a, b) = key.colliders();
        self.unlink(a, key);
        self.unlink(b, key);
    }

    fn unlink(&mut self, collider: ColliderHandle, key: PairKey) {
        if let Some(keys) = self.by_collider.get_mut(&collider) {
            if let Some(i) = keys.iter().position(|&k| k == key) {
                keys.swap_remove(i);
            }
            if keys.is_empty() {
                self.by_collider.remove(&collider);
            }
        }
    }

    #[inline]
    pub(crate) fn len(&self) -> usize {
        self.pairs.len()
    }

    #[inline]
    pub(crate) fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }

    pub(crate) fn iter(&self) -> impl Iterator<Item = (PairKey, &PairState)> + '_ {
        self.pairs.iter().map(|(key, state)| (*key, state))
    }
}

/// The pose of a collider's body, or the identity for a collider without one.
fn body_pose(bodies: &RigidBodySet, body: Option<RigidBodyHandle>) -> Pose {
    body.and_then(|handle| bodies.get(handle))
        .map_or(Pose::IDENTITY, |body| *body.position())
}

/// Freezes `contacts` (world anchors, as the contact-modification hook sees
/// them) in each body's frame.
pub(crate) fn freeze(
    bodies: &RigidBodySet,
    body1: Option<RigidBodyHandle>,
    body2: Option<RigidBodyHandle>,
    subshapes: (u32, u32),
    normal: Vector,
    contacts: &[SolverContact],
) -> FrozenManifold {
    let (pose1, pose2) = (body_pose(bodies, body1), body_pose(bodies, body2));
    FrozenManifold {
        subshapes,
        normal: pose1.inverse_transform_vector(normal),
        contacts: contacts
            .iter()
            .map(|contact| FrozenContact {
                anchor1: pose1.inverse_transform_point(contact.anchor1),
                anchor2: pose2.inverse_transform_point(contact.anchor2),
                dist: contact.dist - (contact.anchor2 - contact.anchor1).dot(normal),
                contact: *contact,
            })
            .collect(),
    }
}

/// Replays a frozen manifold at the bodies' current poses: the anchors move
/// with their bodies, and the distance follows them along the frozen normal.
/// Sets `normal`, and gives the contacts to put in place of the solver's
/// (a `Vec` in 3D, a two-contact array in 2D).
pub(crate) fn thaw<'a>(
    bodies: &RigidBodySet,
    body1: Option<RigidBodyHandle>,
    body2: Option<RigidBodyHandle>,
    frozen: &'a FrozenManifold,
    normal: &mut Vector,
) -> impl Iterator<Item = SolverContact> + 'a {
    let (pose1, pose2) = (body_pose(bodies, body1), body_pose(bodies, body2));
    *normal = pose1.transform_vector(frozen.normal);
    let normal = *normal;
    frozen.contacts.iter().map(move |f| {
        let anchor1 = pose1.transform_point(f.anchor1);
        let anchor2 = pose2.transform_point(f.anchor2);
        let mut contact = f.contact;
        contact.anchor1 = anchor1;
        contact.anchor2 = anchor2;
        contact.dist = f.dist + (anchor2 - anchor1).dot(normal);
        contact
    })
}

impl FrozenManifold {
    pub(crate) fn subshapes(&self) -> (u32, u32) {
        self.subshapes
    }
}
