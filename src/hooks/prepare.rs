//! Before Rapier's step: noticing what changed (edits, objects removed or
//! changed through Rapier), planning the colliders' settings and
//! recalculating live pairs. It costs in proportion to what the rules
//! reach and the edits since the last step: a world the rules do not reach
//! costs nothing (`docs/architecture.md`, "Cost per step").

use hashbrown::HashSet;
use super::super::rapier::prelude::*;

use super::step::missing;
use super::{ManifoldUpdate, PairKey, RecalculationPolicy, RuleHooks};
use super::super::planner;
use super::super::{FullPass, Node, StepStats};

/// Before the step.
impl RuleHooks {
    /// Before a bare `PhysicsPipeline::step`: notices what the edits touched
    /// and what changed through Rapier among the objects the rules reach
    /// (removed, moved to another body, changed type, new colliders on a
    /// watched body), plans those colliders' flags and groups (every
    /// reached collider if anything they all depend on changed), and
    /// recalculates live pairs as the policy says. Call
    /// [`wake_edited`](Self::wake_edited) next, then step with these hooks,
    /// then [`after_step`](Self::after_step).
    ///
    /// # Panics
    ///
    /// If Rapier stepped with these hooks since the last `prepare` and
    /// [`after_step`](Self::after_step) was not called after it.
    pub fn prepare(&mut self, bodies: &RigidBodySet, colliders: &mut ColliderSet) {
        if self.boundary.prepared && *self.boundary.stepped.get_mut() {
            missing("after_step", "after the last step");
        }
        self.boundary.prepared = true;
        *self.boundary.stepped.get_mut() = false;
        self.boundary.owe_freeze = self.boundary.unsettled;
        self.boundary.step += 1;
        self.stats = StepStats {
            hooked_colliders: self.planned.hooked,
            tracked_pairs: self.pairs.len(),
            ..StepStats::default()
        };
        let full = self.full_pass();
        self.queued.replan |= self.planned.exhaustive;
        if self.idle() {
            return;
        }
        if full != self.planned.plan.full && (full.is_some() || self.planned.plan.full.is_some()) {
            self.queued.replan = true;
        }

        // 1. What the edits touched starts being watched.
        let changes = self.decide.rules.take_changes();
        // Re-parenting moves colliders from under one side of a specific
        // entry to another: which side is cheaper to hook may change.
        self.queued.replan |= changes.parents && self.decide.rules.has_specific();
        let mut changed = match self.decide.rules.touched_nodes(&changes) {
            // The first step reads the whole rule set: it may have been
            // built, or loaded, before the hooks existed.
            Some(nodes) if !self.planned.exhaustive && self.boundary.step > 1 => nodes,
            // The nodes the edits touched stay in, rules or not: a node
            // whose rules were just cleared has pairs to recalculate.
            touched => {
                self.queued.replan = true;
                let mut nodes = self.decide.rules.ruled_nodes();
                nodes.extend(touched.into_iter().flatten());
                nodes
            }
        };
        for &node in &changed {
            self.watch(bodies, colliders, node);
        }

        // 2. Look at what is watched: removals, changes, additions.
        let everything = self.planned.plan.full.is_some() || full.is_some() || self.planned.exhaustive;
        // Whether the rules still reach a watched object changes only with an
        // edit of it (marked by `watch`), or with a global one.
        let ask_all = self.queued.replan;
        let look = {
            let (rules, plan) = (&self.decide.rules, &self.planned.plan);
            self.planned.roster
                .look(bodies, colliders, everything, ask_all, |node| {
                    reached(rules, plan, bodies, colliders, node)
                })
        };
        // Which side of a specific entry is cheaper to hook follows the
        // colliders under each side and their bodies' types (asked before
        // removed bodies leave the parent map).
        self.queued.replan |= look
            .left
            .iter()
            .map(|&b| Node::Body(b))
            .chain(look.added.iter().map(|&c| Node::Collider(c)))
            .chain(look.changed.iter().copied())
            .any(|node| planner::touches_entries(&self.decide.rules, bodies, colliders, node));
        self.forget_removed(bodies, &look.removed_colliders, &look.removed_bodies);
        for &c in &look.released {
            self.planned.plan.colliders.remove(c);
        }
        if !(look.removed_colliders.is_empty() && look.released.is_empty()) {
            self.count_hooked();
        }
        changed.extend(look.changed);
        // Forgetting a removed parent changes its children's chains.
        let removal_changes = self.decide.rules.take_changes();
        if let Some(more) = self.decide.rules.touched_nodes(&removal_changes) {
            changed.extend(more);
        }
        // The project changed a setting the plan is combined with, or
        // colliders came or went in a world whose plan shares bits or types
        // with every collider's project settings: plan again.
        let recount = self
            .planned
            .plan
            .room
            .is_some_and(|(_, count)| count != colliders.len());
        if recount || !look.project_changed.is_empty() {
            self.queued.replan = true;
        }
        // A project setting can change a pair's rule (the kinematic entry
        // gives way to wider types): those colliders' pairs are recalculated.
        changed.extend(look.project_changed.iter().map(|&c| Node::Collider(c)));

        // 3. Plan the colliders under every changed node, and those newly
        // watched (a collider moved onto a watched body may have hooked pairs
        // whose rule its new chain changes).
        let mut under: HashSet<ColliderHandle> = look.added.iter().copied().collect();
        self.queued.candidates.extend(look.added);
        for &node in &changed {
            under.extend(self.colliders_under(node, bodies, colliders));
        }
        // Their pairs may have changed in Rapier too: looked up after the step.
        self.queued.touched.extend(under.iter().copied());
        self.queued.touched.extend(self.queued.candidates.iter().copied());
        if self.queued.replan {
            self.apply_plan(bodies, colliders);
        } else {
            self.queued.candidates.extend(under.iter().copied());
            if !self.queued.candidates.is_empty() {
                self.apply_partial_plan(bodies, colliders);
            }
        }

        // 4. Recalculate live pairs as the policy says.
        let mut drop_overrides = HashSet::new();
        for node in std::mem::take(&mut self.queued.forced) {
            drop_overrides.extend(self.colliders_under(node, bodies, colliders));
        }
        let everything = self.decide.policy == RecalculationPolicy::EveryStep
            || (self.decide.policy == RecalculationPolicy::OnChange
                && (changes.everything || std::mem::take(&mut self.queued.recalculate_all)));
        let mut affected = HashSet::new();
        if self.decide.policy == RecalculationPolicy::OnChange && !everything {
            affected = under;
        }
        if self.decide.policy == RecalculationPolicy::Manual {
            self.queued.recalculate_all = false;
        }
        if everything || !affected.is_empty() || !drop_overrides.is_empty() {
            let refresh =
                self.recalculate(bodies, colliders, everything, &affected, &drop_overrides);
            for handle in refresh {
                if let Some(collider) = colliders.get_mut(handle) {
                    let groups = collider.collision_groups();
                    collider.set_collision_groups(InteractionGroups::none());
                    collider.set_collision_groups(groups);
                    self.queued.regrouped.insert(handle);
                }
            }
        }
        for c in std::mem::take(&mut self.queued.wake_colliders) {
            self.queued.to_wake
                .extend(colliders.get(c).and_then(|c| c.parent()));
        }
        self.stats.hooked_colliders = self.planned.hooked;
        self.stats.full_pass = self.planned.plan.full;
        self.stats.shares_project_bits = self.planned.plan.room.is_some();
        self.stats.watched_colliders = self.planned.roster.collider_count();
        self.stats.watched_bodies = self.planned.roster.body_count();
    }

    /// Whether the rules reach nothing and nothing waits: the common case
    /// of a world without rules, which costs a few branches per step.
    #[inline]
    pub(super) fn idle(&self) -> bool {
        self.planned.roster.collider_count() == 0
            && self.planned.roster.body_count() == 0
            && self.pairs.is_empty()
            && self.planned.plan.full.is_none()
            && !self.queued.replan
            && !self.decide.rules.has_changes()
            && self.queued.candidates.is_empty()
            && self.queued.forced.is_empty()
            && self.queued.wake_colliders.is_empty()
            && self.queued.touched.is_empty()
            && self.queued.regrouped.is_empty()
            && !self.queued.recalculate_all
            && self.decide.policy != RecalculationPolicy::EveryStep
            && self.full_pass().is_none()
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
    fn watch(&mut self, bodies: &RigidBodySet, colliders: &ColliderSet, node: Node) {
        match node {
            Node::Body(body) => {
                self.planned.roster.watch_body(bodies, body);
            }
            // Watched even if Rapier removed it: the look then forgets it.
            Node::Collider(c) => {
                if self.planned.roster.watch_collider(bodies, colliders, c) {
                    self.queued.candidates.push(c);
                }
            }
        }
        self.planned.roster.mark(node);
        for c in self.colliders_under(node, bodies, colliders) {
            if self.planned.roster.watch_collider(bodies, colliders, c) {
                self.queued.candidates.push(c);
            }
            self.planned.roster.mark(Node::Collider(c));
        }
    }

    /// Forgets objects Rapier removed: their rules, the entries naming
    /// them, their parent links, their plan and their pairs. A handle Rapier
    /// reuses therefore starts with no rules.
    fn forget_removed(
        &mut self,
        bodies: &RigidBodySet,
        removed: &[(ColliderHandle, Option<RigidBodyHandle>)],
        removed_bodies: &[RigidBodyHandle],
    ) {
        if !removed.is_empty() {
            let gone: HashSet<ColliderHandle> = removed.iter().map(|r| r.0).collect();
            self.pairs.retain(|key, _| {
                let (a, b) = key.colliders();
                !gone.contains(&a) && !gone.contains(&b)
            });
        }
        for &(handle, body) in removed {
            self.decide.rules.remove_node(handle);
            self.planned.plan.colliders.remove(handle);
            self.planned.written.remove(handle);
            // A body that keeps other colliders is in the look's `left`.
            if let Some(body) = body.filter(|&b| !bodies.contains(b)) {
                self.decide.rules.remove_node(body);
            }
        }
        for &body in removed_bodies {
            self.decide.rules.remove_node(body);
        }
        self.stats.removed_objects = removed.len() + removed_bodies.len();
    }

    /// The pinned pairs: an override or a manifold setting keeps them hooked.
    pub(super) fn pinned(&self) -> Vec<PairKey> {
        let mut pinned: Vec<PairKey> = self
            .pairs
            .iter()
            .filter(|(_, s)| s.overridden.is_some() || s.manifold != ManifoldUpdate::ByRule)
            .map(|(k, _)| k)
            .collect();
        pinned.sort_unstable_by_key(|k| {
            let (a, b) = k.colliders();
            (a.into_raw_parts(), b.into_raw_parts())
        });
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
