//! A naive model of the rule set and a reference resolver transcribed
//! straight from `docs/semantics.md`, as slowly and plainly as possible: the
//! oracle the crate's resolver is compared against.

use std::collections::HashMap;

use super::rapier::prelude::*;
use super::rules::{CollisionGroup, CollisionRule, Node, RuleError};

#[derive(Clone, Debug, Default)]
pub struct Record {
    pub personal: CollisionRule,
    pub group: Option<CollisionGroup>,
    pub specific: HashMap<Node, CollisionRule>,
}

/// The rules as plain maps. Records are never freed; nodes name them by index.
#[derive(Clone, Debug)]
pub struct Model {
    pub records: Vec<Record>,
    pub owner: HashMap<Node, usize>,
    pub parents: HashMap<RigidBodyHandle, RigidBodyHandle>,
    pub table: HashMap<(CollisionGroup, CollisionGroup), CollisionRule>,
    pub default_rule: CollisionRule,
    /// Every node forgotten as removed.
    pub forgotten: Vec<Node>,
}

impl Default for Model {
    fn default() -> Self {
        let k = CollisionGroup::DEFAULT_KINEMATIC;
        Model {
            records: Vec::new(),
            owner: HashMap::new(),
            parents: HashMap::new(),
            table: HashMap::from([((k, k), CollisionRule::NoPair)]),
            default_rule: CollisionRule::Normal,
            forgotten: Vec::new(),
        }
    }
}

fn ordered(a: CollisionGroup, b: CollisionGroup) -> (CollisionGroup, CollisionGroup) {
    if a <= b { (a, b) } else { (b, a) }
}

impl Model {
    pub fn record(&self, node: Node) -> Option<&Record> {
        self.owner.get(&node).map(|&i| &self.records[i])
    }

    /// A side table holds one generation per slot: a handle is dead once a
    /// newer generation of its slot has been stored, and storing a handle
    /// evicts the older generations of its slot.
    fn superseded<T>(
        table: &HashMap<T, impl Sized>,
        handle: T,
        raw: impl Fn(T) -> (u32, u32),
    ) -> bool
    where
        T: Copy + Eq + std::hash::Hash,
    {
        let (index, generation) = raw(handle);
        table
            .keys()
            .any(|&k| raw(k).0 == index && raw(k).1 > generation)
    }

    fn evict<T, V>(table: &mut HashMap<T, V>, handle: T, raw: impl Fn(T) -> (u32, u32))
    where
        T: Copy + Eq + std::hash::Hash,
    {
        let (index, generation) = raw(handle);
        table.retain(|&k, _| !(raw(k).0 == index && raw(k).1 < generation));
    }

    fn node_raw(node: Node) -> (u32, u32) {
        // Colliders and bodies live in different tables: keep them apart.
        match node {
            Node::Collider(c) => c.into_raw_parts(),
            Node::Body(b) => {
                let (index, generation) = b.into_raw_parts();
                (index | 1 << 31, generation)
            }
        }
    }

    /// A handle of a removed object: the last of its slot forgotten, or its
    /// slot holds a newer generation in a side table.
    pub fn is_removed(&self, node: Node) -> bool {
        let (index, generation) = Self::node_raw(node);
        // Only the last handle of a slot forgotten is remembered.
        let last = self
            .forgotten
            .iter()
            .rev()
            .find(|&&dead| Self::node_raw(dead).0 == index);
        last.is_some_and(|&dead| Self::node_raw(dead).1 == generation)
            || Self::superseded(&self.owner, node, Self::node_raw)
            || matches!(node, Node::Body(b) if Self::superseded(&self.parents, b, |b| b.into_raw_parts()))
    }

    pub fn record_mut(&mut self, node: Node) -> Option<&mut Record> {
        if self.is_removed(node) {
            return None;
        }
        let index = match self.owner.get(&node) {
            Some(&i) => i,
            None => {
                self.records.push(Record::default());
                self.attach(node, self.records.len() - 1);
                self.records.len() - 1
            }
        };
        Some(&mut self.records[index])
    }

    fn attach(&mut self, node: Node, record: usize) {
        Self::evict(&mut self.owner, node, Self::node_raw);
        self.owner.insert(node, record);
    }

    /// Drops `node`'s record if it is empty and `node` its only user, as
    /// the crate frees it (which makes the slot free for another
    /// generation again).
    pub fn tidy(&mut self, node: Node) {
        let Some(&index) = self.owner.get(&node) else {
            return;
        };
        let r = &self.records[index];
        let empty =
            r.personal == CollisionRule::Defer && r.group.is_none() && r.specific.is_empty();
        let alone = self.owner.values().filter(|&&i| i == index).count() == 1;
        if empty && alone {
            self.owner.remove(&node);
        }
    }

    pub fn share(&mut self, from: Node, to: Node) {
        let (f, t) = (Self::node_raw(from), Self::node_raw(to));
        let older_in_slot = f.0 == t.0 && t.1 < f.1;
        if from == to || older_in_slot || self.is_removed(to) || self.record_mut(from).is_none() {
            return;
        }
        let index = self.owner[&from];
        self.attach(to, index);
    }

    pub fn set_parent(
        &mut self,
        child: RigidBodyHandle,
        parent: RigidBodyHandle,
    ) -> Result<(), RuleError> {
        for body in [child, parent] {
            if self.is_removed(Node::Body(body)) {
                return Err(RuleError::Removed {
                    node: Node::Body(body),
                });
            }
        }
        if child == parent {
            return Err(RuleError::SelfParent { body: child });
        }
        let mut up = Some(parent);
        while let Some(body) = up {
            if body == child {
                return Err(RuleError::Cycle { child, parent });
            }
            up = self.parents.get(&body).copied();
        }
        Self::evict(&mut self.parents, child, |b| b.into_raw_parts());
        self.parents.insert(child, parent);
        Ok(())
    }

    pub fn set_table(&mut self, a: CollisionGroup, b: CollisionGroup, rule: CollisionRule) {
        self.table.insert(ordered(a, b), rule);
    }

    pub fn remove_table(&mut self, a: CollisionGroup, b: CollisionGroup) {
        self.table.remove(&ordered(a, b));
    }

    /// Every descendant of `node`: bodies whose parent chain passes through
    /// it, and the colliders of it and of them.
    pub fn descendants(&self, node: Node, bodies: &RigidBodySet) -> Vec<Node> {
        let Node::Body(root) = node else {
            return Vec::new();
        };
        let mut result = Vec::new();
        for (handle, body) in bodies.iter() {
            // A chain ends below a body missing from the world.
            let mut below = handle == root;
            let mut up = self.parents.get(&handle).copied();
            while let Some(p) = up.filter(|&p| bodies.contains(p)) {
                below |= p == root;
                up = self.parents.get(&p).copied();
            }
            if below {
                if handle != root {
                    result.push(Node::Body(handle));
                }
                result.extend(body.colliders().iter().map(|&c| Node::Collider(c)));
            }
        }
        result
    }

    pub fn forget(&mut self, node: Node) {
        let held = self.record(node).is_some_and(|r| {
            r.personal != CollisionRule::Defer || r.group.is_some() || !r.specific.is_empty()
        }) || self
            .owner
            .values()
            .any(|&i| self.records[i].specific.contains_key(&node))
            || matches!(node, Node::Body(b) if self.parents.contains_key(&b) || self.parents.values().any(|&p| p == b));
        if held {
            self.forgotten.push(node);
        }
        self.owner.remove(&node);
        // The nodes whose records named it: a record left empty that one
        // of them alone uses is freed, as by hand.
        let namers: Vec<Node> = self
            .owner
            .iter()
            .filter(|&(_, &i)| self.records[i].specific.contains_key(&node))
            .map(|(&n, _)| n)
            .collect();
        for record in &mut self.records {
            record.specific.remove(&node);
        }
        for namer in namers {
            self.tidy(namer);
        }
        if let Node::Body(body) = node {
            self.parents.remove(&body);
            self.parents.retain(|_, parent| *parent != body);
        }
    }

    // ---- the reference resolver ----

    /// A chain: `[c, body(c), parent(body(c)), ...]`; handles missing from the
    /// sets end the chain.
    fn chain(
        &self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        c: ColliderHandle,
    ) -> Vec<Node> {
        let mut chain = vec![Node::Collider(c)];
        let mut body = colliders.get(c).and_then(|collider| collider.parent());
        while let Some(b) = body.filter(|&b| bodies.contains(b)) {
            chain.push(Node::Body(b));
            body = self.parents.get(&b).copied();
        }
        chain
    }

    /// A stale collider carries no rules.
    fn rules_of(&self, colliders: &ColliderSet, node: Node) -> Option<&Record> {
        match node {
            Node::Collider(c) if !colliders.contains(c) => None,
            _ => self.record(node),
        }
    }

    fn dynamic(bodies: &RigidBodySet, colliders: &ColliderSet, node: Node) -> bool {
        let body = match node {
            Node::Collider(c) => colliders.get(c).and_then(|c| c.parent()),
            Node::Body(b) => Some(b),
        };
        body.and_then(|b| bodies.get(b))
            .is_some_and(|b| b.is_dynamic())
    }

    /// The effective group: own group, else nearest explicit group up the chain, else the
    /// default group of the colliding body, the chain's collider's own body (`chain[0]`),
    /// whatever the types of the ancestors.
    fn effective_group(
        &self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        chain: &[Node],
        i: usize,
    ) -> CollisionGroup {
        for &node in &chain[i..] {
            if let Some(group) = self.rules_of(colliders, node).and_then(|r| r.group) {
                return group;
            }
        }
        if Self::dynamic(bodies, colliders, chain[0]) {
            CollisionGroup::DEFAULT_DYNAMIC
        } else {
            CollisionGroup::DEFAULT_KINEMATIC
        }
    }

    fn spec(&self, colliders: &ColliderSet, x: Node, y: Node) -> CollisionRule {
        let about = |from: Node, to: Node| {
            self.rules_of(colliders, from)
                .and_then(|r| r.specific.get(&to).copied())
                .unwrap_or(CollisionRule::Defer)
        };
        std::cmp::max(about(x, y), about(y, x))
    }

    fn pers(&self, colliders: &ColliderSet, x: Node, y: Node) -> CollisionRule {
        let personal = |n: Node| {
            self.rules_of(colliders, n)
                .map_or(CollisionRule::Defer, |r| r.personal)
        };
        std::cmp::max(personal(x), personal(y))
    }

    pub fn resolve(
        &self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        a: ColliderHandle,
        b: ColliderHandle,
    ) -> CollisionRule {
        let rule = self.calculate(bodies, colliders, a, b);
        let a_dynamic = Self::dynamic(bodies, colliders, Node::Collider(a));
        let b_dynamic = Self::dynamic(bodies, colliders, Node::Collider(b));
        if !a_dynamic && !b_dynamic && rule == CollisionRule::Normal {
            CollisionRule::NoResponse
        } else {
            rule
        }
    }

    fn calculate(
        &self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        a: ColliderHandle,
        b: ColliderHandle,
    ) -> CollisionRule {
        use CollisionRule::Defer;
        let ca = self.chain(bodies, colliders, a);
        let cb = self.chain(bodies, colliders, b);
        let (m, n) = (ca.len() - 1, cb.len() - 1);

        // 1. Specific stage.
        for k in 0..=m.max(n) {
            let (i, j) = (k.min(m), k.min(n));
            let direct = self.spec(colliders, ca[i], cb[j]);
            if direct != Defer {
                return direct;
            }
            let mut t = 1;
            loop {
                let mut results = Vec::new();
                if j + t <= n {
                    results.push(self.spec(colliders, ca[i], cb[j + t]));
                }
                if i + t <= m {
                    results.push(self.spec(colliders, ca[i + t], cb[j]));
                }
                if results.is_empty() {
                    break;
                }
                let combined = results.into_iter().max().unwrap();
                if combined != Defer {
                    return combined;
                }
                t += 1;
            }
        }
        // 2. Personal stage.
        for k in 0..=m.max(n) {
            let (i, j) = (k.min(m), k.min(n));
            let rule = self.pers(colliders, ca[i], cb[j]);
            if rule != Defer {
                return rule;
            }
        }
        // 3. Group stage.
        for k in 0..=m.max(n) {
            let (i, j) = (k.min(m), k.min(n));
            let ga = self.effective_group(bodies, colliders, &ca, i);
            let gb = self.effective_group(bodies, colliders, &cb, j);
            let rule = self.table.get(&ordered(ga, gb)).copied().unwrap_or(Defer);
            if rule != Defer {
                return rule;
            }
        }
        // 4. Default.
        self.default_rule
    }
}
