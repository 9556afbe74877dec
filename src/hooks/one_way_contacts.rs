//! The contacts of a pair with a one-way surface (`docs/semantics.md`,
//! "One-way surfaces"), kept or dropped in `modify_solver_contacts` as
//! Rapier's `update_as_oneway_platform` does, for whichever side is the
//! surface, in the surface's body's frame, with Godot's semantics as an
//! option.

use super::super::rapier::prelude::*;

use super::super::OneWayKind;
use super::super::model::body_of;
use super::RuleHooks;

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
    /// response have solver contacts to drop.
    pub(super) fn apply_one_ways(&self, context: &mut ContactModificationContext<'_>) {
        let rules = &self.decide.rules;
        if !rules.uses_one_ways() {
            return;
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
            return;
        }
        let Some(rigid) = context.rigid_mut() else {
            return;
        };
        // Both sides decide on the contacts as Rapier made them; the
        // contacts are dropped once, after.
        let empty = rigid.solver_contacts.is_empty();
        let separated = rigid.solver_contacts.iter().all(|c| c.dist > 0.0);
        let mut drop = false;
        for (side, surface) in surfaces.into_iter().enumerate() {
            let Some((one_way, normal, arriving)) = surface else {
                continue;
            };
            // The manifold's normal points from the first collider to the
            // second: out of the surface when it is the first.
            let out = if side == 0 { *rigid.normal } else { -*rigid.normal };
            let known = out.length_squared() > 0.1;
            let mut ok = known && out.dot(normal) >= one_way.max_angle().cos();
            if one_way.kind() == OneWayKind::Godot {
                // Godot lets through a body leaving along the normal.
                ok &= arriving <= 0.0;
            }
            let next = match standing(*rigid.user_data, side) {
                Standing::Unknown if ok => Standing::Allowed,
                Standing::Unknown => {
                    drop = true;
                    // A zero normal (touching at a point) tells nothing: wait.
                    if known { Standing::Forbidden } else { Standing::Unknown }
                }
                Standing::Forbidden if ok && separated => Standing::Allowed,
                Standing::Forbidden => {
                    drop = true;
                    Standing::Forbidden
                }
                Standing::Allowed if empty => Standing::Unknown,
                Standing::Allowed => Standing::Allowed,
            };
            set_standing(rigid.user_data, side, next);
        }
        if drop {
            rigid.solver_contacts.clear();
        }
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
