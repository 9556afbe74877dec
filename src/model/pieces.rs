//! What a piece of a cut or torn soft body keeps of the body it came from
//! (`docs/semantics.md`, "Soft bodies").

use super::super::rapier::prelude::RigidBodyHandle;

use super::super::{CollisionRule, CollisionRuleSet, Node};

/// Which root takes a soft body's rules from the root it had.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Heir {
    /// The root of a piece split off: rules it holds itself (given to it
    /// after the split, or to it as a cluster proxy before) stay its own.
    Piece,
    /// The body's own new root (its root's cluster went): the body's rules
    /// replace what the proxy held.
    NewRoot,
}

impl CollisionRuleSet {
    /// Gives `piece` (the root body of a soft body split off by a cut or a
    /// tear) the rules of `source` (the root body of the body it came from):
    /// it shares `source`'s record (personal rule, group, its specific
    /// entries, and later edits through either), every entry another node
    /// holds about `source` is held about `piece` too, and `piece` gets
    /// `source`'s parent unless it has one. A [`Heir::Piece`] that holds
    /// rules of its own keeps its record, and takes from `source`'s what
    /// its own does not say (a group, a personal rule, a one-way surface,
    /// an entry about a node its own entries do not name). Returns whether
    /// `piece` took `source`'s rules: false for a removed `piece`.
    ///
    /// With `copy`, `piece` gets a record of its own with a copy of
    /// `source`'s personal rule, group and specific entries instead of
    /// sharing it (for a project that keeps each piece's rules itself, as
    /// the Bevy plugin does with each piece's components).
    pub(crate) fn give_piece(&mut self, source: RigidBodyHandle, piece: RigidBodyHandle, copy: bool, heir: Heir) -> bool {
        let (from, to) = (Node::Body(source), Node::Body(piece));
        // `piece` is in the world: the set names no newer body of its slot.
        self.forget_unborn(piece);
        if self.is_removed(to) {
            return false;
        }
        let own = heir == Heir::Piece && self.record(to).is_some_and(|r| !r.is_empty());
        match self.record(from).filter(|r| !r.is_empty()).cloned() {
            // A cluster proxy with rules of its own became the piece's root:
            // before the split its colliders read the proxy's rules, then
            // the source's. The source's fill in what the proxy does not
            // say, as the chain did (`docs/semantics.md`, "Soft bodies").
            Some(record) if own => {
                if self.group(to).is_none() && record.group.is_some() {
                    self.set_group(to, record.group);
                }
                if !self.personal(to).is_decided() && record.personal.is_decided() {
                    self.set_personal(to, record.personal);
                }
                if self.one_way(to).is_none() && record.one_way.is_some() {
                    self.set_one_way(to, record.one_way);
                }
                for (other, rule) in record.specific {
                    if !self.specific(to, other).is_decided() {
                        self.set_specific_keeping_end(to, other, rule, (from, other));
                    }
                }
            }
            Some(record) if copy => {
                self.set_group(to, record.group);
                self.set_personal(to, record.personal);
                self.set_one_way(to, record.one_way);
                for (other, rule) in record.specific {
                    self.set_specific_keeping_end(to, other, rule, (from, other));
                }
            }
            Some(_) => self.share_rules(from, to),
            None => {}
        }
        if self.is_named(from) {
            let holders: Vec<(Node, CollisionRule)> = self.entries_about(from).collect();
            for (holder, rule) in holders {
                // An entry about a cluster proxy that became the root came
                // before the one about the source in its colliders' chains:
                // it stays (a fresh root has none).
                if !self.specific(holder, to).is_decided() {
                    self.set_specific_keeping_end(holder, to, rule, (holder, from));
                }
            }
        }
        if let Some(parent) = self.parent(source).filter(|_| self.parent(piece).is_none()) {
            // A piece is a leaf of Rapier's making: no cycle goes through it.
            let _ = self.set_parent(piece, parent);
        }
        true
    }

    /// `set_specific`, with the end the entry `like` has, if any: a piece's
    /// copy of a rule with an end ends on its own, when the piece is apart.
    fn set_specific_keeping_end(&mut self, node: Node, other: Node, rule: CollisionRule, like: (Node, Node)) {
        match self.specific_until(like.0, like.1) {
            Some(until) => self.set_specific_until(node, other, rule, until),
            None => self.set_specific(node, other, rule),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_piece_takes_its_rules_past_a_newer_handle_of_its_slot() {
        // A set not saved with its world names generation 4 of slot 4,
        // which Rapier has not handed out; the piece's root is generation 2.
        let body = |index, generation| RigidBodyHandle::from_raw_parts(index, generation);
        let (source, piece, unborn, child) = (body(3, 1), body(4, 2), body(4, 4), body(5, 0));
        for linked in [false, true] {
            let mut rules = CollisionRuleSet::default();
            rules.set_personal(source, CollisionRule::NoResponse);
            if linked {
                rules.set_parent(unborn, child).expect("no cycle");
            } else {
                rules.set_personal(unborn, CollisionRule::NoPair);
            }
            assert!(rules.is_removed(Node::Body(piece)), "the unborn handle makes the piece dead");
            assert!(rules.give_piece(source, piece, false, Heir::Piece));
            assert_eq!(rules.personal(piece), CollisionRule::NoResponse, "linked: {linked}");
            assert_eq!(rules.personal(unborn), CollisionRule::Defer, "linked: {linked}");
            assert_eq!(rules.parent(unborn), None, "linked: {linked}");
            assert!(!rules.is_removed(Node::Body(unborn)), "Rapier may hand out the unborn handle later");
        }
    }
}
