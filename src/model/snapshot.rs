//! The saved form of a rule set (feature `serde`): the group table, the
//! default rule, each record with the nodes that use it, and the parent map.
//! Handles are saved as Rapier saves them, so a rule set is saved and loaded
//! together with the Rapier sets it belongs to.

use super::super::rapier::prelude::RigidBodyHandle;
use serde::{Deserialize, Serialize};

use super::super::{CollisionGroup, CollisionRule, CollisionRuleSet, Node, RuleError};

/// One rule record and the nodes that share it.
#[derive(Serialize, Deserialize)]
struct SavedRecord {
    users: Vec<Node>,
    personal: CollisionRule,
    group: Option<CollisionGroup>,
    specific: Vec<(Node, CollisionRule)>,
}

#[derive(Serialize, Deserialize)]
pub(crate) struct Snapshot {
    default_rule: CollisionRule,
    group_count: u32,
    group_rules: Vec<(CollisionGroup, CollisionGroup, CollisionRule)>,
    records: Vec<SavedRecord>,
    parents: Vec<(RigidBodyHandle, RigidBodyHandle)>,
}

impl From<CollisionRuleSet> for Snapshot {
    fn from(rules: CollisionRuleSet) -> Snapshot {
        let mut records: Vec<(super::records::RecordId, SavedRecord)> = Vec::new();
        for node in rules.nodes() {
            let id = rules.record_id(node).expect("a listed node has a record");
            match records.iter_mut().find(|(r, _)| *r == id) {
                Some((_, saved)) => saved.users.push(node),
                None => {
                    let record = rules.records.get(id);
                    let mut specific: Vec<_> =
                        record.specific.iter().map(|(&n, &r)| (n, r)).collect();
                    specific.sort_by_key(|(n, _)| sort_key(*n));
                    records.push((
                        id,
                        SavedRecord {
                            users: vec![node],
                            personal: record.personal,
                            group: record.group,
                            specific,
                        },
                    ));
                }
            }
        }
        let mut group_rules: Vec<_> = rules.group_rules().collect();
        group_rules.sort();
        let mut parents: Vec<_> = rules.parents().collect();
        parents.sort_by_key(|(c, _)| c.into_raw_parts());
        Snapshot {
            default_rule: rules.default_rule(),
            group_count: rules.group_count(),
            group_rules,
            records: records.into_iter().map(|(_, r)| r).collect(),
            parents,
        }
    }
}

fn sort_key(node: Node) -> (u8, (u32, u32)) {
    match node {
        Node::Collider(h) => (0, h.into_raw_parts()),
        Node::Body(h) => (1, h.into_raw_parts()),
    }
}

impl Snapshot {
    /// What no saved rule set of this crate holds: a group past the saved
    /// count (a later `create_group` would hand it out again), a node in two
    /// records or twice in one, a body with two parents. A parent cycle is
    /// refused by `set_parent` while loading. Checked before anything is
    /// built, so that a refused load is an error naming the problem, never a
    /// panic or a rule set that breaks later.
    fn check(&self) -> Result<(), String> {
        let count = self.group_count.max(2);
        if count == u32::MAX {
            return Err(format!(
                "saved group count {count}: no group could be created"
            ));
        }
        let known = |g: CollisionGroup| {
            if g.id() < count {
                Ok(())
            } else {
                Err(format!(
                    "saved group {} is past the group count {count}",
                    g.id()
                ))
            }
        };
        for &(a, b, _) in &self.group_rules {
            known(a)?;
            known(b)?;
        }
        let mut users = hashbrown::HashSet::new();
        for record in &self.records {
            if let Some(group) = record.group {
                known(group)?;
            }
            for &user in &record.users {
                if !users.insert(user) {
                    return Err(format!("saved node {user:?} uses more than one record"));
                }
            }
        }
        let mut children = hashbrown::HashSet::new();
        for &(child, _) in &self.parents {
            if !children.insert(child) {
                return Err(format!("saved body {child:?} has more than one parent"));
            }
        }
        Ok(())
    }
}

impl TryFrom<Snapshot> for CollisionRuleSet {
    type Error = String;

    fn try_from(saved: Snapshot) -> Result<CollisionRuleSet, String> {
        saved.check()?;
        let mut rules = CollisionRuleSet::default();
        rules.groups.restore(saved.group_count, saved.group_rules);
        rules.set_default_rule(saved.default_rule);
        for record in saved.records {
            let Some(&first) = record.users.first() else {
                continue;
            };
            rules.set_personal(first, record.personal);
            rules.set_group(first, record.group);
            for (other, rule) in record.specific.into_iter().filter(|(_, r)| r.is_decided()) {
                rules.put_specific(first, other, rule);
            }
            for &user in &record.users[1..] {
                rules.share_rules(first, user);
            }
        }
        for (child, parent) in saved.parents {
            match rules.set_parent(child, parent) {
                // A link naming an object whose slot the save also names at
                // another generation: the link changes no chain (it ends
                // below a body missing from the world), and the hooks
                // would forget it at the next step. Skipped, as entries
                // about such objects are.
                Ok(()) | Err(RuleError::Removed { .. }) => {}
                Err(e) => return Err(format!("saved parent map: {e}")),
            }
        }
        // Put in place of a rule set the hooks hold (`*hooks.rules_mut() =
        // loaded`), every pair and plan is to be looked at again.
        rules.mark_all_changed();
        Ok(rules)
    }
}
