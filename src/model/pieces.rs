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
    /// copy of a rule with an end ends on its own, when the piece is apart,
    /// and its count comes at the step the source's does (a copy of the
    /// end as given, not of what is left of it, which rounds a time).
    fn set_specific_keeping_end(&mut self, node: Node, other: Node, rule: CollisionRule, like: (Node, Node)) {
        // A piece's root is never its source's: `set_specific` would forget
        // the end to copy.
        debug_assert_ne!((node, other), like, "an entry copied onto itself");
        let end = self.end_key(like.0, like.1);
        self.set_specific(node, other, rule);
        if let Some(from) = end
            && self.specific(node, other) != CollisionRule::Defer
        {
            self.endings.copy(from, (node, other));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use super::super::super::Until;
    use super::super::super::rapier::prelude::Real;

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

    /// Found by a review: a piece's copy of an end was given again, from
    /// what was left of it rounded to a `Real`, so a time a few of its last
    /// bits from the edge of a step could end the piece's entry a step
    /// apart from its source's. The copy is the end as given.
    #[test]
    fn a_piece_copy_of_an_end_comes_at_the_step_the_source_does() {
        let body = |index| RigidBodyHandle::from_raw_parts(index, 0);
        let (source, piece, floor) = (body(1), body(2), body(3));
        let dt: Real = 1.0 / 60.0;
        let mut checked = 0;
        for n in 2..20u16 {
            let edge = (f64::from(n) + 0.499) * f64::from(dt);
            for bits in -12..=12 {
                let seconds = f32::from_bits((edge as f32).to_bits().wrapping_add_signed(bits));
                let until = Until::seconds(seconds).even_if_overlapping();
                for split_at in 1..n {
                    let mut rules = CollisionRuleSet::default();
                    for _ in 0..7 {
                        rules.count_ends(dt);
                    }
                    // The source's own entry, copied to a piece with a
                    // record of its own; the floor's about the source, held
                    // about the piece too.
                    rules.set_specific_until(source, floor, CollisionRule::NoPair, until);
                    rules.set_specific_until(floor, source, CollisionRule::NoResponse, until);
                    let mut came = Vec::new();
                    for step in 0..usize::from(n) + 3 {
                        if step == usize::from(split_at) {
                            assert!(rules.give_piece(source, piece, true, Heir::Piece));
                        }
                        let due: Vec<(Node, Node)> =
                            rules.count_ends(dt).into_iter().map(|d| (d.node, d.other)).collect();
                        came.push(due);
                    }
                    let first = |key: (Node, Node)| came.iter().position(|due| due.contains(&key));
                    let (s, p, f) = (Node::Body(source), Node::Body(piece), Node::Body(floor));
                    assert_eq!(first((p, f)), first((s, f)), "{seconds} s, split at step {split_at}");
                    assert_eq!(first((f, p)), first((f, s)), "{seconds} s, split at step {split_at}");
                    assert!(first((s, f)).is_some(), "{seconds} s came");
                    checked += 1;
                }
            }
        }
        assert!(checked > 3_000, "{checked} splits");
    }
}
