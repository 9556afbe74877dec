//! A context saved with bevy_rapier's serde and restored while the app
//! runs (`docs/bevy.md`, "Saving a context"): restored into the live
//! components, with `CollisionRules::world_replaced`, it goes on bit for
//! bit as the app that never saved, though its rules changed and came back
//! in between; restored by inserting the components again, the plugin
//! starts the hooks over by itself and the rules hold.

use bevy::prelude::*;
use bevy_rapier::plugin::context::{
    RapierContextColliders, RapierContextJoints, RapierContextSimulation, RapierRigidBodySet,
};
use bevy_rapier::prelude::*;
use bevy_rapier_collision_rules::PlanCause;
use bevy_rapier_collision_rules::prelude::*;

use super::scene::{DT, Sim, cuboid, floor};

/// bevy_rapier's four serialized components of a context, as JSON.
struct Saved {
    simulation: String,
    colliders: String,
    bodies: String,
    joints: String,
}

fn save(sim: &mut Sim) -> Saved {
    let context = sim.context();
    let world = sim.app.world();
    let json = |value: Result<String, serde_json::Error>| value.expect("a context saves");
    Saved {
        simulation: json(serde_json::to_string(
            world
                .get::<RapierContextSimulation>(context)
                .expect("simulation"),
        )),
        colliders: json(serde_json::to_string(
            world
                .get::<RapierContextColliders>(context)
                .expect("colliders"),
        )),
        bodies: json(serde_json::to_string(
            world.get::<RapierRigidBodySet>(context).expect("bodies"),
        )),
        joints: json(serde_json::to_string(
            world.get::<RapierContextJoints>(context).expect("joints"),
        )),
    }
}

/// The four components, loaded.
fn load(
    saved: &Saved,
) -> (
    RapierContextSimulation,
    RapierContextColliders,
    RapierRigidBodySet,
    RapierContextJoints,
) {
    (
        serde_json::from_str(&saved.simulation).expect("simulation loads"),
        serde_json::from_str(&saved.colliders).expect("colliders load"),
        serde_json::from_str(&saved.bodies).expect("bodies load"),
        serde_json::from_str(&saved.joints).expect("joints load"),
    )
}

/// The saved sets moved into the context's live components, which keep
/// what bevy_rapier's serde leaves out (its entity maps and the transforms
/// it last wrote: inserting the components again loses them, and
/// bevy_rapier then moves every body to its Bevy transform).
fn restore_in_place(sim: &mut Sim, saved: &Saved) {
    let (simulation, colliders, bodies, joints) = load(saved);
    let context = sim.context();
    let mut entity = sim.app.world_mut().entity_mut(context);
    {
        let mut live = entity
            .get_mut::<RapierContextSimulation>()
            .expect("simulation");
        live.islands = simulation.islands;
        live.broad_phase = simulation.broad_phase;
        live.narrow_phase = simulation.narrow_phase;
        live.ccd_solver = simulation.ccd_solver;
        live.integration_parameters = simulation.integration_parameters;
    }
    entity
        .get_mut::<RapierContextColliders>()
        .expect("colliders")
        .colliders = colliders.colliders;
    {
        let mut live = entity.get_mut::<RapierRigidBodySet>().expect("bodies");
        live.bodies = bodies.bodies;
        live.soft_bodies = bodies.soft_bodies;
    }
    {
        let mut live = entity.get_mut::<RapierContextJoints>().expect("joints");
        live.impulse_joints = joints.impulse_joints;
        live.multibody_joints = joints.multibody_joints;
    }
}

/// The saved components inserted again, as bevy_rapier's own round trip
/// does.
fn restore_by_insert(sim: &mut Sim, saved: &Saved) {
    let context = sim.context();
    sim.app.world_mut().entity_mut(context).insert(load(saved));
}

/// A pile of twelve boxes on a floor: two groups that do not respond to
/// each other, a box that falls through everything (`NoResponse`), and a
/// pair without contacts. Returns the app, the boxes and the red group.
fn pile() -> (Sim, Vec<Entity>, CollisionGroup) {
    let mut sim = Sim::new();
    sim.app.insert_resource(TimestepMode::Fixed {
        dt: DT,
        substeps: 1,
    });
    let mut table = sim.table();
    let (red, blue) = (table.create_group(), table.create_group());
    table.set_group_rule(red, blue, CollisionRule::NoResponse);
    sim.spawn(floor());
    let boxes: Vec<Entity> = (0..12)
        .map(|i| {
            let (column, layer) = ((i % 4) as f32, (i / 4) as f32);
            sim.spawn((
                Transform::from_xyz(column * 0.9 - 1.35 + 0.05 * layer, 0.4 + layer * 0.85, 0.0)
                    .with_rotation(Quat::from_rotation_z(0.05 * (i % 3) as f32)),
                RigidBody::Dynamic,
                cuboid(0.4, 0.4, 0.4),
            ))
        })
        .collect();
    for (i, &b) in boxes.iter().enumerate() {
        match i % 4 {
            1 => {
                sim.entity_mut(b).insert(RuleGroup(red));
            }
            2 => {
                sim.entity_mut(b).insert(RuleGroup(blue));
            }
            _ => {}
        }
    }
    sim.entity_mut(boxes[3])
        .insert(PersonalRule(CollisionRule::NoResponse));
    sim.entity_mut(boxes[8])
        .insert(SpecificRules::new().with(boxes[4], CollisionRule::NoContacts));
    (sim, boxes, red)
}

/// Every box's transform, bit for bit.
fn poses(sim: &Sim, boxes: &[Entity]) -> Vec<u32> {
    boxes
        .iter()
        .flat_map(|&b| {
            let t = sim.app.world().get::<Transform>(b).expect("a box");
            t.translation
                .to_array()
                .into_iter()
                .chain(t.rotation.to_array())
        })
        .map(f32::to_bits)
        .collect()
}

#[test]
fn a_context_restored_in_place_goes_on_as_the_app_that_never_saved() {
    let (mut sim, boxes, red) = pile();
    let (mut twin, twin_boxes, _) = pile();
    sim.run(30);
    twin.run(30);
    let saved = save(&mut sim);
    // The game goes on; a box leaves its group and comes back before the
    // load, so what the hooks wrote meanwhile is not what the save holds.
    sim.entity_mut(boxes[1]).remove::<RuleGroup>();
    sim.run(30);
    sim.entity_mut(boxes[1]).insert(RuleGroup(red));
    restore_in_place(&mut sim, &saved);
    let context = sim.context();
    sim.app
        .world_mut()
        .get_mut::<CollisionRules>(context)
        .expect("the context's rules")
        .world_replaced();
    for frame in 1..=30 {
        sim.run(1);
        twin.run(1);
        let (a, b) = (poses(&sim, &boxes), poses(&twin, &twin_boxes));
        let differ = a.iter().zip(&b).filter(|(x, y)| x != y).count();
        assert_eq!(
            differ, 0,
            "{differ} pose values differ {frame} frames after the restore"
        );
    }
    assert_eq!(
        sim.pair_rule(boxes[1], boxes[2]),
        twin.pair_rule(twin_boxes[1], twin_boxes[2])
    );
}

#[test]
fn a_context_restored_by_insert_starts_its_hooks_over_and_keeps_its_rules() {
    let (mut sim, boxes, _) = pile();
    sim.run(30);
    let saved = save(&mut sim);
    sim.run(30);
    restore_by_insert(&mut sim, &saved);
    sim.run(1);
    let stats = sim.rules().hooks().stats();
    assert_eq!(
        stats.full_plan,
        Some(PlanCause::FirstStep),
        "the hooks started over on the restored world: {stats:?}"
    );
    sim.run(90);
    let ghost = sim.y(boxes[3]);
    assert!(
        ghost < -1.0,
        "the NoResponse box still falls through: y = {ghost}"
    );
    let resting = sim.y(boxes[0]);
    assert!(resting > 0.0, "a box without rules rests: y = {resting}");
}
