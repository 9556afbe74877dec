//! Random scenes and edit sequences, applied to the crate's rule set and to
//! the naive model of `reference.rs`: every collider pair must resolve as the
//! reference says, in both argument orders, and the getters must agree.

use super::rapier::prelude::*;
use super::rules::{CollisionGroup, CollisionRule, CollisionRuleSet, Node};
use proptest::prelude::*;
use proptest::test_runner::Config;

use super::reference::Model;

#[derive(Clone, Debug)]
enum Op {
    Parent(usize, usize),
    Unparent(usize),
    Group(usize, Option<usize>),
    Personal(usize, CollisionRule),
    Specific(usize, usize, CollisionRule),
    RemoveSpecific(usize, usize),
    Share(usize, usize),
    Recursive(usize),
    GroupRule(usize, usize, CollisionRule),
    RemoveGroupRule(usize, usize),
    InSet(Vec<usize>, CollisionRule, CollisionRule),
    RemoveInSet(Vec<usize>),
    WithSet(usize, Vec<usize>, CollisionRule),
    RemoveWithSet(usize, Vec<usize>),
    BetweenSets(Vec<usize>, Vec<usize>, CollisionRule),
    RemoveBetweenSets(Vec<usize>, Vec<usize>),
    DefaultRule(CollisionRule),
    Kind(usize, usize),
    RemoveCollider(usize),
    RemoveBody(usize),
    AddCollider(Option<usize>),
    AddBody(usize),
}

const KINDS: [RigidBodyType; 4] = [
    RigidBodyType::Dynamic,
    RigidBodyType::Fixed,
    RigidBodyType::KinematicPositionBased,
    RigidBodyType::KinematicVelocityBased,
];

/// Groups in play: the two built-in ones and four created ones.
const GROUPS: usize = 6;

fn rule() -> impl Strategy<Value = CollisionRule> {
    proptest::sample::select(CollisionRule::ALL.to_vec())
}

fn groups() -> impl Strategy<Value = Vec<usize>> {
    proptest::collection::vec(0..GROUPS, 0..4)
}

fn op() -> impl Strategy<Value = Op> {
    let n = 0..64usize;
    prop_oneof![
        4 => (n.clone(), n.clone()).prop_map(|(c, p)| Op::Parent(c, p)),
        1 => n.clone().prop_map(Op::Unparent),
        4 => (n.clone(), proptest::option::of(0..GROUPS)).prop_map(|(x, g)| Op::Group(x, g)),
        4 => (n.clone(), rule()).prop_map(|(x, r)| Op::Personal(x, r)),
        5 => (n.clone(), n.clone(), rule()).prop_map(|(x, y, r)| Op::Specific(x, y, r)),
        1 => (n.clone(), n.clone()).prop_map(|(x, y)| Op::RemoveSpecific(x, y)),
        2 => (n.clone(), n.clone()).prop_map(|(x, y)| Op::Share(x, y)),
        1 => n.clone().prop_map(Op::Recursive),
        4 => (0..GROUPS, 0..GROUPS, rule()).prop_map(|(a, b, r)| Op::GroupRule(a, b, r)),
        1 => (0..GROUPS, 0..GROUPS).prop_map(|(a, b)| Op::RemoveGroupRule(a, b)),
        1 => (groups(), rule(), rule()).prop_map(|(s, a, b)| Op::InSet(s, a, b)),
        1 => groups().prop_map(Op::RemoveInSet),
        1 => (0..GROUPS, groups(), rule()).prop_map(|(g, s, r)| Op::WithSet(g, s, r)),
        1 => (0..GROUPS, groups()).prop_map(|(g, s)| Op::RemoveWithSet(g, s)),
        1 => (groups(), groups(), rule()).prop_map(|(a, b, r)| Op::BetweenSets(a, b, r)),
        1 => (groups(), groups()).prop_map(|(a, b)| Op::RemoveBetweenSets(a, b)),
        1 => rule().prop_map(Op::DefaultRule),
        2 => (n.clone(), 0..KINDS.len()).prop_map(|(b, k)| Op::Kind(b, k)),
        1 => n.clone().prop_map(Op::RemoveCollider),
        1 => n.clone().prop_map(Op::RemoveBody),
        1 => proptest::option::of(n.clone()).prop_map(Op::AddCollider),
        1 => (0..KINDS.len()).prop_map(Op::AddBody),
    ]
}

#[derive(Clone, Debug)]
struct Scenario {
    bodies: Vec<usize>,
    colliders: Vec<Option<usize>>,
    ops: Vec<Op>,
}

fn scenario() -> impl Strategy<Value = Scenario> {
    (
        proptest::collection::vec(0..KINDS.len(), 1..7),
        proptest::collection::vec(proptest::option::of(0..64usize), 1..9),
        proptest::collection::vec(op(), 0..28),
    )
        .prop_map(|(bodies, colliders, ops)| Scenario {
            bodies,
            colliders,
            ops,
        })
}

/// The world, the crate's rule set and the model, edited in lockstep.
struct Run {
    world: PhysicsWorld,
    rules: CollisionRuleSet,
    model: Model,
    groups: Vec<CollisionGroup>,
    /// Every body and collider ever made, removed ones included.
    bodies: Vec<RigidBodyHandle>,
    colliders: Vec<ColliderHandle>,
}

impl Run {
    fn new(scenario: &Scenario) -> Run {
        let mut rules = CollisionRuleSet::default();
        let mut groups = vec![
            CollisionGroup::DEFAULT_DYNAMIC,
            CollisionGroup::DEFAULT_KINEMATIC,
        ];
        groups.extend((2..GROUPS).map(|_| rules.create_group()));
        let mut run = Run {
            world: PhysicsWorld::new(),
            rules,
            model: Model::default(),
            groups,
            bodies: Vec::new(),
            colliders: Vec::new(),
        };
        for &kind in &scenario.bodies {
            run.add_body(kind);
        }
        for &body in &scenario.colliders {
            run.add_collider(body);
        }
        run
    }

    fn add_body(&mut self, kind: usize) {
        let handle = self.world.insert_body(RigidBodyBuilder::new(KINDS[kind]));
        self.bodies.push(handle);
    }

    fn add_collider(&mut self, body: Option<usize>) {
        let parent = body
            .map(|i| self.bodies[i % self.bodies.len()])
            .filter(|&b| self.world.bodies.contains(b));
        let handle = self
            .world
            .insert_collider(ColliderBuilder::ball(0.5), parent);
        self.colliders.push(handle);
    }

    fn node(&self, i: usize) -> Node {
        let all = self.bodies.len() + self.colliders.len();
        let i = i % all;
        match i.checked_sub(self.bodies.len()) {
            None => Node::Body(self.bodies[i]),
            Some(c) => Node::Collider(self.colliders[c]),
        }
    }

    fn body(&self, i: usize) -> RigidBodyHandle {
        self.bodies[i % self.bodies.len()]
    }

    fn set(&self, indices: &[usize]) -> Vec<CollisionGroup> {
        indices.iter().map(|&i| self.groups[i]).collect()
    }

    fn apply(&mut self, op: &Op) {
        match op {
            Op::Parent(c, p) => {
                let (child, parent) = (self.body(*c), self.body(*p));
                let got = self.rules.set_parent(child, parent);
                let expected = self.model.set_parent(child, parent);
                assert_eq!(got, expected, "set_parent({child:?}, {parent:?})");
            }
            Op::Unparent(c) => {
                let child = self.body(*c);
                self.rules.remove_parent(child);
                self.model.parents.remove(&child);
            }
            Op::Group(x, g) => {
                let (node, group) = (self.node(*x), g.map(|g| self.groups[g]));
                self.rules.set_group(node, group);
                // Clearing a node that has no rules stores nothing.
                let stores = group.is_some() || self.model.owner.contains_key(&node);
                if let Some(record) = stores.then(|| self.model.record_mut(node)).flatten() {
                    record.group = group;
                }
                self.model.tidy(node);
            }
            Op::Personal(x, r) => {
                let node = self.node(*x);
                self.rules.set_personal(node, *r);
                let stores = r.is_decided() || self.model.owner.contains_key(&node);
                if let Some(record) = stores.then(|| self.model.record_mut(node)).flatten() {
                    record.personal = *r;
                }
                self.model.tidy(node);
            }
            Op::Specific(x, y, r) => {
                let (node, other) = (self.node(*x), self.node(*y));
                self.rules.set_specific(node, other, *r);
                if *r == CollisionRule::Defer {
                    if let Some(record) = self.model.owner.get(&node) {
                        self.model.records[*record].specific.remove(&other);
                    }
                    self.model.tidy(node);
                } else if self.model.is_removed(other) {
                    // An entry about a removed object names nothing.
                } else if let Some(record) = self.model.record_mut(node) {
                    record.specific.insert(other, *r);
                }
            }
            Op::RemoveSpecific(x, y) => {
                let (node, other) = (self.node(*x), self.node(*y));
                self.rules.remove_specific(node, other);
                if let Some(&record) = self.model.owner.get(&node) {
                    self.model.records[record].specific.remove(&other);
                }
                self.model.tidy(node);
            }
            Op::Share(x, y) => {
                let (from, to) = (self.node(*x), self.node(*y));
                self.rules.share_rules(from, to);
                self.model.share(from, to);
            }
            Op::Recursive(x) => {
                let node = self.node(*x);
                let (rules, model) = (&mut self.rules, &mut self.model);
                let (bodies, colliders) = (&self.world.bodies, &self.world.colliders);
                rules.set_rules_recursive(node, bodies, colliders);
                let descendants = if model.is_removed(node) {
                    Vec::new()
                } else {
                    model.descendants(node, bodies)
                };
                for descendant in descendants {
                    model.share(node, descendant);
                }
            }
            Op::GroupRule(a, b, r) => {
                let (a, b) = (self.groups[*a], self.groups[*b]);
                self.rules.set_group_rule(a, b, *r);
                self.model.set_table(a, b, *r);
            }
            Op::RemoveGroupRule(a, b) => {
                let (a, b) = (self.groups[*a], self.groups[*b]);
                self.rules.remove_group_rule(a, b);
                self.model.remove_table(a, b);
            }
            Op::InSet(set, self_rule, other_rule) => {
                let set = self.set(set);
                self.rules
                    .set_group_rules_in_set(&set, *self_rule, *other_rule);
                for &a in &set {
                    for &b in &set {
                        let rule = if a == b { *self_rule } else { *other_rule };
                        self.model.set_table(a, b, rule);
                    }
                }
            }
            Op::RemoveInSet(set) => {
                let set = self.set(set);
                self.rules.remove_group_rules_in_set(&set);
                for &a in &set {
                    for &b in &set {
                        self.model.remove_table(a, b);
                    }
                }
            }
            Op::WithSet(g, set, r) => {
                let (group, set) = (self.groups[*g], self.set(set));
                self.rules.set_group_rules_with_set(group, &set, *r);
                for &b in &set {
                    self.model.set_table(group, b, *r);
                }
            }
            Op::RemoveWithSet(g, set) => {
                let (group, set) = (self.groups[*g], self.set(set));
                self.rules.remove_group_rules_with_set(group, &set);
                for &b in &set {
                    self.model.remove_table(group, b);
                }
            }
            Op::BetweenSets(a, b, r) => {
                let (a, b) = (self.set(a), self.set(b));
                self.rules.set_group_rules_between_sets(&a, &b, *r);
                for &x in &a {
                    for &y in &b {
                        self.model.set_table(x, y, *r);
                    }
                }
            }
            Op::RemoveBetweenSets(a, b) => {
                let (a, b) = (self.set(a), self.set(b));
                self.rules.remove_group_rules_between_sets(&a, &b);
                for &x in &a {
                    for &y in &b {
                        self.model.remove_table(x, y);
                    }
                }
            }
            Op::DefaultRule(r) => {
                self.rules.set_default_rule(*r);
                self.model.default_rule = *r;
            }
            Op::Kind(b, k) => {
                let handle = self.body(*b);
                if let Some(body) = self.world.bodies.get_mut(handle) {
                    body.set_body_type(KINDS[*k], true);
                }
            }
            Op::RemoveCollider(c) => {
                let handle = self.colliders[*c % self.colliders.len()];
                if self.world.remove_collider(handle).is_some() {
                    self.forget(Node::Collider(handle));
                }
            }
            Op::RemoveBody(b) => {
                let handle = self.body(*b);
                if let Some(body) = self.world.remove_body(handle) {
                    for &collider in body.colliders() {
                        self.forget(Node::Collider(collider));
                    }
                    self.forget(Node::Body(handle));
                }
            }
            Op::AddCollider(body) => self.add_collider(*body),
            Op::AddBody(kind) => self.add_body(*kind),
        }
    }

    fn forget(&mut self, node: Node) {
        self.rules.remove_node(node);
        self.model.forget(node);
    }

    fn check(&self) {
        let (bodies, colliders) = (&self.world.bodies, &self.world.colliders);
        for (n, &a) in self.colliders.iter().enumerate() {
            for &b in &self.colliders[n..] {
                let got = self.rules.resolve(bodies, colliders, a, b);
                let expected = self.model.resolve(bodies, colliders, a, b);
                assert_eq!(got, expected, "resolve({a:?}, {b:?}) against the reference");
                let swapped = self.rules.resolve(bodies, colliders, b, a);
                assert_eq!(swapped, got, "resolve({b:?}, {a:?}) is not symmetric");
                let why = self.rules.explain(bodies, colliders, a, b);
                assert_eq!(why.rule, got, "explain disagrees with resolve: {why:?}");
            }
        }
        // Saved and loaded, the rule set resolves every pair as before.
        #[cfg(feature = "serde")]
        {
            let text = serde_json::to_string(&self.rules).expect("the rule set saves");
            let loaded: CollisionRuleSet = serde_json::from_str(&text).expect("the rule set loads");
            for &a in &self.colliders {
                for &b in &self.colliders {
                    let (x, y) = (
                        loaded.resolve(bodies, colliders, a, b),
                        self.rules.resolve(bodies, colliders, a, b),
                    );
                    assert_eq!(x, y, "resolve({a:?}, {b:?}) after loading");
                }
            }
        }
        // Whatever was edited, forgetting what left the world leaves it clean.
        let mut swept = self.rules.clone();
        swept.remove_missing(bodies, colliders);
        assert_eq!(
            swept.validate(bodies, colliders),
            Ok(()),
            "not clean after remove_missing"
        );
        for i in 0..self.bodies.len() + self.colliders.len() {
            let node = self.node(i);
            let record = self.model.record(node);
            let personal = record.map_or(CollisionRule::Defer, |r| r.personal);
            assert_eq!(self.rules.personal(node), personal, "personal({node:?})");
            assert_eq!(
                self.rules.group(node),
                record.and_then(|r| r.group),
                "group({node:?})"
            );
            if let Node::Body(body) = node {
                let parent = self.model.parents.get(&body).copied();
                assert_eq!(self.rules.parent(body), parent, "parent({body:?})");
            }
        }
    }
}

fn config(cases: u32) -> Config {
    props_config(cases, 0x5eed_c011_1de5)
}

/// Proptest's settings for `cases` cases on a fixed seed (`seed` unless
/// `PROPS_SEED`, in hex, says another); `PROPS_CASES` sets another count.
pub(super) fn props_config(cases: u32, seed: u64) -> Config {
    use super::world::env_or;
    Config {
        cases: env_or("PROPS_CASES", cases, |v| v.parse().ok()),
        rng_seed: proptest::test_runner::RngSeed::Fixed(env_or("PROPS_SEED", seed, |v| {
            u64::from_str_radix(v, 16).ok()
        })),
        failure_persistence: None,
        ..Config::default()
    }
}

proptest! {
    #![proptest_config(config(2500))]

    /// After every edit, every pair resolves as the reference says.
    #[test]
    fn resolve_matches_the_reference(scenario in scenario()) {
        let mut run = Run::new(&scenario);
        run.check();
        for op in &scenario.ops {
            run.apply(op);
            run.check();
        }
    }
}

/// Scenes whose bodies form one long parent chain (17 to 28 bodies, past
/// the 16 nodes `resolve` keeps inline before it spills to the heap), a
/// collider on each, and random rules on them.
fn long_chain() -> impl Strategy<Value = Scenario> {
    (
        17..29usize,
        proptest::collection::vec(
            prop_oneof![
                3 => (0..64usize, rule()).prop_map(|(x, r)| Op::Personal(x, r)),
                3 => (0..64usize, 0..64usize, rule()).prop_map(|(x, y, r)| Op::Specific(x, y, r)),
                2 => (0..64usize, proptest::option::of(0..GROUPS)).prop_map(|(x, g)| Op::Group(x, g)),
                2 => (0..GROUPS, 0..GROUPS, rule()).prop_map(|(a, b, r)| Op::GroupRule(a, b, r)),
                1 => (0..64usize, 0..64usize).prop_map(|(x, y)| Op::Share(x, y)),
            ],
            0..40,
        ),
    )
        .prop_map(|(n, rules)| {
            // Body i + 1 is the child of body i: a chain n bodies deep, and
            // a collider on every body, so some chains hold n + 1 nodes.
            let links = (0..n - 1).map(|i| Op::Parent(i + 1, i));
            Scenario {
                bodies: vec![0; n],
                colliders: (0..n).map(Some).collect(),
                ops: links.chain(rules).collect(),
            }
        })
}

proptest! {
    #![proptest_config(config(300))]

    /// Chains longer than the inline buffer resolve as the reference says.
    #[test]
    fn long_chains_match_the_reference(scenario in long_chain()) {
        let mut run = Run::new(&scenario);
        for op in &scenario.ops {
            run.apply(op);
        }
        run.check();
    }
}
