//! Personal rules that Rapier's groups decide: colliders of dynamic bodies
//! whose chain's personal rules all say one `Normal`, `NoResponse` or
//! `NoPair`.

use hashbrown::{HashMap, HashSet};
use super::super::rapier::prelude::*;

use super::plan::Request;
use super::super::{CollisionRule, CollisionRuleSet, Node};

/// The first decided personal rule up the chain of `leaf`, and its depth
/// (0 for the collider itself).
pub(crate) fn first_personal(
    rules: &CollisionRuleSet,
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    leaf: ColliderHandle,
) -> Option<(CollisionRule, usize)> {
    let mut node = Some(Node::Collider(leaf));
    let mut depth = 0;
    while let Some(current) = node {
        let personal = rules.record(current).map(|r| r.personal);
        if let Some(rule) = personal.filter(|r| r.is_decided()) {
            return Some((rule, depth));
        }
        node = rules.hierarchy.next(bodies, colliders, current);
        depth += 1;
    }
    None
}

/// The rule of `leaf`'s chain at the personal stage when every personal
/// rule of the chain says the same `Normal`, `NoResponse` or `NoPair`, with
/// the depth of the first.
pub(super) fn personal_rule(
    rules: &CollisionRuleSet,
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    leaf: ColliderHandle,
) -> Option<(CollisionRule, usize)> {
    let (rule, depth) = first_personal(rules, bodies, colliders, leaf)?;
    let native = matches!(
        rule,
        CollisionRule::Normal | CollisionRule::NoResponse | CollisionRule::NoPair
    );
    let mut node = Some(Node::Collider(leaf));
    while let Some(current) = node {
        let personal = rules.record(current).map(|r| r.personal);
        if personal.is_some_and(|r| r.is_decided() && r != rule) {
            return None;
        }
        node = rules.hierarchy.next(bodies, colliders, current);
    }
    native.then_some((rule, depth))
}

/// The first personal rules of the planned colliders, counted by depth and
/// rule. Whether Rapier's groups can say a collider's personal `NoPair` or
/// `NoResponse` depends on the least restrictive first personal rule of
/// every shallower depth (see [`native_personal`]): the plan keeps the
/// counts, so that a collider coming or going with a personal rule is
/// planned alone unless it changes what the others read.
#[derive(Clone, Debug, Default)]
pub(crate) struct PersonalDepths {
    counts: HashMap<(usize, CollisionRule), usize>,
}

/// The least restrictive first personal rule shallower than each depth:
/// what decides whether another collider's personal rule is native.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) struct Shallower(Vec<Option<CollisionRule>>);

impl PersonalDepths {
    /// Counts a collider's first personal rule (rule and depth) in, or out.
    pub(super) fn count(&mut self, first: Option<(CollisionRule, usize)>, inside: bool) {
        let Some((rule, depth)) = first else {
            return;
        };
        if inside {
            *self.counts.entry((depth, rule)).or_default() += 1;
        } else if let Some(count) = self.counts.get_mut(&(depth, rule)) {
            *count -= 1;
            if *count == 0 {
                self.counts.remove(&(depth, rule));
            }
        }
    }

    /// Whether moving one collider's first personal rule from `old` to
    /// `new` makes a kind (a depth and rule) appear or disappear: only then
    /// can what the others read change.
    pub(super) fn changes_kinds(
        &self,
        old: Option<(CollisionRule, usize)>,
        new: Option<(CollisionRule, usize)>,
    ) -> bool {
        let count = |first: Option<(CollisionRule, usize)>| {
            first.map(|(rule, depth)| self.counts.get(&(depth, rule)).copied().unwrap_or(0))
        };
        count(old) == Some(1) || count(new) == Some(0)
    }

    /// The least restrictive first personal rule above each depth, in one
    /// pass over the counted (depth, rule) kinds, whatever the number of
    /// colliders.
    pub(super) fn shallower(&self) -> Shallower {
        let deepest = self.counts.keys().map(|&(depth, _)| depth + 1).max().unwrap_or(0);
        let mut least: Vec<Option<CollisionRule>> = vec![None; deepest];
        for &(depth, rule) in self.counts.keys() {
            least[depth] = Some(least[depth].map_or(rule, |r| r.min(rule)));
        }
        let mut shallower = vec![None; deepest + 1];
        for d in 0..deepest {
            shallower[d + 1] = match (shallower[d], least[d]) {
                (Some(a), Some(b)) => Some(CollisionRule::min(a, b)),
                (a, b) => a.or(b),
            };
        }
        // Past the deepest counted rule, every depth reads the same: two
        // tables that differ only in how deep they go say the same.
        while shallower.len() > 1 && shallower[shallower.len() - 1] == shallower[shallower.len() - 2] {
            shallower.pop();
        }
        Shallower(shallower)
    }
}

impl Shallower {
    /// The least restrictive first personal rule at a depth below `depth`.
    fn than(&self, depth: usize) -> Option<CollisionRule> {
        self.0[depth.min(self.0.len() - 1)]
    }
}

/// The personal rule Rapier's groups can say for `handle` (hooked by its
/// chain, of a body `dynamic` or not), if any.
///
/// The personal stage compares the two chains step by step: a collider `c`
/// whose chain says one rule `r` from depth `d` up gets `r` with every
/// collider whose first personal rule is deeper, the more restrictive of the
/// two with one at depth `d`, and the other's rule with one shallower.
/// Rapier's test gives `c` and a native other side the more restrictive of
/// their two encodings, and lets a hooked side restrict further. So `c` is
/// exact unless some collider whose first personal rule is shallower than
/// `d` says a less restrictive rule than `r` (then `c` is hooked), and
/// unless a specific entry or a pinned pair may reach its pairs and `r`
/// keeps the pair from the hook (`NoPair`, `NoResponse`). Every collider
/// with a personal rule is reached, so the plan's [`PersonalDepths`] count
/// them all.
pub(super) fn native_personal(
    request: &Request<'_>,
    shallower: &Shallower,
    pinned: &HashSet<ColliderHandle>,
    handle: ColliderHandle,
    dynamic: bool,
) -> Option<CollisionRule> {
    let Request {
        rules,
        bodies,
        colliders,
        ..
    } = *request;
    if !dynamic {
        return None;
    }
    let (rule, depth) = personal_rule(rules, bodies, colliders, handle)
        .filter(|&(rule, _)| request.native_rule(rule))?;
    if rule != CollisionRule::Normal {
        let overridden = shallower.than(depth).is_some_and(|r| r < rule);
        let reached_by_entries =
            pinned.contains(&handle) || touches_entries(rules, bodies, colliders, handle);
        if overridden || reached_by_entries {
            return None;
        }
    }
    Some(rule)
}

/// Whether `start` or a node above it carries specific entries or is named
/// by one.
fn touches_entries(
    rules: &CollisionRuleSet,
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    start: impl Into<Node>,
) -> bool {
    rules
        .hierarchy
        .chain(bodies, colliders, start.into())
        .any(|node| rules.in_entries(node))
}

#[cfg(test)]
mod tests {
    use super::*;
    use CollisionRule::*;

    #[test]
    fn the_others_read_the_least_restrictive_rule_of_each_shallower_depth() {
        let mut depths = PersonalDepths::default();
        assert_eq!(depths.shallower(), Shallower(vec![None]), "no personal rule");
        // Ghosts: `NoResponse` on their bodies (depth 1).
        for _ in 0..2 {
            depths.count(Some((NoResponse, 1)), true);
        }
        let ghosts = depths.shallower();
        assert_eq!((ghosts.than(1), ghosts.than(2), ghosts.than(9)), (None, Some(NoResponse), Some(NoResponse)));
        // A third ghost, or one ghost less, is a kind already counted.
        assert!(!depths.changes_kinds(None, Some((NoResponse, 1))));
        assert!(!depths.changes_kinds(Some((NoResponse, 1)), None));
        // A collider's own `Normal` (depth 0) is a new kind, and shallower
        // than the ghosts' rule: it is what they read from depth 1 down.
        assert!(depths.changes_kinds(None, Some((Normal, 0))));
        depths.count(Some((Normal, 0)), true);
        let shallower = depths.shallower();
        assert_eq!(shallower, Shallower(vec![None, Some(Normal)]), "deeper depths read the same");
        assert_ne!(shallower, ghosts);
        // Its last member gone, the kind goes and the ghosts read as before.
        assert!(depths.changes_kinds(Some((Normal, 0)), None));
        depths.count(Some((Normal, 0)), false);
        assert_eq!(depths.shallower(), ghosts);
    }
}
