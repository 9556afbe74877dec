//! The crate's mark on a collider it writes: which of the collider's
//! settings are the crate's, kept on the collider itself so that a world
//! saved by any means (Rapier's serde of its sets, a game's own save) tells
//! the hooks that load it what is theirs and what is the project's
//! (`docs/semantics.md`, "Saving and loading").
//!
//! The mark lives in the top bits of the collider's [`ActiveEvents`], which
//! Rapier reads only through `contains(COLLISION_EVENTS)` and
//! `contains(CONTACT_FORCE_EVENTS)`: the bits change no test Rapier makes,
//! and its serde keeps bits it does not know. The project's own event bits
//! are never touched.

use super::super::rapier::prelude::*;

use super::settings::{Settings, Written};

/// The bit that says a collider carries the crate's writes.
const MARKED: u32 = 1 << 31;
/// The collision groups are the crate's (the project's are Rapier's
/// defaults: the crate narrows no other).
const COLLISION: u32 = 1 << 30;
/// The solver groups are the crate's.
const SOLVER: u32 = 1 << 29;
/// The hook bits the crate added (`ActiveHooks` bits 0-2, shifted).
const HOOKS_SHIFT: u32 = 26;
const HOOK_BITS: u32 = 0b111;
/// The collision types the crate added, one bit per type it can add.
const TYPES: [(ActiveCollisionTypes, u32); 3] = [
    (ActiveCollisionTypes::KINEMATIC_KINEMATIC, 1 << 23),
    (ActiveCollisionTypes::KINEMATIC_FIXED, 1 << 24),
    (ActiveCollisionTypes::FIXED_FIXED, 1 << 25),
];
/// Where the digests of the groups the crate wrote go (8 bits each): a
/// project that sets a collider's groups after the crate wrote them (before
/// saving, or in the loaded world before the hooks' first step) is told
/// from the crate's write by its digest.
const COLLISION_DIGEST: u32 = 15;
const SOLVER_DIGEST: u32 = 7;
/// Every bit the mark may use: bits 7 to 31 (Rapier's own events use bits
/// 0 and 1).
const ALL: u32 = !0 << SOLVER_DIGEST;

/// Which of a collider's settings the crate wrote over the project's.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Mark(u32);

impl Mark {
    /// The mark of a collider the crate wrote `written.wrote` on over the
    /// project's `written.own`; no mark where the two are the same.
    pub(crate) fn of_written(written: Option<&Written>) -> Mark {
        let Some(&Written { own, wrote }) = written else {
            return Mark(0);
        };
        if own == wrote {
            return Mark(0);
        }
        let mut bits = MARKED;
        if wrote.collision != own.collision {
            bits |= COLLISION | digest(wrote.collision) << COLLISION_DIGEST;
        }
        if wrote.solver != own.solver {
            bits |= SOLVER | digest(wrote.solver) << SOLVER_DIGEST;
        }
        bits |= ((wrote.hooks - own.hooks).bits() & HOOK_BITS) << HOOKS_SHIFT;
        for (types, bit) in TYPES {
            if wrote.types.contains(types) && !own.types.contains(types) {
                bits |= bit;
            }
        }
        Mark(bits)
    }

    /// The mark `collider` carries.
    pub(crate) fn on(collider: &Collider) -> Mark {
        Mark(collider.active_events().bits() & ALL)
    }

    /// Whether the collider carries the crate's writes.
    pub(crate) fn is_marked(self) -> bool {
        self.0 & MARKED != 0
    }

    /// What the crate wrote on a collider whose settings are `now`: the
    /// project's own under them, read back from the mark (`None`: no mark).
    /// A setting the project changed since the crate wrote it (groups whose
    /// digest differs, hook bits or types that lack what the crate added)
    /// is the project's, as the hooks that wrote it would read it
    /// (`docs/semantics.md`, "The project's own settings").
    pub(crate) fn written(self, now: Settings) -> Option<Written> {
        if !self.is_marked() {
            return None;
        }
        let mut own = now;
        let digest_of = |shift: u32| (self.0 >> shift) & 0xff;
        if self.0 & COLLISION != 0 && digest(now.collision) == digest_of(COLLISION_DIGEST) {
            own.collision = InteractionGroups::all();
        }
        if self.0 & SOLVER != 0 && digest(now.solver) == digest_of(SOLVER_DIGEST) {
            own.solver = InteractionGroups::all();
        }
        let hooks = ActiveHooks::from_bits_retain((self.0 >> HOOKS_SHIFT) & HOOK_BITS);
        if now.hooks.contains(hooks) {
            own.hooks -= hooks;
        }
        let types = TYPES
            .iter()
            .filter(|&&(_, bit)| self.0 & bit != 0)
            .fold(ActiveCollisionTypes::empty(), |all, &(types, _)| all | types);
        if now.types.contains(types) {
            own.types -= types;
        }
        // The project changed every setting the crate wrote: none is the
        // crate's any more.
        (own != now).then_some(Written { own, wrote: now })
    }

    /// Whether the crate wrote the groups of `kind` (0: collision, 1:
    /// solver).
    pub(crate) fn wrote_groups(self, kind: usize) -> bool {
        self.0 & [COLLISION, SOLVER][kind] != 0
    }

    /// Whether the crate added the hook bits of a hooked collider.
    pub(crate) fn hooked(self) -> bool {
        let added = ActiveHooks::from_bits_retain((self.0 >> HOOKS_SHIFT) & HOOK_BITS);
        added.contains(ActiveHooks::FILTER_CONTACT_PAIRS | ActiveHooks::FILTER_INTERSECTION_PAIR)
    }

    /// `events` with this mark in place of the one they carry; the
    /// project's own bits kept.
    pub(crate) fn in_events(self, events: ActiveEvents) -> ActiveEvents {
        ActiveEvents::from_bits_retain((events.bits() & !ALL) | self.0)
    }
}

/// Eight bits that tell most other groups from `groups`.
fn digest(groups: InteractionGroups) -> u32 {
    let mode = u64::from(matches!(groups.test_mode, InteractionTestMode::Or)) << 63;
    let bits = (u64::from(groups.memberships.bits()) << 32 | u64::from(groups.filter.bits())) ^ mode;
    (bits.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 56) as u32
}

#[cfg(test)]
mod tests {
    use super::*;

    fn settings(hooks: ActiveHooks, types: ActiveCollisionTypes) -> Settings {
        Settings {
            collision: InteractionGroups::all(),
            solver: InteractionGroups::all(),
            types,
            hooks,
        }
    }

    #[test]
    fn the_project_settings_come_back_from_the_mark() {
        let layer = InteractionGroups::new(Group::GROUP_2, Group::ALL, InteractionTestMode::And);
        let own = Settings {
            collision: layer,
            ..settings(
                ActiveHooks::MODIFY_SOLVER_CONTACTS,
                ActiveCollisionTypes::default() | ActiveCollisionTypes::KINEMATIC_FIXED,
            )
        };
        let bit = InteractionGroups::new(Group::GROUP_5, Group::ALL, InteractionTestMode::And);
        let wrote = Settings {
            collision: layer,
            solver: bit,
            types: ActiveCollisionTypes::all(),
            hooks: own.hooks | ActiveHooks::FILTER_CONTACT_PAIRS | ActiveHooks::FILTER_INTERSECTION_PAIR,
        };
        let written = Written { own, wrote };
        let mark = Mark::of_written(Some(&written));
        assert!(mark.is_marked() && mark.hooked() && mark.wrote_groups(1) && !mark.wrote_groups(0));
        let events = mark.in_events(ActiveEvents::COLLISION_EVENTS);
        assert!(events.contains(ActiveEvents::COLLISION_EVENTS));
        let mut collider = ColliderBuilder::ball(1.0).active_events(events).build();
        collider.set_active_events(events);
        assert_eq!(Mark::on(&collider), mark);
        assert_eq!(mark.written(wrote), Some(written));
        // Cleared, the project's event bits stay.
        assert_eq!(Mark::default().in_events(events), ActiveEvents::COLLISION_EVENTS);
    }

    #[test]
    fn a_setting_the_project_changed_since_is_the_projects() {
        let own = settings(ActiveHooks::empty(), ActiveCollisionTypes::default());
        let bit = InteractionGroups::new(Group::GROUP_3, Group::ALL, InteractionTestMode::And);
        let wrote = Settings {
            collision: bit,
            types: ActiveCollisionTypes::all(),
            hooks: ActiveHooks::FILTER_CONTACT_PAIRS | ActiveHooks::FILTER_INTERSECTION_PAIR,
            ..own
        };
        let mark = Mark::of_written(Some(&Written { own, wrote }));
        let layer = InteractionGroups::new(Group::GROUP_1, Group::GROUP_2, InteractionTestMode::And);
        let kinematic_fixed = ActiveCollisionTypes::default() | ActiveCollisionTypes::KINEMATIC_FIXED;
        let now = Settings {
            collision: layer,
            types: kinematic_fixed,
            hooks: ActiveHooks::FILTER_CONTACT_PAIRS,
            ..wrote
        };
        assert_eq!(mark.written(now), None, "every setting changed since is the project's");
    }

    #[test]
    fn nothing_written_is_no_mark() {
        let own = settings(ActiveHooks::empty(), ActiveCollisionTypes::default());
        let mark = Mark::of_written(Some(&Written { own, wrote: own }));
        assert!(!mark.is_marked());
        assert_eq!(mark.written(own), None);
        assert_eq!(Mark::of_written(None), Mark::default());
    }
}
