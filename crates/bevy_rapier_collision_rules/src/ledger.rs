//! What each entity's rule components put into which context's rule set,
//! so that a change, a removal or a new physics object replaces exactly
//! that (`docs/bevy.md`).

use std::collections::{HashMap, HashSet};

use crate::collision_rules::{
    CollisionGroup, CollisionRule, CollisionRuleSet, Node, OneWay, Until,
};
use bevy::prelude::*;

/// Where an entity's rules live: its context entity and its node there.
pub(crate) type Place = (Entity, Node);

/// How an entity holds its node. Two entities can hold one: a
/// `SoftBodyCluster` entity holds its proxy body as its own, and the soft
/// body entity of a piece whose root that proxy became holds it as its
/// root. Before the tear the cluster's colliders read the cluster's rules,
/// then the soft body's: the first holder's rules come first
/// (`docs/bevy.md`, "A cluster's own rules").
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Holder {
    /// The entity's own body (a rigid body or a cluster's proxy) or collider.
    Own,
    /// The root body of the entity's soft body.
    SoftRoot,
}

/// The rules one entity's components gave, as last applied.
#[derive(Clone, Debug)]
pub(crate) struct Applied {
    pub(crate) place: Place,
    pub(crate) holder: Holder,
    pub(crate) group: Option<CollisionGroup>,
    pub(crate) personal: CollisionRule,
    pub(crate) one_way: Option<OneWay>,
    pub(crate) specific: Vec<AppliedEntry>,
}

/// A specific entry as applied.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct AppliedEntry {
    /// The entity named.
    pub(crate) target: Entity,
    /// Its node when the entry was set.
    pub(crate) node: Node,
    /// How it holds that node: of two entries of one entity about one
    /// node, the one about the node's first holder is the one set.
    pub(crate) holds: Holder,
    pub(crate) rule: CollisionRule,
    /// The end as the component gave it (the count runs in the rule set).
    pub(crate) until: Option<Until>,
    /// The component's setting that made it: an entry set again is applied
    /// again, and its end restarts.
    pub(crate) setting: u32,
}

/// An entity that specific rules name.
#[derive(Debug, Default)]
pub(crate) struct Named {
    /// Its place when the entries were set (`None`: it had no physics object).
    pub(crate) at: Option<Place>,
    /// The entities whose entries name it.
    pub(crate) by: HashSet<Entity>,
}

/// The plugin's book of applied rules.
#[derive(Resource, Debug, Default)]
pub(crate) struct Ledger {
    /// What each entity's components gave. An entity comes, goes or
    /// changes place only through the methods, which keep `at` in step.
    pub(crate) applied: HashMap<Entity, Applied>,
    /// The entities whose applied rules are at each place.
    at: HashMap<Place, Vec<Entity>>,
    pub(crate) named: HashMap<Entity, Named>,
    /// Entities whose rules could not all be applied yet (an entry names
    /// an entity without a physics object, or the context has no rules
    /// component yet): tried again every frame while they wait.
    pub(crate) waiting: HashSet<Entity>,
    /// Pieces of cuts and tears holding their source's rules in the book
    /// until bevy_rapier gives them their components: applied again, with
    /// the entities naming them, once they have them (a component the
    /// source lost in the frame of the split is not copied onto the piece).
    pub(crate) pieces: HashSet<Entity>,
    /// Entities that lost a rule component since the last application.
    pub(crate) removed: Vec<Entity>,
    /// Entities that got or lost a parent, or got a new rigid body.
    pub(crate) moved: Vec<Entity>,
    /// Colliders that lost one of bevy_rapier's settings components.
    pub(crate) settings_removed: Vec<Entity>,
    /// Contexts that dropped their own table.
    pub(crate) table_dropped: Vec<Entity>,
    /// Entities whose applied entries may include one with an end (some
    /// may have ended or gone since): looked at after each step.
    pub(crate) ending: HashSet<Entity>,
    /// How many rule components (and contexts' own tables) the world
    /// holds: counted as they come and go.
    pub(crate) carriers: usize,
    /// Some context's hooks watched, tracked or hooked something in their
    /// last step, or planned with bits from the project's room: changes of
    /// the project's settings must reach them.
    pub(crate) hooks_reach: bool,
    /// A system that takes `CollisionRulesHooks` was initialized (see
    /// [`HooksProbe`](super::misuse::HooksProbe)): bevy_rapier steps with
    /// them somewhere.
    pub(crate) hooks_in_use: bool,
    /// A rule component on an entity with no physics object was warned
    /// about (once per app).
    warned_bare: bool,
}

impl Ledger {
    /// Warns, once per app, that `entity` carries a rule component but has
    /// no rigid body, collider or soft body, so that its rules reach
    /// nothing (`docs/bevy.md`, "How components map to the rules").
    pub(crate) fn warn_bare(&mut self, entity: Entity) {
        if !std::mem::replace(&mut self.warned_bare, true) {
            log::warn!("{}", super::misuse::bare_carrier(entity));
        }
    }

    /// Whether the edits have nothing to follow or apply this frame: no
    /// rule component in the world, nothing held in the book or noted by
    /// the observers, and no context whose hooks read the project's
    /// settings (`docs/bevy.md`, "Cost").
    pub(crate) fn at_rest(&self) -> bool {
        self.carriers == 0
            && !self.hooks_reach
            && self.applied.is_empty()
            && self.named.is_empty()
            && self.waiting.is_empty()
            && self.pieces.is_empty()
            && self.removed.is_empty()
            && self.moved.is_empty()
            && self.settings_removed.is_empty()
            && self.table_dropped.is_empty()
            && self.ending.is_empty()
    }

    /// Forgets that `entity`'s entries name their targets.
    pub(crate) fn unname(&mut self, entity: Entity, applied: &Applied) {
        for entry in &applied.specific {
            self.unname_target(entity, entry.target);
        }
    }

    /// Forgets that an entry of `entity` names `target`.
    pub(crate) fn unname_target(&mut self, entity: Entity, target: Entity) {
        if let Some(named) = self.named.get_mut(&target) {
            named.by.remove(&entity);
            if named.by.is_empty() {
                self.named.remove(&target);
            }
        }
    }

    /// Notes `applied` as what `entity`'s components gave now.
    pub(crate) fn note_applied(&mut self, entity: Entity, applied: Applied) {
        if applied.specific.iter().any(|e| e.until.is_some()) {
            self.ending.insert(entity);
        }
        let place = applied.place;
        if let Some(old) = self.applied.insert(entity, applied) {
            self.leave(entity, old.place);
        }
        self.at.entry(place).or_default().push(entity);
    }

    /// Takes `entity`'s applied rules out of the book, and forgets what
    /// their entries name.
    pub(crate) fn take_applied(&mut self, entity: Entity) -> Option<Applied> {
        let applied = self.applied.remove(&entity)?;
        self.leave(entity, applied.place);
        self.unname(entity, &applied);
        Some(applied)
    }

    /// Notes that `entity`'s applied rules are at `place` now (the rule
    /// set moved them there).
    pub(crate) fn move_applied(&mut self, entity: Entity, place: Place) {
        if let Some(mut applied) = self.applied.remove(&entity) {
            self.leave(entity, applied.place);
            applied.place = place;
            self.note_applied(entity, applied);
        }
    }

    fn leave(&mut self, entity: Entity, place: Place) {
        if let Some(holders) = self.at.get_mut(&place) {
            holders.retain(|&e| e != entity);
            if holders.is_empty() {
                self.at.remove(&place);
            }
        }
    }

    /// What the rule set holds at `place` from the book, with `extra`'s
    /// rules there too (an entity out of the book while it is applied).
    pub(crate) fn node_rules(&self, place: Place, extra: Option<(Entity, &Applied)>) -> NodeRules {
        let mut holders: Vec<(Entity, &Applied)> = self
            .at
            .get(&place)
            .into_iter()
            .flatten()
            .filter_map(|&e| Some((e, self.applied.get(&e)?)))
            .chain(extra)
            .collect();
        holders.sort_by_key(|&(entity, applied)| (applied.holder, entity));
        NodeRules::over(holders)
    }

    /// Notes that `entity`'s entries name their targets, each at `place`.
    pub(crate) fn name(&mut self, entity: Entity, target: Entity, place: Option<Place>) {
        let named = self.named.entry(target).or_default();
        named.at = place;
        named.by.insert(entity);
    }
}

/// The rules at one node, as the entities holding it give them together:
/// each setting from the first holder that gives it, and of the entries
/// about one node the first holder's (`docs/bevy.md`, "A cluster's own
/// rules"). With one holder, its rules.
#[derive(Debug, PartialEq)]
pub(crate) struct NodeRules {
    pub(crate) group: Option<CollisionGroup>,
    pub(crate) personal: CollisionRule,
    pub(crate) one_way: Option<OneWay>,
    pub(crate) specific: Vec<ShownEntry>,
}

/// An entry the rule set holds at a node, and the entity that gave it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ShownEntry {
    pub(crate) by: Entity,
    pub(crate) entry: AppliedEntry,
}

impl NodeRules {
    /// The rules of `holders`, first holder first.
    fn over(holders: Vec<(Entity, &Applied)>) -> NodeRules {
        let mut rules = NodeRules {
            group: None,
            personal: CollisionRule::Defer,
            one_way: None,
            specific: Vec::new(),
        };
        for (by, applied) in holders {
            rules.group = rules.group.or(applied.group);
            if !rules.personal.is_decided() {
                rules.personal = applied.personal;
            }
            rules.one_way = rules.one_way.or(applied.one_way);
            let before = rules.specific.len();
            for &entry in &applied.specific {
                let shown = ShownEntry { by, entry };
                let at = rules
                    .specific
                    .iter()
                    .position(|s| s.entry.node == entry.node);
                match at {
                    None => rules.specific.push(shown),
                    // This holder's own two entries about one node.
                    Some(i)
                        if i >= before
                            && (entry.holds, entry.target)
                                < (
                                    rules.specific[i].entry.holds,
                                    rules.specific[i].entry.target,
                                ) =>
                    {
                        rules.specific[i] = shown;
                    }
                    Some(_) => {}
                }
            }
        }
        rules
    }

    /// The entry about `node`, if any.
    pub(crate) fn entry(&self, node: Node) -> Option<&AppliedEntry> {
        self.specific
            .iter()
            .map(|s| &s.entry)
            .find(|e| e.node == node)
    }

    /// Whether the rule set holds `entry` as `by`'s.
    pub(crate) fn shows(&self, by: Entity, entry: &AppliedEntry) -> bool {
        self.specific
            .iter()
            .any(|s| s.by == by && s.entry == *entry)
    }

    /// Edits `set` at `node` from these rules to `to`.
    pub(crate) fn write(&self, to: &NodeRules, set: &mut CollisionRuleSet, node: Node) {
        if self.group != to.group {
            set.set_group(node, to.group);
        }
        if self.personal != to.personal {
            set.set_personal(node, to.personal);
        }
        if self.one_way != to.one_way {
            set.set_one_way(node, to.one_way);
        }
        for old in &self.specific {
            if to.entry(old.entry.node).is_none() {
                set.remove_specific(node, old.entry.node);
            }
        }
        for shown in &to.specific {
            if !self.specific.iter().any(|s| s.entry == shown.entry) {
                shown.entry.set(set, node);
            }
        }
    }
}

impl AppliedEntry {
    /// Sets the entry in `set`, held by `node`.
    pub(crate) fn set(&self, set: &mut CollisionRuleSet, node: Node) {
        match self.until {
            Some(until) => set.set_specific_until(node, self.node, self.rule, until),
            None => set.set_specific(node, self.node, self.rule),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::collision_rules::CollisionRuleSet as Table;
    use bevy_rapier::rapier::prelude::RigidBodyHandle;

    fn applied(place: Place, holder: Holder) -> Applied {
        Applied {
            place,
            holder,
            group: None,
            personal: CollisionRule::Defer,
            one_way: None,
            specific: Vec::new(),
        }
    }

    fn entry(target: Entity, node: Node, holds: Holder, rule: CollisionRule) -> AppliedEntry {
        AppliedEntry {
            target,
            node,
            holds,
            rule,
            until: None,
            setting: 0,
        }
    }

    /// The cluster's entity comes first at a node it shares with a piece,
    /// whatever the order they were noted in; the piece's settings fill in
    /// where the cluster gives none, and its part goes with it.
    #[test]
    fn the_first_holder_s_settings_come_first_and_the_others_fill_in() {
        let mut table = Table::default();
        let (mine, theirs) = (table.create_group(), table.create_group());
        let context = Entity::from_raw_u32(1).unwrap();
        let node = Node::from(RigidBodyHandle::from_raw_parts(3, 0));
        let (other, far) = (
            Node::from(RigidBodyHandle::from_raw_parts(7, 0)),
            Node::from(RigidBodyHandle::from_raw_parts(9, 0)),
        );
        let place = (context, node);
        let (cluster, piece, named) = (
            Entity::from_raw_u32(10).unwrap(),
            Entity::from_raw_u32(5).unwrap(),
            Entity::from_raw_u32(20).unwrap(),
        );
        let mut ledger = Ledger::default();
        let mut held = applied(place, Holder::SoftRoot);
        held.group = Some(theirs);
        held.personal = CollisionRule::NoPair;
        held.specific = vec![
            entry(named, other, Holder::Own, CollisionRule::NoPair),
            entry(named, far, Holder::Own, CollisionRule::NoContacts),
        ];
        ledger.note_applied(piece, held);
        let mut own = applied(place, Holder::Own);
        own.group = Some(mine);
        own.specific = vec![entry(named, other, Holder::Own, CollisionRule::NoResponse)];
        let rules = ledger.node_rules(place, Some((cluster, &own)));
        assert_eq!(rules.group, Some(mine));
        assert_eq!(rules.personal, CollisionRule::NoPair);
        assert_eq!(
            rules.entry(other).map(|e| e.rule),
            Some(CollisionRule::NoResponse)
        );
        assert_eq!(
            rules.entry(far).map(|e| e.rule),
            Some(CollisionRule::NoContacts)
        );
        ledger.note_applied(cluster, own);
        let givers: Vec<Entity> = ledger
            .node_rules(place, None)
            .specific
            .iter()
            .map(|s| s.by)
            .collect();
        assert_eq!(givers, [cluster, piece]);
        ledger.take_applied(piece).expect("the piece's part");
        let rules = ledger.node_rules(place, None);
        assert_eq!(
            (rules.group, rules.personal),
            (Some(mine), CollisionRule::Defer)
        );
        assert_eq!(rules.entry(far), None);
        // Moved elsewhere, the cluster's rules leave the place.
        let elsewhere = (context, far);
        ledger.move_applied(cluster, elsewhere);
        assert_eq!(ledger.node_rules(place, None).group, None);
        assert_eq!(ledger.node_rules(elsewhere, None).group, Some(mine));
    }

    /// Of one holder's two entries about one node, the one naming the
    /// node's own holder is set, in either order.
    #[test]
    fn of_one_holder_s_two_entries_about_a_node_the_one_about_its_own_holder_wins() {
        let context = Entity::from_raw_u32(1).unwrap();
        let (node, shared) = (
            Node::from(RigidBodyHandle::from_raw_parts(3, 0)),
            Node::from(RigidBodyHandle::from_raw_parts(4, 0)),
        );
        let (cluster, piece) = (
            Entity::from_raw_u32(10).unwrap(),
            Entity::from_raw_u32(5).unwrap(),
        );
        let about_cluster = entry(cluster, shared, Holder::Own, CollisionRule::NoResponse);
        let about_piece = entry(piece, shared, Holder::SoftRoot, CollisionRule::NoPair);
        for specific in [
            vec![about_cluster, about_piece],
            vec![about_piece, about_cluster],
        ] {
            let mut namer = applied((context, node), Holder::Own);
            namer.specific = specific;
            let rules = Ledger::default().node_rules(
                (context, node),
                Some((Entity::from_raw_u32(2).unwrap(), &namer)),
            );
            let set: Vec<AppliedEntry> = rules.specific.iter().map(|s| s.entry).collect();
            assert_eq!(set, [about_cluster]);
        }
    }
}
