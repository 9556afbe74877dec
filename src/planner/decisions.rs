//! How each specific entry is decided, kept with the entry: Rapier's groups
//! with a bit of its own ([`Decision::Bits`]), or one side hooked
//! ([`Decision::Hooked`]) (`docs/architecture.md`, "The planner").
//!
//! A decision is made the first time a plan meets its entry with colliders
//! on both sides, and kept for the entry's life: a whole plan and a plan of
//! a few colliders read and make decisions the same way (in the node order
//! of the entries), so a world's plan is the same however many whole plans
//! it had, and a plan of a few colliders never has to look at the rest of
//! the world. A `Bits` decision is checked again whenever a plan meets its
//! entry (a collider under a side changed, or a new entry links the sides)
//! and gives way to a hooked side where it is no longer exact; a hooked side
//! is always exact.

use hashbrown::{HashMap, HashSet};
use smallvec::SmallVec;

use super::super::rapier::prelude::*;

use super::carriers::side_cost;
use super::class::Class;
use super::collider_plan::ColliderPlan;
use super::plan::{Request, ordered};
use super::super::model::{CollidersUnder, Decision, NodeMap, SmallSet};
use super::super::world::Mark;
use super::super::{CollisionRule, Node};

/// A collider's plan before the entries: its class's, a personal one, or
/// hooked by its own chain.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Base {
    pub(crate) plan: ColliderPlan,
    /// Native by a personal rule (never carries a bit).
    pub(crate) personal: bool,
    /// The first personal rule of its chain, and its depth.
    pub(crate) first_personal: Option<(CollisionRule, usize)>,
    /// Its class by its chain (whether or not its group is native).
    pub(crate) class: Option<Class>,
    pub(crate) dynamic: bool,
    /// Its body: a collider moved to another body has another base, and its
    /// entries are checked again (a parent-map edit, which changes chains
    /// without changing bodies, names its colliders to the planner itself).
    pub(crate) body: Option<RigidBodyHandle>,
}

/// The decisions of every entry a plan met, each entry (its nodes in the
/// node order) listed under both of its nodes, and what they say of each
/// node, so that a collider's plan reads its chain, not the entries.
#[derive(Clone, Debug, Default)]
pub(crate) struct Decisions {
    made: HashMap<(Node, Node), Decision>,
    /// The entries under each node.
    listed: NodeMap<SmallSet<(Node, Node)>>,
    /// What the decisions say of each node they name: one record, read
    /// once for each node of a collider's chain.
    says: NodeMap<Say>,
    /// How many nodes carry each bit, and how many leave it out: a bit is
    /// a star, one node on one end and any number on the other, so that
    /// each of its carriers meets each node that leaves it out through an
    /// entry (see [`bits_for`](Self::bits_for)).
    carriers_on: NodesOnBits,
    others_on: NodesOnBits,
    /// The decisions made and undone since the hooks last took them, in
    /// order (`None`: undone): the hooks copy them into the rule set, which
    /// a saved set carries (`docs/semantics.md`, "Saving and loading").
    journal: Vec<((Node, Node), Option<Decision>)>,
}

/// What the decisions say of one node's colliders (all that
/// [`Decisions::apply`] reads of a node): hooked, the membership bit it
/// carries and the bit it leaves out, of each kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Footprint {
    hooked: bool,
    carrying: [Option<u32>; 2],
    shared: [Option<u32>; 2],
}

/// A bit of one kind a node carries or leaves out, and how many entries
/// use it there.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Users {
    bit: u32,
    entries: u32,
}

/// What the decisions say of one node, with how many say it: how many hook
/// its colliders, and of each kind the bit it carries and the bit it leaves
/// out.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Say {
    hooked: u32,
    carrying: [Option<Users>; 2],
    shared: [Option<Users>; 2],
}

/// Which of a node's bits an entry uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Role {
    /// The membership bit its colliders carry.
    Carrying,
    /// The bit its colliders leave out.
    Shared,
}

impl Say {
    fn bits(&mut self, role: Role) -> &mut [Option<Users>; 2] {
        match role {
            Role::Carrying => &mut self.carrying,
            Role::Shared => &mut self.shared,
        }
    }

    fn footprint(&self) -> Footprint {
        let bit = |users: Option<Users>| users.map(|u| u.bit);
        Footprint {
            hooked: self.hooked > 0,
            carrying: self.carrying.map(bit),
            shared: self.shared.map(bit),
        }
    }
}

/// What deciding reads besides the rules and the world.
pub(super) struct Facts<'a> {
    /// The base of a collider the rules reach (`None`: not planned).
    pub(super) base: &'a dyn Fn(ColliderHandle) -> Option<Base>,
    /// Colliders in pinned pairs (never carry a bit).
    pub(super) pinned: &'a dyn Fn(ColliderHandle) -> bool,
    /// The bits free for entries: the room the project's settings leave,
    /// less the groups' bits. Looked up only when an entry asks for a bit
    /// (the room is then read over the whole world, once).
    pub(super) free: &'a mut dyn FnMut() -> Group,
}


/// An entry whose decision [`Decisions::decide`] undid, to be made again.
struct Undone {
    entry: (Node, Node),
    /// The first node's side holds the rule (the owner's side hooks on a tie).
    owner_is_first: bool,
    /// 0 for `NoPair`, 1 for `NoResponse`, else no bit.
    kind: Option<usize>,
    /// The colliders under each node.
    under: (CollidersUnder, CollidersUnder),
}

/// How many nodes are on each bit of each kind (`[kind][bit]`).
type NodesOnBits = [[u32; 32]; 2];

impl Decisions {
    /// Decisions saved with a rule set, for hooks that have made none: a
    /// world saved mid-run goes on with the decisions it was stepped with,
    /// which rest on the pairs Rapier had when each was made
    /// (`planner/carriers.rs`), not on those of the loaded world.
    pub(crate) fn seed(&mut self, saved: impl IntoIterator<Item = ((Node, Node), Decision)>) {
        let mut saved: Vec<_> = saved.into_iter().collect();
        saved.sort_unstable_by_key(|&(entry, _)| entry);
        for (entry, decision) in saved {
            self.list(entry);
            self.make(entry, decision);
        }
    }

    /// Whether no entry has a decision.
    pub(crate) fn is_empty(&self) -> bool {
        self.made.is_empty()
    }

    /// Every decision, in no order.
    pub(crate) fn all(&self) -> impl Iterator<Item = ((Node, Node), Decision)> + '_ {
        self.made.iter().map(|(&entry, &decision)| (entry, decision))
    }

    /// The decisions made and undone since the last call, in order (the
    /// journal keeps its room for the next step's).
    pub(crate) fn drain_journal(
        &mut self,
    ) -> impl Iterator<Item = ((Node, Node), Option<Decision>)> + '_ {
        self.journal.drain(..)
    }

    /// The entries listed under `node`, in no order.
    pub(super) fn listed(&self, node: Node) -> impl Iterator<Item = (Node, Node)> + '_ {
        self.listed.get(node).into_iter().flat_map(SmallSet::iter)
    }

    /// How many entries are listed under `node`.
    fn listed_count(&self, node: Node) -> usize {
        self.listed.get(node).map_or(0, SmallSet::len)
    }

    /// Forgets every entry not in `keep` (sorted): a whole plan's entries.
    pub(super) fn keep_only(&mut self, keep: &[(Node, Node)]) {
        let mut gone: Vec<(Node, Node)> = self
            .made
            .keys()
            .copied()
            .chain(self.listed.values().flat_map(SmallSet::iter))
            .filter(|e| keep.binary_search(e).is_err())
            .collect();
        gone.sort_unstable();
        gone.dedup();
        for entry in gone {
            self.forget(entry);
        }
    }

    /// Forgets the entries listed under `node` that `ended` says have ended
    /// (a removed object's, or one an edit removed), and returns their
    /// nodes whose colliders are planned again: those the decisions now
    /// say another thing of, and those `reached` says no entry reaches
    /// through any more (a personal rule may decide them now). A turret
    /// whose ball leaves keeps its bit for its other balls, and its plan.
    pub(crate) fn forget_ended(
        &mut self,
        node: Node,
        ended: impl Fn((Node, Node)) -> bool,
        reached: impl Fn(Node) -> bool,
    ) -> SmallVec<[Node; 4]> {
        // Asked of every node an edit touches or a removal takes, most of
        // which no entry names (a streamed level's tiles): those cost one
        // look-up, not a collection of nothing (`docs/performance.md`,
        // "Run 49").
        let Some(listed) = self.listed.get(node) else {
            return SmallVec::new();
        };
        // A removed ball ends the one entry about its turret: a handful,
        // kept off the heap.
        let mut gone: SmallVec<[(Node, Node); 4]> = listed.iter().filter(|&e| ended(e)).collect();
        if gone.is_empty() {
            return SmallVec::new();
        }
        // In the node order, whatever the set's.
        gone.sort_unstable();
        let mut nodes: SmallVec<[Node; 4]> = gone.iter().flat_map(|&(x, y)| [x, y]).collect();
        nodes.sort_unstable();
        nodes.dedup();
        let before: SmallVec<[Footprint; 4]> = nodes.iter().map(|&n| self.footprint(n)).collect();
        for entry in gone {
            self.forget(entry);
        }
        nodes
            .into_iter()
            .zip(before)
            .filter(|&(n, was)| self.footprint(n) != was || !reached(n))
            .map(|(n, _)| n)
            .collect()
    }

    /// What the decisions say of `node`'s colliders.
    pub(super) fn footprint(&self, node: Node) -> Footprint {
        self.says.get(node).copied().unwrap_or_default().footprint()
    }

    /// Whether `entry` has a decision.
    pub(super) fn made(&self, entry: (Node, Node)) -> bool {
        self.made.contains_key(&entry)
    }

    /// The entries with a `Bits` decision that a new entry `e` may link
    /// (a node of `e` in the chains of each side's colliders, which makes
    /// their bit inexact): those listed under the chains of the colliders
    /// under both of `e`'s nodes.
    pub(super) fn linked_by(&self, request: &Request<'_>, e: (Node, Node)) -> Vec<(Node, Node)> {
        let Request {
            rules,
            bodies,
            colliders,
            ..
        } = *request;
        // The entries listed under the chains of the colliders under `node`
        // that have a bit (each once per listing).
        let near = |node: Node| -> Vec<(Node, Node)> {
            rules
                .colliders_under(node, bodies, colliders)
                .into_iter()
                .flat_map(|c| rules.hierarchy.chain(bodies, colliders, Node::Collider(c)))
                .flat_map(|n| self.listed(n))
                .filter(|&other| other != e)
                .filter(|other| matches!(self.made.get(other), Some(Decision::Bits { .. })))
                .collect()
        };
        // One side is usually a new object whose chains list nothing with a
        // bit (a ball about its turret): the hub's side is not read then.
        let (small, large) = if self.listed_count(e.0) <= self.listed_count(e.1) {
            (e.0, e.1)
        } else {
            (e.1, e.0)
        };
        let first = near(small);
        if first.is_empty() {
            return first;
        }
        let first: HashSet<(Node, Node)> = first.into_iter().collect();
        let mut linked: Vec<(Node, Node)> =
            near(large).into_iter().filter(|o| first.contains(o)).collect();
        linked.sort_unstable();
        linked.dedup();
        linked
    }

    fn list(&mut self, entry: (Node, Node)) {
        for node in [entry.0, entry.1] {
            match self.listed.get_mut(node) {
                Some(listed) => listed.insert(entry),
                None => {
                    self.listed.get_or_insert_with(node, || SmallSet::One(entry));
                }
            }
        }
    }

    fn forget(&mut self, entry: (Node, Node)) -> Option<Decision> {
        let decision = self.unmake(entry);
        for node in [entry.0, entry.1] {
            if self.listed.get_mut(node).is_some_and(|l| l.remove(entry)) {
                self.listed.remove(node);
            }
        }
        decision
    }

    fn make(&mut self, entry: (Node, Node), decision: Decision) {
        self.unmake(entry);
        match decision {
            Decision::Bits {
                carrying,
                other,
                kind,
                bit,
            } => {
                self.count_in(carrying, Role::Carrying, kind, bit);
                self.count_in(other, Role::Shared, kind, bit);
            }
            Decision::Hooked { side } => self.says.or_default(side).hooked += 1,
        }
        self.made.insert(entry, decision);
        self.journal.push((entry, Some(decision)));
    }

    fn unmake(&mut self, entry: (Node, Node)) -> Option<Decision> {
        let decision = self.made.remove(&entry)?;
        self.journal.push((entry, None));
        match decision {
            Decision::Bits {
                carrying,
                other,
                kind,
                ..
            } => {
                self.count_out(carrying, Role::Carrying, kind);
                self.count_out(other, Role::Shared, kind);
            }
            Decision::Hooked { side } => {
                if let Some(say) = self.says.get_mut(side) {
                    say.hooked -= 1;
                }
                self.drop_if_silent(side);
            }
        }
        Some(decision)
    }

    /// One more entry using `node`'s bit of `kind` in `role`, and one more
    /// node on the bit if `node` had none.
    fn count_in(&mut self, node: Node, role: Role, kind: usize, bit: u32) {
        let users = self.says.or_default(node).bits(role)[kind]
            .get_or_insert(Users { bit, entries: 0 });
        users.entries += 1;
        if users.entries == 1 {
            let bit = users.bit;
            self.nodes_on(role)[kind][bit as usize] += 1;
        }
    }

    /// One entry less using `node`'s bit of `kind` in `role`, and one node
    /// less on the bit if that was the last.
    fn count_out(&mut self, node: Node, role: Role, kind: usize) {
        let Some(slot) = self.says.get_mut(node).map(|say| &mut say.bits(role)[kind]) else {
            return;
        };
        let Some(users) = slot else {
            return;
        };
        users.entries -= 1;
        if users.entries > 0 {
            return;
        }
        let bit = users.bit;
        *slot = None;
        self.nodes_on(role)[kind][bit as usize] -= 1;
        self.drop_if_silent(node);
    }

    /// How many nodes are on each bit in `role`.
    fn nodes_on(&mut self, role: Role) -> &mut NodesOnBits {
        match role {
            Role::Carrying => &mut self.carriers_on,
            Role::Shared => &mut self.others_on,
        }
    }

    /// Forgets `node`'s record once the decisions say nothing of it.
    fn drop_if_silent(&mut self, node: Node) {
        if self.says.get(node).is_some_and(|say| *say == Say::default()) {
            self.says.remove(node);
        }
    }

    /// The bit `node` carries (`Role::Carrying`) or leaves out of `kind`.
    fn bit(&self, node: Node, role: Role, kind: usize) -> Option<u32> {
        let say = self.says.get(node)?;
        let bits = match role {
            Role::Carrying => &say.carrying,
            Role::Shared => &say.shared,
        };
        bits[kind].map(|users| users.bit)
    }

    /// Whether a decision hooks the colliders under `node`.
    fn hooks_side(&self, node: Node) -> bool {
        self.says.get(node).is_some_and(|say| say.hooked > 0)
    }

    /// Every bit an entry uses.
    fn used(&self) -> Group {
        // The count of nodes on each bit says it without a walk of the
        // nodes: a new entry asks this once per decision.
        (0..32u32)
            .filter(|&bit| self.others_on.iter().any(|on| on[bit as usize] > 0))
            .fold(Group::empty(), |g, bit| g | Group::from_bits_retain(1 << bit))
    }

    /// Decides `entries` (sorted, each once) that have no decision or whose
    /// `Bits` decision is no longer exact, and forgets those that ended.
    /// Returns the entries whose decision changed: the colliders under
    /// their nodes are planned again.
    pub(super) fn decide(
        &mut self,
        request: &Request<'_>,
        facts: &mut Facts<'_>,
        entries: &[(Node, Node)],
    ) -> Vec<(Node, Node)> {
        let Request {
            rules,
            bodies,
            colliders,
            ..
        } = *request;
        let mut changed = Vec::new();
        // Every decision that no longer holds is undone before any is made
        // again: a bit the room no longer leaves, or a star another entry
        // of the same bit left, is then free to be taken anew by the first
        // entry that asks, whatever the order of the entries.
        let mut undone = Vec::new();
        for &(x, y) in entries {
            let (xy, yx) = (rules.specific(x, y), rules.specific(y, x));
            if xy == CollisionRule::Defer && yx == CollisionRule::Defer {
                if self.made.contains_key(&(x, y)) {
                    changed.push((x, y));
                }
                self.forget((x, y));
                continue;
            }
            self.list((x, y));
            let kind = match xy.most_restrictive(yx) {
                CollisionRule::NoPair => Some(0),
                CollisionRule::NoResponse if request.native_rule(CollisionRule::NoResponse) => {
                    Some(1)
                }
                _ => None,
            };
            // A hooked side is exact whatever comes under it: kept without
            // looking at the sides.
            let made = self.made.get(&(x, y)).copied();
            if matches!(made, Some(Decision::Hooked { .. })) {
                continue;
            }
            let under = |node: Node| rules.colliders_under(node, bodies, colliders);
            let (cx, cy) = (under(x), under(y));
            let kept = match made {
                Some(Decision::Hooked { .. }) => true,
                // The entry's rule changed: its bit says another rule.
                Some(Decision::Bits { kind: k, .. }) if Some(k) != kind => false,
                Some(Decision::Bits {
                    carrying,
                    kind,
                    bit,
                    ..
                }) => {
                    let (carried, other) = if carrying == x { (&cx, &cy) } else { (&cy, &cx) };
                    let fits = (facts.free)().contains(Group::from_bits_retain(1 << bit));
                    fits && self.bits_exact(request, facts, (x, y), carried, other, kind, bit)
                }
                // No pair to decide yet: decided when colliders come.
                None => cx.is_empty() || cy.is_empty(),
            };
            if !kept {
                self.unmake((x, y));
                undone.push(Undone {
                    entry: (x, y),
                    owner_is_first: xy != CollisionRule::Defer,
                    kind,
                    under: (cx, cy),
                });
            }
        }
        let undone = if request.loaded {
            self.decide_as_found(request, facts, undone, &mut changed)
        } else {
            undone
        };
        for entry in undone {
            let (x, y) = entry.entry;
            let decision = self.decide_new(request, facts, &entry);
            self.make((x, y), decision);
            changed.push((x, y));
        }
        changed
    }

    /// How an entry with no decision is decided in a new world: a bit of
    /// its own where that is exact, else the cheaper side hooked (the
    /// owner's side on a tie).
    fn decide_new(&self, request: &Request<'_>, facts: &mut Facts<'_>, entry: &Undone) -> Decision {
        let Undone {
            entry: (x, y),
            owner_is_first,
            kind,
            under: (cx, cy),
        } = entry;
        let bits = kind.and_then(|kind| self.bits_for(request, facts, (*x, *y), cx, cy, kind));
        bits.unwrap_or_else(|| {
            let (owner, owner_side, other, other_side) = if *owner_is_first {
                (*x, cx, *y, cy)
            } else {
                (*y, cy, *x, cx)
            };
            let hooked = |c: ColliderHandle| self.hooks(request, facts, c);
            let pairs = request.pairs_of;
            let side = if side_cost(request, other_side, hooked, pairs)
                < side_cost(request, owner_side, hooked, pairs)
            {
                other
            } else {
                owner
            };
            Decision::Hooked { side }
        })
    }

    /// In a world loaded without its saved decisions, decides `undone` as
    /// the world's settings show (`docs/semantics.md`, "Saving and
    /// loading") and returns the entries the world shows nothing of. An
    /// entry both of whose sides the world shows hooked hooks the side
    /// nothing else hooks, once the others are decided: its decision
    /// depends on theirs, which the run that wrote the world made in its
    /// own order.
    fn decide_as_found(
        &mut self,
        request: &Request<'_>,
        facts: &mut Facts<'_>,
        undone: Vec<Undone>,
        changed: &mut Vec<(Node, Node)>,
    ) -> Vec<Undone> {
        let mut unknown = Vec::new();
        let mut both = Vec::new();
        let mut unseen_bits = Vec::new();
        for entry in undone {
            let (x, y) = entry.entry;
            let (cx, cy) = (&entry.under.0, &entry.under.1);
            match self.found(request, facts, (x, y), cx, cy, entry.kind) {
                Found::Decision(decision) => {
                    self.make((x, y), decision);
                    changed.push((x, y));
                }
                Found::BitsIfHookedElsewhere(decision) => unseen_bits.push((entry, decision)),
                Found::BothHooked => both.push(entry),
                Found::Nothing => unknown.push(entry),
            }
        }
        loop {
            let before = both.len();
            if before == 0 || self.resolve_hooked_sides(request, facts, &mut both, changed) {
                if unseen_bits.is_empty() {
                    break;
                }
                // No more both-hooked entries can be told apart: the bits
                // whose carriers the world shows hooked are decided, which
                // may tell the rest.
                for (entry, decision) in std::mem::take(&mut unseen_bits) {
                    let Decision::Bits {
                        carrying, other, ..
                    } = decision
                    else {
                        continue;
                    };
                    let (carried, others) = if carrying == entry.entry.0 {
                        (&entry.under.0, &entry.under.1)
                    } else {
                        (&entry.under.1, &entry.under.0)
                    };
                    // A side the world shows hooked that nothing else hooks
                    // is hooked by this entry.
                    let unexplained = |side: &[ColliderHandle]| {
                        side.iter()
                            .any(|&c| shows_hooked(request, c) && !self.hooks(request, facts, c))
                    };
                    let decision = if unexplained(carried) {
                        Decision::Hooked { side: carrying }
                    } else if unexplained(others) {
                        Decision::Hooked { side: other }
                    } else {
                        decision
                    };
                    self.make(entry.entry, decision);
                    changed.push(entry.entry);
                }
            }
        }
        unknown.extend(both);
        unknown
    }

    /// Decides the entries of `both` (both sides hooked in a loaded world)
    /// whose one side nothing else hooks; `true` when none could be.
    fn resolve_hooked_sides(
        &mut self,
        request: &Request<'_>,
        facts: &mut Facts<'_>,
        both: &mut Vec<Undone>,
        changed: &mut Vec<(Node, Node)>,
    ) -> bool {
        let before = both.len();
        let mut waiting = Vec::new();
        for entry in std::mem::take(both) {
            let (x, y) = entry.entry;
            let otherwise = |side: &[ColliderHandle]| {
                side.iter().all(|&c| self.hooks(request, facts, c))
            };
            let side = match (otherwise(&entry.under.0), otherwise(&entry.under.1)) {
                (true, false) => Some(y),
                (false, true) => Some(x),
                // Hooked either way: the new world's choice.
                (true, true) => Some(match self.decide_new(request, facts, &entry) {
                    Decision::Hooked { side } => side,
                    Decision::Bits { .. } => x,
                }),
                (false, false) => None,
            };
            match side {
                Some(side) => {
                    self.make((x, y), Decision::Hooked { side });
                    changed.push((x, y));
                }
                None => waiting.push(entry),
            }
        }
        *both = waiting;
        both.len() == before
    }

    /// A `Bits` decision for entry `e`, where it is exact and a bit is
    /// free: every collider under both sides is native with Rapier's default
    /// groups (in its class's plan and its project's settings), in no
    /// pinned pair and not native by a personal rule; the carrying side is
    /// all dynamic (the smaller where both are, the first node on a tie)
    /// and its colliders carry no other bit of the kind; the sides share no
    /// collider, and no other entry links a node of one side's chains to a
    /// node of the other's (so the specific stage finds this entry for each
    /// of their pairs).
    fn bits_for(
        &self,
        request: &Request<'_>,
        facts: &mut Facts<'_>,
        e: (Node, Node),
        cx: &[ColliderHandle],
        cy: &[ColliderHandle],
        kind: usize,
    ) -> Option<Decision> {
        let side_dynamic = |side: &[ColliderHandle]| -> Option<bool> {
            side.iter()
                .map(|&c| eligible(request, facts, c))
                .try_fold(true, |all, d| d.map(|d| all && d))
        };
        let (x_dynamic, y_dynamic) = (side_dynamic(cx)?, side_dynamic(cy)?);
        let (carrying, carried, other, others) = match (x_dynamic, y_dynamic) {
            (true, true) if cy.len() < cx.len() => (e.1, cy, e.0, cx),
            (true, _) => (e.0, cx, e.1, cy),
            (false, true) => (e.1, cy, e.0, cx),
            (false, false) => return None,
        };
        // A bit is a star: every carrier of it meets every node that leaves
        // it out through an entry. So the entries about one `other` share
        // its bit while `other` is the only node leaving it out (many ghosts
        // over one floor), and the entries of one carrier share its bit
        // while it is the only carrier (a car through many pickups); else a
        // free bit.
        let carried_bit = self.bit(carrying, Role::Carrying, kind);
        let free = (facts.free)();
        let bit = match self.bit(other, Role::Shared, kind) {
            Some(bit) if carried_bit == Some(bit) => bit,
            Some(bit) if self.others_on[kind][bit as usize] == 1 => bit,
            Some(_) => return None,
            None => match carried_bit {
                Some(bit) if self.carriers_on[kind][bit as usize] == 1 => bit,
                _ => {
                    let unused = free - self.used();
                    (0..32u32).find(|&b| unused.contains(Group::from_bits_retain(1 << b)))?
                }
            },
        };
        // A shared bit the room no longer leaves is not taken again.
        if !free.contains(Group::from_bits_retain(1 << bit)) {
            return None;
        }
        // Both sides were found eligible above, the carrying one dynamic.
        self.links_exact(request, e, carried, others, kind, bit)
            .then_some(Decision::Bits {
                carrying,
                other,
                kind,
                bit,
            })
    }

    /// What a loaded world's settings show of entry `e`, in hooks that
    /// have no saved decisions (`docs/semantics.md`, "Saving and
    /// loading"): a bit of `kind` that every collider under one side leaves
    /// out of its filter, as the crate wrote it, and that every collider
    /// under the other carries as its only membership or does not show
    /// because it is hooked (a hooked collider keeps every bit), where the
    /// bit is still free and exact; else the side whose colliders all carry
    /// the hook bits the crate added, or both sides hooked (decided once
    /// the others are, see `decide_as_found`).
    fn found(
        &self,
        request: &Request<'_>,
        facts: &mut Facts<'_>,
        e: (Node, Node),
        cx: &[ColliderHandle],
        cy: &[ColliderHandle],
        kind: Option<usize>,
    ) -> Found {
        let colliders = request.colliders;
        let hooked = |c: ColliderHandle| shows_hooked(request, c);
        if let Some(kind) = kind {
            let groups = |co: &Collider| [co.collision_groups(), co.solver_groups()][kind];
            let written = |c: ColliderHandle| {
                let co = colliders.get(c)?;
                Mark::on(co).wrote_groups(kind).then(|| groups(co))
            };
            let sides = [(e.0, cx, e.1, cy), (e.1, cy, e.0, cx)];
            for (carrying, carried, other, others) in sides {
                if carried.is_empty() || others.is_empty() {
                    continue;
                }
                // A hooked collider keeps every bit and shows none; some
                // other entry must hook it for this one to have a bit.
                let mut hidden = false;
                // The carried side's one membership bit, where it shows one.
                let mut shown = None;
                let carries = carried.iter().all(|&c| match written(c) {
                    Some(g) => single_bit(g.memberships)
                        .is_some_and(|b| *shown.get_or_insert(b) == b),
                    None => {
                        hidden = true;
                        hooked(c)
                    }
                });
                // The bits every collider under `other` that shows its
                // filter leaves out.
                let mut left_out = None;
                let leaves_out = others.iter().all(|&c| match written(c) {
                    Some(g) => {
                        left_out = Some(left_out.unwrap_or(Group::ALL) & !g.filter);
                        true
                    }
                    None => {
                        hidden = true;
                        hooked(c)
                    }
                });
                if !(carries && leaves_out) {
                    continue;
                }
                let bits_of = |group: Group| -> Vec<u32> {
                    (0..32u32)
                        .filter(|&b| group.contains(Group::from_bits_retain(1 << b)))
                        .collect()
                };
                let candidates = match (shown, left_out) {
                    (Some(bit), Some(left_out)) => bits_of(left_out)
                        .into_iter()
                        .filter(|&b| b == bit)
                        .collect(),
                    (Some(bit), None) => vec![bit],
                    (None, Some(left_out)) => bits_of(left_out),
                    (None, None) => Vec::new(),
                };
                let agrees = |node, role, bit| self.bit(node, role, kind).is_none_or(|b| b == bit);
                for bit in candidates {
                    let mask = Group::from_bits_retain(1 << bit);
                    if agrees(carrying, Role::Carrying, bit)
                        && agrees(other, Role::Shared, bit)
                        && (facts.free)().contains(mask)
                        && self.bits_exact(request, facts, e, carried, others, kind, bit)
                    {
                        let decision = Decision::Bits {
                            carrying,
                            other,
                            kind,
                            bit,
                        };
                        return if hidden {
                            Found::BitsIfHookedElsewhere(decision)
                        } else {
                            Found::Decision(decision)
                        };
                    }
                }
            }
        }
        let all_hooked = |side: &[ColliderHandle]| !side.is_empty() && side.iter().all(|&c| hooked(c));
        match (all_hooked(cx), all_hooked(cy)) {
            (true, false) => Found::Decision(Decision::Hooked { side: e.0 }),
            (false, true) => Found::Decision(Decision::Hooked { side: e.1 }),
            (true, true) => Found::BothHooked,
            (false, false) => Found::Nothing,
        }
    }

    /// Whether bit `bit` of `kind`, carried by `carried` and left out by
    /// `others`, decides entry `e` exactly (see [`bits_for`](Self::bits_for)).
    #[allow(clippy::too_many_arguments)]
    fn bits_exact(
        &self,
        request: &Request<'_>,
        facts: &mut Facts<'_>,
        e: (Node, Node),
        carried: &[ColliderHandle],
        others: &[ColliderHandle],
        kind: usize,
        bit: u32,
    ) -> bool {
        let all_eligible = |side: &[ColliderHandle], dynamic: bool| {
            side.iter().all(|&c| {
                eligible(request, facts, c).is_some_and(|d| d || !dynamic)
            })
        };
        all_eligible(carried, true)
            && all_eligible(others, false)
            && self.links_exact(request, e, carried, others, kind, bit)
    }

    /// Whether bit `bit` of `kind` decides entry `e` exactly, where every
    /// collider of `carried` and `others` may carry or leave out a bit and
    /// those of `carried` are dynamic (see [`bits_exact`](Self::bits_exact)).
    fn links_exact(
        &self,
        request: &Request<'_>,
        e: (Node, Node),
        carried: &[ColliderHandle],
        others: &[ColliderHandle],
        kind: usize,
        bit: u32,
    ) -> bool {
        let Request {
            rules,
            bodies,
            colliders,
            ..
        } = *request;
        if carried.iter().any(|c| others.contains(c)) {
            return false;
        }
        // A side is usually a ball and its body, or a turret: a few nodes,
        // kept off the heap.
        let chains = |side: &[ColliderHandle]| -> SmallVec<[Node; 8]> {
            let mut nodes: SmallVec<[Node; 8]> = side
                .iter()
                .flat_map(|&c| rules.hierarchy.chain(bodies, colliders, Node::Collider(c)))
                .collect();
            nodes.sort_unstable();
            nodes.dedup();
            nodes
        };
        let (from, to) = (chains(carried), chains(others));
        // Another entry from a node of `a` to a node of `b` than `e`. A hub's
        // record holds an entry for each of hundreds of objects (a turret's
        // balls), a chain a few nodes: the smaller is walked.
        let other_entry = |a: &[Node], b: &[Node]| {
            a.iter().any(|&n| {
                rules.record(n).is_some_and(|r| {
                    if r.specific.len() <= b.len() {
                        r.specific
                            .keys()
                            .any(|&m| b.binary_search(&m).is_ok() && ordered(n, m) != e)
                    } else {
                        b.iter()
                            .any(|&m| r.specific.contains_key(&m) && ordered(n, m) != e)
                    }
                })
            })
        };
        if other_entry(&from, &to) || other_entry(&to, &from) {
            return false;
        }
        // Each carrying collider holds one membership bit of a kind.
        !carried.iter().any(|&c| {
            rules
                .hierarchy
                .chain(bodies, colliders, Node::Collider(c))
                .any(|node| self.bit(node, Role::Carrying, kind).is_some_and(|b| b != bit))
        })
    }

    /// Whether `c` ends up hooked: by its own chain, or under the hooked
    /// side of a decided entry.
    fn hooks(&self, request: &Request<'_>, facts: &Facts<'_>, c: ColliderHandle) -> bool {
        match (facts.base)(c) {
            Some(base) if base.plan.hooked() => true,
            None => false,
            Some(_) => request
                .rules
                .hierarchy
                .chain(request.bodies, request.colliders, Node::Collider(c))
                .any(|node| self.hooks_side(node)),
        }
    }

    /// `base`, the plan of collider `c` before the entries, with what the
    /// decided entries reaching it say: hooked under a hooked side, a
    /// membership bit under a carrying side, bits left out under the other.
    pub(super) fn apply(&self, request: &Request<'_>, c: ColliderHandle, base: Base) -> ColliderPlan {
        let mut plan = base.plan;
        if plan.hooked() {
            return plan;
        }
        let mut membership: [Option<u32>; 2] = [None; 2];
        let mut excluded = [Group::empty(); 2];
        let chain = request
            .rules
            .hierarchy
            .chain(request.bodies, request.colliders, Node::Collider(c));
        for node in chain {
            let Some(say) = self.says.get(node) else {
                continue;
            };
            if say.hooked > 0 {
                return ColliderPlan::hooked_plan(base.dynamic);
            }
            for kind in 0..2 {
                if let Some(users) = say.carrying[kind] {
                    membership[kind] = Some(users.bit);
                }
                if let Some(users) = say.shared[kind] {
                    excluded[kind] |= Group::from_bits_retain(1 << users.bit);
                }
            }
        }
        let narrow = |groups: InteractionGroups, bit: Option<u32>, excluded: Group| {
            if bit.is_none() && excluded.is_empty() {
                return groups;
            }
            let memberships = bit.map_or(groups.memberships, |b| Group::from_bits_retain(1 << b));
            InteractionGroups::new(memberships, groups.filter - excluded, InteractionTestMode::And)
        };
        plan.collision = narrow(plan.collision, membership[0], excluded[0]);
        plan.solver = narrow(plan.solver, membership[1], excluded[1]);
        plan
    }
}

/// What a loaded world shows of an entry's decision (see
/// [`Decisions::found`]).
enum Found {
    Decision(Decision),
    /// A `Bits` decision whose carrying side's colliders are hooked in the
    /// world, which shows no bit: the bit where another entry hooks that
    /// side, else that side hooked by this entry.
    BitsIfHookedElsewhere(Decision),
    /// Both sides' colliders carry the crate's hook bits.
    BothHooked,
    /// Nothing: decided as in a new world.
    Nothing,
}

/// Whether collider `c` of a loaded world carries the hook bits the crate
/// added (its mark says so).
fn shows_hooked(request: &Request<'_>, c: ColliderHandle) -> bool {
    request.colliders.get(c).is_some_and(|co| Mark::on(co).hooked())
}

/// The one bit of `group`, if it has exactly one.
fn single_bit(group: Group) -> Option<u32> {
    (group.bits().count_ones() == 1).then(|| group.bits().trailing_zeros())
}

/// `Some(dynamic)` if collider `c` may carry or leave out an entry's bit:
/// native with Rapier's default groups in its class's plan and in its
/// project's settings, in no pinned pair, not native by a personal rule.
fn eligible(request: &Request<'_>, facts: &Facts<'_>, c: ColliderHandle) -> Option<bool> {
    let base = (facts.base)(c)?;
    if base.plan.hooked() || base.personal || (facts.pinned)(c) {
        return None;
    }
    let own = (request.own)(c, request.colliders.get(c)?);
    let all = InteractionGroups::all();
    let defaults = [base.plan.collision, base.plan.solver, own.collision, own.solver];
    defaults.iter().all(|&g| g == all).then_some(base.dynamic)
}
