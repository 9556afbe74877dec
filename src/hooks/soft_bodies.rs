//! Soft bodies: what the hooks follow of Rapier's soft-body set between
//! steps (`docs/semantics.md`, "Soft bodies").
//!
//! To the rules a soft body is its root body ([`SoftBody::root_body`]),
//! which holds the colliders of its surface; the proxy body of each further
//! cluster is given the root as parent in the parent map, so that a rule of
//! the root reaches every collider of the body. A piece split off by a cut
//! or a tear (a soft body whose `origin` is a body the hooks know) takes
//! the rules of the body it came from, before the step after the split; its
//! colliders, which Rapier copies from the source's with what the crate
//! wrote on them, keep the project's settings of the source's colliders.
//!
//! The look costs one lookup per soft body while the numbers of soft bodies
//! and of rigid bodies stay the same and every soft body is one the hooks
//! have seen (a cluster added to a soft body adds a proxy body), and a pass
//! over the soft bodies and their clusters (not their particles) otherwise.

use std::sync::Arc;

use hashbrown::HashMap;

use super::super::rapier::prelude::*;

use super::super::{CollisionRuleSet, Node};
use super::super::model::{CollidersUnder, Heir};
use super::super::world::Settings;
use super::tears::TearLog;
use super::{PlanCause, RuleHooks};

/// A piece of a cut or a tear that the hooks gave the rules of the soft
/// body it came from (see [`RuleHooks::split_pieces`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct SplitPiece {
    /// The piece.
    pub piece: SoftBodyHandle,
    /// The soft body it came from.
    pub source: SoftBodyHandle,
}

/// What the hooks know of the world's soft bodies.
#[derive(Debug, Default)]
pub(super) struct SoftBodies {
    /// The world holds soft bodies: no `NoResponse` is left to Rapier's
    /// solver groups, which its soft-body solver does not read.
    pub(super) present: bool,
    /// How many soft bodies, and (while there are some) rigid bodies, the
    /// sets had at the last look.
    counts: (usize, usize),
    /// The soft bodies seen so far, each as last seen.
    known: HashMap<SoftBodyHandle, Seen>,
    /// Pieces get a copy of their source's rules, not its record (see
    /// [`RuleHooks::set_pieces_copy_rules`]).
    copy_to_pieces: bool,
    /// The pieces given their source's rules since the last step.
    pieces: Vec<SplitPiece>,
    /// The tears heard during steps since the last follow.
    tears: Arc<TearLog>,
    /// A plan met a collider of a soft body's mesh since the last follow:
    /// the world has soft bodies, whether or not the hooks were told.
    meshes_planned: bool,
}

impl SoftBodies {
    /// Whether pieces get a copy of their source's rules.
    pub(super) fn copies_to_pieces(&self) -> bool {
        self.copy_to_pieces
    }

    pub(super) fn copy_to_pieces(&mut self, copy: bool) {
        self.copy_to_pieces = copy;
    }

    /// A step ends: the pieces it followed are told.
    pub(super) fn forget_pieces(&mut self) {
        self.pieces.clear();
    }

    pub(super) fn tear_log(&self) -> &Arc<TearLog> {
        &self.tears
    }

    /// Hooks started over keep the log their listeners write to, emptied.
    pub(super) fn keep_tear_log(&mut self, old: &SoftBodies) {
        self.tears = Arc::clone(&old.tears);
        self.tears.clear();
    }

    /// A plan met a collider of a soft body's mesh.
    pub(super) fn mesh_planned(&mut self) {
        self.meshes_planned = true;
    }

    /// Whether the world has soft bodies, as far as the hooks can tell
    /// without being told: a plan has met a soft body's collider since the
    /// last follow, or a soft body the last follow saw is still there (its
    /// root body is: Rapier removes the root with the soft body).
    pub(super) fn seen(&self, bodies: &RigidBodySet) -> bool {
        self.meshes_planned
            || (self.present && self.known.values().any(|seen| bodies.contains(seen.root)))
    }

    /// Whether the hooks have seen soft body `handle`.
    pub(super) fn knows(&self, handle: SoftBodyHandle) -> bool {
        self.known.contains_key(&handle)
    }

    /// The root of soft body `handle` the hooks knew: where its rules are.
    pub(super) fn known_root(&self, handle: SoftBodyHandle) -> Option<RigidBodyHandle> {
        self.known.get(&handle).map(|seen| seen.root)
    }
}

/// Rapier's copy of a cut soft body's collider, waiting for its record
/// (see [`RuleHooks::settle_pieces`]).
#[derive(Debug, Clone)]
pub(super) struct Copied {
    /// The copy.
    copy: ColliderHandle,
    /// The colliders it may copy, the likeliest first.
    originals: CollidersUnder,
    /// How many of `originals` are likeliest: mesh by mesh, then the first.
    likeliest: usize,
}

/// A soft body as the hooks last saw it.
#[derive(Debug, Clone)]
struct Seen {
    /// Its root body: a cut may give the handle's side a new root and the
    /// piece the old one (rapier 0.36.1 does), so the rules are found on the
    /// root the hooks knew, not on either side's root now.
    root: RigidBodyHandle,
    /// The colliders of its meshes: a cut copies them to the other side,
    /// and the project may remove the originals before the hooks see the
    /// cut (the copies still hold what the crate wrote on them).
    meshes: CollidersUnder,
}

impl Seen {
    fn of(body: &SoftBody) -> Seen {
        Seen {
            root: body.root_body(),
            meshes: mesh_colliders(body),
        }
    }

    /// A soft body the hooks see for the first time. Cut before they ever
    /// saw it (pieces of it are new too), it may have given its root to a
    /// piece and taken a new one (rapier 0.36.1): the root it had, where the
    /// rules were given, is the one of those the rules name.
    fn first_sight(handle: SoftBodyHandle, body: &SoftBody, soft_bodies: &SoftBodySet, rules: &CollisionRuleSet) -> Seen {
        let mut seen = Seen::of(body);
        let named = |root: RigidBodyHandle| rules.holds_rules_about(Node::Body(root));
        if !body.pieces().is_empty() && !named(seen.root) {
            let pieces = body.pieces().iter().filter_map(|&p| soft_bodies.get(p));
            if let Some(piece) = pieces.filter(|p| p.origin() == Some(handle)).find(|p| named(p.root_body())) {
                seen.root = piece.root_body();
            }
        }
        seen
    }
}

/// A soft body whose root is no longer `old` (a piece, or a body whose root
/// cluster went): its root now, a proxy the hooks may have linked to `old`,
/// is not `old`'s child any more, and its other proxies linked to `old` are
/// linked to it (`docs/semantics.md`, "Soft bodies").
fn relink_proxies(rules: &mut CollisionRuleSet, body: &SoftBody, old: RigidBodyHandle) {
    let root = body.root_body();
    // The root is in the world: the set names no newer body of its slot.
    rules.forget_unborn(root);
    if rules.parent(root) == Some(old) {
        rules.remove_parent(root);
    }
    for (_, cluster) in body.live_clusters() {
        let proxy = cluster.proxy();
        if proxy != root && rules.parent(proxy) == Some(old) {
            // A proxy is a leaf of Rapier's making: no cycle goes through it.
            let _ = rules.set_parent(proxy, root);
        }
    }
}

/// The colliders of a soft body's meshes.
fn mesh_colliders(body: &SoftBody) -> CollidersUnder {
    body.meshes().map(|m| m.collider()).collect()
}

impl RuleHooks {
    /// Follows the world's soft bodies: pieces of cuts and tears take the
    /// rules of the body they came from, the proxy bodies of a soft body's
    /// clusters get its root body as parent (unless they have one) once the
    /// rules name the root, and
    /// while soft bodies exist `NoResponse` is said by the hook.
    /// [`step`](Self::step) and [`step_pipeline`](Self::step_pipeline) call
    /// it; a project that calls [`prepare`](Self::prepare) itself calls it
    /// before, with the world's `soft_bodies` and `bodies`.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, RuleHooks};
    ///
    /// let mut world = PhysicsWorld::new();
    /// let ground = world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)));
    /// world.insert_collider(ColliderBuilder::cuboid(20.0, 0.5, 20.0), Some(ground));
    /// let bar = SoftBodyBuilder::cuboid(Vector::new(0.0, 0.6, 0.0), Vector::new(1.0, 0.25, 0.25), 6, 2, 2);
    /// let bar = world.insert_soft_body(bar);
    /// let mut hooks = RuleHooks::default();
    /// hooks.rules_mut().set_specific(ground, world.soft_bodies[bar].root_body(), CollisionRule::NoPair);
    /// hooks.step(&mut world);
    /// // A triangle in the plane x = 0.1 that spans the bar.
    /// let blade = [Vector::new(0.1, -10.0, -10.0), Vector::new(0.1, 20.0, -10.0), Vector::new(0.1, -10.0, 20.0)];
    /// let cut = world.cut_soft_body(bar, &blade).expect("the blade crosses the bar");
    /// for _ in 0..60 {
    ///     hooks.step(&mut world);
    /// }
    /// for piece in cut.bodies() {
    ///     let lowest = world.soft_bodies[piece].particle_positions().map(|p| p.y).fold(f32::MAX, f32::min);
    ///     assert!(lowest < -1.0, "each piece falls through the ground: lowest particle at {lowest}");
    /// }
    /// ```
    #[inline]
    pub fn follow_soft_bodies(&mut self, soft_bodies: &SoftBodySet, bodies: &RigidBodySet) {
        self.boundary.followed = true;
        self.soft.meshes_planned = false;
        // A world that never had soft bodies: two compares a step.
        if soft_bodies.is_empty() && !self.soft.present {
            // A soft body inserted, torn and removed between two follows.
            self.soft.tears.clear();
            return;
        }
        self.follow_soft_body_set(soft_bodies, bodies);
        // The pieces torn during the last steps have their rules now.
        self.soft.tears.clear();
    }

    /// Whether the pieces of cuts and tears get a copy of their source's
    /// rules, each in a record of its own, instead of sharing the source's
    /// record (the default: a later edit through the source or any piece
    /// reaches all of them, `docs/semantics.md`, "Soft bodies"). For a
    /// project that keeps each piece's rules itself: the Bevy plugin copies
    /// a torn entity's components onto each piece's entity and turns this on.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, RuleHooks};
    ///
    /// let mut world = PhysicsWorld::new();
    /// let bar = SoftBodyBuilder::cuboid(Vector::new(0.0, 2.0, 0.0), Vector::new(1.0, 0.25, 0.25), 6, 2, 2);
    /// let bar = world.insert_soft_body(bar);
    /// let root = world.soft_bodies[bar].root_body();
    /// let mut hooks = RuleHooks::default();
    /// hooks.set_pieces_copy_rules(true);
    /// hooks.rules_mut().set_personal(root, CollisionRule::NoResponse);
    /// hooks.step(&mut world);
    /// let blade = [Vector::new(0.1, -10.0, -10.0), Vector::new(0.1, 20.0, -10.0), Vector::new(0.1, -10.0, 20.0)];
    /// let cut = world.cut_soft_body(bar, &blade).expect("the blade crosses the bar");
    /// hooks.step(&mut world);
    /// let roots: Vec<_> = cut.bodies().map(|p| world.soft_bodies[p].root_body()).collect();
    /// // Each piece has the rule, in a record of its own.
    /// assert!(roots.iter().all(|&r| hooks.rules().personal(r) == CollisionRule::NoResponse));
    /// assert!(!hooks.rules().shares_rules(roots[0], roots[1]));
    /// ```
    pub fn set_pieces_copy_rules(&mut self, copy: bool) {
        self.soft.copy_to_pieces(copy);
    }

    /// The pieces of cuts and tears that the hooks gave the rules of the
    /// soft body they came from since the last step, in the order they
    /// were followed (a piece whose root is a cluster proxy with rules of
    /// its own holds them over its source's): for a project that
    /// keeps rules of its own beside each soft body (the Bevy plugin's
    /// book of each entity's components) and must note what each piece
    /// was given. Read it after
    /// [`follow_soft_bodies`](Self::follow_soft_bodies), before the step;
    /// the step empties it.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, RuleHooks, SplitPiece};
    ///
    /// let mut world = PhysicsWorld::new();
    /// let bar = SoftBodyBuilder::cuboid(Vector::new(0.0, 2.0, 0.0), Vector::new(1.0, 0.25, 0.25), 6, 2, 2);
    /// let bar = world.insert_soft_body(bar);
    /// let mut hooks = RuleHooks::default();
    /// hooks.rules_mut().set_personal(world.soft_bodies[bar].root_body(), CollisionRule::NoResponse);
    /// hooks.step(&mut world);
    /// let blade = [Vector::new(0.1, -10.0, -10.0), Vector::new(0.1, 20.0, -10.0), Vector::new(0.1, -10.0, 20.0)];
    /// let cut = world.cut_soft_body(bar, &blade).expect("the blade crosses the bar");
    /// hooks.follow_soft_bodies(&world.soft_bodies, &world.bodies);
    /// let piece = cut.bodies().find(|&p| p != bar).expect("a piece");
    /// let split: Vec<_> = hooks.split_pieces().iter().map(|s: &SplitPiece| (s.piece, s.source)).collect();
    /// assert_eq!(split, [(piece, bar)]);
    /// hooks.step(&mut world);
    /// assert!(hooks.split_pieces().is_empty());
    /// ```
    pub fn split_pieces(&self) -> &[SplitPiece] {
        &self.soft.pieces
    }

    /// [`follow_soft_bodies`](Self::follow_soft_bodies) where the world
    /// holds, or held, soft bodies.
    fn follow_soft_body_set(&mut self, soft_bodies: &SoftBodySet, bodies: &RigidBodySet) {
        let present = !soft_bodies.is_empty();
        if present != self.soft.present {
            self.soft.present = present;
            // `NoResponse` moves between Rapier's groups and the hook, also
            // for a group rule whose groups have no member the hooks watch
            // (a rule of the default groups reaches every collider).
            let rules = &self.decide.rules;
            let any_rule = rules.groups.iter().next().is_some()
                || rules.default_rule().is_decided()
                || !rules.ruled_nodes().is_empty();
            if self.planned.roster.collider_count() > 0 || self.planned.plan.full.is_some() || any_rule {
                self.queued.replan.get_or_insert(PlanCause::SoftBodies);
            }
        }
        // A cluster added to a soft body adds its proxy to the bodies.
        // A rule given to a soft body's root links its proxies. A cut and a
        // removal in one step may leave both numbers as they were, and so
        // may a cut that splits a body's root cluster without splitting the
        // body: a soft body the hooks have not seen, or one with another
        // root than they saw, says so (one lookup per soft body).
        let counts = (soft_bodies.len(), if present { bodies.len() } else { 0 });
        let unseen = || {
            soft_bodies
                .iter()
                .any(|(h, body)| self.soft.known.get(&h).is_none_or(|seen| seen.root != body.root_body()))
        };
        if counts == self.soft.counts && !(present && self.decide.rules.has_changes()) && !unseen() {
            return;
        }
        self.soft.counts = counts;
        let mut new: Vec<SoftBodyHandle> = soft_bodies
            .iter()
            .map(|(h, _)| h)
            .filter(|h| !self.soft.known.contains_key(h))
            .collect();
        new.sort_unstable_by_key(|h| h.into_raw_parts());
        // A piece torn off a piece in the same step takes its rules once its
        // own source has them: sources first. A source the project removed
        // since the hooks last saw it is found in their record of it (its
        // rules are still held until the hooks see the removal).
        // What the hooks knew of each source before this look: a source
        // split twice since (two cuts before a step) gave its root to one
        // piece, and its record is refreshed after the first piece.
        let known_before: HashMap<SoftBodyHandle, Seen> = new
            .iter()
            .filter_map(|&h| soft_bodies[h].origin())
            .filter_map(|s| self.soft.known.get(&s).map(|seen| (s, seen.clone())))
            .collect();
        while !new.is_empty() {
            let before = new.len();
            new.retain(|&handle| {
                let body = &soft_bodies[handle];
                let source = body.origin();
                let held = source.and_then(|s| known_before.get(&s).or_else(|| self.soft.known.get(&s)).cloned());
                let Some((source, held)) = source.zip(held) else {
                    // A source new this step waits for its turn; no source,
                    // or one never seen: the piece starts with no rules.
                    if source.is_some_and(|s| soft_bodies.contains(s)) {
                        return true;
                    }
                    let seen = Seen::first_sight(handle, body, soft_bodies, &self.decide.rules);
                    self.soft.known.insert(handle, seen);
                    return false;
                };
                let from = soft_bodies.get(source);
                // The rules are on the root the source had: the roots of both
                // sides now that are not it take them, and the proxies the
                // hooks linked to it on a side that no longer has it are
                // linked to that side's root.
                // Whether the piece holds its source's rules: it keeps the
                // root that holds them, or its root takes them.
                let mut took = true;
                for (side, is_piece) in from.map(|f| (f, false)).into_iter().chain([(body, true)]) {
                    if side.root_body() != held.root {
                        relink_proxies(&mut self.decide.rules, side, held.root);
                        let gave = self.decide.rules.give_piece(held.root, side.root_body(), self.soft.copy_to_pieces, Heir::Piece);
                        took &= gave || !is_piece;
                    }
                }
                let sides: [CollidersUnder; 2] = [
                    from.map(mesh_colliders).unwrap_or_default(),
                    mesh_colliders(body),
                ];
                if let Some(from) = from {
                    self.soft.known.insert(source, Seen::of(from));
                }
                self.soft.known.insert(handle, Seen::of(body));
                if took {
                    self.soft.pieces.push(SplitPiece { piece: handle, source });
                }
                self.copy_settings_across_cut(&held.meshes, &sides);
                false
            });
            if new.len() == before {
                // Sources no longer in the set: the pieces keep no rules.
                for handle in new.drain(..) {
                    self.soft.known.insert(handle, Seen::of(&soft_bodies[handle]));
                }
            }
        }
        self.soft.known.retain(|&h, _| soft_bodies.contains(h));
        self.follow_moved_roots(soft_bodies);
        let rules = &mut self.decide.rules;
        for (_, body) in soft_bodies.iter() {
            let root = body.root_body();
            // Only roots the rules name: a link alone would have the hooks
            // watch a world without rules.
            if !rules.holds_rules_about(Node::Body(root)) {
                continue;
            }
            for (_, cluster) in body.live_clusters() {
                let proxy = cluster.proxy();
                if proxy != root && rules.parent(proxy).is_none() {
                    rules.forget_unborn(proxy);
                    // A proxy is a leaf of Rapier's making: no cycle goes
                    // through it.
                    let _ = rules.set_parent(proxy, root);
                }
            }
        }
    }

    /// A soft body whose root changed without a cut (the project removed
    /// its root's cluster: rapier 0.36.1 makes the proxy of another cluster
    /// the root) keeps its rules: the new root takes them from the old one,
    /// whose rules are still held until the hooks see its removal, and the
    /// proxies linked to the old root are linked to the new one. The record
    /// of each soft body is refreshed on the way (meshes added since).
    fn follow_moved_roots(&mut self, soft_bodies: &SoftBodySet) {
        for (handle, body) in soft_bodies.iter() {
            let Some(seen) = self.soft.known.get_mut(&handle) else {
                continue;
            };
            let (old, new) = (seen.root, body.root_body());
            *seen = Seen::of(body);
            if old == new || old == RigidBodyHandle::invalid() {
                continue;
            }
            relink_proxies(&mut self.decide.rules, body, old);
            // The same body: its record replaces the proxy's (shared: the
            // old root goes with its cluster).
            self.decide.rules.give_piece(old, new, false, Heir::NewRoot);
        }
    }

    /// A cut gives one side the source's colliders and the other Rapier's
    /// copies of them (the source's side may keep the copies), with what the
    /// crate had written on them when the cut was asked for: each copy keeps
    /// the project's settings of the collider it copies, and is planned
    /// before the next step, as a full pass would. Rules the source's
    /// colliders held as colliders stay with those colliders. `seen` are the
    /// source's colliders before the cut: the original of a copy whose side
    /// lost it since (the project removed it) is found there. Which
    /// original a copy is, is settled before the plan (see
    /// [`settle_pieces`](Self::settle_pieces)): Rapier does not say, and
    /// with several meshes the sides' lists need not line up.
    fn copy_settings_across_cut(&mut self, seen: &[ColliderHandle], sides: &[CollidersUnder; 2]) {
        // Whether the crate knows the project's settings of a collider (a
        // copy made by an earlier cut of this step included).
        let known = |c: ColliderHandle, pieces: &[Copied]| {
            self.planned.written.get(c).is_some() || pieces.iter().any(|p| p.copy == c)
        };
        for (side, other) in [(0, 1), (1, 0)] {
            for (i, &copy) in sides[side].iter().enumerate() {
                if known(copy, &self.queued.pieces) {
                    continue;
                }
                // Mesh by mesh where the sides still match, then the first,
                // then every other collider of the two lists.
                let other = &sides[other];
                let mut originals = CollidersUnder::new();
                let positional = [other.get(i), seen.get(i), other.first(), seen.first()];
                for &c in positional.into_iter().flatten() {
                    if !originals.contains(&c) {
                        originals.push(c);
                    }
                }
                let likeliest = originals.len();
                for &c in other.iter().chain(seen.iter()) {
                    if !originals.contains(&c) {
                        originals.push(c);
                    }
                }
                // A copy of colliders the crate never wrote on holds the
                // project's settings alone: nothing to settle.
                if originals[..likeliest].iter().any(|&c| known(c, &self.queued.pieces)) {
                    self.queued.pieces.push(Copied {
                        copy,
                        originals,
                        likeliest,
                    });
                    self.queued.candidates.push(copy);
                }
            }
        }
    }

    /// Before a plan: a cut piece's colliders hold what Rapier copied from
    /// the source's when it made them: what the crate wrote in its last plan
    /// and the project's changes of the original made before the cut. The
    /// copy takes the original's record of what the crate wrote and what
    /// the project's settings were then, so that what differs on the copy
    /// is the project's (a change before the cut is kept, one of the
    /// original after it is not the copy's), and the plan gives the copy
    /// the project's settings with the plan on top, never the crate's old
    /// bits as if they were the project's. The original is the likeliest
    /// candidate that holds what the copy holds (Rapier copied that), in
    /// the world, so that the choice does not depend on which colliders the
    /// crate wrote on: one it never wrote on leaves the copy with the
    /// project's settings it holds. Else (the project changed or removed the
    /// original since the cut) the likeliest candidate the crate wrote on.
    pub(super) fn settle_pieces(&mut self, colliders: &ColliderSet) {
        // In the order of the cuts: a copy of a copy finds its original's
        // record settled.
        for Copied {
            copy,
            originals,
            likeliest,
        } in std::mem::take(&mut self.queued.pieces)
        {
            let Some(holds) = colliders.get(copy).map(Settings::of) else {
                continue;
            };
            let alike = originals
                .iter()
                .find(|&&o| colliders.get(o).map(Settings::of) == Some(holds));
            let written = match alike {
                Some(&original) => self.planned.written.get(original).copied(),
                None => originals[..likeliest].iter().find_map(|&o| self.planned.written.get(o).copied()),
            };
            if let Some(written) = written {
                self.keep_written(copy, Some(written));
                // The copy may carry a hook flag before any plan of it.
                self.planned.recount = true;
            }
        }
    }
}
