//! The rules of each node (group, personal, specific entries) and their
//! sharing: the verbs that edit them, and the walks down from a node.

use super::super::rapier::prelude::{ColliderHandle, ColliderSet, RigidBodyHandle, RigidBodySet};
use smallvec::SmallVec;

use super::super::{CollisionGroup, CollisionRule, CollisionRuleSet, Node};

/// The verbs on each node's rules.
/// The colliders under a node, inline up to four (see
/// [`CollisionRuleSet::colliders_under`]).
pub(crate) type CollidersUnder = SmallVec<[ColliderHandle; 4]>;

impl CollisionRuleSet {
    /// Puts `node` in `group` (`None`: no explicit group; the node then takes
    /// the nearest explicit group up its chain, or its body's default group).
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::CollisionRuleSet;
    ///
    /// let mut bodies = RigidBodySet::new();
    /// let body = bodies.insert(RigidBodyBuilder::dynamic());
    /// let mut rules = CollisionRuleSet::default();
    /// let players = rules.create_group();
    /// rules.set_group(body, Some(players));
    /// assert_eq!(rules.group(body), Some(players));
    /// ```
    ///
    /// # Panics
    ///
    /// As [`set_group_rule`](Self::set_group_rule).
    #[track_caller]
    pub fn set_group(&mut self, node: impl Into<Node>, group: Option<CollisionGroup>) {
        self.check_groups(group.as_slice());
        let node = node.into();
        if (group.is_none() && self.record_id(node).is_none()) || self.is_removed(node) {
            return;
        }
        if let Some(record) = self.record_mut(node) {
            record.group = group;
        }
        self.tidy(node);
    }

    /// The node's own explicit group (not inherited, not a default).
    #[must_use]
    pub fn group(&self, node: impl Into<Node>) -> Option<CollisionGroup> {
        self.record(node.into()).and_then(|record| record.group)
    }

    /// The node's personal rule (stage 2); `Defer` clears it.
    pub fn set_personal(&mut self, node: impl Into<Node>, rule: CollisionRule) {
        let node = node.into();
        if (rule == CollisionRule::Defer && self.record_id(node).is_none()) || self.is_removed(node)
        {
            return;
        }
        if let Some(record) = self.record_mut(node) {
            record.personal = rule;
        }
        self.tidy(node);
    }

    /// The node's personal rule, `Defer` if it has none.
    #[must_use]
    pub fn personal(&self, node: impl Into<Node>) -> CollisionRule {
        self.record(node.into())
            .map_or(CollisionRule::Defer, |record| record.personal)
    }

    /// What `node` says about `other` (stage 1). `Defer` removes the entry.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, CollisionRuleSet};
    ///
    /// let mut bodies = RigidBodySet::new();
    /// let (a, b) = (bodies.insert(RigidBodyBuilder::dynamic()), bodies.insert(RigidBodyBuilder::dynamic()));
    /// let mut rules = CollisionRuleSet::default();
    /// rules.set_specific(a, b, CollisionRule::NoContacts);
    /// assert_eq!(rules.specific(a, b), CollisionRule::NoContacts);
    /// assert_eq!(rules.specific(b, a), CollisionRule::Defer, "each side has its own entry");
    /// rules.remove_specific(a, b);
    /// assert_eq!(rules.specific(a, b), CollisionRule::Defer);
    /// ```
    pub fn set_specific(
        &mut self,
        node: impl Into<Node>,
        other: impl Into<Node>,
        rule: CollisionRule,
    ) {
        let (node, other) = (node.into(), other.into());
        self.forget_ending(node, other);
        if rule == CollisionRule::Defer {
            self.remove_specific(node, other);
        } else if !self.is_removed(other) {
            // An entry about a removed object would name nothing.
            self.put_specific(node, other, rule);
        }
    }

    /// Stores an entry of `node` (not a removed object) about `other`. The
    /// loader stores a save's entries this way, whatever `other` is, so
    /// that a loaded rule set is the one saved.
    pub(crate) fn put_specific(&mut self, node: Node, other: Node, rule: CollisionRule) {
        if self.is_removed(node) {
            return;
        }
        if let Some(record) = self.record_mut(node) {
            let held_entries = !record.specific.is_empty();
            if record.specific.insert(other, rule).is_none() {
                let id = self.record_id(node).expect("record_mut made one");
                self.name(other, id);
            }
            self.touch_entry(node, other, held_entries);
            self.changes.subject(other);
        }
    }

    /// What `node` says about `other`, `Defer` if nothing.
    #[must_use]
    pub fn specific(&self, node: impl Into<Node>, other: impl Into<Node>) -> CollisionRule {
        let other = other.into();
        self.record(node.into())
            .and_then(|record| record.specific.get(&other).copied())
            .unwrap_or(CollisionRule::Defer)
    }

    /// Removes what `node` says about `other`.
    pub fn remove_specific(&mut self, node: impl Into<Node>, other: impl Into<Node>) {
        let (node, other) = (node.into(), other.into());
        self.forget_ending(node, other);
        if let Some(id) = self.record_id(node) {
            if self.records.get_mut(id).specific.remove(&other).is_some() {
                self.unname(other, id);
                self.touch_entry(node, other, true);
            } else {
                self.tidy(node);
            }
            self.changes.subject(other);
        }
    }

    /// From now on `to` uses `from`'s rule record: its group, personal rule
    /// and specific entries, and any later edit through either node is seen
    /// by both. `to`'s own rules are dropped.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, CollisionRuleSet};
    ///
    /// let mut bodies = RigidBodySet::new();
    /// let (a, b) = (bodies.insert(RigidBodyBuilder::dynamic()), bodies.insert(RigidBodyBuilder::dynamic()));
    /// let mut rules = CollisionRuleSet::default();
    /// rules.share_rules(a, b);
    /// rules.set_personal(b, CollisionRule::NoResponse);
    /// assert_eq!(rules.personal(a), CollisionRule::NoResponse);
    /// assert!(rules.shares_rules(a, b));
    /// ```
    pub fn share_rules(&mut self, from: impl Into<Node>, to: impl Into<Node>) {
        let (from, to) = (from.into(), to.into());
        // `from` newer than `to` in one slot: storing `from` makes `to` a
        // removed object's handle.
        let older_in_slot = from.slot() == to.slot() && to.generation() < from.generation();
        if from == to || older_in_slot || self.is_removed(to) || self.record_mut(from).is_none() {
            return;
        }
        let id = self.record_id(from).expect("record_mut made one");
        if self.record_id(to) == Some(id) {
            return;
        }
        let record = self.records.get_mut(id);
        record.users += 1;
        record.only_user = None;
        self.attach(to, id);
        self.changes.node(to);
    }

    /// Whether `a` and `b` use one rule record.
    #[must_use]
    pub fn shares_rules(&self, a: impl Into<Node>, b: impl Into<Node>) -> bool {
        let (a, b) = (a.into(), b.into());
        a == b || matches!((self.record_id(a), self.record_id(b)), (Some(x), Some(y)) if x == y)
    }

    /// Makes every descendant of `node` share `node`'s rule record (the
    /// BEPU design's recursive rule setting): the colliders of a body, and
    /// every body below it in the parent map with their colliders. Later
    /// edits through any of them reach all of them. Bodies or colliders
    /// added later are not included.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, CollisionRuleSet, RuleError};
    ///
    /// let mut bodies = RigidBodySet::new();
    /// let mut colliders = ColliderSet::new();
    /// let chassis = bodies.insert(RigidBodyBuilder::dynamic());
    /// let wheel = bodies.insert(RigidBodyBuilder::dynamic());
    /// let tyre = colliders.insert_with_parent(ColliderBuilder::ball(0.4), wheel, &mut bodies);
    /// let mut rules = CollisionRuleSet::default();
    /// rules.set_parent(wheel, chassis)?;
    /// rules.set_rules_recursive(chassis, &bodies, &colliders);
    /// rules.set_personal(tyre, CollisionRule::NoContacts);
    /// assert_eq!(rules.personal(chassis), CollisionRule::NoContacts);
    /// # Ok::<(), RuleError>(())
    /// ```
    pub fn set_rules_recursive(
        &mut self,
        node: impl Into<Node>,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
    ) {
        let node = node.into();
        if self.is_removed(node) {
            return;
        }
        for descendant in self.descendants(node, bodies, colliders) {
            self.share_rules(node, descendant);
        }
    }

    /// `node` itself if it is a collider in the set, and every collider
    /// below it: the colliders whose chains hold `node`. Inline for the
    /// common sizes (a collider, a body's few colliders): the planner asks
    /// this of every node a step's changes touch.
    pub(crate) fn colliders_under(
        &self,
        node: Node,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
    ) -> CollidersUnder {
        let in_world = |c: &&ColliderHandle| colliders.contains(**c);
        match node {
            Node::Collider(c) => {
                let mut one = CollidersUnder::new();
                one.extend(colliders.contains(c).then_some(c));
                one
            }
            // No body below it in the parent map (the common case): its
            // own colliders, without a walk of the parent map.
            Node::Body(root) if !self.hierarchy.is_parent(root) => bodies
                .get(root)
                .map(|body| body.colliders().iter().filter(in_world).copied().collect())
                .unwrap_or_default(),
            Node::Body(_) => self
                .descendants(node, bodies, colliders)
                .into_iter()
                .filter_map(|n| match n {
                    Node::Collider(c) => Some(c),
                    Node::Body(_) => None,
                })
                .collect(),
        }
    }

    /// The nodes below `node`: for a body, its colliders and every body below
    /// it in the parent map with their colliders; a collider has none. A
    /// body Rapier has removed is not in the world: neither it nor the
    /// bodies under it are descendants (their chains end below it).
    #[must_use]
    pub fn descendants(
        &self,
        node: impl Into<Node>,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
    ) -> Vec<Node> {
        let Node::Body(root) = node.into() else {
            return Vec::new();
        };
        let mut body_list = self.hierarchy.descendants(root);
        body_list.push(root);
        // Bodies missing from the set are not in the world: not descendants,
        // and a chain ends below one (as `resolve` reads it), so neither are
        // the bodies under it.
        let reaches_root = |mut body: RigidBodyHandle| loop {
            if !bodies.contains(body) {
                return false;
            }
            match self.hierarchy.parent(body) {
                _ if body == root => return true,
                Some(parent) => body = parent,
                None => return false,
            }
        };
        body_list.retain(|&b| reaches_root(b));
        let mut nodes = Vec::new();
        for (body, rigid_body) in body_list.iter().filter_map(|&b| Some((b, bodies.get(b)?))) {
            nodes.extend(
                rigid_body
                    .colliders()
                    .iter()
                    .filter(|&&c| colliders.contains(c))
                    .map(|&c| Node::Collider(c)),
            );
            if body != root {
                nodes.push(Node::Body(body));
            }
        }
        nodes
    }
}
