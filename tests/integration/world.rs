//! The world the live-pair property tests, the fuzz driver and the soak
//! test edit and step: a ground slab and boxes, `RuleHooks`, and every edit
//! a user can make, each followed by checks of the hooks' invariants.

use std::collections::HashMap;

use super::rapier::prelude::*;
use super::rules::{
    CollisionGroup, CollisionRule, Node, OneWay, OneWayKind, RuleEvent, RuleHooks, Stage, Until,
};
use super::{at, blade_at_x, cube, pose_bits, slab, soft_bar, soft_piece};

#[derive(Clone, Debug)]
pub enum Edit {
    Personal(usize, CollisionRule),
    Group(usize, Option<usize>),
    Specific(usize, usize, CollisionRule),
    /// `set_specific_until` with an end from [`ends`] (an index).
    SpecificUntil(usize, usize, CollisionRule, usize),
    /// `set_one_way` on a node: an index into [`one_ways`], past its end
    /// for none.
    OneWay(usize, usize),
    GroupRule(usize, usize, CollisionRule),
    Parent(usize, usize),
    Unparent(usize),
    Share(usize, usize),
    DefaultRule(CollisionRule),
    Kind(usize, usize),
    RemoveCollider(usize),
    RemoveBody(usize),
    AddCube(f32, f32, usize),
    /// A second collider on a body.
    AddCollider(usize),
    /// A collider moved to another body through Rapier.
    MoveCollider(usize, usize),
    Sleep(usize),
    Wake(usize),
    /// The project sets a collider's collision groups through Rapier:
    /// indices into [`LAYERS`] for membership and filter.
    ProjectCollision(usize, usize, usize),
    /// The same for solver groups.
    ProjectSolver(usize, usize, usize),
    /// The project sets a collider's active collision types: an index into
    /// [`TYPES`].
    ProjectTypes(usize, usize),
    Step(usize),
    /// `remove_specific` between two nodes.
    RemoveSpecific(usize, usize),
    /// `set_rules_recursive` from a node.
    Recursive(usize),
    /// `set_group_rules_in_set` on some groups (indices), then
    /// `remove_group_rules_in_set` when the flag says so.
    InSet(Vec<usize>, CollisionRule, CollisionRule, bool),
    /// A body without colliders (a ragdoll's pelvis, a vehicle's frame).
    AddBody(usize),
    /// Several Rapier steps between one `prepare` and one `after_step`
    /// (what bevy_rapier does with substeps).
    Bracket(usize),
    /// The world saved and loaded back into a fresh world and fresh hooks
    /// (with `serde`), without any extra call: with its rule set (`true`),
    /// or alone, its rules given again as code gives them (the rule set
    /// without what its hooks wrote and decided).
    Reload(bool),
    /// A small soft body at a point: its root body and surface join the
    /// bodies and colliders the edits name.
    AddSoft(f32, f32),
    /// A soft body (by index among those added) cut across its middle:
    /// the pieces join the bodies and colliders the edits name.
    CutSoft(usize),
    /// A soft body torn along the edges that cross its middle.
    TearSoft(usize),
    /// A soft body removed, with its proxies and colliders.
    RemoveSoft(usize),
    /// A soft body put to sleep by hand (its root body's `sleep`, which
    /// Rapier extends to the soft body and the island it touches).
    SleepSoft(usize),
    /// A cluster of a soft body's upper particles added and its root's
    /// cluster removed: another cluster's proxy becomes the root.
    NewSoftRoot(usize),
    /// A soft bar pinned at both ends, the ends pulled apart step by step
    /// until it tears during a Rapier step (a strain tear).
    AddTearable(f32, f32),
    /// A save with one number changed (the leaf picked by the first value,
    /// the number the second) loaded into the hooks if the loader takes it
    /// (with `serde`): loads as an error or as a rule set the hooks keep
    /// clean.
    Corrupt(usize, u32),
}

/// What the rules held before a split (see `Run::check_pieces`).
struct Held {
    /// On the source's root.
    source: (CollisionRule, Option<CollisionGroup>),
    /// On every cluster proxy of every soft body.
    own: HashMap<RigidBodyHandle, (CollisionRule, Option<CollisionGroup>)>,
}

/// Layer sets a project may use as memberships or filters.
pub const LAYERS: [Group; 5] = [
    Group::ALL,
    Group::GROUP_1,
    Group::GROUP_2,
    Group::GROUP_1.union(Group::GROUP_2),
    Group::ALL.difference(Group::GROUP_1),
];

/// Collision types a project may set. Not every type: the crate gives a
/// hooked non-dynamic collider every type, and a project value equal to
/// what the crate wrote is read as no change (`docs/semantics.md`, section
/// 6), which the planner on and off would then read differently.
pub const TYPES: [ActiveCollisionTypes; 3] = [
    ActiveCollisionTypes::DYNAMIC_DYNAMIC
        .union(ActiveCollisionTypes::DYNAMIC_KINEMATIC)
        .union(ActiveCollisionTypes::DYNAMIC_FIXED),
    ActiveCollisionTypes::DYNAMIC_DYNAMIC
        .union(ActiveCollisionTypes::DYNAMIC_KINEMATIC)
        .union(ActiveCollisionTypes::DYNAMIC_FIXED)
        .union(ActiveCollisionTypes::KINEMATIC_FIXED),
    ActiveCollisionTypes::all().difference(ActiveCollisionTypes::FIXED_FIXED),
];

pub const KINDS: [RigidBodyType; 3] = [
    RigidBodyType::Dynamic,
    RigidBodyType::KinematicPositionBased,
    RigidBodyType::Fixed,
];
pub const GROUPS: usize = 4;

/// The one-way settings a node may be given: up in each semantics, and
/// sideways.
pub fn one_ways() -> [OneWay; 3] {
    [
        OneWay::new(at(0.0, 1.0)),
        OneWay::new(at(0.0, 1.0)).with_kind(OneWayKind::Godot),
        OneWay::new(at(1.0, 0.0)).with_max_angle(1.0),
    ]
}

/// The ends a rule may be given: apart (with and without a margin), a
/// count that is due at once, counts and a time that wait for apart, and a
/// count that ends even inside an overlap.
pub fn ends() -> [Until; 6] {
    [
        Until::apart(),
        Until::apart().with_margin(0.1),
        Until::steps(0),
        Until::steps(3),
        Until::seconds(0.05),
        Until::steps(2).even_if_overlapping(),
    ]
}

/// A handle's raw parts, to sort and compare pairs.
pub type Raw = (u32, u32);

pub struct Run {
    pub world: PhysicsWorld,
    /// Dynamic bodies are created with all axes locked (they never move).
    locked: bool,
    pub hooks: RuleHooks,
    groups: Vec<CollisionGroup>,
    bodies: Vec<RigidBodyHandle>,
    colliders: Vec<ColliderHandle>,
    removed: Vec<ColliderHandle>,
    /// The soft bodies added, and the pieces of their cuts.
    softs: Vec<SoftBodyHandle>,
    /// Soft bodies pulled apart until they tear.
    pulled: Vec<Pulled>,
    /// The settings the project gave colliders through Rapier.
    project: HashMap<ColliderHandle, Project>,
    /// For colliders the project changed since the last step: their
    /// settings then (what the crate wrote) and the project's then.
    since_step: HashMap<ColliderHandle, (Project, Project)>,
    /// The number of colliders, and of removed ones, when this run last
    /// stepped.
    at_last_step: (usize, usize),
    /// A one-way surface was given since the run began.
    pub one_ways: bool,
    /// With rule events recorded: the live pairs as the events tell them.
    replayed: Option<std::collections::BTreeMap<(Raw, Raw), CollisionRule>>,
}

/// A soft body pulled apart: the particles of its ends with where they
/// started and which way they go, the number of soft bodies when the pull
/// began, the steps pulled.
struct Pulled {
    soft: SoftBodyHandle,
    ends: Vec<(u32, Vector, f32)>,
    softs: usize,
    steps: usize,
}

impl Pulled {
    /// Moves the ends' targets 2.5 cm a step further apart, for a second at
    /// most, until a piece splits off (or the body is cut or gone). Whether
    /// to keep pulling.
    fn pull(&mut self, world: &mut PhysicsWorld) -> bool {
        let softs = world.soft_bodies.len();
        let Some(body) = world.soft_bodies.get_mut(self.soft) else {
            return false;
        };
        if softs != self.softs || self.steps >= 60 {
            return false;
        }
        self.steps += 1;
        let pull = 0.025 * self.steps as f32;
        for &(i, start, way) in &self.ends {
            if (i as usize) < body.num_particles() {
                body.set_particle_kinematic_target(i as usize, start + at(way * pull, 0.0));
            }
        }
        true
    }
}

/// The mean x of a soft body's particles.
fn middle_x(body: &SoftBody) -> f32 {
    body.particle_positions().map(|p| p.x).sum::<f32>() / body.num_particles().max(1) as f32
}

/// The edges of a soft body that cross the plane (or line) at `x`.
pub fn edges_across(body: &SoftBody, x: f32) -> Vec<u32> {
    let left = |v: u32| body.particle_position(v as usize).x < x;
    (0..body.edges().len() as u32)
        .filter(|&e| {
            let [a, b] = body.edges()[e as usize].vertices;
            left(a) != left(b)
        })
        .collect()
}

/// A collider's settings as its project set them.
#[derive(Clone, Copy, Debug)]
struct Project {
    collision: InteractionGroups,
    solver: InteractionGroups,
    types: ActiveCollisionTypes,
}

impl Default for Project {
    fn default() -> Self {
        Project {
            collision: InteractionGroups::all(),
            solver: InteractionGroups::all(),
            types: ActiveCollisionTypes::default(),
        }
    }
}

impl Run {
    pub fn new(cubes: &[(f32, f32, usize)], planner: bool, locked: bool) -> Run {
        let mut world = PhysicsWorld::new();
        if locked {
            world.gravity = Vector::ZERO;
        }
        // Recycling makes native pairs' contacts differ in the last bits from
        // hooked ones; without it the two runs can be compared exactly.
        world.integration_parameters.contact_recycling = !locked;
        let ground = world.insert_body(RigidBodyBuilder::fixed().translation(at(0.0, -0.5)));
        let floor = world.insert_collider(slab(5.0, 0.5), Some(ground));
        let mut hooks = RuleHooks::default();
        hooks.set_planner(planner);
        let mut groups = vec![
            CollisionGroup::DEFAULT_DYNAMIC,
            CollisionGroup::DEFAULT_KINEMATIC,
        ];
        groups.extend((2..GROUPS).map(|_| hooks.rules_mut().create_group()));
        let mut run = Run {
            world,
            locked,
            hooks,
            groups,
            bodies: vec![ground],
            colliders: vec![floor],
            removed: Vec::new(),
            softs: Vec::new(),
            pulled: Vec::new(),
            project: HashMap::new(),
            since_step: HashMap::new(),
            at_last_step: (0, 0),
            replayed: None,
            one_ways: false,
        };
        for &(x, y, kind) in cubes {
            run.add_cube(x, y, kind);
        }
        run
    }

    fn add_cube(&mut self, x: f32, y: f32, kind: usize) {
        let mut builder = RigidBodyBuilder::new(KINDS[kind]).translation(at(x, y));
        if self.locked {
            builder = builder.locked_axes(LockedAxes::all()).can_sleep(false);
        }
        let body = self.world.insert_body(builder);
        let collider = self.world.insert_collider(cube(0.4), Some(body));
        self.bodies.push(body);
        self.colliders.push(collider);
    }

    /// Names the pieces of cuts and tears (strain tears happen in Rapier's
    /// step) in the edits. A cut leaves the source's colliders on one side
    /// and Rapier's copies of them, the project's settings on them
    /// included, on the other (the source's side may get the copies, and
    /// the piece the source's root): each copy has the project's settings
    /// of the collider it copies, mesh by mesh.
    fn adopt_pieces(&mut self) {
        let mut pieces: Vec<SoftBodyHandle> = self
            .world
            .soft_bodies
            .iter()
            .map(|(h, _)| h)
            .filter(|h| !self.softs.contains(h))
            .collect();
        pieces.sort_unstable_by_key(|h| h.into_raw_parts());
        for piece in pieces {
            let bodies = &self.world.soft_bodies;
            let meshes = |h: SoftBodyHandle| -> Vec<ColliderHandle> {
                bodies
                    .get(h)
                    .map_or_else(Vec::new, |b| b.meshes().map(|m| m.collider()).collect())
            };
            let source = bodies[piece].origin().filter(|&o| bodies.contains(o));
            let sides = [source.map_or_else(Vec::new, meshes), meshes(piece)];
            let source_root = source.map(|s| bodies[s].root_body());
            self.adopt_soft(piece);
            if let Some(root) = source_root.filter(|r| !self.bodies.contains(r)) {
                self.bodies.push(root);
            }
            for (side, other) in [(0, 1), (1, 0)] {
                for (i, &copy) in sides[side].iter().enumerate() {
                    if !self.colliders.contains(&copy) {
                        self.colliders.push(copy);
                    }
                    if self.project.contains_key(&copy) {
                        continue;
                    }
                    let original = sides[other].get(i).or(sides[other].first());
                    if let Some(&project) = original.and_then(|c| self.project.get(c)) {
                        self.project.insert(copy, project);
                    }
                }
            }
        }
    }

    /// What the rules hold on a soft body's root: its personal rule and
    /// group.
    fn soft_rules(&self, root: RigidBodyHandle) -> (CollisionRule, Option<CollisionGroup>) {
        let rules = self.hooks.rules();
        (rules.personal(root), rules.group(root))
    }

    /// What the rules hold, before a cut or a tear, on the source's root
    /// and on every body that may become a piece's root (the proxies of
    /// every soft body's clusters), once the hooks have followed what came
    /// before (a piece takes what its source holds when the hooks first
    /// see it: an edit between an earlier split and that reaches it too).
    fn before_split(&mut self, root: RigidBodyHandle) -> Held {
        self.hooks
            .follow_soft_bodies(&self.world.soft_bodies, &self.world.bodies);
        let proxies = self
            .world
            .soft_bodies
            .iter()
            .flat_map(|(_, b)| b.live_clusters().map(|(_, c)| c.proxy()));
        Held {
            source: self.soft_rules(root),
            own: proxies.map(|p| (p, self.soft_rules(p))).collect(),
        }
    }

    /// Every soft body a cut or a tear left holds on its root the rules the
    /// source's root held before it, once the hooks follow, unless its root
    /// held rules of its own then (a proxy the edits gave rules, or a piece
    /// of an earlier split): it keeps those. A check of its own, beside the
    /// comparisons of whole runs, which follow alike.
    fn check_pieces(&mut self, split: Option<SoftBodyTearEvent>, held: Held) {
        let Some(split) = split else {
            return;
        };
        self.hooks
            .follow_soft_bodies(&self.world.soft_bodies, &self.world.bodies);
        for piece in split.bodies() {
            let Some(body) = self.world.soft_bodies.get(piece) else {
                continue;
            };
            let root = body.root_body();
            let own = held
                .own
                .get(&root)
                .copied()
                .filter(|&r| r != (CollisionRule::Defer, None));
            let expected = own.unwrap_or(held.source);
            assert_eq!(
                self.soft_rules(root),
                expected,
                "piece {piece:?} (root {root:?}) of {:?}",
                split.soft_body
            );
        }
    }

    /// Whether `other` names the same objects as this run, so that the
    /// same edits do the same to both: a cut of a soft body that moved
    /// differently in each may split it differently.
    pub fn names_alike(&self, other: &Run) -> bool {
        self.bodies == other.bodies
            && self.colliders == other.colliders
            && self.softs == other.softs
    }

    /// Whether a soft body was ever added to the world.
    pub fn has_soft_bodies(&self) -> bool {
        !self.softs.is_empty()
    }

    /// The soft body an edit names by `i` (among those added), if it is
    /// still in the world.
    fn soft(&self, i: usize) -> Option<(SoftBodyHandle, &SoftBody)> {
        let soft = *self.softs.get(i % self.softs.len().max(1))?;
        Some((soft, self.world.soft_bodies.get(soft)?))
    }

    /// Names a soft body's root body and surface colliders in the edits.
    fn adopt_soft(&mut self, soft: SoftBodyHandle) {
        let Some(body) = self.world.soft_bodies.get(soft) else {
            return;
        };
        self.softs.push(soft);
        self.bodies.push(body.root_body());
        self.colliders.extend(body.meshes().map(|m| m.collider()));
    }

    fn node(&self, i: usize) -> Node {
        let i = i % (self.bodies.len() + self.colliders.len());
        match i.checked_sub(self.bodies.len()) {
            None => Node::Body(self.bodies[i]),
            Some(c) => Node::Collider(self.colliders[c]),
        }
    }

    fn body(&self, i: usize) -> RigidBodyHandle {
        self.bodies[i % self.bodies.len()]
    }

    pub fn apply(&mut self, edit: &Edit) {
        let groups = self.groups.clone();
        match *edit {
            Edit::Personal(x, r) => {
                let node = self.node(x);
                self.hooks.rules_mut().set_personal(node, r);
            }
            Edit::Group(x, g) => {
                let node = self.node(x);
                self.hooks.rules_mut().set_group(node, g.map(|g| groups[g]));
            }
            Edit::Specific(x, y, r) => {
                let (node, other) = (self.node(x), self.node(y));
                self.hooks.rules_mut().set_specific(node, other, r);
            }
            Edit::OneWay(x, w) => {
                let node = self.node(x);
                let one_way = one_ways().get(w).copied();
                self.one_ways |= one_way.is_some();
                self.hooks.rules_mut().set_one_way(node, one_way);
            }
            Edit::SpecificUntil(x, y, r, u) => {
                let (node, other) = (self.node(x), self.node(y));
                let until = ends()[u % ends().len()];
                self.hooks
                    .rules_mut()
                    .set_specific_until(node, other, r, until);
            }
            Edit::GroupRule(a, b, r) => self
                .hooks
                .rules_mut()
                .set_group_rule(groups[a], groups[b], r),
            Edit::Parent(c, p) => {
                let (child, parent) = (self.body(c), self.body(p));
                let _ = self.hooks.rules_mut().set_parent(child, parent);
            }
            Edit::Unparent(c) => {
                let child = self.body(c);
                self.hooks.rules_mut().remove_parent(child);
            }
            Edit::Share(a, b) => {
                let (from, to) = (self.node(a), self.node(b));
                self.hooks.rules_mut().share_rules(from, to);
            }
            Edit::DefaultRule(r) => self.hooks.rules_mut().set_default_rule(r),
            Edit::Kind(b, k) => {
                let handle = self.body(b);
                // A soft body's proxy gets its type from Rapier alone.
                let soft = self
                    .world
                    .bodies
                    .get(handle)
                    .is_some_and(|b| b.is_soft_frame());
                if let Some(body) = self.world.bodies.get_mut(handle).filter(|_| !soft) {
                    body.set_body_type(KINDS[k], true);
                }
            }
            Edit::RemoveCollider(c) => {
                let handle = self.colliders[c % self.colliders.len()];
                if self.world.remove_collider(handle).is_some() {
                    self.removed.push(handle);
                }
            }
            Edit::RemoveBody(b) => {
                let handle = self.body(b);
                if let Some(body) = self.world.remove_body(handle) {
                    self.removed.extend_from_slice(body.colliders());
                }
            }
            Edit::AddCube(x, y, kind) => self.add_cube(x, y, kind),
            Edit::AddSoft(x, y) => {
                let soft = self.world.insert_soft_body(soft_piece(at(x, y)));
                self.adopt_soft(soft);
            }
            Edit::CutSoft(i) => {
                let Some((soft, body)) = self.soft(i) else {
                    return;
                };
                let (middle, root) = (middle_x(body) + 0.01, body.root_body());
                let held = self.before_split(root);
                let cut = self.world.cut_soft_body(soft, &blade_at_x(middle));
                self.adopt_pieces();
                self.check_pieces(cut, held);
            }
            Edit::TearSoft(i) => {
                let Some((soft, body)) = self.soft(i) else {
                    return;
                };
                let (edges, root) = (edges_across(body, middle_x(body)), body.root_body());
                let held = self.before_split(root);
                let tear = self.world.tear_soft_body(soft, &edges, &[]);
                self.adopt_pieces();
                self.check_pieces(tear, held);
            }
            Edit::RemoveSoft(i) => {
                let Some((soft, body)) = self.soft(i) else {
                    return;
                };
                let meshes: Vec<ColliderHandle> = body.meshes().map(|m| m.collider()).collect();
                if self.world.remove_soft_body(soft).is_some() {
                    self.removed.extend(meshes);
                }
            }
            Edit::SleepSoft(i) => {
                let Some((_, body)) = self.soft(i) else {
                    return;
                };
                let root = body.root_body();
                if let Some(root) = self.world.bodies.get_mut(root) {
                    root.sleep();
                }
            }
            Edit::NewSoftRoot(i) => {
                let Some((soft, body)) = self.soft(i) else {
                    return;
                };
                let Some((root_cluster, _)) = body
                    .live_clusters()
                    .find(|(_, c)| c.proxy() == body.root_body())
                else {
                    return;
                };
                let middle = body.particle_positions().map(|p| p.y).sum::<f32>()
                    / body.particle_positions().count().max(1) as f32;
                let upper: Vec<u32> = (0..body.particle_positions().count() as u32)
                    .filter(|&v| body.particle_position(v as usize).y > middle)
                    .collect();
                if self.world.add_soft_body_cluster(soft, &upper).is_some() {
                    let meshes: Vec<ColliderHandle> = self.world.soft_bodies[soft]
                        .meshes()
                        .map(|m| m.collider())
                        .collect();
                    self.world.remove_soft_body_cluster(soft, root_cluster);
                    // The root's meshes go with its cluster.
                    if let Some(body) = self.world.soft_bodies.get(soft) {
                        let left: Vec<ColliderHandle> =
                            body.meshes().map(|m| m.collider()).collect();
                        self.removed
                            .extend(meshes.into_iter().filter(|c| !left.contains(c)));
                        let root = body.root_body();
                        if !self.bodies.contains(&root) {
                            self.bodies.push(root);
                        }
                    } else {
                        self.removed.extend(meshes);
                    }
                }
            }
            Edit::AddTearable(x, y) => {
                let builder = soft_bar(at(x, y), 1.0);
                let ends: Vec<u32> = (0..builder.particle_positions().len() as u32)
                    .filter(|&i| (builder.particle_positions()[i as usize].x - x).abs() > 0.99)
                    .collect();
                let soft = self
                    .world
                    .insert_soft_body(builder.pinned_particles(ends.clone()).tear_strain(0.3));
                let body = &self.world.soft_bodies[soft];
                let ends = ends
                    .iter()
                    .map(|&i| {
                        let start = body.particle_position(i as usize);
                        (i, start, if start.x > x { 1.0 } else { -1.0 })
                    })
                    .collect();
                let softs = self.world.soft_bodies.len();
                self.pulled.push(Pulled {
                    soft,
                    ends,
                    softs,
                    steps: 0,
                });
                self.adopt_soft(soft);
            }
            Edit::AddCollider(b) => {
                let handle = self.body(b);
                if self.world.bodies.contains(handle) {
                    let shape = ColliderBuilder::ball(0.3).translation(at(0.0, 0.5));
                    let collider = self.world.insert_collider(shape, Some(handle));
                    self.colliders.push(collider);
                }
            }
            Edit::MoveCollider(c, b) => {
                let (handle, body) = (self.colliders[c % self.colliders.len()], self.body(b));
                let world = &mut self.world;
                // A soft body's surface stays bound to its cluster; rigid
                // colliders move between rigid bodies and proxies.
                let bound = world
                    .colliders
                    .get(handle)
                    .is_some_and(|c| c.deformable_mesh_ref().is_some());
                if world.colliders.contains(handle) && world.bodies.contains(body) && !bound {
                    world
                        .colliders
                        .set_parent(handle, Some(body), &mut world.bodies);
                }
            }
            Edit::Sleep(b) => {
                if let Some(body) = self.world.bodies.get_mut(self.body(b)) {
                    body.sleep();
                }
            }
            Edit::Wake(b) => {
                let handle = self.body(b);
                if self.world.bodies.contains(handle) {
                    self.world.wake_up(handle, true);
                }
            }
            // The crate takes a setting that differs, at the next step, from
            // what it wrote as the project's new one; one that comes back to
            // what the crate wrote changes nothing (`docs/semantics.md`,
            // section 6). The crate wrote what the collider had when this
            // run last stepped.
            Edit::ProjectCollision(c, m, f) | Edit::ProjectSolver(c, m, f) => {
                let handle = self.colliders[c % self.colliders.len()];
                let groups = InteractionGroups::new(LAYERS[m], LAYERS[f], InteractionTestMode::And);
                self.remember(handle);
                if let Some(collider) = self.world.colliders.get_mut(handle) {
                    if matches!(edit, Edit::ProjectCollision(..)) {
                        collider.set_collision_groups(groups);
                    } else {
                        collider.set_solver_groups(groups);
                    }
                }
                self.project_changed(handle);
                self.settings_changed();
            }
            Edit::ProjectTypes(c, t) => {
                let handle = self.colliders[c % self.colliders.len()];
                self.remember(handle);
                if let Some(collider) = self.world.colliders.get_mut(handle) {
                    collider.set_active_collision_types(TYPES[t]);
                    // Rapier sets no change flag for the types: nudging the
                    // groups makes it look at the collider's pairs again.
                    let groups = collider.collision_groups();
                    collider.set_collision_groups(InteractionGroups::none());
                    collider.set_collision_groups(groups);
                }
                self.project_changed(handle);
                self.settings_changed();
            }
            Edit::Step(n) => {
                for _ in 0..n {
                    self.step();
                }
            }
            Edit::RemoveSpecific(x, y) => {
                let (node, other) = (self.node(x), self.node(y));
                self.hooks.rules_mut().remove_specific(node, other);
            }
            Edit::Recursive(x) => {
                let node = self.node(x);
                let (bodies, colliders) = (&self.world.bodies, &self.world.colliders);
                self.hooks
                    .rules_mut()
                    .set_rules_recursive(node, bodies, colliders);
            }
            Edit::InSet(ref set, a, b, remove) => {
                let set: Vec<CollisionGroup> = set.iter().map(|&g| groups[g % GROUPS]).collect();
                let rules = self.hooks.rules_mut();
                if remove {
                    rules.remove_group_rules_in_set(&set);
                } else {
                    rules.set_group_rules_in_set(&set, a, b);
                }
            }
            Edit::Bracket(n) => {
                self.before_step();
                let (hooks, w) = (&mut self.hooks, &mut self.world);
                hooks.follow_soft_bodies(&w.soft_bodies, &w.bodies);
                hooks.prepare(&w.bodies, &mut w.colliders);
                hooks.freeze_manifolds(&w.narrow_phase);
                hooks.wake_edited(&mut w.islands, &mut w.bodies);
                for _ in 0..n {
                    w.step_with_events(&*hooks, &());
                }
                hooks.after_step(&w.narrow_phase, &w.bodies, &w.colliders);
                self.adopt_pieces();
                self.check();
                self.replay_events();
            }
            Edit::Reload(_with_rule_set) => {
                // The world saved, as a game saves (no extra call), and
                // loaded into a fresh world and fresh hooks, which go on from
                // there (`docs/semantics.md`, "Saving and loading"): with its
                // rule set, or alone with the rules given again by code.
                #[cfg(feature = "serde")]
                {
                    let mut rules =
                        serde_json::to_value(self.hooks.rules()).expect("a rule set saves");
                    if !_with_rule_set {
                        let fields = rules.as_object_mut().expect("a rule set is a map");
                        fields.remove("writes");
                        fields.remove("decisions");
                    }
                    let saved = serde_json::to_string(&(&self.world, rules))
                        .expect("a world and its rule set save");
                    let (world, rules): (PhysicsWorld, super::rules::CollisionRuleSet) =
                        serde_json::from_str(&saved).expect("a save loads");
                    let mut hooks = RuleHooks::new(rules);
                    hooks.set_planner(self.hooks.planner());
                    if self.replayed.is_some() {
                        // Fresh hooks tell every live pair as started.
                        hooks.record_rule_events(true);
                        self.replayed = Some(Default::default());
                    }
                    self.world = world;
                    self.hooks = hooks;
                }
            }
            Edit::Corrupt(_leaf, _number) => {
                #[cfg(feature = "serde")]
                {
                    let mut value =
                        serde_json::to_value(self.hooks.rules()).expect("a rule set saves");
                    let mut leaves = Vec::new();
                    numeric_leaves(&value, String::new(), &mut leaves);
                    if let Some(at) = leaves.get(_leaf % leaves.len().max(1)) {
                        if let Some(leaf) = value.pointer_mut(at) {
                            *leaf = serde_json::json!(_number);
                        }
                    }
                    if std::env::var("DRIVER_LOG").is_ok() {
                        eprintln!(
                            "corrupt {:?} -> {_number}: {value}",
                            leaves.get(_leaf % leaves.len().max(1))
                        );
                    }
                    if let Ok(loaded) = serde_json::from_value(value) {
                        let rules = self.hooks.rules_mut();
                        *rules = loaded;
                        // A smaller saved group count forgets groups this
                        // run hands out: made again, with the same ids.
                        while (rules.group_count() as usize) < GROUPS {
                            rules.create_group();
                        }
                    }
                }
            }
            Edit::AddBody(kind) => {
                let mut builder = RigidBodyBuilder::new(KINDS[kind % KINDS.len()]);
                if self.locked {
                    builder = builder.locked_axes(LockedAxes::all()).can_sleep(false);
                }
                let body = self.world.insert_body(builder);
                self.bodies.push(body);
            }
        }
    }

    pub fn step(&mut self) {
        let world = &mut self.world;
        self.pulled.retain_mut(|pulled| pulled.pull(world));
        self.before_step();
        self.hooks.step(&mut self.world);
        self.adopt_pieces();
        self.check();
        self.replay_events();
    }

    /// Records rule events from the next step on, and checks after every
    /// step that they tell the live pairs (see `replay_events`).
    pub fn record_rule_events(&mut self) {
        self.hooks.record_rule_events(true);
        self.replayed = Some(Default::default());
    }

    /// With rule events recorded: applies this step's events to the live
    /// pairs they told so far, checking each event against them (a pair is
    /// created only if it was not live, changes or ends only with the rule
    /// it had), and checks that the result is the live pairs `pairs` gives.
    fn replay_events(&mut self) {
        let Some(mut replayed) = self.replayed.take() else {
            return;
        };
        let events: Vec<RuleEvent> = self.hooks.drain_rule_events().collect();
        let mut last = None;
        for event in events {
            let (key, told) = match event {
                RuleEvent::PairStarted {
                    collider1,
                    collider2,
                    rule,
                } => {
                    let key = (collider1.into_raw_parts(), collider2.into_raw_parts());
                    assert!(!replayed.contains_key(&key), "{event:?}: the pair was live");
                    assert_ne!(rule, CollisionRule::NoPair, "{event:?}");
                    (key, Some(rule))
                }
                RuleEvent::RuleChanged {
                    collider1,
                    collider2,
                    from,
                    to,
                    ..
                } => {
                    let key = (collider1.into_raw_parts(), collider2.into_raw_parts());
                    assert_eq!(
                        replayed.get(&key),
                        Some(&from),
                        "{event:?}: the rule it had"
                    );
                    assert_ne!(from, to, "{event:?}");
                    (key, (to != CollisionRule::NoPair).then_some(to))
                }
                RuleEvent::PairEnded {
                    collider1,
                    collider2,
                    rule,
                } => {
                    let key = (collider1.into_raw_parts(), collider2.into_raw_parts());
                    assert_eq!(
                        replayed.get(&key),
                        Some(&rule),
                        "{event:?}: the rule it had"
                    );
                    (key, None)
                }
                _ => unreachable!("{event:?}: a new kind of event"),
            };
            assert!(key.0 < key.1, "{event:?}: colliders in handle order");
            assert!(
                last < Some(key),
                "{event:?}: events in the pairs' order, one per pair"
            );
            last = Some(key);
            match told {
                Some(rule) => replayed.insert(key, rule),
                None => replayed.remove(&key),
            };
        }
        let told: Vec<(Raw, Raw, CollisionRule)> =
            replayed.iter().map(|(&(a, b), &r)| (a, b, r)).collect();
        assert_eq!(told, self.live(), "the rule events tell the live pairs");
        self.replayed = Some(replayed);
    }

    /// The live pairs with their rules, sorted.
    pub fn live(&self) -> Vec<(Raw, Raw, CollisionRule)> {
        let mut live: Vec<_> = self
            .hooks
            .pairs(&self.world)
            .map(|(a, b, rule)| {
                let (a, b) = (a.into_raw_parts(), b.into_raw_parts());
                (a.min(b), a.max(b), rule)
            })
            .collect();
        live.sort();
        live
    }

    /// The live pairs the hooks keep in their own table (`hooked_pairs()`),
    /// sorted.
    pub fn known(&self) -> Vec<(Raw, Raw, CollisionRule)> {
        let mut known: Vec<_> = self
            .hooks
            .hooked_pairs()
            .map(|(a, b, rule)| {
                let (a, b) = (a.into_raw_parts(), b.into_raw_parts());
                (a.min(b), a.max(b), rule)
            })
            .collect();
        known.sort();
        known
    }

    /// Every body's position, bit for bit, in handle order, then every
    /// soft body's particles.
    pub fn poses(&self) -> Vec<Vec<u32>> {
        let mut poses: Vec<_> = self
            .world
            .bodies
            .iter()
            .map(|(handle, body)| {
                let (index, _) = handle.into_raw_parts();
                (index, pose_bits(body.position()))
            })
            .collect();
        poses.sort_by_key(|p| p.0);
        // And every soft body's particles, in handle order.
        let mut softs: Vec<_> = self
            .world
            .soft_bodies
            .iter()
            .map(|(handle, soft)| {
                let bits = soft
                    .particle_positions()
                    .flat_map(|p| p.to_array().map(f32::to_bits))
                    .collect::<Vec<u32>>();
                (handle.into_raw_parts(), bits)
            })
            .collect();
        softs.sort_by_key(|s| s.0);
        poses
            .into_iter()
            .map(|p| p.1)
            .chain(softs.into_iter().map(|s| s.1))
            .collect()
    }

    /// The pairs with contacts, sorted.
    pub fn touching(&self) -> Vec<(Raw, Raw)> {
        let mut touching: Vec<_> = self
            .world
            .narrow_phase
            .contact_pairs()
            .filter(|pair| pair.has_any_active_contact())
            .map(|pair| {
                let (a, b) = (
                    pair.collider1.into_raw_parts(),
                    pair.collider2.into_raw_parts(),
                );
                (a.min(b), a.max(b))
            })
            .collect();
        touching.sort();
        touching
    }

    fn settings_of(&self, handle: ColliderHandle) -> Option<Project> {
        let collider = self.world.colliders.get(handle)?;
        Some(Project {
            collision: collider.collision_groups(),
            solver: collider.solver_groups(),
            types: collider.active_collision_types(),
        })
    }

    /// Before the project's first change of `handle` since the last step:
    /// its settings then (what the crate wrote) and the project's.
    fn remember(&mut self, handle: ColliderHandle) {
        if let Some(stepped) = self.settings_of(handle) {
            let model = self.project_of(handle);
            self.since_step.entry(handle).or_insert((stepped, model));
        }
    }

    /// Records what the project's settings of `handle` are after it changed
    /// one through Rapier: a setting that differs from what the collider had
    /// when this run last stepped is the project's.
    fn project_changed(&mut self, handle: ColliderHandle) {
        let (Some(now), Some(&(stepped, model))) =
            (self.settings_of(handle), self.since_step.get(&handle))
        else {
            return;
        };
        let mut project = model;
        if now.collision != stepped.collision {
            project.collision = now.collision;
        }
        if now.solver != stepped.solver {
            project.solver = now.solver;
        }
        if now.types != stepped.types {
            project.types = now.types;
        }
        self.project.insert(handle, project);
    }

    /// Starts a step. A step that removed as many colliders as it added,
    /// some with layers of their own, leaves the count of colliders as it
    /// was: the project says so (`docs/semantics.md`, "Where the two meet
    /// in Rapier's 32 bits").
    fn before_step(&mut self) {
        self.since_step.clear();
        let (count, removed) = self.at_last_step;
        let layered_gone = self.removed[removed.min(self.removed.len())..]
            .iter()
            .any(|c| self.project.contains_key(c));
        if layered_gone && self.world.colliders.len() == count {
            self.settings_changed();
        }
        self.at_last_step = (self.world.colliders.len(), self.removed.len());
    }

    /// What a project is told to do after changing settings through
    /// Rapier while the plan shares group bits with them
    /// (`docs/semantics.md`, section 6): the hooks do not look at colliders
    /// the rules do not reach.
    fn settings_changed(&mut self) {
        if self.hooks.stats().shares_project_bits {
            self.hooks.project_settings_changed();
        }
    }

    fn project_of(&self, c: ColliderHandle) -> Project {
        self.project.get(&c).copied().unwrap_or_default()
    }

    /// Whether the project's own collision groups let `a` and `b` pair.
    pub fn project_allows(&self, a: ColliderHandle, b: ColliderHandle) -> bool {
        self.project_of(a)
            .collision
            .test(self.project_of(b).collision)
    }

    /// The rule of a pair, read from the rules and the project's settings:
    /// `resolve`, except that a pair of two non-dynamic bodies the
    /// project's collision types let Rapier see is not refused by the
    /// `(DEFAULT_KINEMATIC, DEFAULT_KINEMATIC)` entry.
    pub fn reference(&self, a: ColliderHandle, b: ColliderHandle) -> CollisionRule {
        let (bodies, colliders) = (&self.world.bodies, &self.world.colliders);
        let rules = self.hooks.rules();
        let why = rules.explain(bodies, colliders, a, b);
        let kind = |c: ColliderHandle| {
            colliders
                .get(c)
                .and_then(|c| c.parent())
                .and_then(|b| bodies.get(b))
                .map_or(RigidBodyType::Fixed, |b| b.body_type())
        };
        let (ka, kb) = (kind(a), kind(b));
        // The groups that met in the table: a node up a chain counts as the
        // colliding body's default group (`semantics.md`, "Terms"), which
        // its own `effective_group` (its own body's) need not be.
        let kinematic = CollisionGroup::DEFAULT_KINEMATIC;
        let by_entry = why.stage == Stage::Group
            && why.rule == CollisionRule::NoPair
            && why.groups == Some((kinematic, kinematic));
        let typed = self.project_of(a).types.test(ka, kb) || self.project_of(b).types.test(ka, kb);
        if by_entry && !ka.is_dynamic() && !kb.is_dynamic() && typed {
            match rules.default_rule() {
                CollisionRule::Normal => CollisionRule::NoResponse,
                other => other,
            }
        } else {
            why.rule
        }
    }

    /// What decides the pair of `a` and `b`, for assert messages.
    fn describe(&self, a: ColliderHandle, b: ColliderHandle) -> String {
        let (bodies, colliders) = (&self.world.bodies, &self.world.colliders);
        let groups =
            |g: InteractionGroups| format!("{:#x}/{:#x}", g.memberships.bits(), g.filter.bits());
        let side = |c: ColliderHandle| {
            let collider = &colliders[c];
            let kind = collider.parent().map(|b| bodies[b].body_type());
            let project = self.project_of(c);
            format!(
                "{kind:?}, project groups {} solver {} types {:#x}, now groups {} types {:#x} hooks {:#x}",
                groups(project.collision),
                groups(project.solver),
                project.types.bits(),
                groups(collider.collision_groups()),
                collider.active_collision_types().bits(),
                collider.active_hooks().bits()
            )
        };
        format!(
            "{:?}, active bodies {}; {:?}; a: {}; b: {}",
            self.hooks.stats(),
            self.world.islands.num_active_bodies(),
            self.hooks.rules().explain(bodies, colliders, a, b),
            side(a),
            side(b)
        )
    }

    fn check(&self) {
        let (bodies, colliders) = (&self.world.bodies, &self.world.colliders);
        let rules = self.hooks.rules();
        for (a, b, rule) in self.hooks.hooked_pairs() {
            assert!(
                colliders.contains(a) && colliders.contains(b),
                "live pair ({a:?}, {b:?}) names a removed collider"
            );
            let fresh = self.reference(a, b);
            assert_eq!(
                rule,
                fresh,
                "live pair ({a:?}, {b:?}) is stale: {}",
                self.describe(a, b)
            );
            assert_ne!(rule, CollisionRule::NoPair);
        }
        let narrow_phase = &self.world.narrow_phase;
        let sensors = narrow_phase.intersection_pairs().map(|(a, b, _)| (a, b));
        // Colliders of one body form no pair, though Rapier's graph may
        // hold an edge for them.
        let body = |c: ColliderHandle| colliders.get(c).and_then(|c| c.parent());
        let rapier: Vec<_> = narrow_phase
            .contact_pairs()
            .map(|p| (p.collider1, p.collider2))
            .chain(sensors)
            .filter(|&(a, b)| body(a).is_none() || body(a) != body(b))
            .collect();
        for &(a, b) in &rapier {
            // Live only where both the project's groups and the rules allow.
            let expected = Some(self.reference(a, b))
                .filter(|&r| r != CollisionRule::NoPair && self.project_allows(a, b));
            assert_eq!(
                self.hooks.pair_rule(&self.world, a, b),
                expected,
                "Rapier's pair ({a:?}, {b:?}): {}",
                self.describe(a, b)
            );
            // The hooks' own table holds the pairs it knows, exactly.
            let known = self
                .hooks
                .hooked_pairs()
                .find(|&(x, y, _)| (x, y) == (a, b) || (y, x) == (a, b))
                .map(|(.., rule)| rule);
            assert!(
                known.is_none() || known == expected,
                "Rapier's pair ({a:?}, {b:?}): the hooks know {known:?}, resolve says {expected:?}: {}",
                self.describe(a, b)
            );
        }
        for (a, b, _) in self.hooks.hooked_pairs() {
            assert!(
                rapier
                    .iter()
                    .any(|&(x, y)| (x, y) == (a, b) || (y, x) == (a, b)),
                "live pair ({a:?}, {b:?}) is not in Rapier's graph"
            );
        }
        assert_eq!(
            rules.validate(bodies, colliders),
            Ok(()),
            "the rule set is not clean"
        );
        for &gone in &self.removed {
            assert!(
                self.hooks
                    .hooked_pairs()
                    .all(|(a, b, _)| a != gone && b != gone)
            );
        }
    }
}

/// The JSON pointers of every number in `value`.
#[cfg(feature = "serde")]
pub fn numeric_leaves(value: &serde_json::Value, at: String, leaves: &mut Vec<String>) {
    match value {
        serde_json::Value::Number(_) => leaves.push(at),
        serde_json::Value::Array(items) => {
            for (i, item) in items.iter().enumerate() {
                numeric_leaves(item, format!("{at}/{i}"), leaves);
            }
        }
        serde_json::Value::Object(fields) => {
            for (key, item) in fields {
                numeric_leaves(item, format!("{at}/{key}"), leaves);
            }
        }
        _ => {}
    }
}

/// The message `act` panics with (a `String`, as `format!` panics give, or
/// a `&str`), or `None` if it returns.
pub fn panic_message(act: impl FnOnce()) -> Option<String> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(act))
        .err()
        .and_then(|panic| match panic.downcast::<String>() {
            Ok(message) => Some(*message),
            Err(panic) => panic.downcast::<&str>().ok().map(|m| m.to_string()),
        })
}

/// The value of the environment variable `name` read by `parse`, else
/// `default`.
pub fn env_or<T>(name: &str, default: T, parse: impl Fn(&str) -> Option<T>) -> T {
    std::env::var(name)
        .ok()
        .and_then(|v| parse(&v))
        .unwrap_or(default)
}
