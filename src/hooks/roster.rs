//! What the hooks watch between steps: the colliders and bodies the rules
//! reach (every collider during a full pass). Rapier lists what changed for
//! its own pipeline only, so the hooks look, before each step, at what they
//! watch and nothing else: objects removed, colliders moved to another
//! body, bodies that changed type, colliders added to a watched body, the
//! project's settings changed. An object without Rapier's change flag is
//! not read further (`docs/architecture.md`, "Rapier's change flags"). The
//! cost of a step's look is proportional to what is watched, not to the
//! world (`docs/architecture.md`, "Cost per step").

use super::super::rapier::data::HasModifiedFlag;
use super::super::rapier::prelude::*;

use super::super::Node;
use super::super::model::{Handle, HandleMap, dynamic_body};
use super::super::world::{Mark, Settings};

/// What the hooks remember of a watched collider.
#[derive(Clone, Copy, Debug)]
struct Known {
    body: Option<RigidBodyHandle>,
    dynamic: bool,
    /// Its body was watched when it was last read: until the body's record
    /// leaves the roster or changes type (which the look that sees it
    /// lists), the record says what `dynamic` compares with.
    on_watched_body: bool,
    /// What it shows since the crate last gave it its plan (what the crate
    /// wrote, or the project's own settings where the crate adds nothing):
    /// the look compares, to notice the project's changes.
    wrote: Option<Settings>,
    /// The crate's mark it carries with what the crate wrote
    /// (`world/mark.rs`): the look compares, to give back a mark the
    /// project's own events setting erased.
    crate_mark: Mark,
    /// An edit touched it: the next look asks whether the rules still reach it.
    marked: bool,
}

/// A collider's body as the look reads it: its type, and whether the
/// roster watches it.
#[derive(Clone, Copy, Debug)]
struct BodyType {
    dynamic: bool,
    watched: bool,
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

/// The watched colliders and bodies, each kept in a list that a look walks
/// in order, with what the hooks remember of it.
#[derive(Debug, Default)]
pub(crate) struct Roster {
    colliders: Watched<ColliderHandle, Known>,
    bodies: Watched<RigidBodyHandle, KnownBody>,
    /// Where the oldest and newest watched objects were when the hooks'
    /// last step of their own ended; `None` until one ends, and after each
    /// look.
    stamp: Option<Stamp>,
    /// Looks since the last that read every watched object.
    looks_since_full: u32,
}

/// Every how many looks the watched objects are all read, whatever their
/// change flags say: what a project does behind the flags' back (collision
/// detection between the hooks' steps, a step without the hooks no witness
/// saw, a world put in place without `world_replaced` where the old one
/// was) is read within this many steps (`docs/architecture.md`, "Rapier's
/// change flags").
const FULL_LOOK_EVERY: u32 = 32;

/// The collider count of a body not yet looked at, which no body has: the
/// first look lists its colliders.
const UNCOUNTED: usize = usize::MAX;

/// What a debug build says when a watched object changed with no flag.
const UNFLAGGED: &str = "an object the rules reach changed since the hooks' last step, and \
     Rapier's change flag does not show it (a step of Rapier's cleared it): Rapier stepped \
     without the RuleHooks (step with `hooks.step(&mut world)`, never `world.step()`), or ran \
     collision detection between their steps after the change (`world.detect_collisions`, a \
     `CollisionPipeline`: call `hooks.project_settings_changed()` after it), or a world was put \
     in place of theirs without `hooks.world_replaced()`";

/// The oldest and newest watched collider and body, each with the address
/// Rapier keeps it at. A world put in place of the hooks' one holds its
/// objects elsewhere, or not at all: the stamp holds where the stamped
/// objects still in the world are all where they were, and one is. Four, so
/// that a game removing its oldest objects (a stream) or its newest (the
/// last shot despawned) keeps one.
#[derive(Clone, Copy, Debug, Default)]
struct Stamp {
    colliders: [Option<(ColliderHandle, usize)>; 2],
    bodies: [Option<(RigidBodyHandle, usize)>; 2],
}

impl Stamp {
    fn of(roster: &Roster, bodies: &RigidBodySet, colliders: &ColliderSet) -> Stamp {
        let collider = |handle: Option<ColliderHandle>| {
            handle.and_then(|h| Some((h, std::ptr::from_ref(colliders.get(h)?).addr())))
        };
        let body = |handle: Option<RigidBodyHandle>| {
            handle.and_then(|h| Some((h, std::ptr::from_ref(bodies.get(h)?).addr())))
        };
        let (c, b) = (&roster.colliders, &roster.bodies);
        Stamp {
            colliders: [collider(c.oldest()), collider(c.newest())],
            bodies: [body(b.oldest()), body(b.newest())],
        }
    }

    /// Whether the world is the one stamped: the stamped objects still in
    /// it are where they were, and one is (or nothing was watched).
    fn holds(self, bodies: &RigidBodySet, colliders: &ColliderSet) -> bool {
        let colliders = self
            .colliders
            .into_iter()
            .flatten()
            .map(|(h, at)| colliders.get(h).map(|c| std::ptr::from_ref(c).addr() == at));
        let bodies = self
            .bodies
            .into_iter()
            .flatten()
            .map(|(h, at)| bodies.get(h).map(|b| std::ptr::from_ref(b).addr() == at));
        let (mut stamped, mut present) = (false, false);
        for found in colliders.chain(bodies) {
            stamped = true;
            match found {
                Some(false) => return false,
                Some(true) => present = true,
                None => {}
            }
        }
        present || !stamped
    }
}

/// The watched objects of one kind: each with what the hooks remember of it
/// (`None`: a handle of no object in the world, which the next look finds
/// removed), in a list that a look walks in order without a second lookup,
/// and the position of each live one by its handle's slot. An object let go
/// leaves a hole, and the list is closed up once half of it is holes: the
/// oldest objects go first in a world that changes every step, and closing
/// up at each of their removals would move every other entry.
#[derive(Debug)]
struct Watched<H, K> {
    list: Vec<(H, Entry<K>)>,
    at: HandleMap<H, u32>,
    holes: usize,
}

/// A place in [`Watched`]'s list.
#[derive(Debug)]
enum Entry<K> {
    Known(K),
    /// A handle of no object in the world.
    Alone,
    /// An object let go.
    Hole,
}

impl<H, K> Default for Watched<H, K> {
    fn default() -> Self {
        Watched {
            list: Vec::new(),
            at: HandleMap::default(),
            holes: 0,
        }
    }
}

impl<H: Handle, K> Watched<H, K> {
    #[inline]
    fn len(&self) -> usize {
        self.list.len() - self.holes
    }

    #[inline]
    fn get(&self, handle: H) -> Option<&K> {
        let &i = self.at.get(handle)?;
        match &self.list[i as usize].1 {
            Entry::Known(known) => Some(known),
            _ => None,
        }
    }

    #[inline]
    fn get_mut(&mut self, handle: H) -> Option<&mut K> {
        let &i = self.at.get(handle)?;
        match &mut self.list[i as usize].1 {
            Entry::Known(known) => Some(known),
            _ => None,
        }
    }

    /// The oldest watched object.
    fn oldest(&self) -> Option<H> {
        self.list.iter().find_map(Self::known)
    }

    /// The newest watched object.
    fn newest(&self) -> Option<H> {
        self.list.iter().rev().find_map(Self::known)
    }

    fn known((handle, entry): &(H, Entry<K>)) -> Option<H> {
        matches!(entry, Entry::Known(_)).then_some(*handle)
    }

    /// The watched handles, in the order they were first watched.
    fn handles(&self) -> impl Iterator<Item = H> + '_ {
        self.list
            .iter()
            .filter(|(_, entry)| !matches!(entry, Entry::Hole))
            .map(|&(handle, _)| handle)
    }

    /// Lists `handle` with `known`. An older generation the slot held stays
    /// listed, with what was known of it: the next look finds it removed.
    fn push(&mut self, handle: H, known: K) {
        self.at.insert_evicting(handle, self.list.len() as u32);
        self.list.push((handle, Entry::Known(known)));
    }

    /// Lists a handle of no object in the world: the next look finds it
    /// removed, without taking its slot from a live object.
    fn push_alone(&mut self, handle: H) {
        self.list.push((handle, Entry::Alone));
    }

    /// Lets go of `handle`, leaving a hole in its place.
    fn let_go(&mut self, handle: H) {
        let Some(i) = self.at.remove(handle) else {
            return;
        };
        self.list[i as usize].1 = Entry::Hole;
        self.holes += 1;
        if self.holes * 2 > self.list.len() {
            self.close_up();
        }
    }

    /// Keeps the listed objects `keep` says (`None`: a handle of no object
    /// in the world), in their order.
    #[inline]
    fn retain(&mut self, mut keep: impl FnMut(H, Option<&mut K>) -> bool) {
        let Watched { list, at, holes } = self;
        // An iterator, not indices: the look walks every watched object
        // each step, and indexing cost 8% of its instructions
        // (`docs/performance.md`, "Run 47").
        for (i, (handle, entry)) in list.iter_mut().enumerate() {
            let handle = *handle;
            let kept = match entry {
                Entry::Hole => continue,
                Entry::Alone => keep(handle, None),
                Entry::Known(known) => keep(handle, Some(known)),
            };
            if !kept {
                let live = matches!(entry, Entry::Known(_));
                *entry = Entry::Hole;
                *holes += 1;
                if live && at.get(handle) == Some(&(i as u32)) {
                    at.remove(handle);
                }
            }
        }
        if self.holes * 2 > self.list.len() {
            self.close_up();
        }
    }

    /// Closes the holes up, keeping the order.
    fn close_up(&mut self) {
        self.list.retain(|(_, entry)| !matches!(entry, Entry::Hole));
        self.holes = 0;
        for (i, (handle, entry)) in self.list.iter().enumerate() {
            if let (Entry::Known(_), Some(at)) = (entry, self.at.get_mut(*handle)) {
                *at = i as u32;
            }
        }
    }
}

/// What one look found.
#[derive(Debug, Default)]
pub(crate) struct Look {
    /// Removed colliders, with the body each was on.
    pub(crate) removed_colliders: Vec<(ColliderHandle, Option<RigidBodyHandle>)>,
    pub(crate) removed_bodies: Vec<RigidBodyHandle>,
    /// The removed handles an edit touched since the hooks' last step
    /// (marked), or that the hooks never found in the world (watched as
    /// [`Entry::Alone`]): a handle of another world, or of an object a
    /// world put in place has yet to hand out, among them. Their rules are
    /// forgotten, the handles not remembered as removed, whatever the hooks
    /// watched before the edit (`docs/semantics.md`, "Handles of removed
    /// objects").
    pub(crate) spared: Vec<Node>,
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
        self.colliders.len()
    }

    #[inline]
    pub(crate) fn body_count(&self) -> usize {
        self.bodies.len()
    }

    /// Whether `collider` is watched.
    #[inline]
    pub(crate) fn watches(&self, collider: ColliderHandle) -> bool {
        self.colliders.get(collider).is_some()
    }

    /// The watched colliders, in the order they were first watched.
    pub(crate) fn colliders(&self) -> impl Iterator<Item = ColliderHandle> + '_ {
        self.colliders.handles()
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
        let Some(co) = colliders
            .get(collider)
            .filter(|_| !self.colliders.at.is_superseded(collider))
        else {
            // A handle of no collider in the world (its slot holds a newer
            // one, or one Rapier has yet to hand out, which a corrupt save
            // can name): listed alone, so that the next look reports it
            // removed, without taking the slot from a live collider.
            self.colliders.push_alone(collider);
            return false;
        };
        let body = co.parent();
        let known = Known {
            body,
            dynamic: dynamic_body(bodies, body),
            on_watched_body: body.is_some_and(|b| self.bodies.get(b).is_some()),
            wrote: None,
            // What it carries when first watched (a loaded world's mark, a
            // cut piece's copy of its source's) until the crate writes it.
            crate_mark: Mark::on(co),
            marked: false,
        };
        // A watched collider in a reused slot stays in the list: the next
        // look finds it removed, and its body lost a collider.
        self.colliders.push(collider, known);
        true
    }

    /// Starts watching `body`; `true` if it was not watched.
    pub(crate) fn watch_body(&mut self, bodies: &RigidBodySet, body: RigidBodyHandle) -> bool {
        if self.bodies.get(body).is_some() {
            return false;
        }
        if self.bodies.at.is_superseded(body) || !bodies.contains(body) {
            self.bodies.push_alone(body);
            return false;
        }
        let known = KnownBody {
            dynamic: dynamic_body(bodies, Some(body)),
            marked: false,
            colliders: UNCOUNTED,
        };
        self.bodies.push(body, known);
        true
    }

    /// Records what a watched collider shows once the crate gave it its
    /// plan, and the crate's mark it carries with it (`None`: nothing to
    /// compare, as after the project's settings were given back).
    pub(crate) fn wrote(&mut self, collider: ColliderHandle, wrote: Option<(Settings, Mark)>) {
        if let Some(known) = self.colliders.get_mut(collider) {
            known.wrote = wrote.map(|(settings, _)| settings);
            known.crate_mark = wrote.map_or(Mark::default(), |(_, mark)| mark);
        }
    }

    /// Stops watching `collider`: the rules no longer reach it.
    pub(crate) fn let_go(&mut self, collider: ColliderHandle) {
        self.colliders.let_go(collider);
    }

    /// A step of the hooks' own ended, which brackets Rapier's: until the
    /// next look, Rapier's change flags say what the project changed (see
    /// `look`).
    pub(crate) fn stepped(&mut self, bodies: &RigidBodySet, colliders: &ColliderSet) {
        self.stamp = Some(Stamp::of(self, bodies, colliders));
    }

    /// The next look reads every watched object whatever its flags say:
    /// Rapier stepped without the hooks, clearing flags they did not read.
    pub(crate) fn read_all_next(&mut self) {
        self.looks_since_full = FULL_LOOK_EVERY;
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
        // Rapier flags every object the project changes through its sets
        // (`get_mut`, `insert`, `set_parent`, a removal's parent body, a
        // body's type) and clears the flags in its step: after a step of
        // the hooks' own, an unflagged object the look asks nothing of is as
        // the last look left it, so it costs a read of its flag
        // (`docs/architecture.md`, "Rapier's change flags").
        let stamp = self.stamp.take();
        self.looks_since_full += 1;
        let flags = !all
            && !ask_all
            && self.looks_since_full < FULL_LOOK_EVERY
            && stamp.is_some_and(|stamp| stamp.holds(bodies, colliders));
        if !flags {
            self.looks_since_full = 0;
        }
        if all {
            for (handle, _) in colliders.iter() {
                if self.watch_collider(bodies, colliders, handle) {
                    look.added.push(handle);
                }
            }
        }
        let watched_colliders = &self.colliders;
        // Bodies whose records changed type or were let go in this look: a
        // collider on one compares its type afresh. A removed body is not
        // listed: Rapier removes its colliders, or detaches them, which
        // flags them.
        let mut unsettled = Vec::new();
        self.bodies.retain(|handle, was| {
            // Gone from Rapier, or an older generation a newer body took the
            // slot of, or never in the world: removed.
            let edited = was.as_ref().is_none_or(|was| was.marked);
            let (Some(body), Some(was)) = (bodies.get(handle), was) else {
                if edited {
                    look.spared.push(Node::Body(handle));
                }
                look.removed_bodies.push(handle);
                return false;
            };
            if flags && !was.marked && was.colliders != UNCOUNTED && !body.has_modified_flag() {
                debug_assert!(
                    was.dynamic == body.is_dynamic() && was.colliders == body.colliders().len(),
                    "{UNFLAGGED}"
                );
                return true;
            }
            if was.dynamic != body.is_dynamic() {
                was.dynamic = body.is_dynamic();
                look.changed.push(Node::Body(handle));
                unsettled.push(handle.raw_parts());
            }
            if was.colliders != body.colliders().len() {
                was.colliders = body.colliders().len();
                for &collider in body.colliders() {
                    if watched_colliders.get(collider).is_none() {
                        look.added.push(collider);
                    }
                }
            }
            let kept = !(std::mem::take(&mut was.marked) || ask_all) || keep(Node::Body(handle));
            if !kept {
                unsettled.push(handle.raw_parts());
            }
            kept
        });
        for i in 0..look.added.len() {
            let collider = look.added[i];
            self.watch_collider(bodies, colliders, collider);
        }

        unsettled.sort_unstable();
        // Bodies that lost a watched collider: a collider may have come in
        // its place, leaving the count as it was.
        let mut recheck = Vec::new();
        let watched_bodies = &self.bodies;
        // A watched body's type was read by the body loop above: its record
        // answers without a second visit to Rapier's body.
        // With whether the body is watched (`Known::on_watched_body`).
        let body_type = |body: Option<RigidBodyHandle>| match body.and_then(|b| watched_bodies.get(b)) {
            Some(known_body) => BodyType { dynamic: known_body.dynamic, watched: true },
            None => BodyType { dynamic: dynamic_body(bodies, body), watched: false },
        };
        self.colliders.retain(|handle, mut known| {
            // Gone from Rapier, or an older generation a newer collider took
            // the slot of (see `watch_collider`), or never in the world.
            let (Some(collider), Some(known)) = (colliders.get(handle), known.as_deref_mut())
            else {
                if known.as_ref().is_none_or(|known| known.marked) {
                    look.spared.push(Node::Collider(handle));
                }
                let body = known.and_then(|k| k.body);
                recheck.extend(body);
                look.removed_colliders.push((handle, body));
                return false;
            };
            if flags && !known.marked && !collider.has_modified_flag() {
                // Its body may have changed type, which flags the body
                // alone. A body watched since the collider was last read,
                // and not listed by this look, kept its type: nothing is
                // looked up (a look of a stream or of a volley of shots
                // walks hundreds of these). Else the body's record (the loop
                // above kept it) or, for a body not watched, Rapier says.
                let settled = match known.body {
                    None => true,
                    Some(b) => known.on_watched_body && unsettled.binary_search(&b.raw_parts()).is_err(),
                };
                let kept_type = settled || {
                    let now = body_type(known.body);
                    known.on_watched_body = now.watched;
                    now.dynamic == known.dynamic
                };
                if kept_type {
                    debug_assert!(
                        known.body == collider.parent()
                            && body_type(known.body).dynamic == known.dynamic
                            && known.wrote.is_none_or(|wrote| Settings::of(collider) == wrote)
                            && Mark::on(collider) == known.crate_mark,
                        "{UNFLAGGED}"
                    );
                    return true;
                }
            }
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
            let BodyType {
                dynamic: is_dynamic,
                watched,
            } = body_type(body);
            known.on_watched_body = watched;
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
                look.released.push(handle);
                false
            }
        });
        look.left.clone_from(&recheck);
        for handle in recheck {
            let Some(body) = bodies.get(handle) else {
                continue;
            };
            let Some(known) = self.bodies.get_mut(handle) else {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn handle(index: u32, generation: u32) -> ColliderHandle {
        ColliderHandle::from_raw_parts(index, generation)
    }

    /// Lets go of the listed handles `drop` names; returns those walked.
    fn walk(watched: &mut Watched<ColliderHandle, u8>, drop: &[u32]) -> Vec<(u32, Option<u8>)> {
        let mut seen = Vec::new();
        watched.retain(|h, known| {
            seen.push((h.into_raw_parts().0, known.as_deref().copied()));
            !drop.contains(&h.into_raw_parts().0)
        });
        seen
    }

    #[test]
    fn a_let_go_object_leaves_a_hole_until_half_the_list_is_holes() {
        let mut watched = Watched::default();
        for i in 0..4 {
            watched.push(handle(i, 0), i as u8 * 10);
        }
        walk(&mut watched, &[0]);
        assert_eq!((watched.list.len(), watched.len()), (4, 3), "one hole, kept");
        assert_eq!(watched.get(handle(0, 0)), None);
        assert_eq!(watched.get(handle(3, 0)), Some(&30));
        // The walk skips the hole and keeps the order.
        assert_eq!(walk(&mut watched, &[1, 2]), vec![(1, Some(10)), (2, Some(20)), (3, Some(30))]);
        assert_eq!((watched.list.len(), watched.len()), (1, 1), "closed up");
        // Each position follows its object when the list closes up.
        assert_eq!(watched.get(handle(3, 0)), Some(&30));
        *watched.get_mut(handle(3, 0)).unwrap() = 31;
        assert_eq!(watched.handles().collect::<Vec<_>>(), vec![handle(3, 0)]);
        assert_eq!(walk(&mut watched, &[]), vec![(3, Some(31))]);
    }

    /// A collider on a body the roster let go reads the body's type from
    /// Rapier: a retype flags the body alone, which the look no longer
    /// walks, and the collider's own flag is clear.
    #[test]
    fn a_collider_follows_the_type_of_a_body_let_go() {
        let mut world = PhysicsWorld::new();
        let body = world.insert_body(RigidBodyBuilder::dynamic());
        let collider = world.insert_collider(ColliderBuilder::ball(0.5), Some(body));
        let mut roster = Roster::default();
        roster.watch_body(&world.bodies, body);
        roster.watch_collider(&world.bodies, &world.colliders, collider);
        // A look (keeping the body or not), then a step of Rapier's, which
        // clears the flags, as the hooks' own step does.
        let look = |roster: &mut Roster, world: &mut PhysicsWorld, keep_body: bool| {
            let look = roster.look(&world.bodies, &world.colliders, false, false, |node| {
                keep_body || node != Node::Body(body)
            });
            world.step();
            roster.stepped(&world.bodies, &world.colliders);
            look
        };
        look(&mut roster, &mut world, true);
        roster.mark(Node::Body(body));
        look(&mut roster, &mut world, false);
        assert_eq!(
            (roster.body_count(), roster.collider_count()),
            (0, 1),
            "the body let go, its collider still watched"
        );
        world.bodies[body].set_body_type(RigidBodyType::Fixed, true);
        let seen = look(&mut roster, &mut world, false);
        assert_eq!(seen.changed, vec![Node::Body(body)], "the retype is seen through the collider");
    }

    #[test]
    fn an_older_generation_stays_listed_with_what_was_known_of_it() {
        let mut watched = Watched::default();
        watched.push(handle(5, 0), 1);
        watched.push(handle(5, 1), 2);
        watched.push_alone(handle(9, 0));
        assert_eq!(watched.get(handle(5, 0)), None, "its slot names the newer one");
        assert_eq!(watched.get(handle(5, 1)), Some(&2));
        assert_eq!(
            walk(&mut watched, &[]),
            vec![(5, Some(1)), (5, Some(2)), (9, None)],
            "each walked, the one alone without a record"
        );
        // Letting the older one go leaves the newer one's place alone.
        let mut first = true;
        watched.retain(|_, _| !std::mem::take(&mut first));
        assert_eq!(watched.get(handle(5, 1)), Some(&2));
        assert_eq!(watched.len(), 2);
    }
}
