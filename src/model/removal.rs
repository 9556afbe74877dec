//! Forgetting removed objects (`docs/semantics.md`, "Handles of removed objects"): their rules,
//! the entries about them and their parent links.

use smallvec::SmallVec;

use super::super::rapier::prelude::{ColliderSet, RigidBodyHandle, RigidBodySet};

use super::super::{CollisionRuleSet, Node};

/// Forgetting removed objects (`docs/semantics.md`, "Decisions where the specification is silent").
impl CollisionRuleSet {
    /// Forgets a node that left the world: its rules (a shared record lives
    /// on for its other users), every specific entry about it, and for a body
    /// every parent link that names it (its children become roots).
    ///
    /// [`RuleHooks`](crate) does this by itself for objects removed through
    /// Rapier; call it when you use the rule set alone. From then on the
    /// handle is dead to the rule set: `set_parent` refuses it with
    /// [`RuleError::Removed`](super::super::RuleError::Removed) and the other editing verbs ignore it
    /// (`docs/semantics.md`, "Handles of removed objects").
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, CollisionRuleSet, RuleError};
    ///
    /// let mut bodies = RigidBodySet::new();
    /// let (a, b) = (bodies.insert(RigidBodyBuilder::dynamic()), bodies.insert(RigidBodyBuilder::dynamic()));
    /// let mut rules = CollisionRuleSet::default();
    /// rules.set_specific(a, b, CollisionRule::NoPair);
    /// rules.set_parent(a, b)?;
    /// rules.remove_node(b);
    /// assert_eq!(rules.specific(a, b), CollisionRule::Defer);
    /// assert_eq!(rules.parent(a), None);
    /// assert_eq!(rules.set_parent(a, b), Err(RuleError::Removed { node: b.into() }));
    /// # Ok::<(), RuleError>(())
    /// ```
    pub fn remove_node(&mut self, node: impl Into<Node>) {
        self.remove_nodes(&[node.into()], Some(&[]));
    }

    /// Forgets nodes that left the world together (the objects Rapier
    /// removed since the last step), as [`remove_node`](Self::remove_node)
    /// does each. Only a node the rules held is remembered as removed:
    /// whether an edit through a handle is refused must not depend on which
    /// objects the hooks happened to watch. Whether each was held is read
    /// before any is forgotten: forgetting one can leave another unnamed (a
    /// collider's entry about the body removed with it, a parent link), and
    /// the order of the removals must not decide which handles are dead.
    /// A node in `spared` (every node for `None`) is forgotten and not
    /// remembered: an edit gave it rules since the hooks' last step, and
    /// its handle may be one Rapier has yet to hand out (another world's,
    /// or one a world put in place holds no object of yet); whether the
    /// hooks watched it before the edit must not decide
    /// (`docs/semantics.md`, "Handles of removed objects").
    pub(crate) fn remove_nodes(&mut self, nodes: &[Node], spared: Option<&[Node]>) {
        // A step's removals: a few dozen, kept off the heap. Those spared
        // are few (removed the step they were edited), so a scan of them
        // costs nothing where there are none.
        let held: SmallVec<[bool; 64]> = nodes
            .iter()
            .map(|&node| self.holds_rules_about(node) && spared.is_some_and(|spared| !spared.contains(&node)))
            .collect();
        for &node in nodes {
            self.forget_node(node);
        }
        for (&node, held) in nodes.iter().zip(held) {
            if held {
                self.removed.bury(node);
            }
        }
    }

    /// Forgets `node`'s rules, the entries about it and its parent links,
    /// without remembering it as removed.
    fn forget_node(&mut self, node: Node) {
        self.detach(node);
        if let Some(namers) = self.named.remove(&node) {
            // The records holding an entry about it, and no other: the nodes
            // using them change their pairs, logged as an edit of theirs
            // would be.
            for id in namers.iter() {
                self.records.get_mut(id).specific.remove(&node);
                self.touch_users(id, node);
                // Freed if left empty, as removing its last entry by hand
                // frees it.
                self.free_if_empty(id);
            }
        }
        if let Node::Body(body) = node {
            for (child, parent) in self.hierarchy.links() {
                if parent == body {
                    self.changes.node(Node::Body(child));
                }
            }
            self.hierarchy.forget(body);
        }
    }

    /// Forgets what the set holds of `live`'s slot at a newer generation.
    /// The caller has the body `live` from the world, so a newer handle of
    /// its slot names a body Rapier has not handed out yet: only a rule set
    /// not saved with this world can hold one, and it must not make the
    /// live body dead (`docs/semantics.md`, "Handles of removed objects").
    /// The newer handle is not remembered as removed: Rapier may hand it
    /// out later.
    pub(crate) fn forget_unborn(&mut self, live: RigidBodyHandle) {
        // A body can be in both the records and the parent map.
        while let Some(unborn) = self.body_records.newer_than(live).or_else(|| self.hierarchy.newer_than(live)) {
            self.forget_node(Node::Body(unborn));
        }
    }

    /// Forgets every node the rule set knows that is missing from the Rapier
    /// sets: bodies and colliders with rules, bodies in the parent map, and
    /// the subjects of specific entries. Returns how many were forgotten.
    pub fn remove_missing(&mut self, bodies: &RigidBodySet, colliders: &ColliderSet) -> usize {
        let exists = |node: Node| match node {
            Node::Collider(handle) => colliders.contains(handle),
            Node::Body(handle) => bodies.contains(handle),
        };
        let mut missing: Vec<Node> = self.nodes().filter(|&n| !exists(n)).collect();
        for (child, parent) in self.hierarchy.links() {
            missing.extend(
                [Node::Body(child), Node::Body(parent)]
                    .into_iter()
                    .filter(|&n| !exists(n)),
            );
        }
        for record in self.records.live() {
            missing.extend(record.specific.keys().copied().filter(|&n| !exists(n)));
        }
        missing.sort_unstable_by_key(|node| match *node {
            Node::Collider(h) => (0, h.into_raw_parts()),
            Node::Body(h) => (1, h.into_raw_parts()),
        });
        missing.dedup();
        self.remove_nodes(&missing, Some(&[]));
        missing.len()
    }

}

#[cfg(test)]
mod tests {
    use super::super::super::rapier::prelude::*;
    use super::super::super::{CollisionRule, CollisionRuleSet, Node, RuleError};

    /// The nodes the change log sends the hooks to, sorted.
    fn touched(rules: &mut CollisionRuleSet) -> Vec<Node> {
        let changes = rules.take_changes();
        let mut nodes = rules.touched_nodes(&changes).expect("no global edit");
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }

    #[test]
    fn removing_a_named_node_clears_and_logs_exactly_the_records_that_name_it() {
        let mut bodies = RigidBodySet::new();
        let colliders = ColliderSet::new();
        let mut body = || bodies.insert(RigidBodyBuilder::dynamic());
        let (a, b, c, lone, x) = (body(), body(), body(), body(), body());
        let mut rules = CollisionRuleSet::default();
        // `a` and `b` share one record naming `x`; `lone` names it alone;
        // `c` names something else.
        rules.share_rules(a, b);
        rules.set_specific(a, x, CollisionRule::NoPair);
        rules.set_specific(lone, x, CollisionRule::NoResponse);
        rules.set_specific(c, lone, CollisionRule::NoContacts);
        touched(&mut rules);
        rules.remove_node(x);
        for holder in [a, b, lone] {
            assert_eq!(rules.specific(holder, x), CollisionRule::Defer);
        }
        assert_eq!(rules.specific(c, lone), CollisionRule::NoContacts, "another entry stays");
        let mut expected = vec![Node::Body(a), Node::Body(b), Node::Body(lone)];
        expected.sort_unstable();
        assert_eq!(touched(&mut rules), expected, "the users of the two records");
        assert_eq!(rules.validate(&bodies, &colliders), Ok(()));

        // A shared record left with one user logs that user's entry alone
        // while the record holds others, and the user once it holds none.
        let (y, z) = (bodies.insert(RigidBodyBuilder::dynamic()), bodies.insert(RigidBodyBuilder::dynamic()));
        rules.set_specific(b, y, CollisionRule::NoPair);
        rules.remove_node(a);
        rules.set_specific(b, z, CollisionRule::NoPair);
        assert_eq!(rules.validate(&bodies, &colliders), Ok(()), "b is the record's one user");
        touched(&mut rules);
        rules.remove_node(y);
        let changes = rules.take_changes();
        assert_eq!(changes.entries(), [(Node::Body(b), Node::Body(y))]);
        assert_eq!(rules.touched_nodes(&changes), Some(Vec::new()));
        assert_eq!(rules.specific(b, z), CollisionRule::NoPair);
        rules.remove_node(z);
        assert_eq!(touched(&mut rules), vec![Node::Body(b)], "b's record holds no entry now");
    }

    /// Objects removed together (a body and a collider whose entry names
    /// it, a child and its parent) are each dead to the rule set, in
    /// either order: forgetting one first used to leave the other unnamed,
    /// and so not remembered as removed.
    #[test]
    fn nodes_removed_together_are_each_remembered_as_removed_in_any_order() {
        let mut bodies = RigidBodySet::new();
        let mut colliders = ColliderSet::new();
        let (b1, b2, spare) = (
            bodies.insert(RigidBodyBuilder::dynamic()),
            bodies.insert(RigidBodyBuilder::dynamic()),
            bodies.insert(RigidBodyBuilder::dynamic()),
        );
        let c2 = colliders.insert_with_parent(ColliderBuilder::ball(0.5), b2, &mut bodies);
        let (child, parent) = (
            bodies.insert(RigidBodyBuilder::dynamic()),
            bodies.insert(RigidBodyBuilder::dynamic()),
        );
        for order in [
            [Node::Collider(c2), Node::Body(b1), Node::Body(child), Node::Body(parent)],
            [Node::Body(parent), Node::Body(child), Node::Body(b1), Node::Collider(c2)],
        ] {
            let mut rules = CollisionRuleSet::default();
            rules.set_specific(c2, b1, CollisionRule::NoPair);
            rules.set_parent(child, parent).expect("two live bodies");
            rules.remove_nodes(&order, Some(&[]));
            for body in [b1, child, parent] {
                assert_eq!(
                    rules.set_parent(body, spare),
                    Err(RuleError::Removed { node: body.into() }),
                    "{body:?} is dead after removing {order:?}"
                );
            }
            assert!(rules.is_removed(Node::Collider(c2)), "removing {order:?}");
        }
    }

    /// Found by trying soft debris as a new user: a node whose one entry
    /// named a removed object kept an empty record, listed among the nodes,
    /// where removing the entry by hand frees it. A record that keeps other
    /// rules, or other users, stays.
    #[test]
    fn a_record_left_empty_by_a_removal_is_freed_as_by_hand() {
        let mut bodies = RigidBodySet::new();
        let mut body = || bodies.insert(RigidBodyBuilder::dynamic());
        let (player, debris, grouped, shared, other) = (body(), body(), body(), body(), body());
        let mut rules = CollisionRuleSet::default();
        let group = rules.create_group();
        rules.set_specific(player, debris, CollisionRule::NoResponse);
        rules.set_specific(grouped, debris, CollisionRule::NoPair);
        rules.set_group(grouped, Some(group));
        rules.share_rules(shared, other);
        rules.set_specific(shared, debris, CollisionRule::NoPair);
        let mut by_hand = rules.clone();
        rules.remove_node(debris);
        for holder in [player, grouped, shared] {
            by_hand.remove_specific(holder, debris);
        }
        by_hand.remove_node(debris);
        let nodes = |rules: &CollisionRuleSet| {
            let mut nodes: Vec<Node> = rules.nodes().collect();
            nodes.sort_unstable();
            nodes
        };
        assert_eq!(nodes(&rules), nodes(&by_hand), "the same nodes as removing the entries by hand");
        assert!(!nodes(&rules).contains(&Node::Body(player)), "the player holds nothing: {:?}", nodes(&rules));
        assert_eq!(rules.group(grouped), Some(group), "a record with a group stays");
        assert!(nodes(&rules).contains(&Node::Body(shared)), "a shared record stays with its users");
        assert_eq!(rules.record_count(), by_hand.record_count());
        assert_eq!(rules.validate(&bodies, &ColliderSet::new()), Ok(()));
    }
}
