//! Soft bodies as entities (`docs/bevy.md`, "Soft bodies"): bevy_rapier's
//! `SoftBody` entity carries `RuleGroup`, `PersonalRule` and
//! `SpecificRules` as a rigid body's does, against the same scene without
//! the floor; the pieces of a cut keep the rules, and a despawned soft body
//! leaves none behind. In 2D the jelly and the bar are grids.

use CollisionRule::*;
use bevy::ecs::system::RunSystemOnce;
use bevy::prelude::*;
use bevy_rapier::plugin::context::RapierRigidBodySet;
use bevy_rapier::prelude::*;
use bevy_rapier::rapier::prelude::{ColliderHandle, RigidBodyHandle};
use bevy_rapier_collision_rules::prelude::*;

use super::scene::{Sim, cuboid, floor};

const FRAMES: usize = 90;

/// How the rule between the soft body and the floor is given.
#[derive(Clone, Copy, Debug)]
enum Given {
    SoftNamesFloor,
    FloorNamesSoft,
    Personal,
    Groups,
}

const GIVENS: [Given; 4] = [
    Given::SoftNamesFloor,
    Given::FloorNamesSoft,
    Given::Personal,
    Given::Groups,
];

fn give(sim: &mut Sim, soft: Entity, floor: Entity, rule: CollisionRule, given: Given) {
    match given {
        Given::SoftNamesFloor => {
            sim.entity_mut(soft)
                .insert(SpecificRules::new().with(floor, rule));
        }
        Given::FloorNamesSoft => {
            sim.entity_mut(floor)
                .insert(SpecificRules::new().with(soft, rule));
        }
        Given::Personal => {
            sim.entity_mut(soft).insert(PersonalRule(rule));
        }
        Given::Groups => {
            let mut table = sim.table();
            let (softs, floors) = (table.create_group(), table.create_group());
            table.set_group_rule(softs, floors, rule);
            sim.entity_mut(soft).insert(RuleGroup(softs));
            sim.entity_mut(floor).insert(RuleGroup(floors));
        }
    }
}

/// A soft cube (4x4x4 particles) whose lowest particles start 0.05 m over
/// the floor's top.
fn jelly() -> impl Bundle {
    #[cfg(feature = "dim3")]
    let body = SoftBody::cuboid(Vec3::splat(0.5), 4, 4, 4);
    #[cfg(feature = "dim2")]
    let body = SoftBody::grid(Vec2::splat(0.5), 4, 4);
    (Transform::from_xyz(0.0, 0.55, 0.0), body)
}

/// The lowest particle of each soft body entity given.
fn lowest(sim: &mut Sim, soft: Entity) -> f32 {
    let context = sim.context();
    let set = sim.app.world().get::<RapierRigidBodySet>(context).unwrap();
    let body = set.soft_body(soft).expect("a soft body entity");
    body.particle_positions()
        .map(|p| p.y)
        .fold(f32::MAX, f32::min)
}

/// The jelly's lowest particle after the frames, with the floor under it
/// and `rule` given as `given`, or with no floor.
fn jelly_fall(floor_and_rule: Option<(CollisionRule, Given)>) -> f32 {
    let mut sim = Sim::new();
    let soft = sim.spawn(jelly());
    if let Some((rule, given)) = floor_and_rule {
        let f = sim.spawn(floor());
        give(&mut sim, soft, f, rule, given);
    }
    sim.run(FRAMES);
    lowest(&mut sim, soft)
}

#[test]
fn a_soft_body_entity_obeys_every_rule_from_every_component() {
    let alone = jelly_fall(None);
    assert!(alone < -1.0, "the jelly alone falls: {alone}");
    for given in GIVENS {
        for rule in [Normal, NoResponse, NoContacts, NoPair] {
            let low = jelly_fall(Some((rule, given)));
            let case = format!("{rule:?} as {given:?}: lowest particle at {low}");
            if rule == Normal {
                assert!(low > -0.05, "{case}: the jelly should rest on the floor");
            } else {
                assert_eq!(
                    low, alone,
                    "{case}: the jelly should fall as with no floor ({alone})"
                );
            }
        }
    }
}

/// A bar 2 m long and 0.5 m thick, of 6 particles along it and 2 across.
fn bar() -> SoftBody {
    #[cfg(feature = "dim3")]
    return SoftBody::cuboid(Vec3::new(1.0, 0.25, 0.25), 6, 2, 2);
    #[cfg(feature = "dim2")]
    return SoftBody::grid(Vec2::new(1.0, 0.25), 6, 2);
}

/// How a soft body is split in two.
#[derive(Clone, Copy, Debug)]
enum Split {
    /// `cut_soft_body` across x = 0.1 (or the x given).
    Cut,
    /// `tear_soft_body` along the edges across x = 0.1 (or the x given).
    Tear,
}

/// Splits the soft body of `soft` and returns the entities of the pieces
/// (the first is `soft`).
fn split(sim: &mut Sim, soft: Entity, how: Split) -> Vec<Entity> {
    split_at(sim, soft, how, 0.1).expect("the bar splits")
}

/// Splits the soft body of `soft` as [`split`] does, a cut across x =
/// `x`: the entities of the pieces, if it split.
fn split_at(sim: &mut Sim, soft: Entity, how: Split, x: f32) -> Option<Vec<Entity>> {
    #[cfg(feature = "dim3")]
    let blade = [
        Vec3::new(x, -10.0, -10.0),
        Vec3::new(x, 20.0, -10.0),
        Vec3::new(x, -10.0, 20.0),
    ];
    #[cfg(feature = "dim2")]
    let blade = [Vec2::new(x, -10.0), Vec2::new(x, 20.0)];
    sim.app
        .world_mut()
        .run_system_once(
            move |mut context: WriteRapierContext, mut commands: Commands| {
                let mut context = context.single_mut().unwrap();
                let result = match how {
                    Split::Cut => context.cut_soft_body(&mut commands, soft, &blade),
                    Split::Tear => {
                        let body = context.rigidbody_set.soft_body(soft).unwrap();
                        let left = |v: u32| body.particle_position(v as usize).x < x;
                        let edges: Vec<u32> = (0..body.edges().len() as u32)
                            .filter(|&e| {
                                let [a, b] = body.edges()[e as usize].vertices;
                                left(a) != left(b)
                            })
                            .collect();
                        context.tear_soft_body(&mut commands, soft, &edges, &[])
                    }
                };
                result.map(|r| r.pieces)
            },
        )
        .unwrap()
}

/// A bar cut or torn after one frame, its lower face 0.15 m inside the
/// floor's top (or over no floor: then a personal rule, which also holds
/// between the pieces, is given alone): the particles of each piece after
/// the frames, and the sim with the pieces' entities.
fn split_bar(
    with_floor: bool,
    rule: CollisionRule,
    given: Given,
    how: Split,
) -> (Sim, Vec<Entity>, Option<Entity>, Vec<Vec<u32>>) {
    let mut sim = Sim::new();
    let bar = sim.spawn((Transform::from_xyz(0.0, 0.1, 0.0), bar()));
    let f = with_floor.then(|| {
        let f = sim.spawn(floor());
        give(&mut sim, bar, f, rule, given);
        f
    });
    if !with_floor && matches!(given, Given::Personal) {
        sim.entity_mut(bar).insert(PersonalRule(rule));
    }
    sim.run(1);
    let pieces = split(&mut sim, bar, how);
    sim.run(FRAMES);
    let context = sim.context();
    let set = sim.app.world().get::<RapierRigidBodySet>(context).unwrap();
    let particles = pieces
        .iter()
        .map(|&piece| {
            let body = set.soft_body(piece).expect("a piece's soft body");
            body.particle_positions()
                .flat_map(|p| p.to_array())
                .map(f32::to_bits)
                .collect()
        })
        .collect();
    (sim, pieces, f, particles)
}

/// The pieces hold the rules from the frame of the cut on: each moves bit
/// for bit as the same piece cut from a bar over no floor (a piece that
/// stepped once without its rules inside the floor would be thrown up).
#[test]
fn the_pieces_of_a_cut_or_a_tear_keep_the_soft_bodys_rules() {
    for how in [Split::Cut, Split::Tear] {
        for given in GIVENS {
            for rule in [NoResponse, NoContacts, NoPair] {
                let case = format!("{how:?}, {rule:?} as {given:?}");
                let (_, alone_pieces, _, alone) = split_bar(false, rule, given, how);
                let (mut sim, pieces, f, particles) = split_bar(true, rule, given, how);
                let f = f.expect("a floor");
                assert_eq!(
                    pieces.len(),
                    alone_pieces.len(),
                    "{case}: pieces {pieces:?}"
                );
                for (i, &piece) in pieces.iter().enumerate() {
                    let low = lowest(&mut sim, piece);
                    assert!(
                        particles[i] == alone[i],
                        "{case}: piece {piece:?} (lowest particle at {low}) moved otherwise than over no floor"
                    );
                    // The components say so too: the pieces carry the bar's,
                    // and the floor's entries name each piece.
                    let world = sim.app.world();
                    let carried = match given {
                        Given::SoftNamesFloor => {
                            world.get::<SpecificRules>(piece).map(|s| s.get(f))
                        }
                        Given::FloorNamesSoft => {
                            world.get::<SpecificRules>(f).map(|s| s.get(piece))
                        }
                        Given::Personal => world.get::<PersonalRule>(piece).map(|p| p.0),
                        Given::Groups => world.get::<RuleGroup>(piece).map(|_| rule),
                    };
                    assert_eq!(carried, Some(rule), "{case}: piece {piece:?}'s components");
                }
            }
        }
    }
}

/// The root body of `soft`'s soft body.
fn root_of(sim: &mut Sim, soft: Entity) -> RigidBodyHandle {
    let context = sim.context();
    let set = sim.app.world().get::<RapierRigidBodySet>(context).unwrap();
    set.soft_body(soft).expect("a soft body entity").root_body()
}

/// What became of a bar torn in two and then cut across x = `x` (as
/// [`split_bar`], with `NoPair` given as `given` with the floor under it,
/// or with the same floor 1 km below), if the cut split it. The floor is
/// there in both, so that every collider has the same handle in both:
/// Rapier visits pairs in the order of their handles, and the same scene
/// numbered otherwise moves otherwise, rules or none (without the floor,
/// this bar's lowest particle ends at -11.66 m after the frames, with the
/// floor 1 km below at -11.41 m).
struct TornThenCut {
    /// Whether the cut gave the bar's root to its piece.
    moved: bool,
    /// Each piece's lowest particle, and its particles' bits.
    pieces: Vec<(Entity, f32, Vec<u32>)>,
}

fn torn_then_cut(with_floor: bool, given: Given, x: f32) -> Option<TornThenCut> {
    let mut sim = Sim::new();
    let bar_entity = sim.spawn((Transform::from_xyz(0.0, 0.1, 0.0), bar()));
    let f = sim.spawn(floor());
    if !with_floor {
        sim.entity_mut(f)
            .insert(Transform::from_xyz(0.0, -1000.0, 0.0));
    }
    give(&mut sim, bar_entity, f, NoPair, given);
    sim.run(1);
    let mut pieces = split(&mut sim, bar_entity, Split::Tear);
    sim.run(1);
    let root = root_of(&mut sim, bar_entity);
    let cut = split_at(&mut sim, bar_entity, Split::Cut, x)?;
    let moved = root_of(&mut sim, bar_entity) != root;
    for piece in cut {
        if !pieces.contains(&piece) {
            pieces.push(piece);
        }
    }
    sim.run(FRAMES);
    let pieces = pieces
        .into_iter()
        .map(|piece| {
            let low = lowest(&mut sim, piece);
            let context = sim.context();
            let set = sim.app.world().get::<RapierRigidBodySet>(context).unwrap();
            let bits = set
                .soft_body(piece)
                .expect("a piece's soft body")
                .particle_positions()
                .flat_map(|p| p.to_array())
                .map(f32::to_bits)
                .collect();
            (piece, low, bits)
        })
        .collect();
    Some(TornThenCut { moved, pieces })
}

/// A bar torn in two, then cut across the half that keeps the entity, for
/// several blades, lying 0.15 m inside the floor with `NoPair` given each
/// way: every piece moves bit for bit as with the floor 1 km below. Some cut gives the
/// bar's root to its piece (rapier 0.36.1 in 2D), which takes the plugin's
/// book along the path for a moved root (`docs/bevy.md`, "Soft bodies").
#[test]
fn a_torn_bar_cut_again_keeps_its_rules_on_every_piece_whichever_root_moves() {
    let (mut moved, mut cuts) = (false, 0);
    for x in [-0.6, -0.4, -0.2, 0.2, 0.4, 0.6] {
        for given in GIVENS {
            let Some(over_floor) = torn_then_cut(true, given, x) else {
                continue;
            };
            let alone = torn_then_cut(false, given, x).expect("the same cut with the floor away");
            cuts += 1;
            moved |= over_floor.moved;
            assert_eq!(
                over_floor.pieces.len(),
                alone.pieces.len(),
                "cut at x = {x}, {given:?}: pieces"
            );
            for (piece, alone) in over_floor.pieces.iter().zip(&alone.pieces) {
                let (entity, low, bits) = piece;
                assert!(
                    *bits == alone.2,
                    "cut at x = {x}, {given:?}: piece {entity:?} (lowest particle at {low}, {} with the floor away) moved otherwise than with the floor away",
                    alone.1
                );
            }
        }
    }
    assert!(cuts >= 2 * GIVENS.len(), "only {cuts} cuts of the torn bar");
    // Rapier 0.36.1 moves the root in some cut in 2D, in none in 3D
    // (`CUT_MOVES_ROOT` in the core's tests).
    assert!(
        moved || cfg!(feature = "dim3"),
        "no cut gave the bar's root to its piece"
    );
}

/// A bar with `PersonalRule(NoPair)` 0.05 m over the floor, after a frame.
fn bar_over_floor() -> (Sim, Entity) {
    let mut sim = Sim::new();
    let bar = sim.spawn((
        Transform::from_xyz(0.0, 0.3, 0.0),
        bar(),
        PersonalRule(NoPair),
    ));
    sim.spawn(floor());
    sim.run(1);
    (sim, bar)
}

/// The pieces' rules are their own: a new `PersonalRule` on one piece
/// changes that piece alone, in its component and in the rule set.
#[test]
fn a_pieces_rules_are_its_own() {
    let (mut sim, bar) = bar_over_floor();
    let pieces = split(&mut sim, bar, Split::Cut);
    sim.run(2);
    let (first, other) = (pieces[0], pieces[1]);
    sim.entity_mut(first).insert(PersonalRule(Normal));
    sim.run(FRAMES);
    let context = sim.context();
    let set = sim.app.world().get::<RapierRigidBodySet>(context).unwrap();
    let root = |e: Entity| set.soft_body(e).unwrap().root_body();
    let (a, b) = (root(first), root(other));
    let rules = sim
        .app
        .world()
        .get::<CollisionRules>(context)
        .unwrap()
        .rules();
    assert_eq!(rules.personal(a), Normal, "the edited piece's rule");
    assert_eq!(
        rules.personal(b),
        NoPair,
        "the other piece keeps its own rule"
    );
    assert!(!rules.shares_rules(a, b), "the pieces share a record");
    let (low_first, low_other) = (lowest(&mut sim, first), lowest(&mut sim, other));
    assert!(
        low_first > -0.1,
        "the piece now Normal rests on the floor: {low_first}"
    );
    assert!(
        low_other < -1.0,
        "the other piece still falls through: {low_other}"
    );
}

#[test]
fn a_despawned_soft_body_leaves_no_rules_behind() {
    let mut sim = Sim::new();
    let soft = sim.spawn((jelly(), PersonalRule(NoPair)));
    sim.spawn(floor());
    sim.run(2);
    assert!(
        sim.rules().rules().record_count() > 0,
        "the jelly's rule is held"
    );
    sim.app.world_mut().despawn(soft);
    sim.run(2);
    let left = sim.rules().rules().nodes().count();
    assert_eq!(left, 0, "nodes left with rules after the despawn");
}

/// A piece despawned after its cut takes its rules with it, as a despawned
/// soft body does, and leaves the bar's. (A piece despawned in the frame of
/// its cut, before bevy_rapier 0.37 gave it its components, makes
/// bevy_rapier panic as it copies them: `docs/bevy.md`, "Soft bodies".)
#[test]
fn a_despawned_piece_leaves_no_rules_behind() {
    for how in [Split::Cut, Split::Tear] {
        let (mut sim, bar) = bar_over_floor();
        let held = sim.rules().rules().nodes().count();
        let pieces = split(&mut sim, bar, how);
        sim.run(1);
        let split_held = sim.rules().rules().nodes().count();
        assert!(
            split_held > held,
            "{how:?}: the pieces hold rules: {split_held} nodes, the bar had {held}"
        );
        for &piece in &pieces[1..] {
            sim.app.world_mut().despawn(piece);
        }
        sim.run(3);
        let left = sim.rules().rules().nodes().count();
        assert_eq!(
            left, held,
            "{how:?}: nodes with rules after the pieces were despawned (the bar alone had {held})"
        );
        let context = sim.context();
        let set = sim.app.world().get::<RapierRigidBodySet>(context).unwrap();
        let root = set.soft_body(bar).expect("the bar's soft body").root_body();
        let rules = sim.app.world().get::<CollisionRules>(context).unwrap();
        assert_eq!(
            rules.rules().personal(root),
            NoPair,
            "{how:?}: the bar keeps its rule"
        );
    }
}

/// A bar's rule with the floor removed in the frame the bar is cut or
/// torn (or cut again after a tear, across several blades): bevy_rapier
/// copies the bar's components onto the pieces after the removal, so no
/// piece keeps the rule, also a piece that takes the bar's old root (which
/// the plugin's book hands over before the piece has its components):
/// every piece comes to rest on the floor.
#[test]
fn a_rule_removed_in_the_frame_of_a_split_stays_off_every_piece() {
    let (mut moved, mut cases) = (0, 0);
    let splits = [(None, Split::Cut, 0.1), (None, Split::Tear, 0.1)]
        .into_iter()
        .chain([-0.6, -0.4, -0.2, 0.2, 0.4, 0.6].map(|x| (Some(Split::Tear), Split::Cut, x)));
    for (first, how, x) in splits {
        // The floor's entry goes with its component, or alone.
        let ways = [
            (Given::Personal, false),
            (Given::SoftNamesFloor, false),
            (Given::FloorNamesSoft, false),
            (Given::FloorNamesSoft, true),
        ];
        for (given, entry_alone) in ways {
            let mut sim = Sim::new();
            let bar_entity = sim.spawn((Transform::from_xyz(0.0, 0.1, 0.0), bar()));
            let f = sim.spawn(floor());
            give(&mut sim, bar_entity, f, NoPair, given);
            sim.run(1);
            if let Some(first) = first {
                // The pieces of the tear keep their own copy of the rule.
                split(&mut sim, bar_entity, first);
                sim.run(1);
            }
            let root = root_of(&mut sim, bar_entity);
            let Some(pieces) = split_at(&mut sim, bar_entity, how, x) else {
                continue;
            };
            cases += 1;
            moved += usize::from(root_of(&mut sim, bar_entity) != root);
            match given {
                Given::Personal => sim.entity_mut(bar_entity).remove::<PersonalRule>(),
                Given::SoftNamesFloor => sim.entity_mut(bar_entity).remove::<SpecificRules>(),
                _ if entry_alone => sim.entity_mut(f).insert(SpecificRules::new()),
                _ => sim.entity_mut(f).remove::<SpecificRules>(),
            };
            sim.run(FRAMES);
            let case = format!(
                "{first:?} then {how:?} at x = {x}, {given:?} (entry alone: {entry_alone})"
            );
            for &piece in &pieces {
                let piece_root = root_of(&mut sim, piece);
                let personal = sim.rules().rules().personal(piece_root);
                assert_eq!(personal, Defer, "{case}: piece {piece:?}'s personal rule");
                let low = lowest(&mut sim, piece);
                assert!(
                    low > -1.0,
                    "{case}: piece {piece:?} fell through the floor to {low}"
                );
            }
        }
    }
    assert!(cases >= 2 * 4, "only {cases} splits");
    // In 2D some cut of a torn bar gives its old root to the piece
    // (rapier 0.36.1; `CUT_MOVES_ROOT` in the core's tests).
    assert!(
        moved > 0 || cfg!(feature = "dim3"),
        "no split gave the bar's root to a piece"
    );
}

/// The particles of `soft`'s soft body past x = 0.3 towards its right or
/// left end.
fn particles_at_end(sim: &mut Sim, soft: Entity, right: bool) -> Vec<u32> {
    let context = sim.context();
    let set = sim.app.world().get::<RapierRigidBodySet>(context).unwrap();
    let body = set.soft_body(soft).expect("a soft body entity");
    (0..body.particle_positions().count() as u32)
        .filter(|&v| {
            let x = body.particle_position(v as usize).x;
            if right { x > 0.3 } else { x < -0.3 }
        })
        .collect()
}

/// The soft body entity whose soft body has `root` as its root body.
fn entity_rooted_at(sim: &mut Sim, root: RigidBodyHandle) -> Option<Entity> {
    let context = sim.context();
    let set = sim.app.world().get::<RapierRigidBodySet>(context).unwrap();
    let (handle, _) = set
        .soft_bodies
        .iter()
        .find(|(_, body)| body.root_body() == root)?;
    set.soft_body_entity(handle)
}

/// A cluster of a bar's end whose tear made its proxy a piece's root.
struct TornCluster {
    cluster: Entity,
    proxy: RigidBodyHandle,
    /// The soft body entity whose root the proxy became.
    piece: Entity,
}

/// Adds to `bar` a cluster (with `bundle`) of its particles at one end,
/// lets `give` add rules now that the cluster's entity exists, steps a
/// frame, tears the bar across x, and steps two more (bevy_rapier gives the
/// piece its components at the next writeback): the cluster, if the tear
/// made its proxy a piece's root.
fn tear_off_cluster(
    sim: &mut Sim,
    bar: Entity,
    (right, x): (bool, f32),
    bundle: impl Bundle,
    give: impl FnOnce(&mut Sim, Entity),
) -> Option<TornCluster> {
    let end = particles_at_end(sim, bar, right);
    let cluster = sim.spawn((SoftBodyCluster::new(bar, end), bundle));
    give(sim, cluster);
    sim.run(1);
    let proxy = sim.body(cluster);
    split_at(sim, bar, Split::Tear, x).expect("the bar tears");
    sim.run(2);
    let piece = entity_rooted_at(sim, proxy)?;
    Some(TornCluster {
        cluster,
        proxy,
        piece,
    })
}

/// Clusters at the right or left end of the bar, torn across x: those that
/// split the cluster's end off give the piece the cluster's proxy as root.
const CLUSTER_TEARS: [(bool, f32); 6] = [
    (true, 0.4),
    (false, -0.4),
    (true, 0.1),
    (false, -0.1),
    (false, 0.4),
    (true, -0.4),
];

/// Runs `case` for each of [`CLUSTER_TEARS`]; `case` says whether its tear
/// gave a piece the cluster's proxy as root. At least one must.
fn for_each_cluster_tear(mut case: impl FnMut(bool, f32) -> bool) {
    let found = CLUSTER_TEARS
        .into_iter()
        .filter(|&(right, x)| case(right, x))
        .count();
    assert!(
        found > 0,
        "no tear gave a piece the cluster's proxy as root"
    );
}

/// A box far from the bar, which the entries name.
fn far_box(sim: &mut Sim) -> Entity {
    sim.spawn((Transform::from_xyz(100.0, 0.0, 0.0), cuboid(0.5, 0.5, 0.5)))
}

/// The collider handle of `entity`.
fn collider_of(sim: &Sim, entity: Entity) -> ColliderHandle {
    sim.app
        .world()
        .get::<RapierColliderHandle>(entity)
        .unwrap()
        .0
}

/// A tear that splits a ruled `SoftBodyCluster` wholly off a bar gives the
/// piece the cluster's proxy as its root (rapier 0.36.1): the cluster's
/// entity and the piece's then describe one node. The cluster's rules come
/// first there and the piece's (the bar's, copied by bevy_rapier) under
/// them, as the cluster's colliders read them before the tear; a change or
/// a removal on either entity changes its own part alone (`docs/bevy.md`,
/// "A cluster's own rules").
#[test]
fn a_piece_rooted_at_a_ruled_cluster_holds_the_cluster_s_rules_over_its_own() {
    for_each_cluster_tear(|right, x| {
        let case = format!(
            "cluster at the {} end, torn across x = {x}",
            if right { "right" } else { "left" }
        );
        let mut sim = Sim::new();
        let bar_entity = sim.spawn((Transform::from_xyz(0.0, 0.1, 0.0), bar()));
        let f = sim.spawn(floor());
        let far = far_box(&mut sim);
        let (bars, clusters, floors) = {
            let mut table = sim.table();
            let groups = (
                table.create_group(),
                table.create_group(),
                table.create_group(),
            );
            table.set_group_rule(groups.0, groups.2, NoPair);
            table.set_group_rule(groups.1, groups.2, NoPair);
            groups
        };
        sim.entity_mut(f).insert(RuleGroup(floors));
        sim.entity_mut(bar_entity).insert((
            RuleGroup(bars),
            PersonalRule(NoPair),
            SpecificRules::new().with(far, NoPair),
        ));
        sim.run(1);
        let cluster_rules = || {
            (
                RuleGroup(clusters),
                SpecificRules::new().with(far, NoResponse),
            )
        };
        let torn = tear_off_cluster(&mut sim, bar_entity, (right, x), cluster_rules(), |_, _| {});
        let Some(TornCluster {
            cluster,
            proxy,
            piece,
        }) = torn
        else {
            return false;
        };
        let far_node = collider_of(&sim, far);
        let at_proxy = |sim: &mut Sim| {
            let rules = sim.rules().rules();
            let group = rules.group(proxy);
            (
                group,
                rules.personal(proxy),
                rules.specific(proxy, far_node),
            )
        };
        let carried = sim.app.world().get::<RuleGroup>(piece).map(|g| g.0);
        assert_eq!(
            carried,
            Some(bars),
            "{case}: the piece's entity carries the bar's group"
        );
        sim.run(FRAMES);
        assert_eq!(
            at_proxy(&mut sim),
            (Some(clusters), NoPair, NoResponse),
            "{case}: the cluster's rules hold at its proxy, the piece's root, over the piece's"
        );
        let all: Vec<Entity> = {
            let context = sim.context();
            let set = sim.app.world().get::<RapierRigidBodySet>(context).unwrap();
            set.soft_bodies
                .iter()
                .filter_map(|(h, _)| set.soft_body_entity(h))
                .collect()
        };
        for soft in all {
            let low = lowest(&mut sim, soft);
            assert!(
                low < -1.0,
                "{case}: {soft:?} falls through the floor both groups ignore: lowest particle at {low}"
            );
        }
        // Without the cluster's rules, the piece's (the bar's) hold.
        sim.entity_mut(cluster)
            .remove::<(RuleGroup, SpecificRules)>();
        sim.run(1);
        let removed = at_proxy(&mut sim);
        assert_eq!(
            removed,
            (Some(bars), NoPair, NoPair),
            "{case}: the cluster's rules removed"
        );
        // The cluster's come back over them; the piece's change, then go.
        sim.entity_mut(cluster).insert(cluster_rules());
        sim.run(1);
        let again = at_proxy(&mut sim);
        assert_eq!(
            again,
            (Some(clusters), NoPair, NoResponse),
            "{case}: the cluster's rules given again"
        );
        sim.entity_mut(piece).insert(RuleGroup(floors));
        sim.run(1);
        let changed = at_proxy(&mut sim);
        assert_eq!(
            changed,
            (Some(clusters), NoPair, NoResponse),
            "{case}: the piece's group changed"
        );
        sim.entity_mut(piece)
            .remove::<(RuleGroup, PersonalRule, SpecificRules)>();
        sim.run(1);
        let gone = at_proxy(&mut sim);
        assert_eq!(
            gone,
            (Some(clusters), Defer, NoResponse),
            "{case}: the piece's rules removed"
        );
        sim.entity_mut(cluster)
            .remove::<(RuleGroup, SpecificRules)>();
        sim.run(1);
        assert_eq!(
            at_proxy(&mut sim),
            (None, Defer, Defer),
            "{case}: both removed"
        );
        true
    });
}

/// Every soft body's particles in the context, by handle, bit for bit.
fn every_particle(sim: &mut Sim) -> Vec<u32> {
    let context = sim.context();
    let set = sim.app.world().get::<RapierRigidBodySet>(context).unwrap();
    let mut bodies: Vec<_> = set.soft_bodies.iter().collect();
    bodies.sort_unstable_by_key(|(h, _)| h.into_raw_parts());
    bodies
        .into_iter()
        .flat_map(|(_, b)| {
            b.particle_positions()
                .flat_map(|p| p.to_array())
                .collect::<Vec<_>>()
        })
        .map(f32::to_bits)
        .collect()
}

/// A bar lying 0.1 m inside the floor (or with the floor 1 km below),
/// pinned at its ends and pulled apart until it tears by strain during one
/// of the three Rapier steps of a frame (a fixed step of three substeps),
/// with `NoContacts` given as `given`: every particle, frame by frame, and
/// how many soft bodies there were at the end.
fn strained_bar(with_floor: bool, given: Given) -> (Vec<Vec<u32>>, usize) {
    let mut sim = Sim::new();
    sim.app.insert_resource(TimestepMode::Fixed {
        dt: 1.0 / 60.0,
        substeps: 3,
    });
    let builder = bar().builder;
    let ends: Vec<u32> = (0..builder.particle_positions().len() as u32)
        .filter(|&i| builder.particle_positions()[i as usize].x.abs() > 0.99)
        .collect();
    let pinned = ends.clone();
    let strained = bar().map(|b| b.pinned_particles(pinned).tear_strain(0.3));
    let bar_entity = sim.spawn((Transform::from_xyz(0.0, -0.1, 0.0), strained));
    let f = sim.spawn(floor());
    if !with_floor {
        sim.entity_mut(f)
            .insert(Transform::from_xyz(0.0, -1000.0, 0.0));
    }
    give(&mut sim, bar_entity, f, NoContacts, given);
    sim.run(1);
    let context = sim.context();
    let start: Vec<_> = {
        let set = sim.app.world().get::<RapierRigidBodySet>(context).unwrap();
        let body = set.soft_body(bar_entity).expect("the bar");
        ends.iter()
            .map(|&i| body.particle_position(i as usize))
            .collect()
    };
    let mut seen = Vec::new();
    for frame in 0..60 {
        let mut set = sim
            .app
            .world_mut()
            .get_mut::<RapierRigidBodySet>(context)
            .unwrap();
        // The particles move to the pieces when the bar tears.
        if set.soft_bodies.len() == 1 {
            let pull = 1.5 * (frame as f32 / 20.0).min(1.0);
            let body = set.soft_body_mut(bar_entity).expect("the bar");
            for (&i, &p) in ends.iter().zip(&start) {
                let mut target = p;
                target.x += if p.x > 0.0 { pull } else { -pull };
                body.set_particle_kinematic_target(i as usize, target);
            }
        }
        sim.run(1);
        seen.push(every_particle(&mut sim));
    }
    let set = sim.app.world().get::<RapierRigidBodySet>(context).unwrap();
    (seen, set.soft_bodies.len())
}

/// A strain tear in one of a frame's Rapier steps: the pieces follow the
/// bar's rules in the frame's next steps (the plugin's `TearListener` on
/// the context), so every particle moves bit for bit as with the floor
/// 1 km below, frame by frame, for every way of giving the rule.
#[test]
fn the_pieces_of_a_strain_tear_between_substeps_follow_the_rules() {
    for given in GIVENS {
        let (ruled, pieces) = strained_bar(true, given);
        let (away, _) = strained_bar(false, given);
        assert!(pieces > 1, "{given:?}: the bar tore ({pieces} soft bodies)");
        for (frame, (ruled, away)) in ruled.iter().zip(&away).enumerate() {
            assert!(
                ruled == away,
                "{given:?}: frame {frame}: the particles part from the scene without the floor"
            );
        }
    }
}

/// After a cut that moves the torn entity's root (rapier 0.36.1 in 2D),
/// the book holds the torn entity's rules at its new root only: removing
/// the rule component of the piece that holds the old root takes the rule
/// off that root.
#[test]
fn the_piece_holding_a_moved_root_gives_its_rule_up_with_its_component() {
    let mut checked = 0;
    for x in [-0.6, -0.4, -0.2, 0.2, 0.4, 0.6] {
        let mut sim = Sim::new();
        let bar_entity = sim.spawn((
            Transform::from_xyz(0.0, 0.1, 0.0),
            bar(),
            PersonalRule(NoPair),
        ));
        sim.spawn(floor());
        sim.run(1);
        split(&mut sim, bar_entity, Split::Tear);
        sim.run(1);
        let root = root_of(&mut sim, bar_entity);
        let Some(cut) = split_at(&mut sim, bar_entity, Split::Cut, x) else {
            continue;
        };
        if root_of(&mut sim, bar_entity) == root {
            continue;
        }
        sim.run(3);
        let Some(piece) = cut
            .into_iter()
            .find(|&p| p != bar_entity && root_of(&mut sim, p) == root)
        else {
            continue;
        };
        checked += 1;
        assert_eq!(
            sim.rules().rules().personal(root),
            NoPair,
            "x = {x}: before"
        );
        sim.entity_mut(piece).remove::<PersonalRule>();
        sim.run(2);
        let personal = sim.rules().rules().personal(root);
        assert_eq!(personal, Defer, "x = {x}: the piece's rule removed");
    }
    assert!(
        checked > 0 || cfg!(feature = "dim3"),
        "no cut moved the root"
    );
}

/// Each frame: the rule set's entry between a proxy and a body, and two
/// entities' components' entries about that body.
type Frames = Vec<(CollisionRule, Option<CollisionRule>, Option<CollisionRule>)>;

/// One entity with an entry about the bar and an entry with an end about
/// the cluster: the second is set at the cluster's proxy, and once it
/// ends the entry about the piece (the bar's, copied by bevy_rapier)
/// shows there, as the component says.
#[test]
fn one_entity_s_entry_about_the_piece_shows_when_its_entry_about_the_cluster_ends() {
    for_each_cluster_tear(|right, x| {
        let mut sim = Sim::new();
        let bar_entity = sim.spawn((Transform::from_xyz(0.0, 0.1, 0.0), bar()));
        let far = far_box(&mut sim);
        sim.run(1);
        let give = |sim: &mut Sim, cluster: Entity| {
            let entries = SpecificRules::new().with(bar_entity, NoPair);
            let entries = entries.with_until(cluster, NoResponse, Until::steps(30));
            sim.entity_mut(far).insert(entries);
        };
        let torn = tear_off_cluster(&mut sim, bar_entity, (right, x), (), give);
        let Some(TornCluster {
            cluster,
            proxy,
            piece,
        }) = torn
        else {
            return false;
        };
        let far_node = collider_of(&sim, far);
        let held = sim.rules().rules().specific(far_node, proxy);
        assert_eq!(held, NoResponse, "x = {x}: the entry about the cluster");
        sim.run(60);
        let component = sim.app.world().get::<SpecificRules>(far).unwrap();
        let (about_piece, about_cluster) = (component.get(piece), component.get(cluster));
        assert_eq!(
            (about_piece, about_cluster),
            (NoPair, Defer),
            "x = {x}: the component"
        );
        let held = sim.rules().rules().specific(far_node, proxy);
        assert_eq!(held, NoPair, "x = {x}: the entry about the piece holds");
        true
    });
}

/// The cluster's and the piece's entries with an end about one body (the
/// piece's copied from the bar): the piece's, hidden under the cluster's,
/// does not run; when the cluster's ends, the piece's shows and starts its
/// end, whichever entity sorts first.
#[test]
fn a_hidden_entry_with_an_end_starts_when_the_one_over_it_ends() {
    for_each_cluster_tear(|right, x| {
        let mut found = false;
        for cluster_first in [true, false] {
            let mut sim = Sim::new();
            let far = far_box(&mut sim);
            let bar_entity = sim.spawn((Transform::from_xyz(0.0, 0.1, 0.0), bar()));
            sim.run(1);
            if !cluster_first {
                // A slot freed before the cluster's spawn: the cluster's
                // entity sorts after the entities spawned fresh.
                let spare = sim.spawn(Transform::default());
                sim.app.world_mut().despawn(spare);
            }
            let entry = || SpecificRules::new().with_until(far, NoPair, Until::steps(20));
            let give = |sim: &mut Sim, _| {
                sim.entity_mut(bar_entity).insert(entry());
            };
            let torn = tear_off_cluster(&mut sim, bar_entity, (right, x), entry(), give);
            let Some(TornCluster {
                cluster,
                proxy,
                piece,
            }) = torn
            else {
                continue;
            };
            found = true;
            let far_node = collider_of(&sim, far);
            let mut frames: Frames = Vec::new();
            for _ in 0..40 {
                sim.run(1);
                let world = sim.app.world();
                let of = |e: Entity| world.get::<SpecificRules>(e).map(|r| r.get(far));
                let (by_cluster, by_piece) = (of(cluster), of(piece));
                let held = sim.rules().rules().specific(proxy, far_node);
                frames.push((held, by_cluster, by_piece));
            }
            let case = format!("x = {x}, cluster first: {cluster_first}: {frames:?}");
            let ended = frames.iter().position(|f| f.1 != Some(NoPair));
            let ended = ended.unwrap_or_else(|| panic!("{case}: the cluster's entry never ended"));
            assert_eq!(
                frames[ended].2,
                Some(NoPair),
                "{case}: the piece's ended with it"
            );
            assert_eq!(frames[ended].0, NoPair, "{case}: the piece's shows");
        }
        found
    });
}
