//! Soft bodies with several collision meshes (`PhysicsWorld::insert_deformable`
//! binds more meshes to a cluster), cut across: each copy Rapier makes of a
//! mesh's collider keeps the project's settings of the collider it copies
//! (`docs/semantics.md`, "Soft bodies", project settings on copies).

use rapier_collision_rules::{CollisionRule, RuleHooks};
use rapier3d::parry::shape::TriMeshFlags;
use rapier3d::prelude::*;

use super::dim3::{blade_at_x, soft_bar};

/// A mesh over the bar's boundary triangles whose vertices all pass `keep`,
/// bound to the bar's root cluster by position.
fn boundary_part(
    world: &PhysicsWorld,
    bar: SoftBodyHandle,
    keep: impl Fn(Vector) -> bool,
) -> ColliderBuilder {
    let body = &world.soft_bodies[bar];
    let vertices: Vec<Vector> = body.particle_positions().collect();
    let indices: Vec<[u32; 3]> = body
        .boundary()
        .iter()
        .copied()
        .filter(|t| t.iter().all(|&v| keep(vertices[v as usize])))
        .collect();
    let root = world.bodies[body.root_body()].position().inverse();
    ColliderBuilder::trimesh_with_flags(vertices, indices, TriMeshFlags::DEFORMABLE)
        .expect("a valid mesh")
        .position(root)
}

/// What the project sets on a collider that the crate also writes.
fn settings(
    c: &Collider,
) -> (
    InteractionGroups,
    InteractionGroups,
    ActiveHooks,
    ActiveCollisionTypes,
) {
    (
        c.collision_groups(),
        c.solver_groups(),
        c.active_hooks(),
        c.active_collision_types(),
    )
}

/// The project's layers of each mesh: memberships and filter.
fn layers(memberships: Group) -> InteractionGroups {
    InteractionGroups::new(memberships, Group::ALL, InteractionTestMode::And)
}

#[test]
fn each_copy_of_a_cut_mesh_keeps_the_project_settings_of_its_own_original() {
    // The half mesh on either side of the cut: one side then has copies of
    // the first and last meshes only.
    for half_side in [-1.0, 1.0] {
        cut_three_meshes(half_side);
    }
}

fn cut_three_meshes(half_side: f32) {
    let mut world = PhysicsWorld::new();
    let ground =
        world.insert_body(RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.5, 0.0)));
    world.insert_collider(ColliderBuilder::cuboid(5.0, 0.5, 5.0), Some(ground));
    let bar = world.insert_soft_body(soft_bar(Vector::new(0.0, 2.0, 0.0), 1.0));
    let root = world.soft_bodies[bar].root_body();
    // Besides the bar's own mesh (the whole boundary): one over its left
    // half and one over the whole boundary, each with the project's layers.
    let left = boundary_part(&world, bar, |v| v.x * half_side > 0.011)
        .collision_groups(layers(Group::GROUP_1));
    let left = world
        .insert_deformable(left, SoftMeshBinding::direct_by_position(1.0e-4), root)
        .expect("the left mesh binds");
    let whole = boundary_part(&world, bar, |_| true)
        .collision_groups(layers(Group::GROUP_2))
        .active_hooks(ActiveHooks::MODIFY_SOLVER_CONTACTS);
    let whole = world
        .insert_deformable(whole, SoftMeshBinding::direct_by_position(1.0e-4), root)
        .expect("the second whole mesh binds");
    let own = world.soft_bodies[bar]
        .collision_mesh()
        .expect("the bar's own mesh")
        .collider();
    let project = |c: ColliderHandle, world: &PhysicsWorld| settings(&world.colliders[c]);
    let originals = [
        (own, project(own, &world)),
        (left, project(left, &world)),
        (whole, project(whole, &world)),
    ];
    let mut hooks = RuleHooks::default();
    // A rule the planner writes into Rapier's groups on the bar's colliders.
    let rules = hooks.rules_mut();
    let (bars, grounds) = (rules.create_group(), rules.create_group());
    rules.set_group(root, Some(bars));
    rules.set_group(ground, Some(grounds));
    rules.set_group_rule(bars, grounds, CollisionRule::NoPair);
    hooks.step(&mut world);
    // Across the middle: the left mesh stays whole on one side.
    let cut = world
        .cut_soft_body(bar, &blade_at_x(0.01))
        .expect("the blade crosses the bar");
    hooks.step(&mut world);
    hooks.restore_project_settings(&mut world.colliders);
    for piece in cut.bodies() {
        let body = &world.soft_bodies[piece];
        // Each mesh of a side, in order, is an original or Rapier's copy of
        // one (copies come in the source's order); the left mesh is on the
        // left side alone.
        let left_side = body.particle_positions().map(|p| p.x).sum::<f32>() * half_side > 0.0;
        let expected: Vec<_> = originals
            .iter()
            .filter(|o| o.0 != left || left_side)
            .collect();
        assert_eq!(
            body.meshes().count(),
            expected.len(),
            "piece {piece:?}'s meshes"
        );
        for (mesh, original) in body.meshes().zip(expected) {
            let c = mesh.collider();
            if !world.colliders.contains(c) {
                // Rapier made the copy without a collider (no collision).
                continue;
            }
            let got = settings(&world.colliders[c]);
            assert_eq!(
                got,
                original.1,
                "piece {piece:?}, mesh {:?} (collider {c:?}): the project's settings of {:?} were expected",
                mesh.id(),
                original.0
            );
        }
    }
}
