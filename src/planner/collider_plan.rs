//! The Rapier settings the planner gives one collider, and how they are
//! combined with the project's own (`docs/semantics.md`, "The project's
//! own settings").

use super::super::rapier::prelude::*;

use super::class::Class;
use super::group_settings::default_refuses;
use super::super::world::Settings;
use super::super::{CollisionGroup, CollisionRule, CollisionRuleSet};

/// The hook flags every hooked collider carries.
const HOOKS: ActiveHooks =
    ActiveHooks::FILTER_CONTACT_PAIRS.union(ActiveHooks::FILTER_INTERSECTION_PAIR);

/// The Rapier settings the planner gives one collider, before they are
/// combined with the project's own (see [`ColliderPlan::combined`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct ColliderPlan {
    /// `None`: the collider is hooked.
    pub(crate) class: Option<Class>,
    pub(crate) collision: InteractionGroups,
    pub(crate) solver: InteractionGroups,
    pub(crate) types: ActiveCollisionTypes,
}

impl ColliderPlan {
    pub(crate) fn hooked(&self) -> bool {
        self.class.is_none()
    }

    /// Whether the plan leaves the collider with Rapier's own settings.
    pub(crate) fn is_rapier_default(&self) -> bool {
        !self.hooked()
            && self.collision == InteractionGroups::all()
            && self.solver == InteractionGroups::all()
            && self.types == ActiveCollisionTypes::default()
    }

    /// The settings a collider gets: the plan combined with the project's
    /// own settings `own` (`docs/semantics.md`, "The project's own settings"). The hook bits are
    /// added to the project's; the project's collision and solver groups are
    /// kept, and narrowed only where the planner gave a group a bit, which it
    /// does only for colliders whose own groups are Rapier's defaults; the
    /// collision types are the project's, widened where a rule lets two
    /// non-dynamic bodies pair (never narrowed). `modifying`: the collider
    /// also modifies contacts (`ManifoldUpdate::Never`).
    pub(crate) fn combined(&self, own: Settings, modifying: bool) -> Settings {
        let mut hooks = own.hooks;
        if self.hooked() {
            hooks |= HOOKS;
        }
        if modifying {
            hooks |= ActiveHooks::MODIFY_SOLVER_CONTACTS;
        }
        let keep = |planned: InteractionGroups, own: InteractionGroups| {
            if planned == InteractionGroups::all() {
                own
            } else {
                planned
            }
        };
        Settings {
            collision: keep(self.collision, own.collision),
            solver: keep(self.solver, own.solver),
            types: own.types | (self.types - ActiveCollisionTypes::default()),
            hooks,
        }
    }

    /// This plan, or the hooked one where it cannot be combined exactly with
    /// the project's settings `own`: a group bit on a collider whose own
    /// groups are narrowed (no single group test says "both allow").
    pub(super) fn fitted(self, own: Settings, dynamic: bool, rules: &CollisionRuleSet) -> ColliderPlan {
        let narrows = |planned: InteractionGroups, own: InteractionGroups| {
            planned != InteractionGroups::all() && own != InteractionGroups::all()
        };
        // The kinematic entry gives way to wider project types (see
        // `CollisionRuleSet::by_kinematic_entry`), pair by pair, which a bit
        // that keeps DEFAULT_KINEMATIC from itself cannot say.
        // Nor can Rapier's type test, where the pairs it lets through get a
        // default rule that refuses them or keeps their contacts out.
        let default_refuses = default_refuses(rules);
        let kinematic = self.class.is_some_and(|c| {
            c.group == CollisionGroup::DEFAULT_KINEMATIC
                && (default_refuses || !self.collision.filter.contains(self.collision.memberships))
        });
        let typed = !dynamic && own.widened() && kinematic;
        if !self.hooked()
            && (narrows(self.collision, own.collision) || narrows(self.solver, own.solver) || typed)
        {
            ColliderPlan::hooked_plan(dynamic)
        } else {
            self
        }
    }

    /// The plan of a dynamic collider native by its personal `rule` (see
    /// [`native_personal`](super::personal::native_personal)): every pair it has with a native collider gets
    /// `rule`, whatever the groups say. Its memberships are every bit, which
    /// every filter that is not empty holds (as a hooked collider's do);
    /// its filters say `rule`: none for `NoPair` (collision groups), none
    /// for `NoResponse` (solver groups), all for `Normal`, which leaves it
    /// with Rapier's defaults. Nothing in it depends on the rest of the
    /// plan, so a partial plan gives it exactly what a whole plan would.
    pub(super) fn personal(rule: CollisionRule) -> ColliderPlan {
        let none = InteractionGroups::new(Group::ALL, Group::NONE, InteractionTestMode::And);
        let (collision, solver) = match rule {
            CollisionRule::NoPair => (none, InteractionGroups::all()),
            CollisionRule::NoResponse => (InteractionGroups::all(), none),
            _ => (InteractionGroups::all(), InteractionGroups::all()),
        };
        ColliderPlan {
            // Its group takes no part in its pairs: the class only marks it
            // native.
            class: Some(Class::unreached(true)),
            collision,
            solver,
            types: ActiveCollisionTypes::default(),
        }
    }

    /// The plan of a collider no rule reaches: Rapier's defaults.
    pub(crate) fn unreached(dynamic: bool) -> ColliderPlan {
        ColliderPlan {
            class: Some(Class::unreached(dynamic)),
            collision: InteractionGroups::all(),
            solver: InteractionGroups::all(),
            types: ActiveCollisionTypes::default(),
        }
    }

    /// A hooked collider keeps a collider's default groups (every bit), which
    /// pass every native test, so the hook decides; a non-dynamic one takes
    /// every collision type so that the hook also sees its pairs with other
    /// non-dynamic colliders.
    pub(super) fn hooked_plan(dynamic: bool) -> ColliderPlan {
        ColliderPlan {
            class: None,
            collision: InteractionGroups::all(),
            solver: InteractionGroups::all(),
            types: if dynamic {
                ActiveCollisionTypes::default()
            } else {
                ActiveCollisionTypes::all()
            },
        }
    }
}
