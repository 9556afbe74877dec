//! Refused edits: the error values, and that a refusal changes nothing.

use super::rapier::prelude::*;
use super::rules::{CollisionRuleSet, RuleError};

fn bodies(n: usize) -> (RigidBodySet, Vec<RigidBodyHandle>) {
    let mut set = RigidBodySet::new();
    let handles = (0..n)
        .map(|_| set.insert(RigidBodyBuilder::dynamic()))
        .collect();
    (set, handles)
}

#[test]
fn self_parent_is_refused() {
    let (_, b) = bodies(1);
    let mut rules = CollisionRuleSet::default();
    assert_eq!(
        rules.set_parent(b[0], b[0]),
        Err(RuleError::SelfParent { body: b[0] })
    );
    assert_eq!(rules.parent(b[0]), None);
}

#[test]
fn a_cycle_of_any_length_is_refused_and_changes_nothing() {
    for length in 2..=5 {
        let (_, b) = bodies(length);
        let mut rules = CollisionRuleSet::default();
        for pair in b.windows(2) {
            rules.set_parent(pair[0], pair[1]).expect("a chain is fine");
        }
        let before: Vec<_> = b.iter().map(|&x| rules.parent(x)).collect();
        let (child, parent) = (b[length - 1], b[0]);
        assert_eq!(
            rules.set_parent(child, parent),
            Err(RuleError::Cycle { child, parent }),
            "closing a loop of {length}"
        );
        let after: Vec<_> = b.iter().map(|&x| rules.parent(x)).collect();
        assert_eq!(before, after, "a refused edit changed the parent map");
    }
}

#[test]
fn reparenting_a_root_under_a_sibling_branch_is_fine() {
    let (_, b) = bodies(3);
    let mut rules = CollisionRuleSet::default();
    rules.set_parent(b[1], b[0]).unwrap();
    rules.set_parent(b[2], b[0]).unwrap();
    assert_eq!(rules.set_parent(b[2], b[1]), Ok(()));
    assert_eq!(rules.parent(b[2]), Some(b[1]));
}

#[test]
fn errors_display_lowercase_and_name_the_handles() {
    let (_, b) = bodies(2);
    let error = RuleError::Cycle {
        child: b[0],
        parent: b[1],
    };
    let text = error.to_string();
    assert_eq!(
        text,
        "making body 1 the parent of body 0 would close a cycle: body 1 is already below \
         body 0; call remove_parent on body 1 (or a body between them) first"
    );
    assert!(format!("{error:?}").contains(&format!("{:?}", b[0])), "Debug keeps the handles");
    let removed = RuleError::Removed {
        node: ColliderHandle::from_raw_parts(5, 2).into(),
    };
    assert!(
        removed.to_string().starts_with("collider 5, generation 2 names an object Rapier has removed"),
        "{removed}"
    );
    let boxed: Box<dyn std::error::Error> = Box::new(error);
    assert!(boxed.source().is_none());
}

/// The panic names the fix, at the caller's line (`#[track_caller]`).
#[test]
#[should_panic(expected = "was not created by this rule set (2 groups exist): use the groups `create_group` of this rule set returned")]
fn a_group_of_another_rule_set_is_a_caller_bug() {
    let mut other = CollisionRuleSet::default();
    for _ in 0..3 {
        other.create_group();
    }
    let foreign = other.create_group();
    let (_, b) = bodies(1);
    let mut rules = CollisionRuleSet::default();
    rules.set_group(b[0], Some(foreign));
}

#[test]
fn a_refused_group_edit_changes_nothing() {
    let mut other = CollisionRuleSet::default();
    other.create_group();
    let foreign = other.create_group();
    let (_, b) = bodies(1);
    let mut rules = CollisionRuleSet::default();
    let before = format!("{rules:?}");
    let refused = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        rules.set_group_rule(foreign, foreign, super::rules::CollisionRule::NoPair);
    }));
    assert!(refused.is_err(), "a foreign group was accepted");
    assert_eq!(
        format!("{rules:?}"),
        before,
        "the refused edit changed the rule set"
    );
    assert_eq!(rules.group(b[0]), None);
}

/// Found by a misuse audit: the removals took a group of another rule set
/// silently, where every other verb of the group table refuses it.
#[test]
fn every_group_table_verb_refuses_a_group_of_another_rule_set() {
    use super::rules::{CollisionGroup, CollisionRule::NoPair};
    use super::world::panic_message;
    type Verb = fn(&mut CollisionRuleSet, CollisionGroup, CollisionGroup);
    let verbs: [(&str, Verb); 8] = [
        ("set_group_rule", |r, own, foreign| r.set_group_rule(own, foreign, NoPair)),
        ("remove_group_rule", |r, own, foreign| r.remove_group_rule(own, foreign)),
        ("set_group_rules_in_set", |r, own, foreign| {
            r.set_group_rules_in_set(&[own, foreign], NoPair, NoPair);
        }),
        ("remove_group_rules_in_set", |r, own, foreign| r.remove_group_rules_in_set(&[own, foreign])),
        ("set_group_rules_with_set", |r, own, foreign| r.set_group_rules_with_set(own, &[foreign], NoPair)),
        ("remove_group_rules_with_set", |r, own, foreign| r.remove_group_rules_with_set(own, &[foreign])),
        ("set_group_rules_between_sets", |r, own, foreign| {
            r.set_group_rules_between_sets(&[own], &[foreign], NoPair);
        }),
        ("remove_group_rules_between_sets", |r, own, foreign| {
            r.remove_group_rules_between_sets(&[own], &[foreign]);
        }),
    ];
    let mut other = CollisionRuleSet::default();
    other.create_group();
    let foreign = other.create_group();
    for (verb, act) in verbs {
        let mut rules = CollisionRuleSet::default();
        let own = rules.create_group();
        let message = panic_message(|| act(&mut rules, own, foreign))
            .unwrap_or_else(|| panic!("{verb} took a group of another rule set"));
        assert!(message.contains("was not created by this rule set"), "{verb}: {message}");
    }
}
