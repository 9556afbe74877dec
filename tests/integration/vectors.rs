//! Table-driven resolution cases: the shared sample vectors (`data/rules.toml`)
//! and the crate's own (`data/cases.toml`), in one format, each checked in
//! both argument orders.

use std::collections::HashMap;

use super::rapier::prelude::*;
use super::rules::{CollisionGroup, CollisionRule, CollisionRuleSet, Node, Stage};
use toml::{Table, Value};

/// A scene built from one `[[case]]`: Rapier sets, a rule set, and names.
pub struct Scene {
    pub id: String,
    pub bodies: RigidBodySet,
    pub colliders: ColliderSet,
    pub rules: CollisionRuleSet,
    nodes: HashMap<String, Node>,
    groups: HashMap<String, CollisionGroup>,
}

pub fn rule(name: &str) -> CollisionRule {
    match name {
        "Defer" => CollisionRule::Defer,
        "Normal" => CollisionRule::Normal,
        "NoResponse" => CollisionRule::NoResponse,
        "NoContacts" => CollisionRule::NoContacts,
        "NoPair" => CollisionRule::NoPair,
        other => panic!("unknown rule {other:?}"),
    }
}

fn body_type(name: &str) -> RigidBodyType {
    match name {
        "dynamic" => RigidBodyType::Dynamic,
        "kinematic" => RigidBodyType::KinematicPositionBased,
        "kinematic_velocity" => RigidBodyType::KinematicVelocityBased,
        "fixed" => RigidBodyType::Fixed,
        other => panic!("unknown body kind {other:?}"),
    }
}

fn text(value: &Value) -> &str {
    value
        .as_str()
        .unwrap_or_else(|| panic!("expected a string, got {value}"))
}

fn list(value: &Value) -> &[Value] {
    value
        .as_array()
        .unwrap_or_else(|| panic!("expected an array, got {value}"))
}

impl Scene {
    pub fn build(case: &Table) -> Scene {
        let id = case["id"].as_str().expect("case id").to_owned();
        let mut scene = Scene {
            id,
            bodies: RigidBodySet::new(),
            colliders: ColliderSet::new(),
            rules: CollisionRuleSet::default(),
            nodes: HashMap::new(),
            groups: HashMap::from([
                (
                    "DEFAULT_DYNAMIC".to_owned(),
                    CollisionGroup::DEFAULT_DYNAMIC,
                ),
                (
                    "DEFAULT_KINEMATIC".to_owned(),
                    CollisionGroup::DEFAULT_KINEMATIC,
                ),
            ]),
        };
        let empty = Table::new();
        let table = |key: &str| case.get(key).and_then(Value::as_table).unwrap_or(&empty);
        for (name, kind) in table("bodies") {
            let body = RigidBodyBuilder::new(body_type(text(kind)));
            let handle = scene.bodies.insert(body);
            scene.nodes.insert(name.clone(), Node::Body(handle));
        }
        for (name, body) in table("colliders") {
            let shape = ColliderBuilder::ball(0.5);
            let handle = match text(body) {
                "none" => scene.colliders.insert(shape),
                body => {
                    let parent = scene.body(body);
                    scene
                        .colliders
                        .insert_with_parent(shape, parent, &mut scene.bodies)
                }
            };
            scene.nodes.insert(name.clone(), Node::Collider(handle));
        }
        for (child, parent) in table("parents") {
            let (child, parent) = (scene.body(child), scene.body(text(parent)));
            scene
                .rules
                .set_parent(child, parent)
                .unwrap_or_else(|e| panic!("case {}: {e}", scene.id));
        }
        for op in case.get("ops").map(list).unwrap_or_default() {
            scene.apply(list(op));
        }
        for (body, kind) in table("body_kind_after") {
            let handle = scene.body(body);
            scene.bodies[handle].set_body_type(body_type(text(kind)), true);
        }
        scene
    }

    pub fn node(&self, name: &str) -> Node {
        *self
            .nodes
            .get(name)
            .unwrap_or_else(|| panic!("case {}: no node {name:?}", self.id))
    }

    fn body(&self, name: &str) -> RigidBodyHandle {
        match self.node(name) {
            Node::Body(handle) => handle,
            Node::Collider(_) => panic!("case {}: {name:?} is not a body", self.id),
        }
    }

    pub fn collider(&self, name: &str) -> ColliderHandle {
        match self.node(name) {
            Node::Collider(handle) => handle,
            Node::Body(_) => panic!("case {}: {name:?} is not a collider", self.id),
        }
    }

    fn group(&mut self, name: &str) -> CollisionGroup {
        if let Some(&group) = self.groups.get(name) {
            return group;
        }
        let group = self.rules.create_group();
        self.groups.insert(name.to_owned(), group);
        group
    }

    fn groups(&mut self, names: &Value) -> Vec<CollisionGroup> {
        list(names).iter().map(|n| self.group(text(n))).collect()
    }

    fn apply(&mut self, op: &[Value]) {
        let arg = |i: usize| text(&op[i]);
        match arg(0) {
            "group_rule" => {
                let (a, b) = (self.group(arg(1)), self.group(arg(2)));
                self.rules.set_group_rule(a, b, rule(arg(3)));
            }
            "remove_group_rule" => {
                let (a, b) = (self.group(arg(1)), self.group(arg(2)));
                self.rules.remove_group_rule(a, b);
            }
            "in_set" => {
                let set = self.groups(&op[1]);
                self.rules
                    .set_group_rules_in_set(&set, rule(arg(2)), rule(arg(3)));
            }
            "remove_in_set" => {
                let set = self.groups(&op[1]);
                self.rules.remove_group_rules_in_set(&set);
            }
            "with_set" => {
                let group = self.group(arg(1));
                let set = self.groups(&op[2]);
                self.rules
                    .set_group_rules_with_set(group, &set, rule(arg(3)));
            }
            "remove_with_set" => {
                let group = self.group(arg(1));
                let set = self.groups(&op[2]);
                self.rules.remove_group_rules_with_set(group, &set);
            }
            "between_sets" => {
                let (a, b) = (self.groups(&op[1]), self.groups(&op[2]));
                self.rules
                    .set_group_rules_between_sets(&a, &b, rule(arg(3)));
            }
            "remove_between_sets" => {
                let (a, b) = (self.groups(&op[1]), self.groups(&op[2]));
                self.rules.remove_group_rules_between_sets(&a, &b);
            }
            "personal" => self.rules.set_personal(self.node(arg(1)), rule(arg(2))),
            "group" => {
                let group = match arg(2) {
                    "none" => None,
                    name => Some(self.group(name)),
                };
                self.rules.set_group(self.node(arg(1)), group);
            }
            "specific" => {
                let (node, other) = (self.node(arg(1)), self.node(arg(2)));
                self.rules.set_specific(node, other, rule(arg(3)));
            }
            "remove_specific" => {
                let (node, other) = (self.node(arg(1)), self.node(arg(2)));
                self.rules.remove_specific(node, other);
            }
            "share" => self.rules.share_rules(self.node(arg(1)), self.node(arg(2))),
            "recursive" => {
                let node = self.node(arg(1));
                self.rules
                    .set_rules_recursive(node, &self.bodies, &self.colliders);
            }
            "default_rule" => self.rules.set_default_rule(rule(arg(1))),
            // The crate's own ops, beyond the shared format.
            "parent" => {
                let (child, parent) = (self.body(arg(1)), self.body(arg(2)));
                self.rules
                    .set_parent(child, parent)
                    .unwrap_or_else(|e| panic!("case {}: {e}", self.id));
            }
            "unparent" => {
                self.rules.remove_parent(self.body(arg(1)));
            }
            "kind" => {
                let handle = self.body(arg(1));
                self.bodies[handle].set_body_type(body_type(arg(2)), true);
            }
            "forget" => self.rules.remove_node(self.node(arg(1))),
            other => panic!("case {}: unknown op {other:?}", self.id),
        }
    }
}

fn cases(source: &str) -> Vec<Table> {
    let document: Table = source.parse().expect("the case file parses");
    list(&document["case"])
        .iter()
        .map(|case| case.as_table().expect("a case is a table").clone())
        .collect()
}

fn stage(name: &str) -> Stage {
    match name {
        "Specific" => Stage::Specific,
        "Personal" => Stage::Personal,
        "Group" => Stage::Group,
        "Default" => Stage::Default,
        other => panic!("unknown stage {other:?}"),
    }
}

/// Builds every case of `source` and checks its `expect` rows (both orders)
/// and its `explain` rows (`[a, b, STAGE, step, distance]`, a's order only).
#[track_caller]
fn check_cases(source: &str) -> usize {
    let mut checked = 0;
    for case in cases(source) {
        let scene = Scene::build(&case);
        let rows = case.get("expect").map(list).unwrap_or_default();
        assert!(!rows.is_empty(), "case {} expects nothing", scene.id);
        for row in rows {
            let row = list(row);
            let (a, b) = (scene.collider(text(&row[0])), scene.collider(text(&row[1])));
            let expected = rule(text(&row[2]));
            for (x, y) in [(a, b), (b, a)] {
                let got = scene.rules.resolve(&scene.bodies, &scene.colliders, x, y);
                assert_eq!(
                    got,
                    expected,
                    "case {}: resolve({}, {}) with order {:?}",
                    scene.id,
                    row[0],
                    row[1],
                    (x, y)
                );
                checked += 1;
            }
        }
        for row in case.get("explain").map(list).unwrap_or_default() {
            let row = list(row);
            let (a, b) = (scene.collider(text(&row[0])), scene.collider(text(&row[1])));
            let why = scene.rules.explain(&scene.bodies, &scene.colliders, a, b);
            let step = row[3].as_integer().expect("step") as usize;
            let distance = row[4].as_integer().expect("distance") as usize;
            assert_eq!(
                (why.stage, why.step, why.distance),
                (stage(text(&row[2])), step, distance),
                "case {}: explain({}, {}) = {why:?}",
                scene.id,
                row[0],
                row[1]
            );
        }
    }
    checked
}

#[test]
fn shared_vectors() {
    let checked = check_cases(include_str!("data/rules.toml"));
    assert!(checked >= 60, "only {checked} resolutions checked");
}

#[test]
fn crate_cases() {
    let checked = check_cases(include_str!("data/cases.toml"));
    assert!(checked >= 100, "only {checked} resolutions checked");
}
