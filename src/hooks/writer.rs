//! Writing the plan into Rapier's colliders, combined with the project's
//! own settings, touching only the colliders whose settings differ.

use hashbrown::HashSet;
use super::super::rapier::prelude::*;

use super::prepare::named;
use super::{ManifoldUpdate, PlanCause, RecalculationPolicy, RuleHooks, own_settings};
use super::super::model::dynamic_body;
use super::super::Node;
use super::super::planner::decisions::Decisions;
use super::super::planner::{self, ColliderPlan, Request};
use super::super::world::{Mark, Settings, Written};

/// Writing the plan.
impl RuleHooks {
    /// Plans every reached collider again (every collider in a full pass)
    /// and gives each the flags, groups and types of its plan, touching only
    /// those that differ; colliders no longer reached get Rapier's defaults back.
    pub(super) fn apply_plan(
        &mut self,
        bodies: &RigidBodySet,
        colliders: &mut ColliderSet,
        graph: Option<&NarrowPhase>,
        cause: PlanCause,
    ) {
        self.adopt_saved_plan(colliders);
        let pinned = self.pinned();
        let ruled = self.decide.rules.ruled_nodes();
        // The watched colliders, and those waiting for a plan of their own
        // (a cut piece's copies of its source's colliders, which carry what
        // the crate wrote on the source).
        let mut reached: Vec<ColliderHandle> = self.planned.roster.colliders().collect();
        let waiting = self.queued.candidates.iter().copied();
        reached.extend(waiting.filter(|&c| colliders.contains(c)));
        // And every collider that carries the crate's writes (a loaded
        // set's among them, which no roster watches yet): one no rule
        // reaches any more, as after an end that came at the first step
        // after loading, gets the project's settings back.
        let carrying = self.planned.written.iter().map(|(c, _)| c);
        reached.extend(carrying.filter(|&c| colliders.contains(c)));
        reached.sort_unstable_by_key(|h| h.into_raw_parts());
        reached.dedup();
        let own = |h: ColliderHandle, c: &Collider| self.own_settings(h, c);
        let pairs_of = pairs_in(graph);
        let request = Request {
            rules: &self.decide.rules,
            bodies,
            colliders,
            reached: &reached,
            ruled: &ruled,
            pinned: &pinned,
            all_hooked: self.full_pass(),
            own: &own,
            pairs_of: &pairs_of,
            decided: &self.planned.plan.decisions,
            soft_bodies: self.soft.present,
            loaded: !self.planned.loaded.is_empty(),
        };
        let plan = planner::plan(&request);
        // Never pairs: the hooked side also modifies the pair's contacts.
        self.planned.modifying = self
            .pairs
            .iter()
            .filter(|(_, s)| s.manifold == ManifoldUpdate::Never)
            .map(|(k, _)| {
                let (a, b) = k.colliders();
                if plan.hooks(a) {
                    a
                } else {
                    b
                }
            })
            .collect();
        // Colliders planned before and not now go back to Rapier's defaults.
        let mut writes: Vec<(ColliderHandle, ColliderPlan)> = Vec::new();
        let mut unplanned = Vec::new();
        for &handle in &reached {
            if plan.colliders.get(handle).is_none() {
                if let Some(collider) = colliders.get(handle) {
                    let dynamic = dynamic_body(bodies, collider.parent());
                    writes.push((handle, ColliderPlan::unreached(dynamic)));
                }
                unplanned.push(handle);
            }
        }
        let resets = writes.len();
        writes.extend(plan.colliders.iter().map(|(h, e)| (h, *e)));
        self.stats.planned_colliders = writes.len() - resets;
        self.stats.full_plan = Some(cause);
        for &(handle, _) in &writes[resets..] {
            self.planned.roster.watch_collider(bodies, colliders, handle);
        }
        self.write_in_order(bodies, colliders, &mut writes);
        for handle in unplanned {
            self.planned.plan.colliders.remove(handle);
        }
        self.planned.plan = plan;
        let planned: Vec<ColliderHandle> = self.planned.plan.colliders.iter().map(|(h, _)| h).collect();
        self.let_go_unnamed(bodies, colliders, &planned);
        self.queued.replan = None;
        self.queued.candidates.clear();
        self.planned.recount = true;
        // The set's copy of the decisions is the plan's (a set built by
        // code and put in place of another starts without them).
        self.planned.plan.decisions.drain_journal().for_each(drop);
        self.decide.rules.decisions = self.planned.plan.decisions.all().collect();
    }

    /// Plans the candidate colliders and decides the entries edited alone
    /// (`(owner, subject)`) when the rest of the plan stands (see
    /// `planner::replan_some`), else everything reached.
    pub(super) fn apply_partial_plan(
        &mut self,
        bodies: &RigidBodySet,
        colliders: &mut ColliderSet,
        graph: Option<&NarrowPhase>,
        edited: &[(Node, Node)],
        rechained: &HashSet<ColliderHandle>,
    ) {
        let mut handles = std::mem::take(&mut self.queued.candidates);
        handles.sort_unstable_by_key(|h| h.into_raw_parts());
        handles.dedup();
        let pinned = self.pinned();
        let written = &self.planned.written;
        let own = |h: ColliderHandle, c: &Collider| own_settings(written, h, c);
        let pairs_of = pairs_in(graph);
        let all_hooked = self.full_pass();
        let decided = Decisions::default();
        let request = Request {
            rules: &self.decide.rules,
            bodies,
            colliders,
            reached: &handles,
            ruled: &[],
            pinned: &pinned,
            all_hooked,
            own: &own,
            pairs_of: &pairs_of,
            decided: &decided,
            soft_bodies: self.soft.present,
            loaded: false,
        };
        let Some(planned) = planner::replan_some(&mut self.planned.plan, &request, &handles, edited, rechained)
        else {
            // The whole plan plans the candidates too (see `apply_plan`).
            self.queued.candidates = handles;
            return self.apply_plan(bodies, colliders, graph, PlanCause::NewClass);
        };
        self.stats.planned_colliders = planned.len();
        // The planned colliders' share of the hooked count, before and
        // after their plan (see `count_hooked`).
        let hooked_before = self.planned.hooked_among(planned.iter().map(|&(h, _)| h));
        for &(handle, _) in &planned {
            self.planned.roster.watch_collider(bodies, colliders, handle);
        }
        let mut planned = planned;
        self.write_in_order(bodies, colliders, &mut planned);
        for &(handle, entry) in &planned {
            self.planned.plan.colliders.insert(handle, entry);
        }
        let handles: Vec<ColliderHandle> = planned.iter().map(|&(h, _)| h).collect();
        self.let_go_unnamed(bodies, colliders, &handles);
        let hooked_after = self.planned.hooked_among(handles.iter().copied());
        self.planned.hooked = (self.planned.hooked + hooked_after).saturating_sub(hooked_before);
    }

    /// Lets go of those of the just planned `handles` that the plan need not
    /// keep: planned with Rapier's defaults, and named by no rule (the look
    /// let them go, or their last rule or the last entry about them went
    /// this step). Their project's settings are back; they are neither
    /// planned nor watched any more, unless every collider is (a full
    /// pass). The look runs before the step's edits are planned, so it
    /// cannot tell these itself.
    fn let_go_unnamed(&mut self, bodies: &RigidBodySet, colliders: &ColliderSet, handles: &[ColliderHandle]) {
        if self.full_pass().is_some() || self.planned.plan.full.is_some() {
            return;
        }
        for &handle in handles {
            let default = self.planned.plan.colliders.get(handle).is_some_and(|e| e.is_rapier_default());
            if default && !named(&self.decide.rules, bodies, colliders, Node::Collider(handle)) {
                // Of a default class, which always counts as having members:
                // forgetting it changes nothing else of the plan.
                self.planned.plan.forget(handle);
                self.planned.roster.let_go(handle);
            }
        }
    }

    /// Writes each collider's plan in the node order, whichever way the
    /// plan came to them: Rapier lists the colliders it is told of in the
    /// order they are touched, and that order decides how its broad phase
    /// rebuilds its tree, the order of new pairs, and the solver's. A plan
    /// of a few colliders and a whole plan that write the same settings
    /// then leave Rapier in the same state, bit for bit.
    fn write_in_order(
        &mut self,
        bodies: &RigidBodySet,
        colliders: &mut ColliderSet,
        writes: &mut [(ColliderHandle, ColliderPlan)],
    ) {
        writes.sort_unstable_by_key(|(h, _)| h.into_raw_parts());
        for &(handle, entry) in writes.iter() {
            self.configure(bodies, colliders, handle, entry);
        }
    }

    /// Counts the watched colliders that carry a hook flag the crate gave
    /// them, after a whole plan or when the crate's contact modification
    /// came or went; other steps keep the count up as they change it
    /// (which a debug build checks against a count of every one).
    pub(super) fn count_hooked(&mut self) {
        let modifies = self.modifies_contacts();
        if !std::mem::take(&mut self.planned.recount) && modifies == self.planned.counted_modifies {
            debug_assert_eq!(
                self.planned.hooked,
                self.planned.hooked_among(self.planned.roster.colliders()),
                "the hooked colliders kept up by the step's changes"
            );
            return;
        }
        self.planned.counted_modifies = modifies;
        self.planned.hooked = self.planned.hooked_among(self.planned.roster.colliders());
    }

    /// Gives one collider its plan entry combined with the project's own
    /// settings, touching it only if they differ, and keeps the bookkeeping
    /// that follows (waking, newly hooked colliders, regrouping).
    fn configure(
        &mut self,
        bodies: &RigidBodySet,
        colliders: &mut ColliderSet,
        handle: ColliderHandle,
        entry: ColliderPlan,
    ) {
        let Some(current) = colliders.get(handle) else {
            return;
        };
        let dynamic = dynamic_body(bodies, current.parent());
        let before = self.planned.plan.entry(handle, dynamic);
        let now = Settings::of(current);
        let own = self.own_settings(handle, current);
        // A hooked soft surface also sees its soft-soft contacts, which a
        // `NoResponse` pair disables (`docs/semantics.md`, "Soft bodies").
        let soft_mesh = current.deformable_mesh_ref().is_some();
        if soft_mesh {
            self.soft.mesh_planned();
        }
        let one_way = self.decide.rules.one_way_of(bodies, colliders, handle).is_some();
        let modifying = self.planned.modifying.contains(&handle) || (entry.hooked() && soft_mesh) || one_way;
        let mut target = entry.combined(own, modifying);
        // A soft body's pairs with a one-way surface are barred in the
        // filter: the soft-body solver reads no solver contacts
        // (`docs/semantics.md`, "One-way surfaces").
        if one_way && self.soft.present {
            target.hooks |= ActiveHooks::FILTER_CONTACT_PAIRS;
        }
        // The project changed a setting through Rapier: its pairs may have
        // ended (Rapier's own filters stop them), looked up after the step.
        if self.planned.written.get(handle).is_some_and(|w| w.own != own) {
            self.queued.touched.push(handle);
        }
        // The collider is the project's again once the crate adds nothing.
        let written = (target != own).then_some(Written { own, wrote: target });
        // The collider carries the mark of what is the crate's, which a
        // world saved by any means keeps (`world/mark.rs`).
        let mark = Mark::of_written(written.as_ref());
        self.keep_written(handle, written);
        // What the collider shows from now on, the crate's write or the
        // project's own settings: the look notices the project's changes
        // of either (`docs/semantics.md`, "Runtime changes").
        self.planned.roster.wrote(handle, Some((target, mark)));
        let events = current.active_events();
        let marked = mark.in_events(events);
        if target == now {
            if marked != events {
                colliders[handle].set_active_events(marked);
            }
            return;
        }
        // New settings take effect on a sleeping body once it wakes (a pair
        // whose rule an edit changed wakes its bodies on its own).
        if self.decide.policy != RecalculationPolicy::Manual && before != entry {
            self.queued.to_wake.extend(current.parent());
        }
        self.queued.touched.push(handle);
        if now.collision != target.collision || now.solver != target.solver {
            self.queued.regrouped.insert(handle);
        }
        // A change of hook flags alone sets no change flag Rapier's narrow
        // phase reads. A collider of a non-dynamic body may never wake: when
        // the hook takes over (or lets go of) its pairs, Rapier must look at
        // them. That holds the first time a rule reaches the collider too: a
        // one-way surface given to a fixed cube reaches its pair with
        // another fixed cube at once. A moving collider that loses its hook
        // flags has pairs Rapier may recycle (a pair without hooks whose
        // pose barely moved keeps its contacts as they were): they would
        // keep what the hook last answered (`docs/semantics.md`, "Decisions
        // about live pairs").
        let rehook = now.hooks != target.hooks && (!dynamic || target.hooks.is_empty());
        if rehook {
            self.queued.regrouped.insert(handle);
        }
        // `get_mut` marks a collider modified: only for those that differ.
        let collider = &mut colliders[handle];
        if rehook && now.types == target.types {
            collider.set_collision_groups(InteractionGroups::none());
        }
        target.write(collider);
        collider.set_active_events(marked);
    }
}

/// What the crate wrote.
impl RuleHooks {
    /// Keeps what the crate wrote on `handle` (`None`: nothing, its
    /// settings are the project's), and the rule set's copy of it, which a
    /// saved rule set carries (`docs/semantics.md`, "Saving and loading").
    pub(super) fn keep_written(&mut self, handle: ColliderHandle, written: Option<Written>) {
        match written {
            Some(written) => {
                self.planned.written.insert_evicting(handle, written);
                self.decide.rules.writes.insert_evicting(handle, written);
            }
            None => {
                self.planned.written.remove(handle);
                self.decide.rules.writes.remove(handle);
            }
        }
    }

    /// Before a whole plan (the first step, a rule set put in place of
    /// another), what a rule set saved with its world carries of the hooks
    /// that stepped it (`docs/semantics.md`, "Saving and loading"): what
    /// the crate had written on each collider, and the project's settings
    /// under it, read as the hooks that wrote them read them (a field that
    /// differs from what was written is the project's, set since or saved
    /// with the project's settings); and hooks that have decided no specific
    /// entry go on with the saved decisions. Then the set's copy of the writes is
    /// the hooks' records again (a set built by code carries none).
    fn adopt_saved_plan(&mut self, colliders: &ColliderSet) {
        for (handle, saved) in self.decide.rules.writes.iter() {
            if colliders.contains(handle) && self.planned.written.get(handle).is_none() {
                self.planned.written.insert_evicting(handle, *saved);
            }
        }
        self.decide.rules.writes = self.planned.written.clone();
        if self.planned.plan.decisions.is_empty() {
            let saved = self.decide.rules.decisions.iter().map(|(&e, &d)| (e, d));
            self.planned.plan.decisions.seed(saved);
        }
    }

    /// At the hooks' first step, what a loaded world's colliders carry of
    /// the run it was saved from, where the rule set does not carry it (a
    /// world saved alone, its rules given again by code): a collider with
    /// the crate's mark holds the crate's writes, and its mark says which,
    /// so the project's settings under them are read back exactly
    /// (`docs/semantics.md`, "Saving and loading"). Each is planned at this
    /// step; the first plan decides the specific entries as the world's
    /// settings show they were decided.
    pub(super) fn adopt_marks(&mut self, colliders: &ColliderSet) {
        for (handle, collider) in colliders.iter() {
            if self.planned.written.get(handle).is_some()
                || self.decide.rules.writes.get(handle).is_some()
            {
                continue;
            }
            if let Some(written) = Mark::on(collider).written(Settings::of(collider)) {
                self.keep_written(handle, Some(written));
                self.planned.loaded.push((handle, written.wrote));
            }
        }
        if !self.planned.loaded.is_empty() {
            let loaded = self.planned.loaded.iter().map(|&(h, _)| h);
            self.queued.candidates.extend(loaded);
            self.queued.replan.get_or_insert(PlanCause::FirstStep);
        }
    }

    /// Gives back the crate's mark to watched colliders that lost it (the
    /// project set their events through Rapier, which takes the whole
    /// field), so that a world saved later still tells the crate's writes
    /// (`world/mark.rs`).
    pub(super) fn give_marks_back(&mut self, colliders: &mut ColliderSet) {
        for handle in std::mem::take(&mut self.queued.unmarked) {
            let expected = Mark::of_written(self.planned.written.get(handle));
            let Some(collider) = colliders.get(handle) else {
                continue;
            };
            if Mark::on(collider) != expected {
                let events = collider.active_events();
                colliders[handle].set_active_events(expected.in_events(events));
            }
        }
    }

    /// Watched colliders carry another run's marks: a world
    /// was put in place of the one these hooks stepped without
    /// `world_replaced`, and its crate's writes would be read as the
    /// project's settings. Said once.
    #[cold]
    pub(super) fn report_foreign_marks(&mut self) {
        self.stats.foreign_marks = true;
        if std::mem::replace(&mut self.boundary.reported_foreign_marks, true) {
            return;
        }
        log::warn!(
            "colliders these hooks wrote now carry what collision rules wrote in another run: a \
             world was put in place of the one these hooks stepped. Call \
             `hooks.world_replaced()` after putting a loaded world in place (in Bevy, \
             `CollisionRules::world_replaced()` on the context), or those writes are read as \
             the project's settings (docs/semantics.md, \"Saving and loading\"). If these \
             hooks step two worlds in turn, or another `RuleHooks` steps this world in turn, \
             give each world one `RuleHooks` instead"
        );
    }

    /// After the first step's plan: what the loaded colliders hold of the
    /// run the world was saved from that the rules given now did not write
    /// again. Those the rules write nothing on now have their project's
    /// settings back; those the plan wrote otherwise part from that run
    /// too. Each is
    /// said once, since the world then steps otherwise than that run
    /// (`docs/semantics.md`, "Saving and loading").
    pub(super) fn report_loaded(&mut self) {
        let loaded = std::mem::take(&mut self.planned.loaded);
        let (mut given_back, mut changed) = (0, 0);
        for (handle, found) in loaded {
            match self.planned.written.get(handle) {
                None => given_back += 1,
                Some(written) if written.wrote != found => changed += 1,
                Some(_) => {}
            }
        }
        self.stats.loaded_writes_given_back = given_back;
        self.stats.loaded_writes_changed = changed;
        if given_back + changed > 0 {
            log::warn!(
                "{given_back} colliders of this world carry settings that collision rules wrote \
                 in the run it was saved from on which the rules now write nothing (they have \
                 their project's settings back), and {changed} on which they write otherwise: \
                 the rules given now, or edits made since loading, differ from that run's, or \
                 how that run decided them cannot be read from the world alone. Where that is \
                 not meant, load the rule set saved with the world, or give the same rules \
                 before the first step (docs/semantics.md, \"Saving and loading\")"
            );
        }
    }

    /// After the phases before a step: the decisions made and undone are
    /// copied into the rule set, which a saved set carries.
    pub(super) fn copy_decisions(&mut self) {
        let copy = &mut self.decide.rules.decisions;
        for (entry, decision) in self.planned.plan.decisions.drain_journal() {
            match decision {
                Some(decision) => copy.insert(entry, decision),
                None => copy.remove(&entry),
            };
        }
    }
}

/// What hooking a collider costs, read in Rapier's graph where it is at
/// hand: its pairs now (see `planner::carriers::side_cost`).
fn pairs_in(graph: Option<&NarrowPhase>) -> impl Fn(ColliderHandle) -> Option<usize> + '_ {
    move |c| graph.map(|g| g.contact_pairs_with(c).count())
}
