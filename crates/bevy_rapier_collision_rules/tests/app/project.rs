//! The project's own bevy_rapier settings and hooks keep working beside
//! the rules.

use CollisionRule::*;
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy_rapier::prelude::*;
use bevy_rapier::rapier::prelude::ActiveHooks as RapierHooks;
use bevy_rapier_collision_rules::prelude::*;

use super::scene::{Sim, ball, fell_through, floor, rests};

/// The floor's membership in the project's own collision groups.
const FLOOR: Group = Group::GROUP_2;

#[test]
fn the_projects_collision_groups_still_filter_where_the_rules_wrote_groups() {
    let mut sim = Sim::new();
    let (ghosts, debris) = {
        let mut table = sim.table();
        (table.create_group(), table.create_group())
    };
    sim.table().set_group_rule(ghosts, debris, NoPair);
    let f = sim.spawn((floor(), CollisionGroups::new(FLOOR, Group::ALL)));
    // The project's groups keep this ball off the floor; the rules give it
    // collision groups of their own too.
    let kept_off = sim.spawn((
        ball(0.0, 1.0),
        RuleGroup(ghosts),
        CollisionGroups::new(Group::GROUP_1, Group::ALL - FLOOR),
    ));
    let lands = sim.spawn((ball(1.0, 1.0), RuleGroup(ghosts)));
    let crumb = sim.spawn((ball(1.0, 3.0), RuleGroup(debris)));
    sim.run(120);
    let groups = sim.collider(kept_off, |c| c.collision_groups());
    assert!(
        fell_through(sim.y(kept_off)),
        "the project's filter holds: y = {}, groups {groups:?}",
        sim.y(kept_off)
    );
    assert!(rests(sim.y(lands)), "y = {}", sim.y(lands));
    assert!(
        rests(sim.y(crumb)),
        "debris passes the ghost, lands: y = {}",
        sim.y(crumb)
    );
    let _ = f;

    // The project changes its groups at runtime: bevy_rapier writes them,
    // the rules combine with them again.
    let late = sim.spawn((
        ball(-2.0, 0.3),
        RuleGroup(ghosts),
        CollisionGroups::default(),
    ));
    sim.run(60);
    assert!(rests(sim.y(late)), "y = {}", sim.y(late));
    sim.app
        .world_mut()
        .get_mut::<CollisionGroups>(late)
        .unwrap()
        .filters = Group::ALL - FLOOR;
    let crumb2 = sim.spawn((ball(-2.0, 2.0), RuleGroup(debris)));
    sim.run(90);
    assert!(
        fell_through(sim.y(late)),
        "the project's new filter holds: y = {}",
        sim.y(late)
    );
    assert!(
        rests(sim.y(crumb2)),
        "and the rules' NoPair still does: y = {}",
        sim.y(crumb2)
    );
}

/// A project's own marker, which its hooks read.
#[derive(Component)]
struct Intangible;

#[derive(SystemParam)]
struct GameHooks<'w, 's> {
    rules: CollisionRulesHooks<'w, 's>,
    intangible: Query<'w, 's, &'static Intangible>,
}

impl BevyPhysicsHooks for GameHooks<'_, '_> {
    fn filter_contact_pair(&self, context: PairFilterContextView) -> Option<SolverFlags> {
        let flags = self.rules.filter_contact_pair(&context)?;
        let asked = self
            .rules
            .project_asks(&context, RapierHooks::FILTER_CONTACT_PAIRS);
        let intangible = |e| self.intangible.contains(e);
        if asked && (intangible(context.collider1()) || intangible(context.collider2())) {
            return None;
        }
        Some(flags)
    }

    fn filter_intersection_pair(&self, context: PairFilterContextView) -> bool {
        self.rules.filter_intersection_pair(&context)
    }

    fn modify_solver_contacts(&self, mut context: ContactModificationContextView) {
        self.rules.modify_solver_contacts(&mut context);
    }
}

#[test]
fn a_projects_own_hooks_keep_working_and_see_only_what_they_asked_for() {
    let mut sim = Sim::with_hooks::<GameHooks>();
    let f = sim.spawn(floor());
    let far = sim.spawn((Transform::from_xyz(0.0, 20.0, 0.0), Collider::ball(0.1)));
    // The project's hook, asked for by its own bit.
    let phantom = sim.spawn((
        ball(0.0, 1.0),
        Intangible,
        ActiveHooks::FILTER_CONTACT_PAIRS,
    ));
    // The rules' hook on a ball of the project's marker, without its bit:
    // the project's logic is not asked, as without the rules.
    let marked = sim.spawn((
        ball(1.0, 1.0),
        Intangible,
        SpecificRules::new().with(far, NoContacts),
    ));
    // The rules alone.
    let ghost = sim.spawn((ball(2.0, 1.0), SpecificRules::new().with(f, NoContacts)));
    sim.run(120);
    assert!(
        fell_through(sim.y(phantom)),
        "the project's hook: y = {}",
        sim.y(phantom)
    );
    assert!(rests(sim.y(marked)), "not asked: y = {}", sim.y(marked));
    assert!(
        fell_through(sim.y(ghost)),
        "the rules: y = {}",
        sim.y(ghost)
    );
    assert!(
        sim.rules().hooks().stats().hooked_colliders >= 2,
        "{:?}",
        sim.rules().hooks().stats()
    );
}

/// Counts the collision events it is given.
#[derive(Clone, Default)]
struct Counter(std::sync::Arc<std::sync::atomic::AtomicUsize>);

impl Counter {
    fn count(&self) -> usize {
        self.0.load(std::sync::atomic::Ordering::Relaxed)
    }
}

impl bevy_rapier::rapier::pipeline::EventHandler for Counter {
    fn handle_collision_event(
        &self,
        _: &bevy_rapier::rapier::prelude::RigidBodySet,
        _: &bevy_rapier::rapier::prelude::ColliderSet,
        _: bevy_rapier::rapier::prelude::CollisionEvent,
        _: Option<&bevy_rapier::rapier::prelude::ContactPair>,
    ) {
        self.0.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    }

    fn handle_contact_force_event(
        &self,
        _: bevy_rapier::rapier::prelude::Real,
        _: &bevy_rapier::rapier::prelude::RigidBodySet,
        _: &bevy_rapier::rapier::prelude::ColliderSet,
        _: &bevy_rapier::rapier::prelude::ContactPair,
        _: bevy_rapier::rapier::prelude::Real,
    ) {
    }

    fn handle_soft_body_tear_event(
        &self,
        _: &bevy_rapier::rapier::prelude::SoftBodySet,
        _: &bevy_rapier::rapier::prelude::SoftBodyTearEvent,
    ) {
    }
}

/// The plugin listens for soft-body tears through the context's event
/// handler (`docs/bevy.md`, "Soft bodies"): a handler the project set
/// before the first frame, or in place of another later, still gets every
/// event.
#[test]
fn a_projects_own_event_handler_still_gets_its_events() {
    let mut sim = Sim::new();
    let context = sim.context();
    let first = Counter::default();
    sim.app
        .world_mut()
        .get_mut::<RapierContextSimulation>(context)
        .unwrap()
        .set_event_handler(first.clone());
    let f = sim.spawn((floor(), ActiveEvents::COLLISION_EVENTS));
    let ghost = sim.spawn((ball(0.0, 1.0), SpecificRules::new().with(f, NoResponse)));
    sim.run(60);
    assert!(
        fell_through(sim.y(ghost)),
        "the ghost passes the floor: y = {}",
        sim.y(ghost)
    );
    let seen = first.count();
    assert!(
        seen >= 2,
        "the project's handler saw the ghost enter and leave: {seen} events"
    );
    let second = Counter::default();
    sim.app
        .world_mut()
        .get_mut::<RapierContextSimulation>(context)
        .unwrap()
        .set_event_handler(second.clone());
    let lands = sim.spawn(ball(1.0, 1.0));
    sim.run(60);
    assert!(
        rests(sim.y(lands)),
        "a ball lands on the floor: y = {}",
        sim.y(lands)
    );
    assert_eq!(
        first.count(),
        seen,
        "the replaced handler gets nothing more"
    );
    assert!(
        second.count() >= 1,
        "the new handler saw the landing: {} events",
        second.count()
    );
}
