//! Specific `NoPair` and `NoResponse` entries that Rapier's groups decide,
//! with a bit of the dynamic side's own.

use hashbrown::{HashMap, HashSet};
use super::super::rapier::prelude::*;

use super::class::Class;
use super::collider_plan::ColliderPlan;
use super::group_settings::GroupSettings;
use super::plan::Request;
use super::room::Room;
use super::super::{CollisionRule, Node};

/// Specific entries that Rapier's groups decide, without the hook: a
/// `NoPair` entry in collision groups, a `NoResponse` entry in solver
/// groups. The colliders under one side, all on dynamic bodies, take a bit
/// of their own as their membership; the colliders under the other side
/// leave that bit out of their filter. Their pairs keep Rapier's contact
/// recycling, which a hooked pair loses (`docs/architecture.md`, "The
/// planner").
///
/// It is exact where the entry decides every pair between the two sides
/// and nothing else changes: both sides' colliders are native with
/// Rapier's default groups in their class and in the project's settings,
/// none is in a pinned pair, no other specific entry links a node of one
/// side's chains to a node of the other's (so the specific stage finds this
/// entry for each of their pairs), and each collider carries at most one
/// bit of each kind. The bit comes from the room the project's settings
/// leave (as a group's bit does), beside the groups' own bits; a side that
/// carries several entries uses one bit for all of them. Where any of this
/// fails, or the bits run out, the entry is carried by a hooked side.
#[derive(Debug, Default)]
pub(super) struct EntryBits {
    /// The entries decided by bits, in both orders.
    pub(super) decided: HashSet<(Node, Node)>,
    /// Each carrying collider's membership bit: collision, solver.
    pub(super) memberships: HashMap<ColliderHandle, [Option<u32>; 2]>,
    /// The bits each collider leaves out of its filters: collision, solver.
    pub(super) excluded: HashMap<ColliderHandle, [Group; 2]>,
    /// The room looked up for the bits, if an entry asked for one: the plan
    /// is made again when colliders come or go, which may change it.
    pub(super) room: Option<Room>,
}

impl EntryBits {
    pub(super) fn plan(
        request: &Request<'_>,
        classes: &[(ColliderHandle, Option<Class>, bool)],
        settings: &GroupSettings,
        personal: &HashMap<ColliderHandle, CollisionRule>,
        hooked: &HashSet<ColliderHandle>,
        looked_up: Option<Room>,
    ) -> EntryBits {
        let Request {
            rules,
            bodies,
            colliders,
            ..
        } = *request;
        let mut bits = EntryBits::default();
        // Each entry once, in a fixed order; its rule is what the specific
        // stage reads between the two nodes (both directions).
        let ordered = |a: Node, b: Node| {
            if a <= b {
                (a, b)
            } else {
                (b, a)
            }
        };
        let mut entries: Vec<(Node, Node)> = request
            .ruled
            .iter()
            .filter_map(|&node| rules.record(node).map(|r| (node, r)))
            .flat_map(|(node, record)| record.specific.keys().map(move |&o| ordered(node, o)))
            .collect();
        entries.sort_unstable();
        entries.dedup();
        let kind_of = |(x, y): (Node, Node)| match rules.specific(x, y).most_restrictive(rules.specific(y, x)) {
            CollisionRule::NoPair => Some(0),
            CollisionRule::NoResponse => Some(1),
            _ => None,
        };
        let entries: Vec<((Node, Node), usize)> = entries
            .into_iter()
            .filter_map(|e| kind_of(e).map(|kind| (e, kind)))
            .collect();
        if entries.is_empty() {
            return bits;
        }

        // A collider may carry a bit if it is native with Rapier's default
        // groups, in its class's plan and in its project's settings.
        let known: HashMap<ColliderHandle, (Option<Class>, bool)> =
            classes.iter().map(|&(h, c, d)| (h, (c, d))).collect();
        let pinned = request.pinned_colliders();
        let all = InteractionGroups::all();
        let eligible = |c: ColliderHandle| -> Option<bool> {
            let &(class, dynamic) = known.get(&c)?;
            if hooked.contains(&c) || personal.contains_key(&c) || pinned.contains(&c) {
                return None;
            }
            let planned = settings.entry(class?)?;
            let own = (request.own)(c, colliders.get(c)?);
            let defaults = [planned.collision, planned.solver, own.collision, own.solver];
            defaults.iter().all(|&g| g == all).then_some(dynamic)
        };
        let chains = |side: &[ColliderHandle]| -> HashSet<Node> {
            side.iter()
                .flat_map(|&c| rules.hierarchy.chain(bodies, colliders, Node::Collider(c)))
                .collect()
        };
        // Another entry from a node of `from` to a node of `to` than `entry`.
        let other_entry = |from: &HashSet<Node>, to: &HashSet<Node>, entry: (Node, Node)| {
            from.iter().any(|&a| {
                rules.record(a).is_some_and(|r| {
                    r.specific
                        .keys()
                        .any(|&b| to.contains(&b) && ordered(a, b) != entry)
                })
            })
        };

        let taken = settings
            .bits
            .values()
            .fold(Group::empty(), |g, &bit| g | Group::from_bits_retain(1 << bit));
        let mut free: Option<Group> = None;
        let mut node_bits: HashMap<(Node, usize), u32> = HashMap::new();
        for ((x, y), kind) in entries {
            let under = |node: Node| rules.colliders_under(node, bodies, colliders);
            let (cx, cy) = (under(x), under(y));
            if cx.is_empty() || cy.is_empty() {
                continue;
            }
            let side = |cs: &[ColliderHandle]| -> Option<bool> {
                cs.iter()
                    .map(|&c| eligible(c))
                    .try_fold(true, |all_dynamic, d| d.map(|d| all_dynamic && d))
            };
            let (Some(x_dynamic), Some(y_dynamic)) = (side(&cx), side(&cy)) else {
                continue;
            };
            // The carrying side: all dynamic, the smaller, the first node on a tie.
            let (owner, carrying, other) = match (x_dynamic, y_dynamic) {
                (true, true) if cy.len() < cx.len() => (y, cy, cx),
                (true, _) => (x, cx, cy),
                (false, true) => (y, cy, cx),
                (false, false) => continue,
            };
            if carrying.iter().any(|c| other.contains(c)) {
                continue;
            }
            let (s_nodes, t_nodes) = (chains(&carrying), chains(&other));
            if other_entry(&s_nodes, &t_nodes, (x, y)) || other_entry(&t_nodes, &s_nodes, (x, y)) {
                continue;
            }
            let bit = match node_bits.get(&(owner, kind)) {
                Some(&bit) => bit,
                None => {
                    // The groups' bits may have looked the room up already.
                    let room = *bits.room.get_or_insert_with(|| {
                        looked_up.unwrap_or_else(|| Room::of_world(colliders, request.own))
                    });
                    let free = free.get_or_insert(room.bits() - taken);
                    let Some(bit) = (0..32u32).find(|&b| free.contains(Group::from_bits_retain(1 << b)))
                    else {
                        continue;
                    };
                    bit
                }
            };
            let carries_other = carrying.iter().any(|c| {
                bits.memberships
                    .get(c)
                    .and_then(|m| m[kind])
                    .is_some_and(|b| b != bit)
            });
            if carries_other {
                continue;
            }
            if node_bits.insert((owner, kind), bit).is_none() {
                if let Some(free) = free.as_mut() {
                    free.remove(Group::from_bits_retain(1 << bit));
                }
            }
            for c in carrying {
                bits.memberships.entry(c).or_default()[kind] = Some(bit);
            }
            for c in other {
                bits.excluded.entry(c).or_insert([Group::empty(); 2])[kind] |=
                    Group::from_bits_retain(1 << bit);
            }
            bits.decided.insert((x, y));
            bits.decided.insert((y, x));
        }
        bits
    }

    /// `entry` with the bits of `collider`, if it carries or leaves out any.
    pub(super) fn apply(&self, collider: ColliderHandle, mut entry: ColliderPlan) -> ColliderPlan {
        let membership = self.memberships.get(&collider).copied().unwrap_or_default();
        let excluded = self
            .excluded
            .get(&collider)
            .copied()
            .unwrap_or([Group::empty(); 2]);
        let narrow = |groups: InteractionGroups, bit: Option<u32>, excluded: Group| {
            if bit.is_none() && excluded.is_empty() {
                return groups;
            }
            let memberships = bit.map_or(groups.memberships, |b| Group::from_bits_retain(1 << b));
            InteractionGroups::new(memberships, groups.filter - excluded, InteractionTestMode::And)
        };
        entry.collision = narrow(entry.collision, membership[0], excluded[0]);
        entry.solver = narrow(entry.solver, membership[1], excluded[1]);
        entry
    }
}
