//! Every rule at work in one small scene: a ragdoll whose limbs ignore each
//! other, a ghost that passes through a wall, a pickup zone, debris that never
//! pairs with the player, and two kinematic platforms. Prints who decided each
//! pair's rule and exits non-zero if any pair is not what the rules promise.

use rapier_collision_rules::{CollisionGroup, CollisionRule, CollisionRuleSet, RuleError, Stage};
use rapier3d::prelude::*;

struct Scene {
    bodies: RigidBodySet,
    colliders: ColliderSet,
    rules: CollisionRuleSet,
    named: Vec<(&'static str, ColliderHandle)>,
}

impl Scene {
    fn add(
        &mut self,
        name: &'static str,
        body: RigidBodyBuilder,
    ) -> (RigidBodyHandle, ColliderHandle) {
        let body = self.bodies.insert(body);
        let collider =
            self.colliders
                .insert_with_parent(ColliderBuilder::ball(0.5), body, &mut self.bodies);
        self.named.push((name, collider));
        (body, collider)
    }

    fn collider(&self, name: &str) -> ColliderHandle {
        self.named
            .iter()
            .find(|(n, _)| *n == name)
            .expect("named collider")
            .1
    }
}

fn build() -> Result<Scene, RuleError> {
    let mut scene = Scene {
        bodies: RigidBodySet::new(),
        colliders: ColliderSet::new(),
        rules: CollisionRuleSet::default(),
        named: Vec::new(),
    };
    let (pelvis, _) = scene.add("pelvis", RigidBodyBuilder::dynamic());
    let (thigh, _) = scene.add("thigh", RigidBodyBuilder::dynamic());
    let (shin, _) = scene.add("shin", RigidBodyBuilder::dynamic());
    let (ghost, _) = scene.add("ghost", RigidBodyBuilder::dynamic());
    let (wall, _) = scene.add("wall", RigidBodyBuilder::fixed());
    let (player, _) = scene.add("player", RigidBodyBuilder::dynamic());
    let (debris, _) = scene.add("debris", RigidBodyBuilder::dynamic());
    let (_, pickup) = scene.add("pickup", RigidBodyBuilder::fixed());
    scene.add("platform_a", RigidBodyBuilder::kinematic_position_based());
    scene.add("platform_b", RigidBodyBuilder::kinematic_position_based());
    scene.add("ground", RigidBodyBuilder::fixed());

    let rules = &mut scene.rules;
    // A ragdoll: one group for the whole hierarchy, and the group ignores itself.
    let ragdoll = rules.create_group();
    rules.set_group_rule(ragdoll, ragdoll, CollisionRule::NoPair);
    rules.set_group(pelvis, Some(ragdoll));
    rules.set_parent(thigh, pelvis)?;
    rules.set_parent(shin, thigh)?;
    // A ghost walks through this one wall (a specific rule) and nothing else.
    rules.set_specific(ghost, wall, CollisionRule::NoResponse);
    // Debris never pairs with the player, by group.
    let (players, rubble) = (rules.create_group(), rules.create_group());
    rules.set_group(player, Some(players));
    rules.set_group(debris, Some(rubble));
    rules.set_group_rule(players, rubble, CollisionRule::NoPair);
    // The pickup zone pairs with the player but computes no contacts.
    rules.set_personal(pickup, CollisionRule::NoContacts);
    Ok(scene)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let scene = build()?;
    let expected = [
        ("pelvis", "thigh", CollisionRule::NoPair, Stage::Group),
        ("thigh", "shin", CollisionRule::NoPair, Stage::Group),
        ("shin", "ground", CollisionRule::Normal, Stage::Default),
        ("ghost", "wall", CollisionRule::NoResponse, Stage::Specific),
        ("ghost", "ground", CollisionRule::Normal, Stage::Default),
        ("player", "debris", CollisionRule::NoPair, Stage::Group),
        (
            "player",
            "pickup",
            CollisionRule::NoContacts,
            Stage::Personal,
        ),
        ("debris", "ground", CollisionRule::Normal, Stage::Default),
        (
            "platform_a",
            "platform_b",
            CollisionRule::NoPair,
            Stage::Group,
        ),
        (
            "platform_a",
            "player",
            CollisionRule::Normal,
            Stage::Default,
        ),
    ];
    println!("collider    other       rule        stage     step  outcome");
    let mut failures = 0;
    for (a, b, rule, stage) in expected {
        let (ca, cb) = (scene.collider(a), scene.collider(b));
        let why = scene.rules.explain(&scene.bodies, &scene.colliders, ca, cb);
        let swapped = scene.rules.resolve(&scene.bodies, &scene.colliders, cb, ca);
        let ok = why.rule == rule && why.stage == stage && swapped == rule;
        failures += usize::from(!ok);
        println!(
            "{a:<11} {b:<11} {:<11} {:<9} {:>4}  {}",
            format!("{:?}", why.rule),
            format!("{:?}", why.stage),
            why.step,
            if ok {
                "as promised".to_owned()
            } else {
                format!("expected {rule:?} by {stage:?}")
            },
        );
    }
    let k = CollisionGroup::DEFAULT_KINEMATIC;
    println!("(the platforms are apart by the built-in entry {k:?} x {k:?} -> NoPair)");
    if failures > 0 {
        return Err(format!("{failures} pair(s) did not get the promised rule").into());
    }
    Ok(())
}
