//! The design document's API (BEPUphysics "Collision Rules") next to this
//! crate's, one call each, every one checked. See also `docs/migration.md`.
//!
//! `cargo run --example bepu_migration`

use rapier_collision_rules::{CollisionGroup, CollisionRule, ManifoldUpdate, RuleError, RuleHooks};
use rapier3d::prelude::*;

fn check(what: &str, ok: bool) -> Result<(), String> {
    println!("  {} {what}", if ok { "ok " } else { "BAD" });
    ok.then_some(())
        .ok_or_else(|| format!("{what} did not hold"))
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut world = PhysicsWorld::new();
    let ground =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)));
    let floor = world.insert_collider(ColliderBuilder::cuboid(10.0, 0.5, 10.0), Some(ground));
    let a = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 0.5, 0.0)));
    let ca = world.insert_collider(ColliderBuilder::cuboid(0.5, 0.5, 0.5), Some(a));
    let b = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(3.0, 0.5, 0.0)));
    let cb = world.insert_collider(ColliderBuilder::cuboid(0.5, 0.5, 0.5), Some(b));
    let mut hooks = RuleHooks::default();
    let (bodies, colliders) = (&world.bodies, &world.colliders);
    let rules = hooks.rules_mut();

    println!("entity.CollisionRules.Personal = NoResponse  ->  rules.set_personal(a, NoResponse)");
    rules.set_personal(a, CollisionRule::NoResponse);
    check(
        "a's pairs are NoResponse",
        rules.resolve(bodies, colliders, ca, floor) == CollisionRule::NoResponse,
    )?;
    rules.set_personal(a, CollisionRule::Defer);

    println!(
        "CollisionRules.AddRule(a, b, NoPair) (SpecificEntities)  ->  rules.set_specific(a, b, NoPair)"
    );
    rules.set_specific(a, b, CollisionRule::NoPair);
    check(
        "a and b never pair",
        rules.resolve(bodies, colliders, cb, ca) == CollisionRule::NoPair,
    )?;
    rules.remove_specific(a, b);

    println!(
        "new CollisionGroup(); entity.CollisionRules.Group = g  ->  rules.create_group(); rules.set_group(a, Some(g))"
    );
    let g = rules.create_group();
    rules.set_group(a, Some(g));
    println!(
        "CollisionGroupRules.Add(new CollisionGroupPair(g, g), NoPair)  ->  rules.set_group_rule(g, g, NoPair)"
    );
    rules.set_group_rule(g, g, CollisionRule::NoPair);
    rules.set_group(b, Some(g));
    check(
        "a and b, both in g, never pair",
        rules.resolve(bodies, colliders, ca, cb) == CollisionRule::NoPair,
    )?;

    println!(
        "CollisionGroup.DefineCollisionRulesInSet(set, self, other)  ->  rules.set_group_rules_in_set(&set, self, other)"
    );
    let set = [rules.create_group(), rules.create_group()];
    rules.set_group_rules_in_set(&set, CollisionRule::NoResponse, CollisionRule::NoPair);
    check(
        "in-set rules",
        rules.group_rule(set[1], set[0]) == CollisionRule::NoPair,
    )?;
    println!(
        "DefineCollisionRulesWithSet / BetweenSets  ->  set_group_rules_with_set / set_group_rules_between_sets"
    );
    rules.set_group_rules_between_sets(&set, &[g], CollisionRule::NoContacts);
    check(
        "between-sets rules",
        rules.group_rule(g, set[0]) == CollisionRule::NoContacts,
    )?;

    println!(
        "DefaultKinematicCollisionGroup / DefaultDynamicCollisionGroup  ->  CollisionGroup::DEFAULT_KINEMATIC / DEFAULT_DYNAMIC"
    );
    let k = CollisionGroup::DEFAULT_KINEMATIC;
    check(
        "kinematic objects do not pair by default",
        rules.group_rule(k, k) == CollisionRule::NoPair,
    )?;
    println!("CollisionDetectionSettings.DefaultCollisionRule  ->  rules.set_default_rule(..)");
    check(
        "the default rule is Normal",
        rules.default_rule() == CollisionRule::Normal,
    )?;

    println!(
        "CompoundBody children / AddBody(child, parent)  ->  a Rapier body's colliders / rules.set_parent(child, parent)"
    );
    rules.set_group(a, None);
    rules.set_group(b, None);
    rules.set_parent(b, a)?;
    check(
        "set_parent refuses a cycle",
        rules.set_parent(a, b)
            == Err(RuleError::Cycle {
                child: a,
                parent: b,
            }),
    )?;
    println!(
        "compound.CollisionRules = rules (recursive)  ->  rules.set_rules_recursive(a, &bodies, &colliders)"
    );
    rules.set_rules_recursive(a, bodies, colliders);
    rules.set_personal(cb, CollisionRule::NoContacts);
    check(
        "a later edit through the child reaches the parent",
        rules.personal(a) == CollisionRule::NoContacts,
    )?;
    println!(
        "other.CollisionRules = entity.CollisionRules (shared instance)  ->  rules.share_rules(from, to)"
    );
    check(
        "the child shares the parent's record",
        rules.shares_rules(a, cb),
    )?;
    rules.remove_parent(b);
    rules.set_personal(a, CollisionRule::Defer);

    println!(
        "BroadPhase.CollisionRuleCalculator = f  ->  hooks.set_calculator(f) (f can call ctx.default_rule())"
    );
    // The second box ignores the floor's contacts; everything else as the
    // default calculation says.
    hooks.set_calculator(move |ctx| {
        if [ctx.collider1, ctx.collider2].contains(&cb) {
            CollisionRule::NoContacts
        } else {
            ctx.default_rule()
        }
    });
    hooks.step(&mut world);
    check(
        "the calculator decides the pair",
        hooks.pair_rule(&world, cb, floor) == Some(CollisionRule::NoContacts),
    )?;
    hooks.remove_calculator();
    hooks.step(&mut world);
    check(
        "removed, the default calculation decides again",
        hooks.pair_rule(&world, cb, floor) == Some(CollisionRule::Normal),
    )?;

    println!("immediate event on pair creation  ->  hooks.on_pair_created(|pair| Some(rule))");
    hooks.on_pair_created(move |pair| {
        [pair.collider1, pair.collider2]
            .contains(&cb)
            .then_some(CollisionRule::NoResponse)
    });
    // The callback also runs when a pair's rule is recalculated.
    hooks.force_recalculation(b);
    hooks.step(&mut world);
    check(
        "the callback's answer holds for the pair",
        hooks.pair_rule(&world, floor, cb) == Some(CollisionRule::NoResponse),
    )?;
    hooks.remove_pair_created();
    hooks.force_recalculation(b);
    hooks.step(&mut world);
    check(
        "removed, the pair follows the rules again",
        hooks.pair_rule(&world, floor, cb) == Some(CollisionRule::Normal),
    )?;
    println!("pair.CollisionRule = rule  ->  hooks.set_pair_rule(&world, a, b, rule)");
    check(
        "the live pair takes the override",
        hooks.set_pair_rule(&world, ca, floor, CollisionRule::NoResponse),
    )?;
    check(
        "pair_rule reads it back",
        hooks.pair_rule(&world, floor, ca) == Some(CollisionRule::NoResponse),
    )?;
    println!(
        "pair.UpdateMode = ManifoldUpdateSetting.AlwaysUpdate  ->  hooks.set_manifold_update(&world, a, b, ManifoldUpdate::Always)"
    );
    check(
        "manifold setting",
        hooks.set_manifold_update(&world, ca, floor, ManifoldUpdate::Always),
    )?;
    println!(
        "entity.CollisionRules changed; ForceCollisionRuleRecalculation()  ->  hooks.force_recalculation(a)"
    );
    hooks.force_recalculation(a);
    hooks.step(&mut world);
    check(
        "the override is gone",
        hooks.pair_rule(&world, ca, floor) == Some(CollisionRule::Normal),
    )?;
    println!(
        "(edits reach live pairs before the next step by default: RecalculationPolicy::OnChange;"
    );
    println!(" RecalculationPolicy::Manual is the design document's behaviour)");
    Ok(())
}

#[test]
fn every_migrated_call_does_what_its_original_did() {
    main().expect("the example's own checks");
}
