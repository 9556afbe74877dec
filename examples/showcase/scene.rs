//! The showcase's scene, written once for both dimensions: every rule at
//! work, stepped for three seconds, with one row per actor and one panel
//! per actor in the picture (see `main.rs` of `showcase` and `showcase2d`).

use approx::abs_diff_eq;
use std::sync::mpsc::{Receiver, channel};

use crate::rapier::math::DIM;
use crate::rapier::prelude::*;
use crate::rules::{CollisionRule, CollisionRuleSet, Explanation, RuleError, RuleHooks, Stage};
use crate::view::{self, Figure, P, Panel, Picture};
use crate::{at, axle, blade_at_y, cuboid, jelly, net};

const STEPS: usize = 180;
/// The instants marked on the trajectories.
const SNAPSHOTS: [usize; 4] = [0, 40, 90, 180];
/// The trajectories are sampled every `SAMPLE` steps.
const SAMPLE: usize = 3;
/// The step at which the rope is cut.
const CUT: usize = 60;

/// One actor of the scene: its colliders, and the pair the table reports.
struct Actor {
    name: &'static str,
    colliders: Vec<ColliderHandle>,
    /// The collider pair whose rule this actor demonstrates.
    pair: (ColliderHandle, ColliderHandle),
    /// What the pair's two colliders are, for the picture's captions.
    roles: [&'static str; 2],
}

struct Scene {
    world: PhysicsWorld,
    rules: CollisionRuleSet,
    actors: Vec<Actor>,
    floor: ColliderHandle,
}

fn body_at(world: &mut PhysicsWorld, builder: RigidBodyBuilder, x: f32, y: f32) -> RigidBodyHandle {
    world.insert_body(builder.translation(at(x, y)))
}

fn evented(collider: ColliderBuilder) -> ColliderBuilder {
    collider.active_events(ActiveEvents::COLLISION_EVENTS)
}

fn build() -> Result<(Scene, Handles), RuleError> {
    let mut world = PhysicsWorld::new();
    let mut rules = CollisionRuleSet::default();
    let ground = body_at(&mut world, RigidBodyBuilder::fixed(), 0.0, -0.5);
    let floor = world.insert_collider(cuboid(50.0, 0.5, 4.0), Some(ground));
    let mut actors = Vec::new();

    // A ragdoll: three overlapping limbs in one group that ignores itself.
    let limbs: Vec<_> = [(-17.0, 4.0), (-16.6, 4.0), (-16.2, 4.0)]
        .iter()
        .map(|&(x, y)| {
            let body = body_at(&mut world, RigidBodyBuilder::dynamic(), x, y);
            let collider = world.insert_collider(cuboid(0.4, 0.25, 0.25), Some(body));
            (body, collider)
        })
        .collect();
    let ragdoll = rules.create_group();
    rules.set_group_rule(ragdoll, ragdoll, CollisionRule::NoPair);
    rules.set_group(limbs[0].0, Some(ragdoll));
    rules.set_parent(limbs[1].0, limbs[0].0)?;
    rules.set_parent(limbs[2].0, limbs[1].0)?;
    actors.push(Actor {
        name: "ragdoll",
        colliders: limbs.iter().map(|l| l.1).collect(),
        pair: (limbs[0].1, limbs[1].1),
        roles: ["limb", "next limb"],
    });

    // A vehicle: wheels jointed under the chassis, inside its outline.
    let chassis = body_at(&mut world, RigidBodyBuilder::dynamic(), -8.0, 1.0);
    let hull = world.insert_collider(cuboid(1.5, 0.4, 0.8), Some(chassis));
    let mut wheels = Vec::new();
    for dx in [-1.0, 1.0] {
        let wheel = body_at(&mut world, RigidBodyBuilder::dynamic(), -8.0 + dx, 0.5);
        let tyre = world.insert_collider(ColliderBuilder::ball(0.5), Some(wheel));
        world.insert_impulse_joint(chassis, wheel, axle(at(dx, -0.5)));
        rules.set_parent(wheel, chassis)?;
        wheels.push(tyre);
    }
    let vehicle = rules.create_group();
    rules.set_group_rule(vehicle, vehicle, CollisionRule::NoPair);
    rules.set_group(chassis, Some(vehicle));
    actors.push(Actor {
        name: "vehicle",
        colliders: [hull].into_iter().chain(wheels.iter().copied()).collect(),
        pair: (hull, wheels[0]),
        roles: ["chassis", "wheel"],
    });

    // A ghost walking through one wall: a specific rule, contacts and events.
    let ghost = body_at(
        &mut world,
        RigidBodyBuilder::dynamic()
            .linvel(at(3.0, 0.0))
            .gravity_scale(0.0),
        -2.0,
        1.2,
    );
    let spirit = world.insert_collider(evented(cuboid(0.4, 0.5, 0.4)), Some(ghost));
    let wall_body = body_at(&mut world, RigidBodyBuilder::fixed(), 2.0, 1.5);
    let wall = world.insert_collider(cuboid(0.1, 1.5, 2.0), Some(wall_body));
    rules.set_specific(ghost, wall_body, CollisionRule::NoResponse);
    actors.push(Actor {
        name: "ghost",
        colliders: vec![spirit],
        pair: (spirit, wall),
        roles: ["ghost", "wall"],
    });

    // The player, standing in a pickup zone, under falling debris.
    let player = body_at(&mut world, RigidBodyBuilder::dynamic(), 10.0, 1.0);
    let avatar = world.insert_collider(evented(ColliderBuilder::capsule_y(0.5, 0.5)), Some(player));
    let zone_body = body_at(&mut world, RigidBodyBuilder::fixed(), 10.0, 1.0);
    let zone = world.insert_collider(cuboid(1.5, 1.0, 1.5), Some(zone_body));
    rules.set_personal(zone, CollisionRule::NoContacts);
    actors.push(Actor {
        name: "pickup",
        colliders: vec![zone],
        pair: (avatar, zone),
        roles: ["player", "pickup zone"],
    });
    let (players, rubble) = (rules.create_group(), rules.create_group());
    rules.set_group(player, Some(players));
    rules.set_group_rule(players, rubble, CollisionRule::NoPair);
    let debris: Vec<_> = [9.8, 10.2]
        .iter()
        .map(|&x| {
            let body = body_at(&mut world, RigidBodyBuilder::dynamic(), x, 4.0);
            rules.set_group(body, Some(rubble));
            world.insert_collider(cuboid(0.2, 0.2, 0.2), Some(body))
        })
        .collect();
    actors.push(Actor {
        name: "debris",
        colliders: debris.clone(),
        pair: (debris[0], avatar),
        roles: ["debris", "player"],
    });
    actors.push(Actor {
        name: "player",
        colliders: vec![avatar],
        pair: (avatar, floor),
        roles: ["player", "floor"],
    });

    // Two kinematic platforms driven through each other.
    let platform = |world: &mut PhysicsWorld, x: f32, vx: f32| {
        let body = body_at(
            world,
            RigidBodyBuilder::kinematic_velocity_based().linvel(at(vx, 0.0)),
            x,
            3.0,
        );
        (
            body,
            world.insert_collider(cuboid(1.0, 0.2, 1.0), Some(body)),
        )
    };
    let (left, a) = platform(&mut world, 17.0, 1.0);
    let (right, b) = platform(&mut world, 21.0, -1.0);
    actors.push(Actor {
        name: "platforms",
        colliders: vec![a, b],
        pair: (a, b),
        roles: ["left platform", "right platform"],
    });

    // CCD bullets: one at a NoResponse shield, one at a Normal wall.
    let bullet = |world: &mut PhysicsWorld, y: f32| {
        let builder = RigidBodyBuilder::dynamic()
            .linvel(at(200.0, 0.0))
            .gravity_scale(0.0)
            .ccd_enabled(true);
        let body = body_at(world, builder, 25.0, y);
        (
            body,
            world.insert_collider(ColliderBuilder::ball(0.1), Some(body)),
        )
    };
    let (shot, round) = bullet(&mut world, 2.0);
    let (stopped, slug) = bullet(&mut world, 4.5);
    let shield_body = body_at(&mut world, RigidBodyBuilder::fixed(), 30.0, 2.0);
    let shield = world.insert_collider(cuboid(0.02, 0.8, 2.0), Some(shield_body));
    let wall2_body = body_at(&mut world, RigidBodyBuilder::fixed(), 30.0, 4.5);
    let wall2 = world.insert_collider(cuboid(0.02, 0.8, 2.0), Some(wall2_body));
    rules.set_specific(shield, shot, CollisionRule::NoResponse);
    actors.push(Actor {
        name: "bullet/shield",
        colliders: vec![round, shield],
        pair: (round, shield),
        roles: ["bullet", "shield"],
    });
    actors.push(Actor {
        name: "bullet/wall",
        colliders: vec![slug, wall2],
        pair: (slug, wall2),
        roles: ["bullet", "wall"],
    });

    // Soft bodies (`docs/semantics.md`, "Soft bodies"), named by their root
    // bodies. A jelly dropped through a gate it does not respond to.
    let gate_body = body_at(&mut world, RigidBodyBuilder::fixed(), -34.0, 1.6);
    let gate = world.insert_collider(evented(cuboid(0.8, 0.1, 0.8)), Some(gate_body));
    let jelly = world.insert_soft_body(jelly(at(-34.0, 3.0)));
    rules.set_specific(
        world.soft_bodies[jelly].root_body(),
        gate_body,
        CollisionRule::NoResponse,
    );
    let skin = soft_colliders(&world, jelly);
    actors.push(Actor {
        name: "jelly/gate",
        colliders: skin.iter().copied().chain([gate]).collect(),
        pair: (skin[0], gate),
        roles: ["jelly", "gate"],
    });

    // A walker passing through a net pinned at its ends, as debris lands on it.
    let net = world.insert_soft_body(net(-29.5, -26.5, 1.2));
    let walker_body = body_at(
        &mut world,
        RigidBodyBuilder::kinematic_velocity_based().linvel(at(1.0, 0.0)),
        -31.0,
        1.2,
    );
    let walker = world.insert_collider(ColliderBuilder::capsule_y(0.5, 0.3), Some(walker_body));
    rules.set_specific(
        walker_body,
        world.soft_bodies[net].root_body(),
        CollisionRule::NoResponse,
    );
    let netting = soft_colliders(&world, net);
    actors.push(Actor {
        name: "walker/net",
        colliders: [walker]
            .into_iter()
            .chain(netting.iter().copied())
            .collect(),
        pair: (walker, netting[0]),
        roles: ["walker", "net"],
    });
    let dropped_body = body_at(&mut world, RigidBodyBuilder::dynamic(), -27.0, 2.5);
    let dropped = world.insert_collider(cuboid(0.15, 0.15, 0.15), Some(dropped_body));
    actors.push(Actor {
        name: "debris/net",
        colliders: vec![dropped],
        pair: (dropped, netting[0]),
        roles: ["debris", "net"],
    });

    // A rope hung from its top end that ignores the floor, cut in two.
    let rope = SoftBodyBuilder::rope(at(-22.5, 4.0), at(-22.5, 1.0), 12).pinned_particles([0]);
    let rope = world.insert_soft_body(rope);
    rules.set_specific(
        world.soft_bodies[rope].root_body(),
        ground,
        CollisionRule::NoPair,
    );
    let strands = soft_colliders(&world, rope);
    actors.push(Actor {
        name: "rope/floor",
        colliders: strands.clone(),
        pair: (strands[0], floor),
        roles: ["rope", "floor"],
    });

    let handles = Handles {
        limbs: limbs.iter().map(|l| l.0).collect(),
        chassis,
        ghost,
        player,
        debris_bodies: debris
            .iter()
            .map(|&c| world.colliders[c].parent().expect("debris has a body"))
            .collect(),
        platforms: (left, right),
        bullets: (shot, stopped),
        jelly,
        net,
        walker: walker_body,
        dropped: dropped_body,
        rope,
    };
    Ok((
        Scene {
            world,
            rules,
            actors,
            floor,
        },
        handles,
    ))
}

/// Bodies whose motion the outcomes measure.
struct Handles {
    limbs: Vec<RigidBodyHandle>,
    chassis: RigidBodyHandle,
    ghost: RigidBodyHandle,
    player: RigidBodyHandle,
    debris_bodies: Vec<RigidBodyHandle>,
    platforms: (RigidBodyHandle, RigidBodyHandle),
    bullets: (RigidBodyHandle, RigidBodyHandle),
    jelly: SoftBodyHandle,
    net: SoftBodyHandle,
    walker: RigidBodyHandle,
    dropped: RigidBodyHandle,
    rope: SoftBodyHandle,
}

/// The colliders of a soft body's meshes.
fn soft_colliders(world: &PhysicsWorld, soft: SoftBodyHandle) -> Vec<ColliderHandle> {
    let colliders: Vec<_> = world.soft_bodies[soft]
        .meshes()
        .map(|m| m.collider())
        .collect();
    assert!(
        !colliders.is_empty(),
        "a soft body of the scene has colliders"
    );
    colliders
}

/// The lowest of a soft body's particles.
fn lowest(world: &PhysicsWorld, soft: SoftBodyHandle) -> f32 {
    world.soft_bodies[soft]
        .particle_positions()
        .map(|p| p.y)
        .fold(f32::MAX, f32::min)
}

/// The mean of a soft body's particles along x.
fn mean_x(world: &PhysicsWorld, soft: SoftBodyHandle) -> f32 {
    let body = &world.soft_bodies[soft];
    body.particle_positions().map(|p| p.x).sum::<f32>() / body.num_particles() as f32
}

/// What a collider is drawn as: itself, or the soft body whose surface it is.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Owner {
    Rigid(ColliderHandle),
    Soft(SoftBodyHandle),
}

fn owner(world: &PhysicsWorld, collider: ColliderHandle) -> Owner {
    world
        .soft_bodies
        .iter()
        .find(|(_, body)| body.mesh_of(collider).is_some())
        .map_or(Owner::Rigid(collider), |(handle, _)| Owner::Soft(handle))
}

/// Where an owner is: a collider's centre, a soft body's mean particle.
fn centre(world: &PhysicsWorld, owner: Owner) -> P {
    match owner {
        Owner::Rigid(c) => {
            let t = world.colliders[c].translation();
            (t.x, t.y)
        }
        Owner::Soft(s) => {
            let body = &world.soft_bodies[s];
            let n = body.num_particles() as f32;
            let (x, y) = body
                .particle_positions()
                .fold((0.0, 0.0), |(x, y), p| (x + p.x, y + p.y));
            (x / n, y / n)
        }
    }
}

/// An owner's outline in the x-y plane: a rigid collider's silhouette (its
/// support points in 32 directions of the plane), or a soft body's
/// structural edges.
fn figure(world: &PhysicsWorld, owner: Owner) -> Figure {
    match owner {
        Owner::Rigid(c) => {
            let collider = &world.colliders[c];
            let mut outline: Vec<P> = match collider.shape().as_support_map() {
                Some(shape) => (0..32)
                    .map(|i| {
                        let angle = i as f32 * std::f32::consts::TAU / 32.0;
                        let p =
                            shape.support_point(collider.position(), at(angle.cos(), angle.sin()));
                        (p.x, p.y)
                    })
                    .collect(),
                None => {
                    let aabb = collider.compute_aabb();
                    let (lo, hi) = (aabb.mins, aabb.maxs);
                    vec![(lo.x, lo.y), (hi.x, lo.y), (hi.x, hi.y), (lo.x, hi.y)]
                }
            };
            outline.dedup_by(|a, b| (a.0 - b.0).abs() < 1e-4 && (a.1 - b.1).abs() < 1e-4);
            Figure {
                paths: vec![outline],
                closed: true,
                particles: Vec::new(),
            }
        }
        Owner::Soft(s) => {
            let body = &world.soft_bodies[s];
            let at = |i: u32| {
                let p = body.particle_position(i as usize);
                (p.x, p.y)
            };
            Figure {
                paths: body
                    .edges()
                    .iter()
                    .filter(|e| e.kind == SoftBodyEdgeKind::Structural)
                    .map(|e| vec![at(e.vertices[0]), at(e.vertices[1])])
                    .collect(),
                closed: false,
                particles: body.particle_positions().map(|p| (p.x, p.y)).collect(),
            }
        }
    }
}

/// Who plays what in an actor's panel: the actor (the owner of the pair's
/// first collider, and every piece of it if it is a soft body), the other
/// object of the pair, and the actor's other colliders (drawn, not traced).
fn cast(world: &PhysicsWorld, actor: &Actor) -> (Vec<Owner>, Owner, Vec<Owner>) {
    let first = owner(world, actor.pair.0);
    let other = owner(world, actor.pair.1);
    let (mut subject, mut companions) = (vec![first], Vec::new());
    for &c in &actor.colliders {
        let o = owner(world, c);
        if o == other || subject.contains(&o) || companions.contains(&o) {
            continue;
        }
        if matches!((first, o), (Owner::Soft(_), Owner::Soft(_))) {
            subject.push(o);
        } else {
            companions.push(o);
        }
    }
    (subject, other, companions)
}

/// What the picture needs of one actor: its trajectory, sampled, and its
/// shapes and the other object's at the first and the last step.
#[derive(Default)]
struct Trail {
    tracks: Vec<(Owner, Vec<(usize, P)>)>,
    start: Vec<Figure>,
    end: Vec<Figure>,
    other: Vec<Figure>,
    other_moved: bool,
    other_at: Vec<P>,
}

impl Trail {
    fn record(&mut self, world: &PhysicsWorld, actor: &Actor, step: usize) {
        let (subject, other, companions) = cast(world, actor);
        for &o in &subject {
            let i = match self.tracks.iter().position(|t| t.0 == o) {
                Some(i) => i,
                None => {
                    // A piece cut off mid-run forks from the track of the
                    // body it was cut from.
                    let origin = match o {
                        Owner::Soft(s) => world.soft_bodies[s].origin(),
                        Owner::Rigid(_) => None,
                    };
                    let fork = origin
                        .and_then(|h| self.tracks.iter().find(|t| t.0 == Owner::Soft(h)))
                        .and_then(|t| t.1.iter().rev().find(|s| s.0 < step).copied());
                    self.tracks.push((o, fork.into_iter().collect()));
                    self.tracks.len() - 1
                }
            };
            self.tracks[i].1.push((step, centre(world, o)));
        }
        if step == 0 || step == STEPS {
            let shapes = subject
                .iter()
                .chain(&companions)
                .map(|&o| figure(world, o))
                .collect();
            let other_figure = figure(world, other);
            let points: Vec<P> = other_figure.paths.iter().flatten().copied().collect();
            if step == 0 {
                self.start = shapes;
                self.other_at = points;
            } else {
                self.end = shapes;
                self.other_moved = points.len() != self.other_at.len()
                    || points
                        .iter()
                        .zip(&self.other_at)
                        .any(|(a, b)| (a.0 - b.0).hypot(a.1 - b.1) > 0.02);
            }
            self.other.push(other_figure);
        }
    }
}

/// The stage that decided a rule, in words.
fn stage_words(stage: Stage) -> &'static str {
    match stage {
        Stage::Specific => "specific rule",
        Stage::Personal => "personal rule",
        Stage::Group => "group table",
        Stage::Default => "default rule",
    }
}

/// What was seen of each actor's pair over the run.
#[derive(Default)]
struct Seen {
    live: Option<CollisionRule>,
    touched: bool,
    started: usize,
    stopped: usize,
}

/// Builds and steps the scene, prints the table, writes one panel per actor
/// (its trajectory, the other object of its rule) to
/// `target/showcase/{picture}` and `docs/showcase_{picture}`; an error if an
/// actor broke its promise.
pub fn run(picture: &str) -> Result<(), Box<dyn std::error::Error>> {
    let (scene, h) = build()?;
    let Scene {
        mut world,
        rules,
        mut actors,
        floor,
    } = scene;
    let explanations: Vec<Explanation> = actors
        .iter()
        .map(|a| rules.explain(&world.bodies, &world.colliders, a.pair.0, a.pair.1))
        .collect();
    let mut hooks = RuleHooks::new(rules);
    let (send, events): (_, Receiver<CollisionEvent>) = channel();
    let collector = ChannelEventCollector::new(send, channel().0, channel().0);
    let mut seen: Vec<Seen> = actors.iter().map(|_| Seen::default()).collect();
    let x0 = |world: &PhysicsWorld, b: RigidBodyHandle| world.bodies[b].translation().x;
    let start = (
        x0(&world, h.platforms.0),
        x0(&world, h.platforms.1),
        x0(&world, h.bullets.0),
    );
    let net_x = mean_x(&world, h.net);
    let rope_actor = actors
        .iter()
        .position(|a| a.name == "rope/floor")
        .expect("the rope");
    let mut rope_pieces = vec![h.rope];

    let out = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target/showcase");
    std::fs::create_dir_all(&out)?;
    let mut trails: Vec<Trail> = actors.iter().map(|_| Trail::default()).collect();
    let floor_figure = figure(&world, Owner::Rigid(floor));
    for step in 0..=STEPS {
        if step % SAMPLE == 0 || step == STEPS || SNAPSHOTS.contains(&step) {
            for (actor, trail) in actors.iter().zip(&mut trails) {
                trail.record(&world, actor, step);
            }
        }
        if step == STEPS {
            break;
        }
        if step == CUT {
            let cut = world
                .cut_soft_body(h.rope, &blade_at_y(-22.5, 2.5))
                .ok_or("the blade misses the rope")?;
            rope_pieces = cut.bodies().collect();
            // The pieces' colliders (one side's are Rapier's copies).
            let strands: Vec<ColliderHandle> = rope_pieces
                .iter()
                .flat_map(|&p| soft_colliders(&world, p))
                .collect();
            actors[rope_actor].pair.0 = strands[0];
            actors[rope_actor].colliders = strands;
        }
        hooks.step_with_events(&mut world, &collector);
        while let Ok(event) = events.try_recv() {
            for (actor, s) in actors.iter().zip(&mut seen) {
                let (a, b) = actor.pair;
                if (event.collider1(), event.collider2()) == (a, b)
                    || (event.collider1(), event.collider2()) == (b, a)
                {
                    if event.started() {
                        s.started += 1
                    } else {
                        s.stopped += 1
                    }
                }
            }
        }
        for (actor, s) in actors.iter().zip(&mut seen) {
            let (a, b) = actor.pair;
            s.live = s.live.or(hooks.pair_rule(&world, a, b));
            s.touched |= world
                .narrow_phase
                .contact_pair(a, b)
                .is_some_and(|p| p.has_any_active_contact());
        }
    }

    // The measured outcome of each actor, and whether it is what the rule promises.
    let t = STEPS as f32 / 60.0;
    let pos = |b: RigidBodyHandle| world.bodies[b].translation();
    let limb_ys: Vec<f32> = h.limbs.iter().map(|&b| pos(b).y).collect();
    let limb_pairs = (0..3).flat_map(|i| (i + 1..3).map(move |j| (i, j)));
    let limbs_apart = limb_pairs
        .map(|(i, j)| hooks.pair_rule(&world, actors[0].colliders[i], actors[0].colliders[j]))
        .all(|rule| rule.is_none());
    let free_bullet = start.2 + 200.0 * t;
    let outcomes: Vec<(String, bool)> = vec![
        (
            format!(
                "limbs landed at y = {:.2}, {:.2}, {:.2}",
                limb_ys[0], limb_ys[1], limb_ys[2]
            ),
            limbs_apart
                && limb_ys
                    .iter()
                    .all(|&y| abs_diff_eq!(y, 0.25, epsilon = 0.05))
                && hooks
                    .pair_rule(&world, actors[0].colliders[2], floor)
                    .is_some(),
        ),
        (
            format!(
                "chassis rides at y = {:.2} over its wheels",
                pos(h.chassis).y
            ),
            abs_diff_eq!(pos(h.chassis).y, 1.0, epsilon = 0.1),
        ),
        (
            format!("walked through the wall to x = {:.2}", pos(h.ghost).x),
            pos(h.ghost).x > 3.0 && seen[2].started >= 1 && seen[2].stopped >= 1,
        ),
        (
            "pair live, no contacts".to_owned(),
            seen[3].live == Some(CollisionRule::NoContacts) && !seen[3].touched,
        ),
        (
            format!(
                "fell through the player to y = {:.2}",
                pos(h.debris_bodies[0]).y
            ),
            seen[4].live.is_none()
                && !seen[4].touched
                && h.debris_bodies.iter().all(|&b| pos(b).y < 0.3),
        ),
        (
            format!("stands at y = {:.2}", pos(h.player).y),
            abs_diff_eq!(pos(h.player).y, 1.0, epsilon = 0.05),
        ),
        (
            format!(
                "passed at x = {:.2}, {:.2} (unpushed)",
                pos(h.platforms.0).x,
                pos(h.platforms.1).x
            ),
            abs_diff_eq!(pos(h.platforms.0).x, (start.0 + t), epsilon = 1e-3)
                && abs_diff_eq!(pos(h.platforms.1).x, (start.1 - t), epsilon = 1e-3)
                && seen[6].live.is_none(),
        ),
        (
            format!(
                "free flight: x = {:.1} (free {:.1})",
                pos(h.bullets.0).x,
                free_bullet
            ),
            abs_diff_eq!(pos(h.bullets.0).x, free_bullet, epsilon = 1e-3),
        ),
        (
            format!("stopped at x = {:.2}", pos(h.bullets.1).x),
            pos(h.bullets.1).x < 30.0,
        ),
        (
            format!(
                "passed the gate, rests at y = {:.2}",
                lowest(&world, h.jelly)
            ),
            (-0.05..0.3).contains(&lowest(&world, h.jelly))
                && seen[9].live == Some(CollisionRule::NoResponse),
        ),
        (
            format!(
                "walked to x = {:.2}, net's mean x moved {:+.3}",
                pos(h.walker).x,
                mean_x(&world, h.net) - net_x
            ),
            (mean_x(&world, h.net) - net_x).abs() < 0.05
                && seen[10].live == Some(CollisionRule::NoResponse),
        ),
        (
            format!("rests on the net at y = {:.2}", pos(h.dropped).y),
            pos(h.dropped).y > 0.9 && seen[11].touched,
        ),
        {
            let lows: Vec<f32> = rope_pieces.iter().map(|&p| lowest(&world, p)).collect();
            let (low, high) = lows
                .iter()
                .fold((f32::MAX, f32::MIN), |(a, b), &y| (a.min(y), b.max(y)));
            // Both halves hold the rope's entry about the ground.
            let ground = world.colliders[floor]
                .parent()
                .expect("the floor has a body");
            let kept = rope_pieces.iter().all(|&p| {
                let root = world.soft_bodies[p].root_body();
                hooks.rules().specific(root, ground) == CollisionRule::NoPair
            });
            (
                format!(
                    "cut at {:.1} s: a half fell to y = {low:.1}, one hangs to {high:.2}",
                    CUT as f32 / 60.0
                ),
                lows.len() == 2 && low < -1.0 && high > 1.5 && kept && seen[12].live.is_none(),
            )
        },
    ];

    println!(
        "{:<14}{:<12}{:<10}{:>5}  {:<5} {:<9} {:<7} outcome",
        "actor", "rule", "stage", "step", "pair", "contacts", "events"
    );
    let mut failures = 0;
    for (((actor, why), s), (outcome, ok)) in
        actors.iter().zip(&explanations).zip(&seen).zip(&outcomes)
    {
        failures += usize::from(!ok);
        println!(
            "{:<14}{:<12}{:<10}{:>5}  {:<5} {:<9} {:<7} {}{}",
            actor.name,
            format!("{:?}", why.rule),
            format!("{:?}", why.stage),
            why.step,
            if s.live.is_some() { "live" } else { "none" },
            if s.touched { "yes" } else { "no" },
            format!("{}/{}", s.started, s.stopped),
            outcome,
            if *ok { "" } else { "   <-- NOT AS PROMISED" },
        );
    }
    println!(
        "(events: Started/Stopped for the actor's pair; {} colliders, {} hooked)",
        world.colliders.len(),
        hooks.stats().hooked_colliders
    );
    println!(
        "(a soft body's NoResponse pair with a rigid collider has no contacts and no events \
         in Rapier 0.36.1: docs/semantics.md, \"Soft bodies\")"
    );

    // One panel per actor: its trajectory, the other object of its pair,
    // and the rule and the measured outcome in words.
    let panels = actors
        .iter()
        .zip(&explanations)
        .zip(&seen)
        .zip(&outcomes)
        .zip(trails)
        .map(|((((actor, why), s), (outcome, ok)), trail)| {
            let events = match (s.started, s.stopped) {
                (0, 0) => "no events".to_owned(),
                (a, b) => format!("events: {a} started, {b} stopped"),
            };
            let [me, other] = actor.roles;
            let mut others = trail.other.into_iter();
            let other_start = others.next().unwrap_or_default();
            let other_end = others.next().filter(|_| trail.other_moved);
            Panel {
                title: actor.name.to_owned(),
                caption: vec![
                    format!(
                        "{me}: {:?} with the {other} ({})",
                        why.rule,
                        stage_words(why.stage)
                    ),
                    format!("→ {outcome}"),
                    format!(
                        "{}, {}, {events}",
                        if s.live.is_some() {
                            "pair live"
                        } else {
                            "never a live pair"
                        },
                        if s.touched {
                            "touched"
                        } else {
                            "never touched"
                        },
                    ),
                ],
                ok: *ok,
                rule: why.rule,
                other: other.to_owned(),
                tracks: trail.tracks.into_iter().map(|t| t.1).collect(),
                start: trail.start,
                end: trail.end,
                other_start,
                other_end,
            }
        })
        .collect();
    let svg = view::render(&Picture {
        title: format!(
            "Every rule at work ({}): each actor's path over {t:.0} s, with the other object of its rule",
            if DIM == 2 { "2D" } else { "3D, seen along z" }
        ),
        panels,
        scenery: vec![floor_figure],
        marks: &SNAPSHOTS,
        steps_per_second: 60.0,
    });
    std::fs::write(out.join(picture), &svg)?;
    // The README's picture, the same each run: regenerated here.
    let docs = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs");
    std::fs::write(docs.join(format!("showcase_{picture}")), &svg)?;
    println!(
        "trajectories, marked at steps {SNAPSHOTS:?}: {} (and docs/showcase_{picture})",
        out.join(picture).display()
    );
    if failures > 0 {
        return Err(format!("{failures} actor(s) did not do what their rule promises").into());
    }
    Ok(())
}
