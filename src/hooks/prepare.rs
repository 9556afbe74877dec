//! Before Rapier's step: noticing what changed (edits, objects removed or
//! changed through Rapier), planning the colliders' settings and
//! recalculating live pairs. It costs in proportion to what the rules
//! reach and the edits since the last step: a world the rules do not reach
//! costs nothing (`docs/architecture.md`, "Cost per step").

use hashbrown::HashSet;
use super::super::rapier::prelude::*;

use super::step::missing;
use super::roster::Look;
use super::super::world::Mark;
use super::{PairKey, PlanCause, RecalculationPolicy, RuleHooks, WorldRef};
use super::super::planner::{self, personal::first_personal, room::Room};
use super::super::{CollisionRule, FullPass, Node, StepStats};

/// What the edits and the look found changed before a step.
struct Changed {
    /// Nodes whose colliders are planned again and whose pairs follow.
    nodes: Vec<Node>,
    /// Colliders the hooks saw for the first time.
    added: Vec<ColliderHandle>,
    /// Entries edited alone, `(owner, subject)`: decided again, and the
    /// pairs of the colliders under their smaller side recalculated.
    entries: Vec<(Node, Node)>,
    /// Bodies whose link in the parent map changed: the colliders under
    /// them changed chains, so the entries that name a node of their chains
    /// are checked again (see `planner::replan_some`).
    rechained: Vec<Node>,
    /// An edit that can reach any pair (the policy recalculates all).
    everything: bool,
}

/// Before the step.
impl RuleHooks {
    /// Before a bare `PhysicsPipeline::step`: notices what the edits touched
    /// and what changed through Rapier among the objects the rules reach
    /// (removed, moved to another body, changed type, new colliders on a
    /// watched body), plans those colliders' flags and groups (every
    /// reached collider if anything they all depend on changed), and
    /// recalculates live pairs as the policy says. In a world with soft
    /// bodies, call [`follow_soft_bodies`](Self::follow_soft_bodies) before
    /// it. Call [`wake_edited`](Self::wake_edited) next, then step with
    /// these hooks, then [`after_step`](Self::after_step).
    ///
    /// Where Rapier's narrow phase is at hand, prefer
    /// [`prepare_with_graph`](Self::prepare_with_graph), as
    /// [`step`](Self::step) does: it hooks the side of a specific entry that
    /// has fewer pairs.
    ///
    /// # Panics
    ///
    /// If Rapier stepped with these hooks since the last `prepare` and
    /// [`after_step`](Self::after_step) was not called after it.
    pub fn prepare(&mut self, bodies: &RigidBodySet, colliders: &mut ColliderSet) {
        self.prepare_seeing(bodies, colliders, None);
    }

    /// [`prepare`](Self::prepare), choosing the side of each specific entry
    /// to hook by the pairs each side has in `narrow_phase` now: a fixed
    /// pickup that touches nothing carries its own rule, a floor under a
    /// pile does not (`docs/architecture.md`, "The planner").
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, RuleHooks};
    ///
    /// let mut world = PhysicsWorld::new();
    /// let ground = world.insert_body(RigidBodyBuilder::fixed());
    /// world.insert_collider(ColliderBuilder::cuboid(10.0, 0.5, 10.0), Some(ground));
    /// let car = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 1.0, 0.0)));
    /// for x in [-0.5, 0.5] {
    ///     world.insert_collider(ColliderBuilder::ball(0.5).translation(Vector::new(x, 0.0, 0.0)), Some(car));
    /// }
    /// let pickup = world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(5.0, 1.0, 0.0)));
    /// let coin = world.insert_collider(ColliderBuilder::ball(0.3), Some(pickup));
    /// let mut hooks = RuleHooks::default();
    /// for _ in 0..30 {
    ///     hooks.step(&mut world);
    /// }
    /// // The car rests on the ground; the pickup touches nothing. NoContacts
    /// // has no form in Rapier's groups: one side is hooked.
    /// hooks.rules_mut().set_specific(car, pickup, CollisionRule::NoContacts);
    /// let w = &mut world;
    /// hooks.prepare_with_graph(&w.bodies, &mut w.colliders, &w.narrow_phase);
    /// assert!(w.colliders[coin].active_hooks().contains(ActiveHooks::FILTER_CONTACT_PAIRS));
    /// hooks.wake_edited(&mut w.islands, &mut w.bodies);
    /// hooks.freeze_manifolds(&w.narrow_phase);
    /// w.step_with_events(&hooks, &());
    /// hooks.after_step(&w.narrow_phase, &w.bodies, &w.colliders);
    /// assert_eq!(hooks.stats().hooked_colliders, 1, "the pickup carries the rule, not the car");
    /// ```
    ///
    /// # Panics
    ///
    /// As [`prepare`](Self::prepare).
    pub fn prepare_with_graph(
        &mut self,
        bodies: &RigidBodySet,
        colliders: &mut ColliderSet,
        narrow_phase: &NarrowPhase,
    ) {
        self.seed_rule_events(WorldRef::new(narrow_phase, bodies, colliders));
        self.prepare_seeing(bodies, colliders, Some(narrow_phase));
    }

    /// The phases of `prepare`, in order.
    fn prepare_seeing(
        &mut self,
        bodies: &RigidBodySet,
        colliders: &mut ColliderSet,
        graph: Option<&NarrowPhase>,
    ) {
        self.open_step();
        self.check_prepared();
        if self.boundary.step == 1 {
            self.adopt_marks(colliders);
        }
        self.settle_pieces(colliders);
        self.end_rules(bodies, colliders);
        let full = self.full_pass();
        if self.planned.exhaustive {
            self.queued.replan.get_or_insert(PlanCause::HookSettings);
        }
        if self.idle(colliders) {
            return;
        }
        // The hooks' own reasons to hook everything came or went. A plan's
        // full pass for the default groups is the plan's own, made again
        // only by the edits that change it: not one of these reasons.
        let hooks_reason = self
            .planned
            .plan
            .full
            .filter(|&reason| reason != FullPass::DefaultGroups);
        if full != hooks_reason {
            self.queued.replan.get_or_insert(PlanCause::HookSettings);
        }
        let mut changed = self.watch_edits(bodies, colliders);
        self.look_at_watched(bodies, colliders, full, &mut changed);
        let replan = self.queued.replan.is_some();
        let under = self.plan_changed(bodies, colliders, graph, &changed);
        // What the edits reached, for rule events: everything after a
        // full plan, else the colliders under the touched nodes.
        if replan || changed.everything {
            self.note_edit(None);
        } else if !under.is_empty() {
            self.note_edit(Some(&under));
        }
        if !self.planned.loaded.is_empty() {
            self.report_loaded();
        }
        if !self.queued.unmarked.is_empty() {
            self.give_marks_back(colliders);
        }
        self.recalculate_changed(bodies, colliders, under, changed.everything);
        for c in std::mem::take(&mut self.queued.wake_colliders) {
            self.queued
                .to_wake
                .extend(colliders.get(c).and_then(|c| c.parent()));
        }
        self.count_hooked();
        self.stats.hooked_colliders = self.planned.hooked;
        self.stats.full_pass = self.planned.plan.full;
        self.stats.shares_project_bits = self.planned.plan.room.is_some();
        self.stats.watched_colliders = self.planned.roster.collider_count();
        self.stats.watched_bodies = self.planned.roster.body_count();
        self.copy_decisions();
    }

    /// The step boundary: checks the last step was finished, counts this one.
    fn open_step(&mut self) {
        if self.boundary.prepared && *self.boundary.stepped.get_mut() {
            missing("after_step", "after the last step");
        }
        self.boundary.prepared = true;
        self.boundary.followed_at_prepare = self.boundary.followed;
        *self.boundary.stepped.get_mut() = false;
        self.boundary.owe_freeze = self.boundary.unsettled;
        self.boundary.step += 1;
        self.stats = StepStats {
            hooked_colliders: self.planned.hooked,
            tracked_pairs: self.pairs.len(),
            shares_project_bits: self.planned.plan.room.is_some(),
            // Counted when the pairs are looked up after a step; a step
            // that skips the look leaves them as they were.
            soft_pairs_without_contacts: self.stats.soft_pairs_without_contacts,
            ..StepStats::default()
        };
    }

    /// Phase 1: what the edits touched starts being watched.
    fn watch_edits(&mut self, bodies: &RigidBodySet, colliders: &ColliderSet) -> Changed {
        let identity = self.decide.rules.identity.number();
        if identity != self.boundary.rules_seen {
            // A set put in place of the one the hooks held, whatever its
            // log says: every pair and plan follows it.
            self.boundary.rules_seen = identity;
            self.decide.rules.mark_all_changed();
        }
        let changes = self.decide.rules.take_changes();
        // The nodes the edits touched, marked for the look (where all the
        // ruled nodes are watched, those are not marked: the whole plan is
        // made again, which asks of each whether the rules still reach it).
        let mut edited = None;
        self.queued.spare_removed = false;
        let nodes = match self.decide.rules.touched_nodes(&changes) {
            Some(nodes) if !self.planned.exhaustive && self.boundary.step > 1 => nodes,
            // The first step reads the whole rule set: it may have been
            // built, or loaded, before the hooks existed. The nodes the
            // edits touched stay in, rules or not: a node whose rules were
            // just cleared has pairs to recalculate.
            touched => {
                let cause = if touched.is_none() && self.boundary.step > 1 {
                    PlanCause::GlobalEdit
                } else {
                    PlanCause::FirstStep
                };
                self.queued.replan.get_or_insert(cause);
                // What the first step reads, or a log that gave up, names
                // no edit: every removal of this step is spared.
                self.queued.spare_removed = touched.is_none() || self.boundary.step <= 1;
                let touched = touched.unwrap_or_default();
                let mut nodes = self.decide.rules.ruled_nodes();
                nodes.extend(touched.iter().copied());
                edited = Some(touched);
                nodes
            }
        };
        for &node in nodes.iter().chain(changes.subjects()) {
            self.watch(bodies, colliders, node, edited.is_none());
        }
        for &node in edited.iter().flatten().chain(changes.subjects()) {
            self.mark_edited(bodies, colliders, node);
        }
        let mut nodes = nodes;
        nodes.extend(self.personal_subjects(changes.subjects(), bodies, colliders));
        // The decisions of entries the edits removed end, and what they said
        // of the colliders under their nodes with them (see
        // `Decisions::forget_ended`).
        let mut ended = Vec::new();
        for &node in &nodes {
            let rules = &self.decide.rules;
            ended.extend(self.planned.plan.decisions.forget_ended(
                node,
                |(x, y)| {
                    rules.specific(x, y) == CollisionRule::Defer
                        && rules.specific(y, x) == CollisionRule::Defer
                },
                |n| rules.in_entries(n),
            ));
        }
        nodes.extend(ended);
        Changed {
            nodes,
            added: Vec::new(),
            entries: changes.entries().to_vec(),
            rechained: changes.rechained().iter().map(|&b| Node::Body(b)).collect(),
            everything: changes.everything,
        }
    }

    /// Phase 2: looks at what is watched (removals, changes, additions),
    /// forgets what Rapier removed, and adds what changed to `changed`.
    fn look_at_watched(
        &mut self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        full: Option<FullPass>,
        changed: &mut Changed,
    ) {
        let everything =
            self.planned.plan.full.is_some() || full.is_some() || self.planned.exhaustive;
        // Whether the rules still reach a watched object changes only with an
        // edit of it (marked by `watch`), or with a global one.
        let ask_all = self.queued.replan.is_some();
        let look = {
            let (rules, plan) = (&self.decide.rules, &self.planned.plan);
            self.planned
                .roster
                .look(bodies, colliders, everything, ask_all, |node| {
                    reached(rules, plan, bodies, colliders, node)
                })
        };
        // The colliders that went leave the hooked count (see
        // `count_hooked`): the look no longer watches them, their plans and
        // writes are still here.
        let left = look.removed_colliders.iter().map(|&(c, _)| c).chain(look.released.iter().copied());
        let left_hooked = self.planned.carrying_hook(left);
        self.planned.hooked = self.planned.hooked.saturating_sub(left_hooked);
        let ended = self.forget_removed(bodies, &look);
        changed.nodes.extend(ended);
        for &c in &look.released {
            if self.planned.plan.forget(c) {
                self.queued.replan.get_or_insert(PlanCause::NewClass);
            }
        }
        // What the crate wrote on a collider the rules let go of goes back
        // to the project's settings: an edit that touched its node plans it
        // anyway, but a global edit names no node.
        self.queued.candidates.extend(look.released.iter().copied());
        changed.nodes.extend(look.changed);
        // Forgetting a removed parent changes its children's chains.
        let removal_changes = self.decide.rules.take_changes();
        match self.decide.rules.touched_nodes(&removal_changes) {
            Some(more) => changed.nodes.extend(more),
            // So many removals that the log gave up: everything, as for an
            // edit log past its limit.
            None => {
                self.queued.replan.get_or_insert(PlanCause::GlobalEdit);
                changed.everything = true;
            }
        }
        changed.entries.extend_from_slice(removal_changes.entries());
        // An entry gone with its owner no longer reaches its subject.
        let subjects = self.personal_subjects(removal_changes.subjects(), bodies, colliders);
        changed.nodes.extend(subjects);
        if !look.project_changed.is_empty() {
            self.queued.replan.get_or_insert(PlanCause::ProjectSettings);
        }
        self.queued.unmarked = look.unmarked;
        if look.foreign_marks {
            self.report_foreign_marks();
        }
        // A project setting can change a pair's rule (the kinematic entry
        // gives way to wider types): those colliders' pairs are recalculated.
        changed
            .nodes
            .extend(look.project_changed.iter().map(|&c| Node::Collider(c)));
        changed.added = look.added;
        self.check_room(colliders);
    }

    /// The subjects of edited or removed entries whose colliders a personal
    /// rule decides: their plans change with the entries that reach them,
    /// since Rapier's groups say a personal rule only for colliders no entry
    /// reaches (see `planner::personal`). Other subjects' colliders keep
    /// their plans.
    fn personal_subjects(
        &self,
        subjects: &[Node],
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
    ) -> Vec<Node> {
        let rules = &self.decide.rules;
        subjects
            .iter()
            .copied()
            .filter(|&subject| {
                self.colliders_under(subject, bodies, colliders)
                    .into_iter()
                    .any(|c| first_personal(rules, bodies, colliders, c).is_some())
            })
            .collect()
    }

    /// Colliders came or went in a world whose plan shares group bits or
    /// collision types with every collider's project settings: the room
    /// those settings leave is read again (a read of each collider, no
    /// planning), and the plan made again only if the room changed
    /// (`docs/architecture.md`, "Cost per step").
    fn check_room(&mut self, colliders: &ColliderSet) {
        let Some((room, count)) = self.planned.plan.room else {
            return;
        };
        if count == colliders.len() || self.queued.replan.is_some() {
            return;
        }
        let now = Room::of_world(colliders, |h, c| self.own_settings(h, c));
        self.stats.read_every_collider = true;
        // Bits are taken from the room: a plan made in another room would
        // take others.
        if now == room {
            self.planned.plan.room = Some((room, colliders.len()));
        } else {
            self.queued.replan.get_or_insert(PlanCause::ProjectSettings);
        }
    }

    /// Phase 3: plans the colliders under every changed node, and those
    /// newly watched (a collider moved onto a watched body may have hooked
    /// pairs whose rule its new chain changes); the whole plan again where
    /// something it depends on changed. Returns the colliders under the
    /// changed nodes, whose pairs follow.
    fn plan_changed(
        &mut self,
        bodies: &RigidBodySet,
        colliders: &mut ColliderSet,
        graph: Option<&NarrowPhase>,
        changed: &Changed,
    ) -> HashSet<ColliderHandle> {
        let mut under: HashSet<ColliderHandle> =
            HashSet::with_capacity(changed.added.len() + changed.nodes.len());
        under.extend(changed.added.iter().copied());
        self.queued.candidates.extend(changed.added.iter().copied());
        for &node in &changed.nodes {
            under.extend(self.colliders_under(node, bodies, colliders));
        }
        // An entry edited alone reaches the pairs between the colliders
        // under its two sides: those of the smaller side's colliders. Its
        // colliders are not planned again unless its decision changes what
        // the decisions say of them (a turret's record names every live
        // ball; the turret is planned again only when its bit changes).
        let mut sides = Vec::new();
        for &(owner, subject) in &changed.entries {
            let (a, b) = (
                self.colliders_under(owner, bodies, colliders),
                self.colliders_under(subject, bodies, colliders),
            );
            sides.extend(if a.len() <= b.len() { a } else { b });
        }
        // Their pairs may have changed in Rapier too: looked up after the step.
        self.queued.touched.extend(under.iter().copied());
        self.queued.touched.extend(sides.iter().copied());
        self.queued
            .touched
            .extend(self.queued.candidates.iter().copied());
        // The colliders under the touched nodes are planned, by a plan of a
        // few or with the rest: one whose last rule this step's edits took
        // (so the look let it go) goes back to Rapier's defaults either way.
        self.queued.candidates.extend(under.iter().copied());
        if let Some(cause) = self.queued.replan {
            self.apply_plan(bodies, colliders, graph, cause);
        } else if !(self.queued.candidates.is_empty() && changed.entries.is_empty()) {
            let mut rechained = HashSet::new();
            for &node in &changed.rechained {
                rechained.extend(self.colliders_under(node, bodies, colliders));
            }
            self.apply_partial_plan(bodies, colliders, graph, &changed.entries, &rechained);
        }
        under.extend(sides);
        under
    }

    /// Phase 4: recalculates live pairs as the policy says: those of the
    /// colliders under the changed nodes (`affected`), every pair after an
    /// edit that reaches any, and the pairs of forced nodes.
    fn recalculate_changed(
        &mut self,
        bodies: &RigidBodySet,
        colliders: &mut ColliderSet,
        affected: HashSet<ColliderHandle>,
        everything_changed: bool,
    ) {
        let mut drop_overrides = HashSet::new();
        for node in std::mem::take(&mut self.queued.forced) {
            drop_overrides.extend(self.colliders_under(node, bodies, colliders));
        }
        let policy = self.decide.policy;
        let everything = policy == RecalculationPolicy::EveryStep
            || (policy == RecalculationPolicy::OnChange
                && (everything_changed || std::mem::take(&mut self.queued.recalculate_all)));
        if policy == RecalculationPolicy::Manual {
            self.queued.recalculate_all = false;
        }
        let affected = if policy == RecalculationPolicy::OnChange && !everything {
            affected
        } else {
            HashSet::new()
        };
        if !(everything || !affected.is_empty() || !drop_overrides.is_empty()) {
            return;
        }
        let refresh = self.recalculate(bodies, colliders, everything, &affected, &drop_overrides);
        for handle in refresh {
            if let Some(collider) = colliders.get_mut(handle) {
                let groups = collider.collision_groups();
                collider.set_collision_groups(InteractionGroups::none());
                collider.set_collision_groups(groups);
                self.queued.regrouped.insert(handle);
            }
        }
    }

    /// Whether the rules reach nothing and nothing waits: the common case
    /// of a world without rules, which costs a few branches per step. A
    /// plan that took bits from the project's room waits on colliders
    /// coming or going, which may change the room (see `check_room`).
    #[inline]
    pub(super) fn idle(&self, colliders: &ColliderSet) -> bool {
        self.planned
            .plan
            .room
            .is_none_or(|(_, count)| count == colliders.len())
            && self.planned.roster.collider_count() == 0
            && self.planned.roster.body_count() == 0
            && self.pairs.is_empty()
            && self.planned.plan.full.is_none()
            && self.queued.replan.is_none()
            && !self.decide.rules.has_changes()
            && self.decide.rules.identity.number() == self.boundary.rules_seen
            && self.queued.candidates.is_empty()
            && self.queued.forced.is_empty()
            && self.queued.wake_colliders.is_empty()
            && self.queued.touched.is_empty()
            && self.queued.regrouped.is_empty()
            && !self.queued.recalculate_all
            && self.decide.policy != RecalculationPolicy::EveryStep
            && self.full_pass().is_none()
            && !self.has_ends()
    }

    /// Why every collider must be looked at and hooked, if it must.
    #[inline]
    pub(super) fn full_pass(&self) -> Option<FullPass> {
        if self.decide.calculator.is_some() {
            Some(FullPass::Calculator)
        } else if self.decide.on_created.is_some() {
            Some(FullPass::PairCreatedCallback)
        } else if self.decide.policy == RecalculationPolicy::Manual {
            Some(FullPass::ManualPolicy)
        } else if !self.planned.enabled {
            Some(FullPass::PlannerOff)
        } else {
            None
        }
    }

    /// Starts watching `node` and every collider under it.
    fn watch(&mut self, bodies: &RigidBodySet, colliders: &ColliderSet, node: Node, edited: bool) {
        match node {
            Node::Body(body) => {
                self.planned.roster.watch_body(bodies, body);
            }
            // Watched even if Rapier removed it: the look then forgets it.
            Node::Collider(c) => self.watch_collider(bodies, colliders, c),
        }
        if edited {
            self.planned.roster.mark(node);
        }
        for c in self.colliders_under(node, bodies, colliders) {
            self.watch_collider(bodies, colliders, c);
            if edited {
                self.planned.roster.mark(Node::Collider(c));
            }
        }
    }

    /// Marks a watched `node` and the colliders under it as touched by an
    /// edit since the last step (see `Roster::mark`).
    fn mark_edited(&mut self, bodies: &RigidBodySet, colliders: &ColliderSet, node: Node) {
        self.planned.roster.mark(node);
        for c in self.colliders_under(node, bodies, colliders) {
            self.planned.roster.mark(Node::Collider(c));
        }
    }

    /// Starts watching collider `c` for an edit, as a candidate for the
    /// plan if it was not watched. One that carries the crate's mark with
    /// no write of these hooks' under it, after their first step, holds
    /// another run's writes (a world put in place without
    /// `world_replaced`; the hooks let go of it since, so the look no
    /// longer compares it): said as the look says it of a watched one.
    fn watch_collider(&mut self, bodies: &RigidBodySet, colliders: &ColliderSet, c: ColliderHandle) {
        if !self.planned.roster.watch_collider(bodies, colliders, c) {
            return;
        }
        self.queued.candidates.push(c);
        let foreign = self.boundary.step > 1
            && self.planned.written.get(c).is_none()
            && colliders.get(c).is_some_and(|co| Mark::on(co).is_marked());
        if foreign {
            self.report_foreign_marks();
        }
    }

    /// Forgets objects Rapier removed: their rules, the entries naming
    /// them, their parent links, their plan, their pairs and the decisions
    /// of their entries. A handle Rapier reuses therefore starts with no
    /// rules. Returns the nodes on the other side of those entries, whose
    /// colliders are planned again.
    fn forget_removed(
        &mut self,
        bodies: &RigidBodySet,
        look: &Look,
    ) -> Vec<Node> {
        let (removed, removed_bodies) = (&look.removed_colliders, &look.removed_bodies);
        let mut gone: Vec<Node> = Vec::new();
        // The bodies of removed colliders that went with them, and the
        // watched bodies removed: a watched body is often both, and is
        // forgotten once.
        let mut gone_bodies: Vec<RigidBodyHandle> = removed_bodies.to_vec();
        for &(handle, body) in removed {
            if self.pairs.remove_collider(handle).0 {
                // The pinned pair's other side was hooked for it.
                self.queued.replan.get_or_insert(PlanCause::PinnedPair);
            }
            if self.planned.plan.forget(handle) {
                self.queued.replan.get_or_insert(PlanCause::NewClass);
            }
            self.keep_written(handle, None);
            gone.push(Node::Collider(handle));
            // A body that keeps other colliders is in the look's `left`.
            gone_bodies.extend(body.filter(|&b| !bodies.contains(b)));
        }
        // In the handles' order: a pair of numbers sorts cheaper than a node.
        gone_bodies.sort_unstable_by_key(|b| b.into_raw_parts());
        gone_bodies.dedup();
        gone.extend(gone_bodies.into_iter().map(Node::Body));
        // Together: whether each is dead to the rule set does not depend on
        // the order Rapier removed them in.
        let spared = if self.queued.spare_removed { None } else { Some(&look.spared[..]) };
        self.decide.rules.remove_nodes(&gone, spared);
        self.stats.removed_objects = removed.len() + removed_bodies.len();
        // A removed object's entries end, and what their decisions said of
        // the colliders on their other side.
        let mut ended = Vec::new();
        let rules = &self.decide.rules;
        for node in gone {
            ended.extend(
                self.planned
                    .plan
                    .decisions
                    .forget_ended(node, |_| true, |n| rules.in_entries(n)),
            );
        }
        ended
    }

    /// The pinned pairs: an override or a manifold setting keeps them hooked.
    pub(super) fn pinned(&self) -> Vec<PairKey> {
        let mut pinned: Vec<PairKey> = self
            .pairs
            .iter()
            .filter(|(_, s)| s.is_pinned())
            .map(|(k, _)| k)
            .collect();
        pinned.sort_unstable();
        pinned
    }
}

/// Whether the rules reach `node`: it carries or is named by rules, is in
/// the parent map, lies under such a node, or has settings of its own in
/// the plan. The hooks watch exactly these.
fn reached(
    rules: &super::super::CollisionRuleSet,
    plan: &planner::Plan,
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    node: Node,
) -> bool {
    if let Node::Collider(c) = node {
        if plan
            .colliders
            .get(c)
            .is_some_and(|p| !p.is_rapier_default())
        {
            return true;
        }
    }
    named(rules, bodies, colliders, node)
}

/// Whether a rule names `node` or a node of its chain: a record, an entry
/// about it, a link of the parent map.
pub(super) fn named(
    rules: &super::super::CollisionRuleSet,
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    node: Node,
) -> bool {
    let mut current = Some(node);
    while let Some(n) = current {
        let linked = match n {
            Node::Body(b) => rules.in_hierarchy(b),
            Node::Collider(_) => false,
        };
        if linked || rules.record(n).is_some() || rules.is_named(n) {
            return true;
        }
        current = rules.hierarchy.next(bodies, colliders, n);
    }
    false
}
