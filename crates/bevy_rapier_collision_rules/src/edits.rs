//! Rule components into the context's rule set: each entity's components
//! are compared with what they gave last (the [`Ledger`]), and only the
//! difference is edited, so that `OnChange` recalculates just the pairs an
//! edit can affect (`docs/bevy.md`).

use crate::collision_rules::{CollisionRule, Node, SplitPiece};
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;
use bevy_rapier::plugin::context::RapierRigidBodySet;
use bevy_rapier::prelude::{
    Collider, RapierColliderHandle, RapierContextEntityLink, RapierRigidBodyHandle,
    RapierSoftBodyHandle, RigidBody, SoftBody, SoftBodyTearEvent,
};

use super::components::SpecificEntry;
use super::ledger::{Applied, AppliedEntry, Holder, Ledger, Place};
use super::{CollisionRules, OneWaySurface, PersonalRule, RuleGroup, SpecificRules};

/// An entity's physics handles: its rigid body, soft body, collider, context.
type Handles = (
    Option<&'static RapierRigidBodyHandle>,
    Option<&'static RapierSoftBodyHandle>,
    Option<&'static RapierColliderHandle>,
    Option<&'static RapierContextEntityLink>,
);

/// Entities with a rigid body, a collider or a soft body, made into Rapier
/// objects or not yet.
type Physical = Or<(With<RigidBody>, With<Collider>, With<SoftBody>)>;

/// Every entity's physics object, if it has one (its rigid body, soft body,
/// collider, context), and the contexts' body sets, where a soft body's
/// root body is found.
#[derive(SystemParam)]
pub(crate) struct Objects<'w, 's> {
    handles: Query<'w, 's, Handles>,
    sets: Query<'w, 's, (Entity, &'static RapierRigidBodySet)>,
    /// Entities that have, or will have, a physics object.
    physical: Query<'w, 's, (), Physical>,
}

impl Objects<'_, '_> {
    /// Where an entity's rules live: the body of an entity with a rigid
    /// body (its colliders inherit them), the root body of an entity with a
    /// soft body (its surface colliders and cluster proxies inherit them,
    /// `docs/semantics.md`, "Soft bodies"), else its collider.
    ///
    /// The entity of a piece of a cut made in `Update` has none of
    /// bevy_rapier's components until the next writeback, but bevy_rapier
    /// maps it to its soft body at once: that soft body's root is its place.
    pub(crate) fn place_of(&self, entity: Entity) -> Option<Place> {
        self.placed(entity).map(|(place, _)| place)
    }

    /// [`place_of`](Self::place_of), and how the entity holds it.
    fn placed(&self, entity: Entity) -> Option<(Place, Holder)> {
        let (body, soft, collider, link) = self.handles.get(entity).ok()?;
        let Some(link) = link else {
            let bare = body.is_none() && soft.is_none() && collider.is_none();
            let place = bare.then(|| self.unsynced_soft_body(entity)).flatten()?;
            return Some((place, Holder::SoftRoot));
        };
        let context = link.0;
        let (node, holder) = match (body, soft, collider) {
            (Some(body), _, _) => (Node::from(body.0), Holder::Own),
            (None, Some(soft), _) => {
                let (_, set) = self.sets.get(context).ok()?;
                let root = set.soft_bodies.get(soft.0)?.root_body();
                (Node::from(root), Holder::SoftRoot)
            }
            (None, None, Some(collider)) => (Node::from(collider.0), Holder::Own),
            (None, None, None) => return None,
        };
        Some(((context, node), holder))
    }

    /// The place of an entity bevy_rapier mapped to a soft body before
    /// giving it its components.
    fn unsynced_soft_body(&self, entity: Entity) -> Option<Place> {
        self.sets.iter().find_map(|(context, set)| {
            set.soft_body(entity)
                .map(|body| (context, Node::from(body.root_body())))
        })
    }

    /// Whether `entity` is a piece of a cut or tear that bevy_rapier has
    /// mapped to its soft body but not yet given its components: the tear's
    /// message, from which [`name_tear_pieces`] names it, comes with them.
    fn awaits_its_tear_message(&self, entity: Entity) -> bool {
        matches!(self.handles.get(entity), Ok((None, None, None, None)))
            && self.unsynced_soft_body(entity).is_some()
    }

    /// Whether `entity` exists.
    fn exists(&self, entity: Entity) -> bool {
        self.handles.contains(entity)
    }

    /// The tear that moved `entity`'s soft body off the root at `was`, if
    /// one did: rapier 0.36.1 gives the soft body that keeps the handle a
    /// new root and the piece the old one.
    fn tear_of(&self, entity: Entity, was: Place) -> Option<Tear> {
        let now = self.place_of(entity)?;
        let (context, Node::Body(old_root)) = was else {
            return None;
        };
        if now == was || now.0 != context {
            return None;
        }
        self.handles.get(entity).ok()?.1?;
        let (_, set) = self.sets.get(context).ok()?;
        let (handle, _) = set
            .soft_bodies
            .iter()
            .find(|(_, body)| body.root_body() == old_root)?;
        let piece = set.soft_body_entity(handle).filter(|&p| p != entity)?;
        Some(Tear { now, piece })
    }
}

/// A soft body entity's tear, seen from the rules' side.
struct Tear {
    /// The entity's place now (its new root).
    now: Place,
    /// The entity of the piece that holds the old root.
    piece: Entity,
}

type Carried = (
    Option<&'static RuleGroup>,
    Option<&'static PersonalRule>,
    Option<&'static SpecificRules>,
    Option<&'static OneWaySurface>,
);

/// An entity with any rule component.
type Ruled = Or<(
    With<RuleGroup>,
    With<PersonalRule>,
    With<SpecificRules>,
    With<OneWaySurface>,
)>;

type Edited = (
    Ruled,
    Or<(
        Changed<RuleGroup>,
        Changed<PersonalRule>,
        Changed<SpecificRules>,
        Changed<OneWaySurface>,
        Changed<RapierRigidBodyHandle>,
        Changed<RapierSoftBodyHandle>,
        Changed<RapierColliderHandle>,
        Changed<RapierContextEntityLink>,
    )>,
);

/// Soft body entities with rule components: a tear may give the soft body
/// another root body without a component changing.
type RuledSoftBodies = (With<RapierSoftBodyHandle>, Ruled);

/// The pieces a soft body tore or was cut into are named wherever the soft
/// body was: an entity whose `SpecificRules` name the torn soft body gets
/// the same rule about each new piece (bevy_rapier gives the pieces copies
/// of the torn entity's own components), so that the pieces keep the rules
/// of the body they came from (`docs/bevy.md`, "Soft bodies").
pub(crate) fn name_tear_pieces(
    mut tears: MessageReader<SoftBodyTearEvent>,
    ledger: Res<Ledger>,
    mut specific: Query<&mut SpecificRules>,
) {
    for tear in tears.read() {
        let Some(named) = ledger.named.get(&tear.soft_body) else {
            continue;
        };
        for &by in &named.by {
            let Ok(mut rules) = specific.get_mut(by) else {
                continue;
            };
            for piece in tear.pieces.iter().map(|p| p.soft_body) {
                rules.copy_entry(tear.soft_body, piece);
            }
        }
    }
}

/// Applies the rule components that changed, were removed, or whose
/// entity (or an entity they name) got a new physics object. Only entities
/// that carry rule components are looked at.
pub(crate) fn apply_rule_components(
    mut ledger: ResMut<Ledger>,
    mut contexts: Query<&mut CollisionRules>,
    objects: Objects,
    carried: Query<Carried>,
    edited: Query<Entity, Edited>,
    softs: Query<Entity, RuledSoftBodies>,
) {
    let ledger = &mut *ledger;
    follow_tears(ledger, &objects, &softs);
    note_split_pieces(ledger, &objects, &contexts);
    let mut dirty: Vec<Entity> = edited.iter().collect();
    dirty.extend(
        softs
            .iter()
            .filter(|&soft| ledger.applied.get(&soft).map(|a| a.place) != objects.place_of(soft)),
    );
    dirty.append(&mut ledger.removed);
    dirty.extend(ledger.waiting.drain());
    // Pieces that got their components (or were despawned) since their
    // tear, and the entities naming them: their rules become what the
    // components say (an entry about the source dropped in between is
    // dropped about the piece too).
    let ready: Vec<Entity> = ledger
        .pieces
        .iter()
        .copied()
        .filter(|&piece| !objects.awaits_its_tear_message(piece))
        .collect();
    for piece in ready {
        ledger.pieces.remove(&piece);
        dirty.push(piece);
        dirty.extend(
            ledger
                .named
                .get(&piece)
                .into_iter()
                .flat_map(|n| n.by.iter().copied()),
        );
    }
    // A named entity that moved (a new object, another context, despawned):
    // the entries about it are set again.
    for (&target, named) in &ledger.named {
        if objects.place_of(target) != named.at {
            dirty.extend(named.by.iter().copied());
        }
    }
    if dirty.is_empty() {
        return;
    }
    dirty.sort_unstable();
    dirty.dedup();
    for entity in dirty {
        let components = carried.get(entity).unwrap_or((None, None, None, None));
        apply(ledger, &mut contexts, &objects, entity, components);
    }
}

/// The ledger follows the tears the rule set followed
/// ([`follow_soft_bodies`](crate::collision_rules::RuleHooks::follow_soft_bodies),
/// run before: both roots hold the torn body's rules). The torn entity's
/// rules are now at its new root; the piece's entity holds them at the old
/// root (bevy_rapier copies the torn entity's components onto it in the
/// next writeback, which then changes nothing); the entries that name the
/// torn entity name the piece too. So nothing is taken back from the piece
/// in between, and it steps with its rules from the frame of the tear
/// (`docs/bevy.md`, "Soft bodies").
fn follow_tears(ledger: &mut Ledger, objects: &Objects, softs: &Query<Entity, RuledSoftBodies>) {
    // An entity that lost its last rule component in the frame of the tear
    // is followed too: its rules are taken off its new root, not the
    // piece's.
    let lost: Vec<Entity> = ledger.removed.clone();
    for soft in softs.iter().chain(lost) {
        let Some(applied) = ledger.applied.get(&soft) else {
            continue;
        };
        let Some(tear) = objects.tear_of(soft, applied.place) else {
            continue;
        };
        let held = applied.clone();
        if !ledger.applied.contains_key(&tear.piece) {
            hand_to_piece(ledger, objects, tear.piece, held);
        }
        ledger.move_applied(soft, tear.now);
    }
    let torn: Vec<(Entity, Place, Tear)> = ledger
        .named
        .iter()
        .filter_map(|(&target, named)| {
            let at = named.at?;
            objects.tear_of(target, at).map(|tear| (target, at, tear))
        })
        .collect();
    for (target, at, tear) in torn {
        let by: Vec<Entity> = ledger.named[&target].by.iter().copied().collect();
        for entity in by {
            let Some(applied) = ledger.applied.get_mut(&entity) else {
                continue;
            };
            let mut pieces = Vec::new();
            for entry in applied.specific.iter_mut().filter(|e| e.target == target) {
                entry.node = tear.now.1;
                pieces.push(AppliedEntry {
                    target: tear.piece,
                    node: at.1,
                    ..*entry
                });
            }
            applied.specific.extend(pieces);
            ledger.name(entity, tear.piece, Some(at));
        }
        if let Some(named) = ledger.named.get_mut(&target) {
            named.at = Some(tear.now);
        }
    }
}

/// Every piece the rule sets gave their source's rules this frame
/// ([`RuleHooks::split_pieces`](crate::collision_rules::RuleHooks::split_pieces))
/// holds in the book what its source's entity held, at the piece's root,
/// and so does every entry that names the source's entity about the
/// piece, until the piece has its components (bevy_rapier copies them
/// from the source's entity at the next writeback): then the piece is
/// applied again, so that a component the source lost in between is
/// taken off the piece too (`docs/bevy.md`, "Soft bodies").
fn note_split_pieces(
    ledger: &mut Ledger,
    objects: &Objects,
    contexts: &Query<&mut CollisionRules>,
) {
    for (context, set) in &objects.sets {
        let Ok(rules) = contexts.get(context) else {
            continue;
        };
        for &SplitPiece { piece, source, .. } in rules.hooks().split_pieces() {
            let (Some(entity), Some(from), Some(body)) = (
                set.soft_body_entity(piece),
                set.soft_body_entity(source),
                set.soft_bodies.get(piece),
            ) else {
                continue;
            };
            if entity == from || ledger.applied.contains_key(&entity) {
                continue;
            }
            let place = (context, Node::from(body.root_body()));
            if let Some(held) = ledger.applied.get(&from).cloned() {
                hand_to_piece(ledger, objects, entity, Applied { place, ..held });
            }
            let namers: Vec<Entity> = ledger
                .named
                .get(&from)
                .map(|n| n.by.iter().copied().collect())
                .unwrap_or_default();
            for namer in namers {
                let Some(applied) = ledger.applied.get_mut(&namer) else {
                    continue;
                };
                let about: Vec<AppliedEntry> = applied
                    .specific
                    .iter()
                    .filter(|e| e.target == from)
                    .map(|e| AppliedEntry {
                        target: entity,
                        node: place.1,
                        ..*e
                    })
                    .filter(|e| !applied.specific.contains(e))
                    .collect();
                if !about.is_empty() {
                    applied.specific.extend(about);
                    ledger.name(namer, entity, Some(place));
                }
            }
            ledger.pieces.insert(entity);
        }
    }
}

/// Notes in the book that `piece` holds `held` (its source's rules, at its
/// root), naming what they name, until it has its components.
fn hand_to_piece(ledger: &mut Ledger, objects: &Objects, piece: Entity, held: Applied) {
    for entry in &held.specific {
        let at = objects.place_of(entry.target).map(|(c, _)| (c, entry.node));
        ledger.name(piece, entry.target, at);
    }
    ledger.note_applied(piece, held);
    ledger.pieces.insert(piece);
}

/// Brings `entity`'s rules in its context's rule set to what its
/// components say, together with the rules of any other entity holding
/// its node ([`Holder`]).
fn apply(
    ledger: &mut Ledger,
    contexts: &mut Query<&mut CollisionRules>,
    objects: &Objects,
    entity: Entity,
    (group, personal, specific, one_way): (
        Option<&RuleGroup>,
        Option<&PersonalRule>,
        Option<&SpecificRules>,
        Option<&OneWaySurface>,
    ),
) {
    let placed = objects.placed(entity);
    let wants = group.is_some() || personal.is_some() || specific.is_some() || one_way.is_some();
    // What the rule set holds from this entity at its place now.
    let before = match ledger.take_applied(entity) {
        Some(old) if wants && placed.map(|(place, _)| place) == Some(old.place) => Some(old),
        Some(old) => {
            // Its rules leave that place; other holders' stay.
            if let Ok(mut rules) = contexts.get_mut(old.place.0) {
                let was = ledger.node_rules(old.place, Some((entity, &old)));
                let now = ledger.node_rules(old.place, None);
                was.write(&now, rules.rules_mut(), old.place.1);
            }
            None
        }
        None => None,
    };
    let Some((place, holder)) = placed.filter(|_| wants) else {
        if wants && placed.is_none() && !objects.physical.contains(entity) {
            ledger.warn_bare(entity);
        }
        return;
    };
    let Ok(mut rules) = contexts.get_mut(place.0) else {
        // The context gets its rules component with the next commands.
        ledger.waiting.insert(entity);
        return;
    };
    let context = place.0;
    if let Some(RuleGroup(g)) = group {
        let count = rules.rules().group_count();
        assert!(
            g.id() < count,
            "{entity}'s RuleGroup({g:?}) was not created by the rule table of its physics \
             context {context} ({count} groups exist there). Fix: create the group with the \
             table that context uses (the RuleTable resource, or the context's own \
             ContextRuleTable) and give it only to entities of that context."
        );
    }
    let mut entries = Vec::new();
    for SpecificEntry {
        other: target,
        rule,
        until,
        setting,
    } in specific.into_iter().flat_map(SpecificRules::entries)
    {
        if !objects.exists(target) {
            // Despawned: its entries went with it.
            continue;
        }
        let at = objects.placed(target);
        ledger.name(entity, target, at.map(|(place, _)| place));
        match at {
            Some(((c, node), holds)) if c == context => entries.push(AppliedEntry {
                target,
                node,
                holds,
                rule,
                until,
                setting,
            }),
            // Another context's object means nothing here.
            Some(_) => {}
            None => {
                ledger.waiting.insert(entity);
            }
        }
    }
    // An entry the book gave about a piece of a tear that moved a root
    // ([`follow_tears`]) stays until the tear's message names the piece in
    // the components: a cut made in `Update` sends it only with the next
    // writeback, and the piece steps before.
    for &entry in before.iter().flat_map(|b| &b.specific) {
        let named = entries.iter().any(|e| e.target == entry.target);
        if !named && objects.awaits_its_tear_message(entry.target) {
            ledger.name(entity, entry.target, objects.place_of(entry.target));
            entries.push(entry);
        }
    }
    let now = Applied {
        place,
        holder,
        group: group.map(|g| g.0),
        personal: personal.map_or(CollisionRule::Defer, |p| p.0),
        one_way: one_way.map(|w| w.0),
        specific: entries,
    };
    let was = ledger.node_rules(place, before.as_ref().map(|b| (entity, b)));
    let will = ledger.node_rules(place, Some((entity, &now)));
    was.write(&will, rules.rules_mut(), place.1);
    ledger.note_applied(entity, now);
}

/// Entries with an end that the hooks ended this frame leave their
/// component and the book too, so that the component says what holds
/// (`docs/bevy.md`, "Rules with an end"). Only entities given an entry
/// with an end are looked at.
pub(crate) fn drop_ended_entries(
    mut ledger: ResMut<Ledger>,
    mut contexts: Query<&mut CollisionRules>,
    mut specific: Query<&mut SpecificRules>,
) {
    if ledger.ending.is_empty() {
        return;
    }
    let ledger = &mut *ledger;
    let mut ending: Vec<Entity> = ledger.ending.iter().copied().collect();
    ending.sort_unstable();
    for entity in ending {
        let Some(place) = ledger.applied.get(&entity).map(|a| a.place) else {
            ledger.ending.remove(&entity);
            continue;
        };
        let Ok(mut rules) = contexts.get_mut(place.0) else {
            continue;
        };
        // Only the entries the rule set holds run: one hidden under another
        // holder's entry about the same node starts when it shows.
        let shown = ledger.node_rules(place, None);
        let set = rules.rules();
        let ended: Vec<AppliedEntry> = ledger.applied[&entity]
            .specific
            .iter()
            .filter(|&e| {
                e.until.is_some()
                    && shown.shows(entity, e)
                    && set.specific_until(place.1, e.node).is_none()
            })
            .copied()
            .collect();
        if let Some(applied) = ledger.applied.get_mut(&entity) {
            applied.specific.retain(|e| !ended.contains(e));
            if !applied.specific.iter().any(|e| e.until.is_some()) {
                ledger.ending.remove(&entity);
            }
        }
        if !ended.is_empty() {
            // An entry about the same node that the ended one hid (another
            // holder's, or this entity's about the node's other holder)
            // shows now.
            let now = ledger.node_rules(place, None);
            for entry in &ended {
                if let Some(next) = now.entry(entry.node) {
                    next.set(rules.rules_mut(), place.1);
                }
            }
        }
        for entry in ended {
            ledger.unname_target(entity, entry.target);
            if let Ok(mut component) = specific.get_mut(entity) {
                // Unless the project has set the entry again since: then
                // it is applied again, with its end from the start.
                if component.setting_of(entry.target) == Some(entry.setting) {
                    component.set(entry.target, CollisionRule::Defer);
                }
            }
        }
    }
}
