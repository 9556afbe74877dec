//! What the project itself tells Rapier about a collider: its collision
//! groups, solver groups, active collision types and hook bits. The crate
//! combines its plan with these and never writes in their place
//! (`docs/semantics.md`, section 6): a pair interacts only as far as both the
//! project's settings and the rules allow.

use super::rapier::prelude::*;

/// The four per-collider settings Rapier reads before the hook.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Settings {
    pub(crate) collision: InteractionGroups,
    pub(crate) solver: InteractionGroups,
    pub(crate) types: ActiveCollisionTypes,
    pub(crate) hooks: ActiveHooks,
}

impl Settings {
    /// The settings `collider` has now.
    pub(crate) fn of(collider: &Collider) -> Settings {
        Settings {
            collision: collider.collision_groups(),
            solver: collider.solver_groups(),
            types: collider.active_collision_types(),
            hooks: collider.active_hooks(),
        }
    }

    /// The fields of `now` that differ from `written` (what the crate wrote
    /// last): the project changed them through Rapier since.
    pub(crate) fn changed_since(self, written: Settings, now: Settings) -> Settings {
        fn pick<T: PartialEq>(own: T, written: T, now: T) -> T {
            if now != written { now } else { own }
        }
        Settings {
            collision: pick(self.collision, written.collision, now.collision),
            solver: pick(self.solver, written.solver, now.solver),
            types: pick(self.types, written.types, now.types),
            hooks: pick(self.hooks, written.hooks, now.hooks),
        }
    }

    /// Gives `collider` these settings, touching only what differs (Rapier
    /// marks a collider modified on every `get_mut`, so the caller checks
    /// first).
    pub(crate) fn write(self, collider: &mut Collider) {
        collider.set_active_hooks(self.hooks);
        collider.set_solver_groups(self.solver);
        if collider.active_collision_types() != self.types {
            collider.set_active_collision_types(self.types);
            // Changing the collision types alone sets no change flag:
            // nudging the collision groups makes Rapier look again.
            collider.set_collision_groups(InteractionGroups::none());
        }
        collider.set_collision_groups(self.collision);
    }

    /// Whether these types let Rapier look at a pair of bodies of these types.
    pub(crate) fn types_allow(
        self,
        other: Settings,
        types: (RigidBodyType, RigidBodyType),
    ) -> bool {
        self.types.test(types.0, types.1) || other.types.test(types.0, types.1)
    }

    /// Whether the types let Rapier pair this collider's non-dynamic body
    /// with another non-dynamic one: more than Rapier's defaults.
    pub(crate) fn widened(self) -> bool {
        !(self.types - ActiveCollisionTypes::default()).is_empty()
    }
}

/// What the project's settings over the whole world leave to the planner.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Room {
    /// Bits the planner may give a group as its membership for collision
    /// groups: every project filter holds them, no narrowed project
    /// membership does.
    pub(crate) collision: Group,
    /// The same for solver groups.
    pub(crate) solver: Group,
    /// Some collider's types pair non-dynamic bodies beyond Rapier's defaults.
    pub(crate) widened: bool,
}

impl Room {
    /// Everything: what the planner assumes before it needs to look.
    pub(crate) const ALL: Room = Room {
        collision: Group::ALL,
        solver: Group::ALL,
        widened: false,
    };

    /// Looks at every collider's project settings.
    ///
    /// A collider `k` the planner narrows has membership `{b}` and filter
    /// `ALL - X` (its own settings being Rapier's defaults). Against any
    /// other collider `j`, whose settings are its project's, Rapier's test
    /// must then answer as with `k`'s defaults, which is `true`: `b` must be
    /// in `j`'s filter, and `j`'s membership must hold a bit outside `X`.
    /// Taking `b` and `X` from bits every filter holds and no narrowed
    /// membership holds gives both.
    pub(crate) fn of_world(
        colliders: &ColliderSet,
        own: impl Fn(ColliderHandle, &Collider) -> Settings,
    ) -> Room {
        let mut room = Room::ALL;
        let mut memberships = (Group::empty(), Group::empty());
        for (handle, collider) in colliders.iter() {
            let settings = own(handle, collider);
            room.collision &= settings.collision.filter;
            room.solver &= settings.solver.filter;
            if settings.collision.memberships != Group::ALL {
                memberships.0 |= settings.collision.memberships;
            }
            if settings.solver.memberships != Group::ALL {
                memberships.1 |= settings.solver.memberships;
            }
            room.widened |= settings.widened();
        }
        room.collision -= memberships.0;
        room.solver -= memberships.1;
        room
    }

    /// Whether one collider's settings `own` leave this room as it is, so
    /// that a plan made with it stays exact with that collider in the world.
    pub(crate) fn holds(self, own: Settings) -> bool {
        let fits = |groups: InteractionGroups, room: Group| {
            groups.filter.contains(room)
                && (groups.memberships == Group::ALL || !groups.memberships.intersects(room))
        };
        fits(own.collision, self.collision)
            && fits(own.solver, self.solver)
            && (self.widened || !own.widened())
    }

    /// The bits free for both collision and solver groups (a group's bit
    /// serves both).
    pub(crate) fn bits(self) -> Group {
        self.collision & self.solver
    }
}

/// The body types of the pair `a`, `b` (fixed for a collider without a body,
/// as Rapier reads it).
pub(crate) fn body_types(
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    a: ColliderHandle,
    b: ColliderHandle,
) -> (RigidBodyType, RigidBodyType) {
    let of = |c: ColliderHandle| {
        colliders
            .get(c)
            .and_then(|c| c.parent())
            .and_then(|b| bodies.get(b))
            .map_or(RigidBodyType::Fixed, |b| b.body_type())
    };
    (of(a), of(b))
}

/// A collider the crate has written settings to: the project's own
/// settings, and what the crate wrote (a difference later means the project
/// changed a setting through Rapier).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Written {
    pub(crate) own: Settings,
    pub(crate) wrote: Settings,
}

impl Written {
    /// The project's settings as of `now`: those the project changed since
    /// the crate wrote, the remembered ones otherwise.
    pub(crate) fn own_as_of(&self, now: Settings) -> Settings {
        self.own.changed_since(self.wrote, now)
    }
}
