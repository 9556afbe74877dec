//! The contacts of a pair with a one-way surface (`docs/semantics.md`,
//! "One-way surfaces"), kept or dropped in `modify_solver_contacts` as
//! Rapier's `update_as_oneway_platform` does, for whichever side is the
//! surface, in the surface's body's frame, with Godot's semantics as an
//! option.

use super::super::rapier::prelude::*;

use std::sync::PoisonError;

use hashbrown::HashMap;

use super::super::OneWayKind;
use super::super::model::{body_of, soft_surface};
use super::super::world::made_of_parts;
use super::{PairKey, RuleHooks};

/// The standings (as in `user_data`) of the manifolds of pairs made of
/// parts, keyed by the pair and the manifold's sub-shapes. rapier3d merges
/// the manifolds of such a pair into clusters for the solver and gives each
/// cluster fresh data every step, `user_data` included, so a standing kept
/// there would be lost (`docs/semantics.md`, "One-way surfaces").
pub(super) type PartStandings = HashMap<(PairKey, u32, u32), u32>;

/// Whether a one-way surface bars each pair of a soft body and a surface
/// (`true`) or lets it through, since the pair was first filtered. Rapier's
/// soft-body solver builds its contacts from the manifold's points, not
/// from the solver contacts `modify_solver_contacts` can drop, so a pair
/// with a soft body is barred in `filter_contact_pair` instead
/// (`docs/semantics.md`, "One-way surfaces").
pub(super) type SoftStandings = HashMap<PairKey, bool>;

/// Where a manifold stands with one surface, kept in two bits of the
/// manifold's `user_data` (the top two for the pair's second collider as
/// the surface, the two below them for the first), so that the rest is
/// left to the project.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Standing {
    Unknown = 0,
    Allowed = 1,
    Forbidden = 2,
}

/// The bit offset of the standing of the pair's collider `side` (0 or 1) as
/// the surface.
const fn offset(side: usize) -> u32 {
    28 + 2 * side as u32
}

/// The bits of a manifold's `user_data` the standings take: the project's
/// own hooks see the rest, and their writes to these are not kept.
pub(super) const STANDING_BITS: u32 = 0b1111 << offset(0);

fn standing(user_data: u32, side: usize) -> Standing {
    match (user_data >> offset(side)) & 0b11 {
        1 => Standing::Allowed,
        2 => Standing::Forbidden,
        _ => Standing::Unknown,
    }
}

fn set_standing(user_data: &mut u32, side: usize, to: Standing) {
    *user_data = (*user_data & !(0b11 << offset(side))) | ((to as u32) << offset(side));
}

impl RuleHooks {
    /// Applies the one-way surface of each collider of the pair, if any, to
    /// the manifold's solver contacts. Only pairs with a collider under a
    /// one-way node are asked (the planner gives those colliders the
    /// contact-modification flag), and only pairs whose contacts get a
    /// response have solver contacts to drop. Returns whether the
    /// manifold's `user_data` holds standings of the crate's (a convex pair
    /// with a surface), which the project's own hooks must not see.
    pub(super) fn apply_one_ways(&self, context: &mut ContactModificationContext<'_>) -> bool {
        let rules = &self.decide.rules;
        if !rules.uses_one_ways() {
            return false;
        }
        let (bodies, colliders) = (context.bodies, context.colliders);
        let sides = [context.collider1, context.collider2];
        // Each side's surface, with its normal in the world and how fast
        // the other side comes towards it.
        let surfaces = [0, 1].map(|side| {
            let (node, one_way) = rules.one_way_of(bodies, colliders, sides[side])?;
            let normal = one_way.world_normal(bodies, colliders, node);
            let arriving = approach_speed(bodies, colliders, sides[side], sides[1 - side], normal);
            Some((one_way, normal, arriving))
        });
        if surfaces.iter().all(Option::is_none) {
            return false;
        }
        // A one-way surface is the crate's answer too: a world whose only
        // rules are one-way surfaces, stepped with the hooks but without
        // their `prepare`, is caught as any other (`docs/semantics.md`,
        // "Stepping without the hooks").
        self.answering();
        let parts = made_of_parts(colliders, sides[0], sides[1]);
        let Some(rigid) = context.rigid_mut() else {
            return false;
        };
        let part = (
            PairKey::new(sides[0], sides[1]),
            rigid.manifold.subshape1,
            rigid.manifold.subshape2,
        );
        // Convex pairs keep their standing in the manifold, and take no lock.
        let mut kept = parts.then(|| self.one_way_parts.lock().unwrap_or_else(PoisonError::into_inner));
        let mut user_data = match &kept {
            Some(kept) => kept.get(&part).copied().unwrap_or(0),
            None => *rigid.user_data,
        };
        // Both sides decide on the contacts as Rapier made them; the
        // contacts are dropped once, after.
        let empty = rigid.solver_contacts.is_empty();
        let separated = rigid.solver_contacts.iter().all(|c| c.dist > 0.0);
        let mut clear = false;
        for (side, surface) in surfaces.into_iter().enumerate() {
            let Some((one_way, normal, arriving)) = surface else {
                // A side that is no surface (any more) has no standing: a
                // stale one would read as forbidden to the witness while
                // this side lets the contacts through, and would block at
                // once if the side became a surface again.
                set_standing(&mut user_data, side, Standing::Unknown);
                continue;
            };
            // The manifold's normal points from the first collider to the
            // second: out of the surface when it is the first.
            let out = if side == 0 { *rigid.normal } else { -*rigid.normal };
            let known = out.length_squared() > 0.1;
            let facing = known && out.dot(normal) >= one_way.max_angle().cos();
            // Godot lets through a body leaving along the normal.
            let leaving = one_way.kind() == OneWayKind::Godot && arriving > 0.0;
            let ok = facing && !leaving;
            let next = match standing(user_data, side) {
                Standing::Unknown if ok => Standing::Allowed,
                Standing::Unknown => {
                    clear = true;
                    // A zero normal (touching at a point) tells nothing,
                    // and neither does a body leaving on the allowed side
                    // (one that bounced on the top): wait. Barring the
                    // latter let it fall through on its way back
                    // (`docs/semantics.md`, "One-way surfaces").
                    if known && !facing { Standing::Forbidden } else { Standing::Unknown }
                }
                Standing::Forbidden if ok && separated => Standing::Allowed,
                Standing::Forbidden => {
                    clear = true;
                    Standing::Forbidden
                }
                Standing::Allowed if empty => Standing::Unknown,
                Standing::Allowed => Standing::Allowed,
            };
            set_standing(&mut user_data, side, next);
        }
        match kept.as_mut() {
            None => *rigid.user_data = user_data,
            Some(kept) if user_data == 0 => {
                kept.remove(&part);
            }
            Some(kept) => {
                kept.insert(part, user_data);
            }
        }
        let convex = kept.is_none();
        drop(kept);
        if clear {
            rigid.solver_contacts.clear();
            if convex && forbids(user_data) {
                self.note_one_way_witness(part.0);
            }
        }
        convex
    }
}

impl RuleHooks {
    /// Whether a one-way surface bars a pair with a soft body. The soft
    /// body's place decides, as a query's does (`query_predicate`): a pair
    /// first filtered while one side is not wholly on the other's blocking
    /// side is barred until it is; a pair first filtered with both wholly
    /// there keeps its contacts until Rapier drops it.
    pub(super) fn soft_one_way_bars(&self, context: &PairFilterContext<'_>) -> bool {
        let rules = &self.decide.rules;
        if !self.soft.present || !rules.uses_one_ways() {
            return false;
        }
        let (bodies, colliders) = (context.bodies, context.colliders);
        let (a, b) = (context.collider1, context.collider2);
        if !soft_surface(colliders, a) && !soft_surface(colliders, b) {
            return false;
        }
        // Whether `surface` lets `other` through: it is a one-way surface
        // and `other` is not wholly on its blocking side.
        let through = |surface: ColliderHandle, other: ColliderHandle| {
            colliders
                .get(surface)
                .is_some_and(|collider| rules.one_way_lets_query_through(bodies, colliders, other, surface, collider))
        };
        if rules.one_way_of(bodies, colliders, a).is_none() && rules.one_way_of(bodies, colliders, b).is_none() {
            return false;
        }
        self.answering();
        let key = PairKey::new(a, b);
        let mut kept = self.soft_one_ways.lock().unwrap_or_else(PoisonError::into_inner);
        let barred = match kept.get(&key) {
            Some(false) => false,
            None | Some(true) => through(a, b) || through(b, a),
        };
        kept.insert(key, barred);
        barred
    }
}

/// Whether a manifold's `user_data` holds a forbidden standing for either
/// side: the hook drops that manifold's solver contacts at every update
/// (a side that is no surface has its standing cleared at each update).
pub(super) fn forbids(user_data: u32) -> bool {
    [0, 1].into_iter().any(|side| standing(user_data, side) == Standing::Forbidden)
}

impl RuleHooks {
    /// Forgets the standings of manifolds Rapier no longer holds, after a
    /// step: a pair that ended, or parts no longer within reach.
    pub(super) fn forget_part_standings(&mut self, narrow_phase: &NarrowPhase, colliders: &ColliderSet) {
        let uses = self.decide.rules.uses_one_ways();
        let soft = self.soft_one_ways.get_mut().unwrap_or_else(PoisonError::into_inner);
        if !uses {
            soft.clear();
        }
        // A pair with a soft body is decided again once Rapier drops it.
        soft.retain(|&key, _| {
            let (a, b) = key.colliders();
            colliders.contains(a) && colliders.contains(b) && narrow_phase.contact_pair(a, b).is_some()
        });
        let kept = self.one_way_parts.get_mut().unwrap_or_else(PoisonError::into_inner);
        if kept.is_empty() {
            return;
        }
        if !uses {
            kept.clear();
            return;
        }
        kept.retain(|&(key, subshape1, subshape2), _| {
            let (a, b) = key.colliders();
            // A handle whose slot was reused must not find the new
            // collider's pair.
            let there = colliders.contains(a) && colliders.contains(b);
            there && narrow_phase.contact_pair(a, b).is_some_and(|pair| {
                // The sub-shapes in the pair's own order, as the hook saw them.
                pair.manifolds()
                    .iter()
                    .any(|m| m.subshape1 == subshape1 && m.subshape2 == subshape2)
            })
        });
    }
}

/// How fast `other`'s body moves along `normal` relative to the surface's
/// body: negative when it comes towards the surface from its blocking side.
fn approach_speed(
    bodies: &RigidBodySet,
    colliders: &ColliderSet,
    surface: ColliderHandle,
    other: ColliderHandle,
    normal: Vector,
) -> Real {
    let velocity =
        |c: ColliderHandle| body_of(bodies, colliders, c).map_or(Vector::ZERO, |b| b.linvel());
    (velocity(other) - velocity(surface)).dot(normal)
}
