//! Soft bodies under the rules (`docs/semantics.md`, "Soft bodies"): a soft
//! block over a fixed ground, a rigid box over a soft block, two soft
//! blocks, and the pieces of a cut, each against the same scene without the
//! other object, for every rule and every way of giving it.

use super::rapier::prelude::*;
use super::rules::{CollisionRule, RuleHooks};
use super::world::edges_across;
use super::{CUT_MOVES_ROOT, at, blade_at_x, cube, pose_bits, slab, soft_bar, soft_block};

const STEPS: usize = 90;

/// How a rule between two objects is given.
#[derive(Clone, Copy, Debug)]
enum Way {
    /// `set_specific(first, second, rule)`.
    Specific,
    /// `set_specific(second, first, rule)`.
    SpecificReversed,
    /// A personal rule on the first object.
    Personal,
    /// Each object in a group of its own, related by the group table.
    Groups,
}

const WAYS: [Way; 4] = [Way::Specific, Way::SpecificReversed, Way::Personal, Way::Groups];

/// The ways that reach only the pair, for scenes where the first object
/// also rests on the ground (a personal rule would reach that pair too).
const PAIR_WAYS: [Way; 3] = [Way::Specific, Way::SpecificReversed, Way::Groups];

fn give(hooks: &mut RuleHooks, way: Way, first: RigidBodyHandle, second: RigidBodyHandle, rule: CollisionRule) {
    let rules = hooks.rules_mut();
    match way {
        Way::Specific => rules.set_specific(first, second, rule),
        Way::SpecificReversed => rules.set_specific(second, first, rule),
        Way::Personal => rules.set_personal(first, rule),
        Way::Groups => {
            let (a, b) = (rules.create_group(), rules.create_group());
            rules.set_group(first, Some(a));
            rules.set_group(second, Some(b));
            rules.set_group_rule(a, b, rule);
        }
    }
}

/// A world with a fixed ground slab whose top is at y = 0: the world and
/// the ground's body.
fn on_ground() -> (PhysicsWorld, RigidBodyHandle) {
    on_ground_at(0.0)
}

/// [`on_ground`] with the ground's top at y = `depth` (1 km below, the same
/// world without the ground in reach, with the same handles).
fn on_ground_at(depth: f32) -> (PhysicsWorld, RigidBodyHandle) {
    let mut world = PhysicsWorld::new();
    let floor = world.insert_body(RigidBodyBuilder::fixed().translation(at(0.0, depth - 0.5)));
    world.insert_collider(slab(5.0, 0.5), Some(floor));
    (world, floor)
}

/// Every particle's position, bit for bit.
fn particles(world: &PhysicsWorld, body: SoftBodyHandle) -> Vec<u32> {
    world.soft_bodies[body]
        .particle_positions()
        .flat_map(|p| p.to_array())
        .map(f32::to_bits)
        .collect()
}

fn lowest(world: &PhysicsWorld, body: SoftBodyHandle) -> f32 {
    world.soft_bodies[body]
        .particle_positions()
        .map(|p| p.y)
        .fold(f32::MAX, f32::min)
}

/// Counts the collision events that start, between the colliders of
/// `between` if it is set.
#[derive(Default)]
struct Events {
    started: std::sync::atomic::AtomicUsize,
    between: Option<(Vec<ColliderHandle>, Vec<ColliderHandle>)>,
}

impl EventHandler for Events {
    fn handle_collision_event(
        &self,
        _bodies: &RigidBodySet,
        _colliders: &ColliderSet,
        event: CollisionEvent,
        _pair: Option<&ContactPair>,
    ) {
        let (a, b) = (event.collider1(), event.collider2());
        let counted = self.between.as_ref().is_none_or(|(x, y)| {
            (x.contains(&a) && y.contains(&b)) || (x.contains(&b) && y.contains(&a))
        });
        if event.started() && counted {
            self.started.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        }
    }

    fn handle_contact_force_event(
        &self,
        _dt: Real,
        _bodies: &RigidBodySet,
        _colliders: &ColliderSet,
        _pair: &ContactPair,
        _total_force_magnitude: Real,
    ) {
    }

    fn handle_soft_body_tear_event(&self, _soft_bodies: &SoftBodySet, _event: &SoftBodyTearEvent) {}
}

/// A soft block falling on a fixed ground (or on nothing), with `rule`
/// between the ground and the block given `way`: the block's particles
/// after the fall and the collision events that started.
fn block_over_ground(ground: bool, rule: Option<(Way, CollisionRule)>, ground_first: bool) -> (Vec<u32>, f32, usize, usize) {
    let mut world = PhysicsWorld::new();
    let floor = world.insert_body(RigidBodyBuilder::fixed().translation(at(0.0, -0.5)));
    if ground {
        world.insert_collider(slab(5.0, 0.5).active_events(ActiveEvents::COLLISION_EVENTS), Some(floor));
    }
    let block = world.insert_soft_body(soft_block(at(0.0, 0.8), 0.5));
    let root = world.soft_bodies[block].root_body();
    let mut hooks = RuleHooks::default();
    if let Some((way, rule)) = rule {
        let (first, second) = if ground_first { (floor, root) } else { (root, floor) };
        give(&mut hooks, way, first, second, rule);
    }
    let events = Events::default();
    let mut without_contacts = 0;
    for _ in 0..STEPS {
        hooks.step_with_events(&mut world, &events);
        without_contacts = without_contacts.max(hooks.stats().soft_pairs_without_contacts);
    }
    let started = events.started.load(std::sync::atomic::Ordering::Relaxed);
    (particles(&world, block), lowest(&world, block), started, without_contacts)
}

#[test]
fn a_soft_block_rests_on_the_ground_as_in_plain_rapier_with_normal_rules() {
    let (plain, low, _, _) = block_over_ground(true, None, false);
    assert!(low > -0.1, "the block rests on the ground: lowest particle at {low}");
    for way in WAYS {
        for ground_first in [false, true] {
            let (ruled, low, _, _) = block_over_ground(true, Some((way, CollisionRule::Normal)), ground_first);
            assert!(ruled == plain, "{way:?} Normal (ground first: {ground_first}) moves the block otherwise: lowest at {low}");
        }
    }
}

#[test]
fn a_soft_block_falls_as_if_the_ground_were_absent_for_every_rule_but_normal() {
    let (alone, alone_low, _, _) = block_over_ground(false, None, false);
    assert!(alone_low < -1.0, "alone, the block falls: lowest particle at {alone_low}");
    for rule in [CollisionRule::NoResponse, CollisionRule::NoContacts, CollisionRule::NoPair] {
        for way in WAYS {
            for ground_first in [false, true] {
                // A personal rule on the ground reaches every pair of the
                // ground; on the block, every pair of the block: both are
                // the pair's rule here.
                let (ruled, low, started, without_contacts) = block_over_ground(true, Some((way, rule)), ground_first);
                assert!(
                    ruled == alone,
                    "{way:?} {rule:?} (ground first: {ground_first}): lowest particle at {low}, alone at {alone_low}"
                );
                // Rapier 0.36.1 solves every contact of a soft-rigid pair
                // (`docs/architecture.md`, "Soft bodies"): such a pair
                // without response has no contacts, hence no events.
                assert_eq!(started, 0, "{way:?} {rule:?}: {started} collision events");
                // `stats()` counts the pair that lost its contacts.
                let expected = usize::from(rule == CollisionRule::NoResponse);
                assert_eq!(without_contacts, expected, "{way:?} {rule:?}: soft pairs without contacts");
            }
        }
    }
}

/// Pins what makes soft-rigid `NoResponse` lose its contacts: in Rapier
/// 0.36.1 a pair whose filter answers "contacts without response" is still
/// solved by the soft-body solver. A Rapier that honours the answer fails
/// this test, and the crate can then keep those pairs' contacts
/// (`docs/architecture.md`, "Soft bodies").
#[test]
fn rapier_still_solves_a_soft_rigid_pair_whose_filter_says_no_response() {
    struct NoResponse;
    impl PhysicsHooks for NoResponse {
        fn filter_contact_pair(&self, _context: &PairFilterContext) -> Option<SolverFlags> {
            Some(SolverFlags::empty())
        }
    }
    let mut world = PhysicsWorld::new();
    let floor = world.insert_body(RigidBodyBuilder::fixed().translation(at(0.0, -0.5)));
    let hooked = slab(5.0, 0.5).active_hooks(ActiveHooks::FILTER_CONTACT_PAIRS);
    world.insert_collider(hooked, Some(floor));
    let block = world.insert_soft_body(soft_block(at(0.0, 0.8), 0.5));
    for _ in 0..STEPS {
        world.step_with_events(&NoResponse, &());
    }
    let low = lowest(&world, block);
    assert!(low > -0.1, "Rapier held the block on the ground: lowest particle at {low}");
}

/// A rigid box falling on a soft block resting on the ground: the box's
/// pose and the block's particles.
fn box_over_block(block: bool, boxed: bool, rule: Option<(Way, CollisionRule)>) -> (Vec<u32>, Vec<u32>) {
    let mut world = PhysicsWorld::new();
    // The box's side of the rule is hooked, which costs its pair with the
    // ground Rapier's contact recycling (`docs/performance.md`): without
    // recycling the box lands bit for bit as it does alone.
    world.integration_parameters.contact_recycling = false;
    let floor = world.insert_body(RigidBodyBuilder::fixed().translation(at(0.0, -0.5)));
    world.insert_collider(slab(5.0, 0.5), Some(floor));
    let soft = world.insert_soft_body(soft_block(at(0.0, 0.5), 0.5));
    let root = world.soft_bodies[soft].root_body();
    if !block {
        world.remove_soft_body(soft);
    }
    let rigid = world.insert_body(RigidBodyBuilder::dynamic().translation(at(0.0, 1.6)));
    if boxed {
        world.insert_collider(cube(0.15), Some(rigid));
    }
    let mut hooks = RuleHooks::default();
    if let Some((way, rule)) = rule {
        give(&mut hooks, way, rigid, root, rule);
    }
    for _ in 0..STEPS {
        hooks.step(&mut world);
    }
    let pose = super::pose_bits(world.bodies[rigid].position());
    let block = if block { particles(&world, soft) } else { Vec::new() };
    (pose, block)
}

#[test]
fn a_rigid_box_passes_through_a_soft_block_that_does_not_respond_to_it() {
    let (box_alone, _) = box_over_block(false, true, None);
    let (_, block_alone) = box_over_block(true, false, None);
    let (box_on_block, _) = box_over_block(true, true, None);
    assert!(box_on_block != box_alone, "with no rule the block holds the box");
    for rule in [CollisionRule::NoResponse, CollisionRule::NoContacts, CollisionRule::NoPair] {
        for way in PAIR_WAYS {
            let (rigid, block) = box_over_block(true, true, Some((way, rule)));
            let apart = distance(&rigid, &box_alone);
            assert!(rigid == box_alone, "{way:?} {rule:?}: the box ends {apart} m from where it ends alone");
            assert!(block == block_alone, "{way:?} {rule:?}: the block moves otherwise than alone");
        }
    }
}

/// How far apart two poses (as `pose_bits`) put their origins.
fn distance(a: &[u32], b: &[u32]) -> f32 {
    let at = |p: &[u32]| -> Vec<f32> { p.iter().take(2).map(|&b| f32::from_bits(b)).collect() };
    at(a).iter().zip(at(b)).map(|(x, y)| (x - y) * (x - y)).sum::<f32>().sqrt()
}

/// A small soft block falling on a larger one: the upper block's
/// particles, and the collision events between the two.
fn block_over_block(lower: bool, rule: Option<(Way, CollisionRule)>) -> (Vec<u32>, usize) {
    let (mut world, _) = on_ground();
    let events_on = ColliderBuilder::ball(0.05).active_events(ActiveEvents::COLLISION_EVENTS);
    let below = world.insert_soft_body(soft_block(at(0.0, 0.5), 0.5).surface_collider(events_on.clone()));
    let above = world.insert_soft_body(soft_block(at(0.0, 1.6), 0.3).surface_collider(events_on));
    let (low_root, high_root) = (world.soft_bodies[below].root_body(), world.soft_bodies[above].root_body());
    if !lower {
        world.remove_soft_body(below);
    }
    let mut hooks = RuleHooks::default();
    if let Some((way, rule)) = rule {
        give(&mut hooks, way, high_root, low_root, rule);
    }
    let surface = |world: &PhysicsWorld, body: SoftBodyHandle| -> Vec<ColliderHandle> {
        world.soft_bodies.get(body).map_or(Vec::new(), |b| b.meshes().map(|m| m.collider()).collect())
    };
    let events = Events {
        between: Some((surface(&world, below), surface(&world, above))),
        ..Events::default()
    };
    for _ in 0..STEPS {
        hooks.step_with_events(&mut world, &events);
    }
    (particles(&world, above), events.started.load(std::sync::atomic::Ordering::Relaxed))
}

#[test]
fn two_soft_blocks_ignore_each_other_as_their_rule_says() {
    let (alone, _) = block_over_block(false, None);
    let (stacked, met) = block_over_block(true, None);
    assert!(stacked != alone && met > 0, "with no rule the lower block holds the upper one ({met} events)");
    for rule in [CollisionRule::NoResponse, CollisionRule::NoContacts, CollisionRule::NoPair] {
        for way in PAIR_WAYS {
            let (upper, met) = block_over_block(true, Some((way, rule)));
            assert!(upper == alone, "{way:?} {rule:?}: the upper block moves otherwise than alone");
            // Two soft surfaces keep their pair's contacts and events
            // without response.
            let expected = usize::from(rule == CollisionRule::NoResponse);
            assert_eq!(met.min(1), expected, "{way:?} {rule:?}: {met} collision events");
        }
    }
}

/// A soft block over the ground with `NoPair` between the two, stepped
/// once: the world, the ground's body, the block and the hooks.
fn block_without_ground() -> (PhysicsWorld, RigidBodyHandle, SoftBodyHandle, RuleHooks) {
    let (mut world, floor) = on_ground();
    let block = world.insert_soft_body(soft_block(at(0.0, 0.8), 0.5));
    let root = world.soft_bodies[block].root_body();
    let mut hooks = RuleHooks::default();
    hooks.rules_mut().set_specific(root, floor, CollisionRule::NoPair);
    hooks.step(&mut world);
    (world, floor, block, hooks)
}

/// Removing a soft body forgets its rules, as removing a rigid body does.
#[test]
fn a_removed_soft_body_leaves_no_rule_behind() {
    let (mut world, floor, block, mut hooks) = block_without_ground();
    let root = world.soft_bodies[block].root_body();
    world.remove_soft_body(block);
    hooks.step(&mut world);
    assert_eq!(hooks.rules().specific(floor, root), CollisionRule::Defer, "the entry went with the body");
    let again = world.insert_soft_body(soft_block(at(0.0, 0.8), 0.5));
    for _ in 0..STEPS {
        hooks.step(&mut world);
    }
    let low = lowest(&world, again);
    assert!(low > -0.1, "a new soft body starts with no rules: lowest particle at {low}");
}

/// Removing the cluster of a soft body's root makes another cluster's proxy
/// its root (rapier 0.36.1): the rules given to the soft body follow it
/// there, so a rigid collider hung on that proxy still falls through the
/// ground the soft body ignores.
#[test]
fn a_soft_body_whose_root_cluster_is_removed_keeps_its_rules_on_its_new_root() {
    for given_before_the_cluster in [true, false] {
        let (mut world, floor) = on_ground();
        let block = world.insert_soft_body(soft_block(at(0.0, 0.8), 0.5));
        let old_root = world.soft_bodies[block].root_body();
        let mut hooks = RuleHooks::default();
        if given_before_the_cluster {
            hooks.rules_mut().set_specific(old_root, floor, CollisionRule::NoPair);
            hooks.step(&mut world);
        }
        let top: Vec<u32> = (0..world.soft_bodies[block].particle_positions().count() as u32)
            .filter(|&v| world.soft_bodies[block].particle_position(v as usize).y > 0.8)
            .collect();
        let cluster = world.add_soft_body_cluster(block, &top).expect("a cluster of the top particles");
        let proxy = world.soft_bodies[block].cluster_proxy(cluster).expect("its proxy");
        let ball = world.insert_collider(cube(0.1), Some(proxy));
        // A third cluster, of the other particles, whose proxy the hooks
        // link to the old root: it is linked to the new one.
        let bottom: Vec<u32> = (0..world.soft_bodies[block].particle_positions().count() as u32)
            .filter(|v| !top.contains(v))
            .collect();
        let third = world.add_soft_body_cluster(block, &bottom).expect("a cluster of the bottom particles");
        let third = world.soft_bodies[block].cluster_proxy(third).expect("its proxy");
        let other_ball = world.insert_collider(cube(0.1), Some(third));
        if !given_before_the_cluster {
            hooks.rules_mut().set_specific(old_root, floor, CollisionRule::NoPair);
        }
        hooks.step(&mut world);
        world.remove_soft_body_cluster(block, 0).expect("the root's cluster goes");
        let root = world.soft_bodies[block].root_body();
        assert_ne!(root, old_root, "the soft body has a new root");
        for _ in 0..STEPS {
            hooks.step(&mut world);
        }
        let case = format!("rule given before the cluster: {given_before_the_cluster}");
        assert_eq!(hooks.rules().specific(root, floor), CollisionRule::NoPair, "{case}: the new root's entry");
        let y = world.colliders[ball].translation().y;
        assert!(y < -1.0, "{case}: the collider on the new root fell to {y}");
        let y = world.colliders[other_ball].translation().y;
        assert!(y < -1.0, "{case}: the collider on the third cluster fell to {y}");
        assert_eq!(hooks.rules().parent(third), Some(root), "{case}: the third cluster's proxy is linked to the new root");
    }
}

/// A soft body cut before the hooks ever saw it, its root already named
/// by a rule: whichever side Rapier gives the old root, both sides keep the
/// rule (the hooks find it on the root the rules name).
#[test]
fn a_soft_body_cut_before_its_first_step_keeps_its_rule_on_both_sides() {
    let (mut moved, mut cuts) = (false, 0);
    for x in [-0.6, -0.4, -0.2, 0.2, 0.4, 0.6] {
        let (mut world, floor) = on_ground();
        let bar = world.insert_soft_body(soft_bar(at(0.0, 0.6), 1.0));
        // Torn in two first: the side that keeps the handle has clusters
        // the tear made.
        let edges = edges_across_middle(&world, bar);
        world.tear_soft_body(bar, &edges, &[]).expect("the bar tears");
        let root = world.soft_bodies[bar].root_body();
        let mut hooks = RuleHooks::default();
        hooks.rules_mut().set_specific(floor, root, CollisionRule::NoPair);
        let Some(cut) = world.cut_soft_body(bar, &blade_at_x(x)) else {
            continue;
        };
        cuts += 1;
        moved |= world.soft_bodies[bar].root_body() != root;
        for _ in 0..STEPS {
            hooks.step(&mut world);
        }
        for piece in cut.bodies() {
            let low = lowest(&world, piece);
            assert!(low < -1.0, "cut at x = {x}: piece {piece:?} rests at {low}");
        }
    }
    // The blades across the half that keeps the handle cut it.
    assert!(cuts >= 2, "only {cuts} of the 6 blades cut the torn bar");
    assert_eq!(moved, CUT_MOVES_ROOT, "whether a cut gave the bar's root to the piece");
}

/// A bar torn in two, with a cluster per column, then cut twice before a
/// step, for many pairs of blades: no soft body's root or proxy is left
/// the child of another soft body's root (the second cut's piece is found
/// against the root the hooks knew before both cuts, not the one the
/// first cut left), and every piece keeps the rule.
#[test]
fn a_soft_body_cut_twice_before_a_step_links_no_piece_to_another() {
    let xs: Vec<f32> = (-6..=6).map(|i| i as f32 * 0.15).collect();
    let mut cut_twice = 0;
    for &first in &xs {
        for &second in &xs {
            let (mut world, floor) = on_ground();
            let bar = world.insert_soft_body(soft_bar(at(0.0, 0.6), 1.0));
            let positions: Vec<Vector> = world.soft_bodies[bar].particle_positions().collect();
            // A cluster per column of particles.
            let mut columns: Vec<f32> = positions.iter().map(|p| p.x).collect();
            columns.sort_by(f32::total_cmp);
            columns.dedup_by(|a, b| (*a - *b).abs() < 1.0e-4);
            for &x in &columns {
                let column: Vec<u32> = (0..positions.len() as u32)
                    .filter(|&v| (positions[v as usize].x - x).abs() < 1.0e-4)
                    .collect();
                world.add_soft_body_cluster(bar, &column).expect("a cluster of a column");
            }
            let root = world.soft_bodies[bar].root_body();
            let mut hooks = RuleHooks::default();
            hooks.rules_mut().set_specific(floor, root, CollisionRule::NoPair);
            hooks.step(&mut world);
            let edges = edges_across_middle(&world, bar);
            world.tear_soft_body(bar, &edges, &[]);
            hooks.step(&mut world);
            let cuts = [first, second].iter().filter(|&&x| world.cut_soft_body(bar, &blade_at_x(x)).is_some()).count();
            cut_twice += usize::from(cuts == 2);
            hooks.step(&mut world);
            let case = format!("blades at {first} and {second}");
            let roots: Vec<RigidBodyHandle> = world.soft_bodies.iter().map(|(_, b)| b.root_body()).collect();
            for (handle, body) in world.soft_bodies.iter() {
                let own = body.root_body();
                let parent = hooks.rules().parent(own);
                assert!(parent.is_none_or(|p| !roots.contains(&p)), "{case}: soft body {handle:?}'s root is the child of {parent:?}");
                for (_, cluster) in body.live_clusters() {
                    let linked = hooks.rules().parent(cluster.proxy());
                    assert!(
                        cluster.proxy() == own || linked.is_none_or(|p| p == own),
                        "{case}: a proxy of {handle:?} is the child of {linked:?}, not of its root {own:?}"
                    );
                }
                assert_eq!(hooks.rules().specific(floor, own), CollisionRule::NoPair, "{case}: soft body {handle:?} lost the rule");
            }
        }
    }
    assert!(cut_twice >= 3, "only {cut_twice} pairs of blades cut the bar twice");
}

/// The edges of `body` that cross x = 0: tearing them splits a bar.
fn edges_across_middle(world: &PhysicsWorld, body: SoftBodyHandle) -> Vec<u32> {
    edges_across(&world.soft_bodies[body], 0.0)
}

/// A piece of a split bar after the fall: its handle, lowest particle,
/// whether it holds the bar's rule, and its particles' bits.
struct Piece {
    handle: SoftBodyHandle,
    low: f32,
    kept: bool,
    bits: Vec<u32>,
}

/// A bar over the ground (its top `depth` m below y = 0) with `rule`
/// between the two, split after one step by `split`; every piece after the
/// fall, stepped with the hooks or, without `hooked`, by plain Rapier.
fn split_bar(
    way: Way,
    rule: CollisionRule,
    depth: f32,
    hooked: bool,
    split: impl Fn(&mut PhysicsWorld, SoftBodyHandle) -> Option<SoftBodyTearEvent>,
) -> Vec<Piece> {
    let (mut world, floor) = on_ground_at(depth);
    let bar = world.insert_soft_body(soft_bar(at(0.0, 0.6), 1.0));
    let root = world.soft_bodies[bar].root_body();
    let mut hooks = RuleHooks::default();
    give(&mut hooks, way, root, floor, rule);
    let step = |world: &mut PhysicsWorld, hooks: &mut RuleHooks| {
        if hooked { hooks.step(world) } else { world.step() }
    };
    step(&mut world, &mut hooks);
    let event = split(&mut world, bar).expect("the bar splits");
    let pieces: Vec<SoftBodyHandle> = event.bodies().collect();
    assert!(pieces.len() >= 2, "the split makes pieces: {}", pieces.len());
    for _ in 0..STEPS {
        step(&mut world, &mut hooks);
    }
    pieces
        .into_iter()
        .map(|handle| {
            let piece_root = world.soft_bodies[handle].root_body();
            let kept = hooks.rules().shares_rules(root, piece_root) || hooks.rules().specific(floor, piece_root) == rule;
            Piece { handle, low: lowest(&world, handle), kept, bits: particles(&world, handle) }
        })
        .collect()
}

/// Both pieces of a bar cut in two, and of a bar torn in two, keep the
/// bar's rule with the ground, however it was given: each piece moves bit
/// for bit as in the same scene with the ground 1 km below (which keeps
/// every handle, so Rapier visits the pairs in the same order), and with
/// `Normal` as in plain Rapier's steps of the same scene.
#[test]
fn the_pieces_of_a_cut_or_a_tear_keep_the_rules_of_the_body_they_came_from() {
    let cut = |world: &mut PhysicsWorld, bar| world.cut_soft_body(bar, &blade_at_x(0.1));
    let tear = |world: &mut PhysicsWorld, bar| {
        let edges = edges_across_middle(world, bar);
        world.tear_soft_body(bar, &edges, &[])
    };
    let rules = [CollisionRule::Normal, CollisionRule::NoResponse, CollisionRule::NoContacts, CollisionRule::NoPair];
    for rule in rules {
        for way in WAYS {
            for how in ["cut", "tear"] {
                let scene = |depth: f32, hooked: bool| match how {
                    "cut" => split_bar(way, rule, depth, hooked, cut),
                    _ => split_bar(way, rule, depth, hooked, tear),
                };
                let pieces = scene(0.0, true);
                let normal = rule == CollisionRule::Normal;
                let reference = if normal { scene(0.0, false) } else { scene(-1000.0, true) };
                assert_eq!(pieces.len(), reference.len(), "{how} {way:?} {rule:?}: pieces");
                for (piece, like) in pieces.iter().zip(&reference) {
                    let (handle, low) = (piece.handle, piece.low);
                    let case = format!("{how} {way:?} {rule:?}: piece {handle:?} (lowest particle at {low}, {} in the reference)", like.low);
                    assert!(piece.bits == like.bits, "{case} moves otherwise than its reference");
                    if normal {
                        assert!(low > -0.1, "{case} rests on the ground");
                    } else {
                        assert!(low < -1.0, "{case} falls through the ground");
                    }
                    if !matches!(way, Way::Groups) {
                        assert!(piece.kept, "{case} lost the bar's rule");
                    }
                }
            }
        }
    }
}

/// A bar at the origin pinned at its ends, which tears past 30% strain,
/// and where its ends started.
struct Strained {
    bar: SoftBodyHandle,
    ends: Vec<u32>,
    start: Vec<Vector>,
}

impl Strained {
    fn insert(world: &mut PhysicsWorld) -> Strained {
        let builder = soft_bar(at(0.0, 0.0), 1.0);
        let ends: Vec<u32> = (0..builder.particle_positions().len() as u32)
            .filter(|&i| builder.particle_positions()[i as usize].x.abs() > 0.99)
            .collect();
        let bar = world.insert_soft_body(builder.pinned_particles(ends.clone()).tear_strain(0.3));
        let start = ends.iter().map(|&i| world.soft_bodies[bar].particle_position(i as usize)).collect();
        Strained { bar, ends, start }
    }

    /// Moves each end `pull` m outward from where it started.
    fn pull(&self, world: &mut PhysicsWorld, pull: f32) {
        for (&i, &p) in self.ends.iter().zip(&self.start) {
            let mut target = p;
            target.x += if p.x > 0.0 { pull } else { -pull };
            if let Some(soft) = world.soft_bodies.get_mut(self.bar) {
                soft.set_particle_kinematic_target(i as usize, target);
            }
        }
    }
}

/// A bar pulled apart past its tear strain tears during Rapier's step; the
/// pieces share the bar's rules from the next step.
#[test]
fn the_pieces_of_a_strain_tear_keep_the_rules_of_the_body_they_came_from() {
    let mut world = PhysicsWorld::new();
    world.gravity = Vector::ZERO;
    let strained = Strained::insert(&mut world);
    let root = world.soft_bodies[strained.bar].root_body();
    let other = world.insert_body(RigidBodyBuilder::fixed().translation(at(0.0, -5.0)));
    let mut hooks = RuleHooks::default();
    hooks.rules_mut().set_personal(root, CollisionRule::NoContacts);
    hooks.rules_mut().set_specific(other, root, CollisionRule::NoPair);
    for k in 0..120 {
        // The particles move to the pieces when the bar tears.
        if world.soft_bodies.len() > 1 {
            break;
        }
        strained.pull(&mut world, 1.5 * (k as f32 / 60.0).min(1.0));
        hooks.step(&mut world);
    }
    // The step after the tear gives the pieces their rules.
    hooks.step(&mut world);
    let family: Vec<SoftBodyHandle> = world.soft_bodies.iter().map(|(h, _)| h).collect();
    assert!(family.len() >= 2, "the bar tore: {} bodies", family.len());
    for piece in family {
        let piece_root = world.soft_bodies[piece].root_body();
        assert!(hooks.rules().shares_rules(root, piece_root), "piece {piece:?} shares the bar's record");
        assert_eq!(hooks.rules().specific(other, piece_root), CollisionRule::NoPair, "piece {piece:?} keeps the entry about it");
    }
}

/// A strain tear in the first of three Rapier steps between `prepare` and
/// `after_step` (as bevy_rapier runs substeps): with the hooks'
/// `TearListener` as the step's event handler, the pieces' pairs in the
/// next two steps follow the bar's rules. Each step, every particle sits
/// where it sits in the same scene whose floor lies 1 km below, given the
/// same rule (the floor keeps its handle, so Rapier visits the pairs in the
/// same order), bit for bit, for every rule, way and planner setting.
#[test]
fn the_pieces_of_a_strain_tear_between_two_steps_of_a_bracket_follow_the_rules() {
    let scene = |depth: f32, way: Way, rule: CollisionRule, planner: bool| {
        let mut world = PhysicsWorld::new();
        world.gravity = Vector::ZERO;
        // The floor's top at y = 0.1, through the middle of the bar.
        let floor = world.insert_body(RigidBodyBuilder::fixed().translation(at(0.0, depth - 0.4)));
        world.insert_collider(slab(5.0, 0.5), Some(floor));
        let strained = Strained::insert(&mut world);
        let root = world.soft_bodies[strained.bar].root_body();
        let mut hooks = RuleHooks::default();
        hooks.set_planner(planner);
        give(&mut hooks, way, root, floor, rule);
        let listener = hooks.tear_listener();
        let mut seen = Vec::new();
        let mut torn_at = None;
        for bracket in 0..40 {
            hooks.follow_soft_bodies(&world.soft_bodies, &world.bodies);
            hooks.prepare_with_graph(&world.bodies, &mut world.colliders, &world.narrow_phase);
            hooks.freeze_manifolds(&world.narrow_phase);
            hooks.wake_edited(&mut world.islands, &mut world.bodies);
            for substep in 0..3 {
                // The particles move to the pieces when the bar tears.
                if torn_at.is_none() {
                    strained.pull(&mut world, 1.5 * ((bracket * 3 + substep) as f32 / 60.0).min(1.0));
                }
                world.step_with_events(&hooks, &listener);
                if world.soft_bodies.len() > 1 {
                    torn_at.get_or_insert((bracket, substep));
                }
                let mut bodies: Vec<_> = world.soft_bodies.iter().map(|(h, _)| h).collect();
                bodies.sort_unstable_by_key(|h| h.into_raw_parts());
                seen.push(bodies.into_iter().flat_map(|b| particles(&world, b)).collect::<Vec<u32>>());
            }
            hooks.after_step(&world.narrow_phase, &world.bodies, &world.colliders);
        }
        (seen, torn_at)
    };
    for planner in [true, false] {
        for rule in [CollisionRule::NoResponse, CollisionRule::NoContacts, CollisionRule::NoPair] {
            for way in WAYS {
                let (ruled, torn_at) = scene(0.0, way, rule, planner);
                let (away, _) = scene(-1000.0, way, rule, planner);
                let case = format!("{way:?} {rule:?}, planner {planner}");
                let (bracket, substep) = torn_at.unwrap_or_else(|| panic!("{case}: the bar never tore"));
                assert!(substep < 2, "{case}: the bar tore in the last step of bracket {bracket}, which tests nothing");
                for (step, (ruled, away)) in ruled.iter().zip(&away).enumerate() {
                    assert!(
                        ruled == away,
                        "{case}: step {step} (the bar tore in step {} of bracket {bracket}): the particles part from the scene without the floor",
                        substep + 1
                    );
                }
            }
        }
    }
}

/// A cluster with rules of its own that lies wholly in a piece of a tear
/// becomes that piece's root (rapier 0.36.1). Before the tear its
/// colliders read the cluster's rules, then the bar's; after it the
/// piece keeps the cluster's and takes the bar's where the cluster says
/// nothing: the bar's group, which ignores the floor's, holds for every
/// piece, the cluster keeps its own entry, and another body's entry about
/// the cluster stays over its entry about the bar.
#[test]
fn a_piece_rooted_at_a_ruled_cluster_keeps_the_cluster_s_rules_over_the_bar_s() {
    let mut found = 0;
    // The cluster over either end, the tear across several places: those
    // that split the cluster's end off give the piece its proxy as root.
    for (end_right, x) in [(true, 0.4), (false, -0.4), (true, 0.2), (false, -0.2), (false, 0.4), (true, -0.4)] {
        let (mut world, floor) = on_ground();
        let bar = world.insert_soft_body(soft_bar(at(0.0, 0.6), 1.0));
        let root = world.soft_bodies[bar].root_body();
        let far = world.insert_body(RigidBodyBuilder::fixed().translation(at(100.0, 0.0)));
        world.insert_collider(cube(0.5), Some(far));
        let near = world.insert_body(RigidBodyBuilder::fixed().translation(at(-100.0, 0.0)));
        world.insert_collider(cube(0.5), Some(near));
        let count = world.soft_bodies[bar].particle_positions().count() as u32;
        let x_of = |world: &PhysicsWorld, v: u32| world.soft_bodies[bar].particle_position(v as usize).x;
        let end: Vec<u32> = (0..count).filter(|&v| (x_of(&world, v) > 0.3 * x.signum()) == end_right).collect();
        let cluster = world.add_soft_body_cluster(bar, &end).expect("a cluster of the bar's end");
        let proxy = world.soft_bodies[bar].cluster_proxy(cluster).expect("its proxy");
        let mut hooks = RuleHooks::default();
        let rules = hooks.rules_mut();
        let (bars, floors) = (rules.create_group(), rules.create_group());
        rules.set_group(root, Some(bars));
        rules.set_group(floor, Some(floors));
        rules.set_group_rule(bars, floors, CollisionRule::NoPair);
        rules.set_specific(proxy, far, CollisionRule::NoResponse);
        // Another body's entries about the cluster and about the bar: the
        // first comes before the second in the cluster colliders' chains.
        rules.set_specific(near, proxy, CollisionRule::NoResponse);
        rules.set_specific(near, root, CollisionRule::NoPair);
        hooks.step(&mut world);
        let edges = edges_across(&world.soft_bodies[bar], x);
        world.tear_soft_body(bar, &edges, &[]).expect("the bar tears");
        hooks.follow_soft_bodies(&world.soft_bodies, &world.bodies);
        let Some(rooted) = world.soft_bodies.iter().find(|(_, b)| b.root_body() == proxy).map(|(h, _)| h) else {
            continue;
        };
        found += 1;
        let case = format!("cluster at the {} end, torn across x = {x}", if end_right { "right" } else { "left" });
        // A project that keeps its own book of each piece's rules (the Bevy
        // plugin) hears of this piece too.
        let listed = hooks.split_pieces().iter().any(|s| s.piece == rooted || s.source == rooted);
        assert!(listed, "{case}: the piece is listed as given its source's rules");
        hooks.step(&mut world);
        assert_eq!(hooks.rules().group(proxy), Some(bars), "{case}: the piece's root takes the bar's group");
        assert_eq!(hooks.rules().specific(proxy, far), CollisionRule::NoResponse, "{case}: and keeps the cluster's own entry");
        assert_eq!(hooks.rules().specific(near, proxy), CollisionRule::NoResponse, "{case}: and the entry about it");
        for _ in 0..STEPS {
            hooks.step(&mut world);
        }
        for (piece, _) in world.soft_bodies.iter() {
            let low = lowest(&world, piece);
            let which = if piece == rooted { "the cluster's piece" } else { "a piece" };
            assert!(low < -1.0, "{case}: {which} {piece:?} falls through the floor its bar ignores: lowest particle at {low}");
        }
    }
    assert!(found > 0, "no tear gave a piece the cluster's proxy as root");
}

/// A rigid collider hung on the proxy of a cluster added to a soft body is
/// reached by the soft body's rules through the root: the block and the
/// ball move bit for bit as in the same scene with the ground 1 km below.
#[test]
fn a_collider_on_a_cluster_proxy_follows_the_soft_bodys_rules() {
    let scene = |depth: f32| {
        let (mut world, floor) = on_ground_at(depth);
        let block = world.insert_soft_body(soft_block(at(0.0, 0.8), 0.5));
        let root = world.soft_bodies[block].root_body();
        let mut hooks = RuleHooks::default();
        hooks.rules_mut().set_specific(root, floor, CollisionRule::NoPair);
        hooks.step(&mut world);
        let cluster = world.add_soft_body_cluster(block, &[0, 1, 2, 3]).expect("a cluster of four particles");
        let proxy = world.soft_bodies[block].cluster_proxy(cluster).expect("the cluster's proxy");
        let hung = world.insert_collider(ColliderBuilder::ball(0.2), Some(proxy));
        for _ in 0..STEPS {
            hooks.step(&mut world);
        }
        assert_eq!(hooks.rules().parent(proxy), Some(root), "the proxy hangs under the root");
        let rule = hooks.rules().resolve(&world.bodies, &world.colliders, hung, world.bodies[floor].colliders()[0]);
        assert_eq!(rule, CollisionRule::NoPair, "the ball on the proxy has the block's rule");
        let mut bits = particles(&world, block);
        bits.extend(pose_bits(world.colliders[hung].position()));
        (bits, lowest(&world, block))
    };
    let (ruled, low) = scene(0.0);
    let (away, low_away) = scene(-1000.0);
    assert!(low < -1.0, "the block and its ball fall through the ground: lowest particle at {low}");
    assert!(ruled == away, "the block and its ball move otherwise than with the ground away (lowest particle {low}, {low_away} away)");
}

/// No rules means plain Rapier, bit for bit, in a world of soft bodies that
/// are cut, torn and given clusters; and the hooks watch nothing.
#[test]
fn a_soft_world_without_rules_steps_as_plain_rapier() {
    let scene = |hooked: bool| {
        let (mut world, _) = on_ground();
        let bar = world.insert_soft_body(soft_bar(at(0.0, 0.6), 1.0));
        let block = world.insert_soft_body(soft_block(at(2.0, 0.8), 0.5));
        let mut hooks = RuleHooks::default();
        let mut step = |world: &mut PhysicsWorld| {
            if hooked { hooks.step(world) } else { world.step() }
        };
        step(&mut world);
        world.cut_soft_body(bar, &blade_at_x(0.1)).expect("the blade crosses the bar");
        world.add_soft_body_cluster(block, &[0, 1, 2, 3]);
        for _ in 0..STEPS {
            step(&mut world);
        }
        let edges = edges_across_middle(&world, block);
        world.tear_soft_body(block, &edges, &[]);
        for _ in 0..20 {
            step(&mut world);
        }
        let all: Vec<Vec<u32>> = world.soft_bodies.iter().map(|(h, _)| particles(&world, h)).collect();
        (all, hooks.stats())
    };
    let (plain, _) = scene(false);
    let (hooked, stats) = scene(true);
    assert!(hooked == plain, "the soft bodies move otherwise with the hooks");
    assert_eq!((stats.watched_colliders, stats.watched_bodies), (0, 0), "{stats:?}");
}

#[test]
fn explain_says_a_soft_rigid_pair_without_response_has_no_contacts() {
    let mut world = PhysicsWorld::new();
    let floor = world.insert_body(RigidBodyBuilder::fixed());
    let ground = world.insert_collider(slab(5.0, 0.5), Some(floor));
    let block = world.insert_soft_body(soft_block(at(0.0, 2.0), 0.5));
    let other = world.insert_soft_body(soft_block(at(3.0, 2.0), 0.5));
    let surface = |b: SoftBodyHandle| world.soft_bodies[b].meshes().next().expect("a surface").collider();
    let (mine, theirs) = (surface(block), surface(other));
    let mut hooks = RuleHooks::default();
    hooks.rules_mut().set_personal(world.soft_bodies[block].root_body(), CollisionRule::NoResponse);
    let why = hooks.rules().explain(&world.bodies, &world.colliders, ground, mine);
    assert_eq!(why.rule, CollisionRule::NoResponse);
    assert!(why.without_contacts, "{why:?}");
    let why = hooks.rules().explain(&world.bodies, &world.colliders, theirs, mine);
    assert!(!why.without_contacts, "two soft surfaces keep their contacts: {why:?}");
}

/// A rigid collider moved onto a soft body's cluster proxy in the same
/// step as another collider is hung on that proxy: with no rules, and
/// with a rule elsewhere in the world, the hooks step as plain Rapier, bit
/// for bit.
#[test]
fn colliders_moved_and_hung_on_a_proxy_in_one_step_move_as_in_plain_rapier() {
    for rule in [false, true] {
        let scene = |hooked: bool| {
            let (mut world, floor) = on_ground();
            let block = world.insert_soft_body(soft_block(at(0.0, 0.8), 0.5));
            let loose = world.insert_body(RigidBodyBuilder::dynamic().translation(at(2.0, 1.0)));
            let moved = world.insert_collider(ColliderBuilder::ball(0.2), Some(loose));
            let mut hooks = RuleHooks::default();
            if rule {
                let far = world.insert_body(RigidBodyBuilder::dynamic().translation(at(50.0, 1.0)));
                world.insert_collider(ColliderBuilder::ball(0.2), Some(far));
                hooks.rules_mut().set_specific(far, floor, CollisionRule::NoPair);
            }
            let mut step = |world: &mut PhysicsWorld| {
                if hooked { hooks.step(world) } else { world.step() }
            };
            step(&mut world);
            let cluster = world.add_soft_body_cluster(block, &[0, 1, 2, 3]).expect("a cluster of four particles");
            let proxy = world.soft_bodies[block].cluster_proxy(cluster).expect("the cluster's proxy");
            for _ in 0..5 {
                step(&mut world);
            }
            let w = &mut world;
            w.colliders.set_parent(moved, Some(proxy), &mut w.bodies);
            world.insert_collider(ColliderBuilder::ball(0.2).translation(at(0.0, 0.3)), Some(proxy));
            for _ in 0..STEPS {
                step(&mut world);
            }
            let mut poses: Vec<Vec<u32>> = world.soft_bodies.iter().map(|(h, _)| particles(&world, h)).collect();
            poses.extend(world.bodies.iter().map(|(_, b)| pose_bits(b.position())));
            poses
        };
        assert!(scene(true) == scene(false), "with a rule elsewhere: {rule}: the world moves otherwise with the hooks");
    }
}

/// A project that changes a soft body's collider between a cut and the
/// next step changes that collider alone: the copy Rapier made at the cut
/// keeps the project's settings from before, under the crate's plan. The
/// project takes the bar's colliders out of every collision group after the
/// cut: the piece with them falls through the ground, the piece with the
/// copies rests on it (a rule elsewhere has the crate write on both).
#[test]
fn a_project_change_of_a_collider_after_a_cut_is_not_its_copys() {
    let (mut world, _floor) = on_ground();
    let bar = world.insert_soft_body(soft_bar(at(0.0, 0.6), 1.0));
    let root = world.soft_bodies[bar].root_body();
    let far = world.insert_body(RigidBodyBuilder::fixed().translation(at(20.0, 0.0)));
    world.insert_collider(cube(0.2), Some(far));
    let mut hooks = RuleHooks::default();
    give(&mut hooks, Way::Groups, root, far, CollisionRule::NoPair);
    hooks.step(&mut world);
    let originals: Vec<ColliderHandle> = world.soft_bodies[bar].meshes().map(|m| m.collider()).collect();
    let cut = world.cut_soft_body(bar, &blade_at_x(0.1)).expect("the blade crosses the bar");
    for &c in &originals {
        world.colliders[c].set_collision_groups(InteractionGroups::none());
    }
    for _ in 0..STEPS {
        hooks.step(&mut world);
    }
    let mut seen = [false; 2];
    for piece in cut.bodies() {
        let holds_originals = world.soft_bodies[piece].meshes().any(|m| originals.contains(&m.collider()));
        let low = lowest(&world, piece);
        if holds_originals {
            assert!(low < -1.0, "the piece the project took out of collisions rests at {low}");
        } else {
            assert!(low > -0.1, "the piece with the copies fell to {low}");
        }
        seen[usize::from(holds_originals)] = true;
    }
    assert_eq!(seen, [true, true], "a piece with the originals and one with the copies");
}

/// A bar cut in two whose source side the project removes before the next
/// step (the numbers of soft and rigid bodies are then as they were before
/// the cut): the piece left takes the bar's `NoPair` with the ground and
/// falls through it.
#[test]
fn a_piece_whose_source_is_removed_before_the_step_keeps_the_rule() {
    for way in WAYS {
        let (mut world, floor) = on_ground();
        let bar = world.insert_soft_body(soft_bar(at(0.0, 0.6), 1.0));
        let root = world.soft_bodies[bar].root_body();
        let mut hooks = RuleHooks::default();
        give(&mut hooks, way, root, floor, CollisionRule::NoPair);
        hooks.step(&mut world);
        let counts = (world.soft_bodies.len(), world.bodies.len());
        let cut = world.cut_soft_body(bar, &blade_at_x(0.1)).expect("the blade crosses the bar");
        let pieces: Vec<SoftBodyHandle> = cut.bodies().filter(|&p| p != bar).collect();
        world.remove_soft_body(bar);
        let after = (world.soft_bodies.len(), world.bodies.len());
        for _ in 0..STEPS {
            hooks.step(&mut world);
        }
        assert!(!pieces.is_empty(), "{way:?}: the cut made a piece");
        for piece in pieces {
            let low = lowest(&world, piece);
            assert!(low < -1.0, "{way:?}: piece {piece:?} rests at {low} (bodies {counts:?} before the cut, {after:?} after the removal)");
        }
    }
}

/// A soft block asleep on the ground wakes for a rule given while it
/// sleeps, and moves as the rule says; put back to sleep by hand (its root
/// body's `sleep`, which Rapier extends to the soft body), it wakes for an
/// edit again.
#[test]
fn a_sleeping_soft_body_wakes_for_a_new_rule() {
    for rule in [CollisionRule::NoResponse, CollisionRule::NoContacts, CollisionRule::NoPair] {
        let (mut world, floor) = on_ground();
        let block = world.insert_soft_body(soft_block(at(0.0, 0.6), 0.5));
        let root = world.soft_bodies[block].root_body();
        let mut hooks = RuleHooks::default();
        let mut steps = 0;
        while !world.soft_bodies[block].is_sleeping() {
            assert!(steps < 600, "{rule:?}: the block never fell asleep (lowest particle at {})", lowest(&world, block));
            hooks.step(&mut world);
            steps += 1;
        }
        let rested = lowest(&world, block);
        // A Normal rule wakes it (an edit wakes what it reaches) and lets it
        // rest; put back to sleep by hand, it sleeps through a step.
        hooks.rules_mut().set_specific(floor, root, CollisionRule::Normal);
        hooks.step(&mut world);
        world.bodies[root].sleep();
        hooks.step(&mut world);
        let low = lowest(&world, block);
        assert!(
            world.soft_bodies[block].is_sleeping() && low > -0.1,
            "{rule:?}: with Normal the block should sleep on the floor again: asleep {}, lowest particle at {low}",
            world.soft_bodies[block].is_sleeping()
        );
        hooks.rules_mut().set_specific(floor, root, rule);
        for _ in 0..STEPS {
            hooks.step(&mut world);
        }
        let low = lowest(&world, block);
        assert!(
            !world.soft_bodies[block].is_sleeping() && low < -1.0,
            "{rule:?}: asleep after {steps} steps at {rested}, the block should wake and fall through: lowest particle at {low}"
        );
    }
}

/// The pieces of a cut and of a tear keep their source's parent link: a
/// rule given to the parent reaches every piece, and the pieces fall
/// through the ground the parent's rule opens.
#[test]
fn the_pieces_of_a_cut_or_a_tear_keep_their_source_s_parent() {
    for how in ["cut", "tear"] {
        let (mut world, floor) = on_ground();
        let bar = world.insert_soft_body(soft_bar(at(0.0, 0.6), 1.0));
        let root = world.soft_bodies[bar].root_body();
        let rig = world.insert_body(RigidBodyBuilder::fixed().translation(at(100.0, 0.0)));
        let mut hooks = RuleHooks::default();
        hooks.rules_mut().set_parent(root, rig).expect("no cycle");
        hooks.rules_mut().set_specific(rig, floor, CollisionRule::NoPair);
        hooks.step(&mut world);
        let event = match how {
            "cut" => world.cut_soft_body(bar, &blade_at_x(0.1)),
            _ => {
                let edges = edges_across_middle(&world, bar);
                world.tear_soft_body(bar, &edges, &[])
            }
        };
        let pieces: Vec<SoftBodyHandle> = event.expect("the bar splits").bodies().collect();
        for _ in 0..STEPS {
            hooks.step(&mut world);
        }
        for piece in pieces {
            let piece_root = world.soft_bodies[piece].root_body();
            assert_eq!(hooks.rules().parent(piece_root), Some(rig), "{how}: piece {piece:?}'s parent");
            let low = lowest(&world, piece);
            assert!(low < -1.0, "{how}: piece {piece:?} falls through the ground its parent ignores: lowest particle at {low}");
        }
    }
}

/// A soft block over the ground, the pair `NoResponse`: it sinks through.
fn sinking_block() -> (PhysicsWorld, RuleHooks, SoftBodyHandle) {
    let (mut world, ground) = on_ground();
    let block = world.insert_soft_body(soft_block(at(0.0, 0.8), 0.5));
    let root = world.soft_bodies[block].root_body();
    let mut hooks = RuleHooks::default();
    hooks.rules_mut().set_specific(root, ground, CollisionRule::NoResponse);
    (world, hooks, block)
}

/// A project that calls the parts of a step itself and leaves out
/// `follow_soft_bodies`. Found by a soft-body game written from the docs
/// alone: the hooks never learnt the world had soft bodies, wrote the
/// jelly's `NoResponse` into solver groups that Rapier's soft-body solver
/// does not read, and the jelly rested on the ground it should fall through,
/// without a word. `after_step` now panics naming the call once the hooks
/// know of soft bodies: a plan met the jelly's collider, or an earlier
/// follow told them (`docs/semantics.md`, "Soft bodies", Stepping). The
/// same brackets with the call step as `hooks.step` does, and say nothing.
#[test]
fn a_bracket_without_follow_soft_bodies_fails_loudly_and_names_it() {
    use super::world::panic_message;
    /// Where a bracket follows the soft bodies.
    #[derive(Clone, Copy, Debug, PartialEq)]
    enum Follow {
        Before,
        Never,
        /// After `prepare`, which planned without it.
        After,
    }
    /// One bare bracket.
    fn bracket(world: &mut PhysicsWorld, hooks: &mut RuleHooks, follow: Follow) {
        if follow == Follow::Before {
            hooks.follow_soft_bodies(&world.soft_bodies, &world.bodies);
        }
        hooks.prepare(&world.bodies, &mut world.colliders);
        if follow == Follow::After {
            hooks.follow_soft_bodies(&world.soft_bodies, &world.bodies);
        }
        hooks.freeze_manifolds(&world.narrow_phase);
        hooks.wake_edited(&mut world.islands, &mut world.bodies);
        world.step_with_events(&*hooks, &());
        hooks.after_step(&world.narrow_phase, &world.bodies, &world.colliders);
    }
    let build = sinking_block;

    // Followed at every bracket: as `hooks.step`, bit for bit.
    let (mut world, mut hooks, block) = build();
    let (mut stepped, mut own, _) = build();
    for _ in 0..STEPS {
        bracket(&mut world, &mut hooks, Follow::Before);
        own.step(&mut stepped);
    }
    assert_eq!(particles(&world, block), particles(&stepped, block), "the brackets step as hooks.step");
    let fell = lowest(&world, block);
    assert!(fell < -0.5, "the block falls through the ground: lowest particle at {fell}");

    // Never followed, followed then left out, or followed after the
    // prepare it should have come before.
    for (followed, then) in [(0, Follow::Never), (3, Follow::Never), (0, Follow::After), (3, Follow::After)] {
        let (mut world, mut hooks, _) = build();
        for _ in 0..followed {
            bracket(&mut world, &mut hooks, Follow::Before);
        }
        let message = panic_message(|| bracket(&mut world, &mut hooks, then))
            .unwrap_or_else(|| panic!("followed {followed} times, then {then:?}: no panic"));
        assert!(
            message.contains("RuleHooks::follow_soft_bodies was not called") && message.contains("NoResponse"),
            "followed {followed} times, then {then:?}: the message names the call and what it does: {message}"
        );
    }

    // Found by a review: a project that follows while there are soft
    // bodies may stop once the last is gone.
    let (mut world, mut hooks, block) = build();
    for _ in 0..3 {
        bracket(&mut world, &mut hooks, Follow::Before);
    }
    world.remove_soft_body(block);
    for _ in 0..3 {
        bracket(&mut world, &mut hooks, Follow::Never);
    }
}

/// `world.step()` slipped in between two steps of the hooks, where a soft
/// block sinks through the ground under `NoResponse`. Found by the same
/// game: the hook answers a soft-rigid pair without response with no
/// contacts, and that pair was never the witness of a step without the
/// hooks, so the plain step pushed the block up unseen (a `NoContacts`
/// pair was caught). It is the witness now, checked as the `NoContacts`
/// answer it is (`docs/semantics.md`, "Stepping without the hooks"): a
/// debug build panics at the next step, a release build warns and says so
/// in that step's stats. With the hooks throughout nothing is said.
#[test]
fn a_step_without_the_hooks_is_caught_at_a_soft_pair_without_response() {
    use super::world::panic_message;
    let build = || {
        let (world, hooks, _) = sinking_block();
        (world, hooks)
    };
    // Until the block is in the ground, its pairs live.
    let sinking = 25;
    let (mut world, mut hooks) = build();
    let mut witnessed = 0;
    for step in 0..STEPS {
        hooks.step(&mut world);
        assert!(!hooks.stats().stepped_without_hooks, "step {step}: stepped with the hooks, said without");
        witnessed += usize::from(hooks.stats().soft_pairs_without_contacts > 0);
    }
    assert!(witnessed > 0, "the block's ground pairs were live without contacts");

    let (mut world, mut hooks) = build();
    for _ in 0..sinking {
        hooks.step(&mut world);
    }
    assert!(hooks.stats().soft_pairs_without_contacts > 0, "the block is in the ground by step {sinking}");
    world.step();
    if !cfg!(debug_assertions) {
        hooks.step(&mut world);
        assert!(hooks.stats().stepped_without_hooks, "went unnoticed: {:?}", hooks.stats());
        return;
    }
    let message = panic_message(|| hooks.step(&mut world)).unwrap_or_else(|| panic!("went unnoticed"));
    assert!(
        message.contains("NoResponse") && message.contains("never `world.step()`"),
        "the message names the rule and the fix: {message}"
    );
}
