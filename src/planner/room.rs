//! The room the project leaves: which group bits and collision types the
//! project's own settings over the whole world leave to the planner.

use super::super::rapier::prelude::*;

use super::super::world::Settings;

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
