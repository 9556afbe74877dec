//! What the hooks watch between steps: the colliders and bodies the rules
//! reach (every collider during a full pass). Rapier tells nobody what
//! changed, so the hooks look, before each step, at what they watch and
//! nothing else: objects removed, colliders moved to another body, bodies
//! that changed type, colliders added to a watched body. The cost of a
//! step's look is proportional to what is watched, not to the world
//! (`docs/architecture.md`, "Cost per step").

use super::super::rapier::prelude::*;

use super::super::Node;
use super::super::model::{HandleMap, dynamic_body};
use super::super::world::{Mark, Settings};

/// What the hooks remember of a watched collider.
#[derive(Clone, Copy, Debug)]
struct Known {
    body: Option<RigidBodyHandle>,
    dynamic: bool,
    /// What the crate last wrote to it, if it differs from the project's
    /// settings: the look compares, to notice the project's changes.
    wrote: Option<Settings>,
    /// The crate's mark it carries with what the crate wrote
    /// (`world/mark.rs`): the look compares, to give back a mark the
    /// project's own events setting erased.
    crate_mark: Mark,
    /// An edit touched it: the next look asks whether the rules still reach it.
    marked: bool,
}

/// What the hooks remember of a watched body.
#[derive(Clone, Copy, Debug)]
struct KnownBody {
    dynamic: bool,
    /// An edit touched it: the next look asks whether the rules still reach it.
    marked: bool,
    /// How many colliders it had: a collider added to it changes the count
    /// (one removed is itself watched, and seen removed).
    colliders: usize,
}

/// The watched colliders and bodies, each in a dense slot-indexed table and
/// a compact list (so that a look walks only them).
#[derive(Debug, Default)]
pub(crate) struct Roster {
    colliders: HandleMap<ColliderHandle, Known>,
    collider_list: Vec<ColliderHandle>,
    /// Each watched body as of the last look.
    bodies: HandleMap<RigidBodyHandle, KnownBody>,
    body_list: Vec<RigidBodyHandle>,
    /// Watched colliders whose slot a newer collider took before the look
    /// that finds them removed, with the body each was on.
    evicted: Vec<(ColliderHandle, Option<RigidBodyHandle>)>,
}

/// What one look found.
#[derive(Debug, Default)]
pub(crate) struct Look {
    /// Removed colliders, with the body each was on.
    pub(crate) removed_colliders: Vec<(ColliderHandle, Option<RigidBodyHandle>)>,
    pub(crate) removed_bodies: Vec<RigidBodyHandle>,
    /// Nodes whose chains changed: a collider moved to another body, a body
    /// whose type changed (its colliders' default group changed).
    pub(crate) changed: Vec<Node>,
    /// Colliders seen for the first time.
    pub(crate) added: Vec<ColliderHandle>,
    /// Bodies that lost a watched collider (removed or moved away).
    pub(crate) left: Vec<RigidBodyHandle>,
    /// Colliders no longer watched: the rules no longer reach them.
    pub(crate) released: Vec<ColliderHandle>,
    /// Watched colliders whose settings differ from what the crate wrote:
    /// the project changed them through Rapier.
    pub(crate) project_changed: Vec<ColliderHandle>,
    /// Watched colliders whose mark is not the one the crate wrote: the
    /// project set their events (which takes the mark), or a world was put
    /// in place without `world_replaced`.
    pub(crate) unmarked: Vec<ColliderHandle>,
    /// Some watched collider carries another of the crate's marks than the
    /// one it carried.
    pub(crate) foreign_marks: bool,
}

impl Roster {
    #[inline]
    pub(crate) fn collider_count(&self) -> usize {
        self.collider_list.len()
    }

    #[inline]
    pub(crate) fn body_count(&self) -> usize {
        self.body_list.len()
    }

    pub(crate) fn colliders(&self) -> &[ColliderHandle] {
        &self.collider_list
    }

    /// Starts watching `collider` (as it is now); `true` if it was not watched.
    pub(crate) fn watch_collider(
        &mut self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        collider: ColliderHandle,
    ) -> bool {
        if self.colliders.get(collider).is_some() {
            return false;
        }
        if self.colliders.is_superseded(collider) || !colliders.contains(collider) {
            // A handle of no collider in the world (its slot holds a newer
            // one, or one Rapier has yet to hand out, which a corrupt save
            // can name): listed alone, so that the next look reports it
            // removed, without taking the slot from a live collider.
            self.collider_list.push(collider);
            return false;
        }
        let body = colliders.get(collider).and_then(|c| c.parent());
        let known = Known {
            body,
            dynamic: dynamic_body(bodies, body),
            wrote: None,
            // What it carries when first watched (a loaded world's mark, a
            // cut piece's copy of its source's) until the crate writes it.
            crate_mark: colliders.get(collider).map_or(Mark::default(), Mark::on),
            marked: false,
        };
        // A watched collider in a reused slot stays in the list: the next
        // look finds it removed, and its body lost a collider.
        if let Some((old, known)) = self.colliders.insert_evicting(collider, known) {
            self.evicted.push((old, known.body));
        }
        self.collider_list.push(collider);
        true
    }

    /// Starts watching `body`; `true` if it was not watched.
    pub(crate) fn watch_body(&mut self, bodies: &RigidBodySet, body: RigidBodyHandle) -> bool {
        if self.bodies.get(body).is_some() {
            return false;
        }
        if self.bodies.is_superseded(body) || !bodies.contains(body) {
            self.body_list.push(body);
            return false;
        }
        // A count no body has: the first look lists its colliders.
        let known = KnownBody {
            dynamic: dynamic_body(bodies, Some(body)),
            marked: false,
            colliders: usize::MAX,
        };
        self.bodies.insert_evicting(body, known);
        self.body_list.push(body);
        true
    }

    /// Records what the crate wrote to a watched collider and the mark it
    /// carries with it (`None`: the project's own settings).
    pub(crate) fn wrote(&mut self, collider: ColliderHandle, wrote: Option<(Settings, Mark)>) {
        if let Some(known) = self.colliders.get_mut(collider) {
            known.wrote = wrote.map(|(settings, _)| settings);
            known.crate_mark = wrote.map_or(Mark::default(), |(_, mark)| mark);
        }
    }

    /// Marks a watched `node`: whether the rules still reach it is asked at
    /// the next look (an edit touched it).
    pub(crate) fn mark(&mut self, node: Node) {
        match node {
            Node::Collider(c) => {
                if let Some(known) = self.colliders.get_mut(c) {
                    known.marked = true;
                }
            }
            Node::Body(b) => {
                if let Some(known) = self.bodies.get_mut(b) {
                    known.marked = true;
                }
            }
        }
    }

    /// Looks at every watched object. With `all`, also walks Rapier's whole
    /// collider set for colliders not yet watched (a full pass). Marked
    /// objects (every object with `ask_all`) that `keep` no longer wants are
    /// let go: the rules no longer reach them.
    pub(crate) fn look(
        &mut self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        all: bool,
        ask_all: bool,
        keep: impl Fn(Node) -> bool,
    ) -> Look {
        let mut look = Look::default();
        if all {
            for (handle, _) in colliders.iter() {
                if self.watch_collider(bodies, colliders, handle) {
                    look.added.push(handle);
                }
            }
        }
        let mut list = std::mem::take(&mut self.body_list);
        list.retain(|&handle| {
            let Some(body) = bodies.get(handle) else {
                self.bodies.remove(handle);
                look.removed_bodies.push(handle);
                return false;
            };
            let Some(was) = self.bodies.get_mut(handle) else {
                // An older generation evicted by a newer one: removed.
                look.removed_bodies.push(handle);
                return false;
            };
            if was.dynamic != body.is_dynamic() {
                was.dynamic = body.is_dynamic();
                look.changed.push(Node::Body(handle));
            }
            if was.colliders != body.colliders().len() {
                was.colliders = body.colliders().len();
                for &collider in body.colliders() {
                    if self.colliders.get(collider).is_none() {
                        look.added.push(collider);
                    }
                }
            }
            if !(std::mem::take(&mut was.marked) || ask_all) || keep(Node::Body(handle)) {
                true
            } else {
                self.bodies.remove(handle);
                false
            }
        });
        self.body_list = list;
        for i in 0..look.added.len() {
            let collider = look.added[i];
            self.watch_collider(bodies, colliders, collider);
        }

        // Bodies that lost a watched collider: a collider may have come in
        // its place, leaving the count as it was.
        let mut recheck = Vec::new();
        let mut list = std::mem::take(&mut self.collider_list);
        list.retain(|&handle| {
            // Gone from Rapier, or from our map: evicted by a newer collider
            // in its slot (see `watch_collider`).
            let (Some(collider), Some(known)) =
                (colliders.get(handle), self.colliders.get_mut(handle))
            else {
                let body = match self.colliders.remove(handle) {
                    Some(known) => known.body,
                    None => self
                        .evicted
                        .iter()
                        .find(|e| e.0 == handle)
                        .and_then(|e| e.1),
                };
                recheck.extend(body);
                look.removed_colliders.push((handle, body));
                return false;
            };
            if known
                .wrote
                .is_some_and(|wrote| Settings::of(collider) != wrote)
            {
                look.project_changed.push(handle);
            }
            let mark = Mark::on(collider);
            if mark != known.crate_mark {
                look.unmarked.push(handle);
                // Another of the crate's marks than the one it carried: the
                // collider holds another run's writes.
                if mark.is_marked() {
                    look.foreign_marks = true;
                }
            }
            let body = collider.parent();
            // A watched body's type was read by the body loop above: its
            // record answers without a second visit to Rapier's body.
            let is_dynamic = match body.and_then(|b| self.bodies.get(b)) {
                Some(known_body) => known_body.dynamic,
                None => dynamic_body(bodies, body),
            };
            if known.body != body {
                recheck.extend(known.body);
                look.changed.push(Node::Collider(handle));
            } else if known.dynamic != is_dynamic {
                look.changed.extend(body.map(Node::Body));
            }
            known.body = body;
            known.dynamic = is_dynamic;
            let ask = std::mem::take(&mut known.marked) || ask_all;
            if all || !ask || keep(Node::Collider(handle)) {
                true
            } else {
                self.colliders.remove(handle);
                look.released.push(handle);
                false
            }
        });
        self.collider_list = list;
        self.evicted.clear();
        look.left.clone_from(&recheck);
        for handle in recheck {
            let (Some(body), Some(known)) = (bodies.get(handle), self.bodies.get_mut(handle))
            else {
                continue;
            };
            known.colliders = body.colliders().len();
            for &collider in body.colliders() {
                if self.watch_collider(bodies, colliders, collider) {
                    look.added.push(collider);
                }
            }
        }
        look
    }
}
