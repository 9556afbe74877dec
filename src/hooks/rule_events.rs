//! Rule events (`docs/semantics.md`, "Rule events"): what changed for live
//! pairs in each step, for a game that asked
//! ([`RuleHooks::record_rule_events`]). The live pairs are those
//! [`RuleHooks::pairs`] answers; after each step they are compared with
//! the step before, and each difference is an event: a pair that became
//! live, a live pair whose rule changed (with why), a pair that stopped
//! being live.
//!
//! Nothing is done when nobody asked. When recording, a step costs a walk
//! of Rapier's pair lists and a look-up per pair; the rule of a pair the
//! hooks do not decide is calculated again only where an edit of the step
//! reaches one of its colliders (everywhere after a global edit), for a
//! new pair, or for one whose body types changed.

use hashbrown::{HashMap, HashSet};

use super::super::model::BodyKinds;
use super::super::rapier::prelude::*;
use super::super::{CollisionRule, Node};
use super::{PairKey, RecalculationPolicy, RuleHooks, WorldRef};

/// What changed for one live pair in one step
/// ([`RuleHooks::drain_rule_events`]). A live pair is one
/// [`RuleHooks::pairs`] answers: Rapier holds it and its rule is not
/// `NoPair`.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RuleEvent {
    /// The pair became live: Rapier made it, or its rule stopped being
    /// `NoPair`. (Not to be confused with the [`PairCreated`](super::PairCreated)
    /// callback, which Rapier's first sighting of a hooked pair calls.)
    PairStarted {
        /// The pair's first collider: the lower by `into_raw_parts`.
        collider1: ColliderHandle,
        /// The other.
        collider2: ColliderHandle,
        /// Its rule.
        rule: CollisionRule,
    },
    /// The rule of a live pair changed (to `NoPair`: the pair is no longer
    /// live, and no `PairEnded` follows).
    RuleChanged {
        /// The pair's first collider: the lower by `into_raw_parts`.
        collider1: ColliderHandle,
        /// The other.
        collider2: ColliderHandle,
        /// The rule it had after the last step.
        from: CollisionRule,
        /// The rule it has now.
        to: CollisionRule,
        /// Why.
        cause: RuleChange,
    },
    /// Rapier no longer holds the pair (its colliders are apart, or one
    /// was removed or disabled).
    PairEnded {
        /// The pair's first collider: the lower by `into_raw_parts`.
        collider1: ColliderHandle,
        /// The other.
        collider2: ColliderHandle,
        /// The rule it had after the last step.
        rule: CollisionRule,
    },
}

/// Why the rule of a live pair changed.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RuleChange {
    /// An edit of the rule set (under `OnChange`, or a pair made again).
    Edit,
    /// [`RuleHooks::set_pair_rule`] (or `Defer`, dropping an override).
    Override,
    /// A rule with an end ended ([`Until`](super::super::Until)): a specific
    /// entry between the pair's sides, or the pair's override.
    Expiry,
    /// [`RuleHooks::force_recalculation`], the `EveryStep` policy, or a
    /// calculator that reads what the crate cannot see.
    Recalculation,
    /// A body of the pair changed type (the default groups follow it).
    BodyType,
}

/// Where rule events go as they happen, the push form of
/// [`RuleHooks::drain_rule_events`], as Rapier's `EventHandler` is for its
/// own events: given with [`RuleHooks::set_rule_event_handler`], called
/// after each step with that step's events, in the order
/// `drain_rule_events` would give them. A closure is a handler, and so is
/// an [`std::sync::mpsc::Sender`] of [`RuleEvent`]s (what Rapier's
/// `ChannelEventCollector` is for its events).
pub trait RuleEventHandler: Send + Sync {
    /// One event of the step that just ended.
    fn handle_rule_event(&self, event: RuleEvent);
}

impl<F: Fn(RuleEvent) + Send + Sync> RuleEventHandler for F {
    fn handle_rule_event(&self, event: RuleEvent) {
        self(event);
    }
}

impl RuleEventHandler for std::sync::mpsc::Sender<RuleEvent> {
    /// Sends the event; a receiver that was dropped no longer listens, and
    /// the event is dropped with it.
    fn handle_rule_event(&self, event: RuleEvent) {
        let _ = self.send(event);
    }
}

/// The recording: the live pairs after the last step, the events not yet
/// drained (or the handler they go to), and what this step did that
/// explains a change.
#[derive(Default)]
pub(super) struct Recording {
    live: HashMap<PairKey, (CollisionRule, BodyKinds)>,
    /// The map of the step before last, kept for its allocation.
    spare: HashMap<PairKey, (CollisionRule, BodyKinds)>,
    events: Vec<RuleEvent>,
    handler: Option<Box<dyn RuleEventHandler>>,
    /// Pairs given or dropped an override since the last step.
    pub(super) overridden: HashSet<PairKey>,
    /// Pairs whose override ended since the last step.
    pub(super) expired_pairs: HashSet<PairKey>,
    /// The sides of specific entries that ended since the last step.
    pub(super) expired: Vec<(Node, Node)>,
    /// `force_recalculation` was asked since the last step.
    pub(super) forced: bool,
    /// The rules or the plan changed since the last step: unhooked pairs
    /// are calculated again.
    pub(super) edited: bool,
    /// An edit this step may change any pair's rule (a full plan, a
    /// global edit): every pair is calculated again.
    everything: bool,
    /// The colliders under the nodes this step's edits touched: the pairs
    /// the hooks do not decide are calculated again only where they reach.
    reached: HashSet<ColliderHandle>,
    /// The hooks started over on another world: its live pairs, read from
    /// its graph before its first step, are what that step is compared with.
    seed: bool,
}

impl Recording {
    /// The recording of hooks that start over on another world: the
    /// handler and the events not yet drained stay; the live pairs are the
    /// new world's, read before its first step where the hooks see its
    /// graph (see [`RuleHooks::seed_rule_events`]).
    pub(super) fn started_over(self) -> Recording {
        Recording {
            events: self.events,
            handler: self.handler,
            seed: true,
            ..Recording::default()
        }
    }
}

impl RuleHooks {
    /// Starts (or stops) recording what changes for live pairs after each
    /// step, for [`drain_rule_events`](Self::drain_rule_events). Off by
    /// default, and free while off. The pairs live when recording starts
    /// come as [`RuleEvent::PairStarted`] after the first step recorded.
    ///
    /// ```
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, RuleChange, RuleEvent, RuleHooks, Until};
    ///
    /// let mut world = PhysicsWorld::new();
    /// let ground = world.insert_body(RigidBodyBuilder::fixed());
    /// let wall = world.insert_collider(ColliderBuilder::cuboid(0.5, 2.0, 2.0), Some(ground));
    /// let ghost = world.insert_body(RigidBodyBuilder::dynamic().gravity_scale(0.0));
    /// let g = world.insert_collider(ColliderBuilder::ball(0.3), Some(ghost));
    /// let mut hooks = RuleHooks::default();
    /// hooks.record_rule_events(true);
    /// // A ghost for five steps, inside the wall.
    /// hooks.rules_mut().set_specific_until(ghost, ground, CollisionRule::NoResponse,
    ///     Until::steps(5).even_if_overlapping());
    /// let mut events = Vec::new();
    /// for _ in 0..8 {
    ///     hooks.step(&mut world);
    ///     events.extend(hooks.drain_rule_events());
    /// }
    /// // In the order of the handles' raw parts.
    /// let (c1, c2) = if g.into_raw_parts() < wall.into_raw_parts() { (g, wall) } else { (wall, g) };
    /// assert_eq!(events[0], RuleEvent::PairStarted { collider1: c1, collider2: c2, rule: CollisionRule::NoResponse });
    /// assert_eq!(events[1], RuleEvent::RuleChanged {
    ///     collider1: c1, collider2: c2,
    ///     from: CollisionRule::NoResponse, to: CollisionRule::Normal, cause: RuleChange::Expiry,
    /// });
    /// ```
    pub fn record_rule_events(&mut self, on: bool) {
        match (on, self.recording.is_some()) {
            (true, false) => self.recording = Some(Box::default()),
            (false, true) => self.recording = None,
            _ => {}
        }
    }

    /// Starts recording rule events, as
    /// [`record_rule_events(true)`](Self::record_rule_events), and sends
    /// each to `handler` after the step that made it instead of keeping it
    /// for [`drain_rule_events`](Self::drain_rule_events) (events already
    /// kept stay there). `record_rule_events(false)` stops it and drops the
    /// handler; calling this again replaces it.
    ///
    /// ```
    /// use std::sync::mpsc;
    /// use rapier3d::prelude::*;
    /// use rapier_collision_rules::{CollisionRule, RuleEvent, RuleHooks, Until};
    ///
    /// let mut world = PhysicsWorld::new();
    /// let ground = world.insert_body(RigidBodyBuilder::fixed());
    /// world.insert_collider(ColliderBuilder::cuboid(0.5, 2.0, 2.0), Some(ground));
    /// let ghost = world.insert_body(RigidBodyBuilder::dynamic().gravity_scale(0.0));
    /// world.insert_collider(ColliderBuilder::ball(0.3), Some(ghost));
    /// let mut hooks = RuleHooks::default();
    /// let (sender, receiver) = mpsc::channel();
    /// hooks.set_rule_event_handler(sender);
    /// hooks.rules_mut().set_specific_until(ghost, ground, CollisionRule::NoResponse,
    ///     Until::steps(5).even_if_overlapping());
    /// for _ in 0..8 {
    ///     hooks.step(&mut world);
    /// }
    /// let events: Vec<RuleEvent> = receiver.try_iter().collect();
    /// assert!(matches!(events[0], RuleEvent::PairStarted { rule: CollisionRule::NoResponse, .. }));
    /// assert!(matches!(events[1], RuleEvent::RuleChanged { to: CollisionRule::Normal, .. }));
    /// assert_eq!(hooks.drain_rule_events().count(), 0, "nothing was kept");
    /// ```
    pub fn set_rule_event_handler(&mut self, handler: impl RuleEventHandler + 'static) {
        self.record_rule_events(true);
        if let Some(recording) = &mut self.recording {
            recording.handler = Some(Box::new(handler));
        }
    }

    /// The rule events recorded since the last call, step by step, and in
    /// each step in the order of the pairs' colliders (by
    /// `into_raw_parts`), one event per pair: the same in every run. Events wait until drained (drain them after each step).
    pub fn drain_rule_events(&mut self) -> impl Iterator<Item = RuleEvent> + '_ {
        self.recording
            .as_mut()
            .map(|recording| recording.events.drain(..))
            .into_iter()
            .flatten()
    }

    /// Notes, for the events of this step, that the rules or the plan
    /// changed: everywhere (`None`: a full plan, a global edit), or for
    /// the colliders `reached` under the touched nodes.
    pub(super) fn note_edit(&mut self, reached: Option<&HashSet<ColliderHandle>>) {
        if let Some(recording) = &mut self.recording {
            recording.edited = true;
            match reached {
                None => recording.everything = true,
                Some(reached) => recording.reached.extend(reached.iter().copied()),
            }
        }
    }

    /// The first step of hooks that started over on another world (a
    /// quickload, a rollback): the live pairs its graph holds, with the
    /// rules as they are before the step, are what the step is compared
    /// with, as the step after the save was in the run that saved it. A
    /// loaded world's graph holds the pairs it was saved with; overrides are
    /// not saved, so a pair that had one is compared with its rule.
    pub(super) fn seed_rule_events(&mut self, world: WorldRef<'_>) {
        let Some(mut recording) = self.recording.take() else {
            return;
        };
        if std::mem::take(&mut recording.seed) {
            for (a, b) in self.held_pairs(world) {
                let key = PairKey::new(a, b);
                let kinds = key.kinds(world.bodies, world.colliders);
                let rule = self.held_rule(world, a, b, || self.resolve(world.bodies, world.colliders, a, b));
                recording.live.insert(key, (rule, kinds));
            }
        }
        self.recording = Some(recording);
    }

    /// With [`Recording`] on, compares the live pairs after this step with
    /// those after the last, and records each difference.
    pub(super) fn record_step(&mut self, world: WorldRef<'_>) {
        let Some(mut recording) = self.recording.take() else {
            return;
        };
        let calculated = recording.everything
            || recording.forced
            || self.decide.policy == RecalculationPolicy::EveryStep
            || self.full_pass().is_some();
        // Last step's map, cleared, holds this step's pairs: no allocation
        // once the world has grown.
        let mut now = std::mem::take(&mut recording.spare);
        now.clear();
        for (a, b) in self.held_pairs(world) {
            let key = PairKey::new(a, b);
            let kinds = key.kinds(world.bodies, world.colliders);
            let reached = recording.reached.contains(&a) || recording.reached.contains(&b);
            let rule = self.held_rule(world, a, b, || match recording.live.get(&key) {
                Some(&(rule, was)) if !calculated && !reached && was == kinds => rule,
                _ => self.resolve(world.bodies, world.colliders, a, b),
            });
            now.insert(key, (rule, kinds));
        }
        let live = |entry: Option<&(CollisionRule, BodyKinds)>| {
            entry.copied().filter(|&(rule, _)| rule != CollisionRule::NoPair)
        };
        let event = |key: PairKey,
                     before: Option<&(CollisionRule, BodyKinds)>,
                     after: Option<&(CollisionRule, BodyKinds)>| {
            let (collider1, collider2) = key.colliders();
            Some(match (live(before), after.copied()) {
                (None, Some((rule, _))) if rule != CollisionRule::NoPair => {
                    RuleEvent::PairStarted { collider1, collider2, rule }
                }
                (Some((from, was)), Some((to, kinds))) if from != to => RuleEvent::RuleChanged {
                    collider1,
                    collider2,
                    from,
                    to,
                    cause: self.cause(&recording, key, was != kinds, world),
                },
                // Rapier dropped the pair because its rule is now `NoPair`
                // (written into its groups, or its body types): as for a
                // pair the hook decides. Else the pair ended.
                (Some((from, was)), None) => {
                    let retyped = was != key.kinds(world.bodies, world.colliders);
                    if self.dropped_by_rule(&recording, key, retyped, world) {
                        RuleEvent::RuleChanged {
                            collider1,
                            collider2,
                            from,
                            to: CollisionRule::NoPair,
                            cause: self.cause(&recording, key, retyped, world),
                        }
                    } else {
                        RuleEvent::PairEnded { collider1, collider2, rule: from }
                    }
                }
                _ => return None,
            })
        };
        // The pairs held now, then those no longer held; only the events
        // are sorted, into the pairs' order.
        let mut events: Vec<(PairKey, RuleEvent)> = now
            .iter()
            .filter_map(|(&key, after)| event(key, recording.live.get(&key), Some(after)).map(|e| (key, e)))
            .collect();
        events.extend(
            recording
                .live
                .iter()
                .filter(|(key, _)| !now.contains_key(*key))
                .filter_map(|(&key, before)| event(key, Some(before), None).map(|e| (key, e))),
        );
        events.sort_unstable_by_key(|&(key, _)| key);
        for (_, event) in events {
            match &recording.handler {
                Some(handler) => handler.handle_rule_event(event),
                None => recording.events.push(event),
            }
        }
        recording.spare = std::mem::replace(&mut recording.live, now);
        recording.overridden.clear();
        recording.expired_pairs.clear();
        recording.expired.clear();
        recording.forced = false;
        recording.edited = false;
        recording.everything = false;
        recording.reached.clear();
        self.recording = Some(recording);
    }

    /// Whether a live pair Rapier no longer holds was dropped for its rule:
    /// both colliders are there, something changed the rules in this step
    /// or a body of the pair changed type (`retyped`: Rapier's own
    /// collision types drop a pair of two bodies that are not dynamic, as
    /// the hook answers `NoPair` for it), and the pair's rule is `NoPair` now.
    fn dropped_by_rule(&self, recording: &Recording, key: PairKey, retyped: bool, world: WorldRef<'_>) -> bool {
        let (a, b) = key.colliders();
        let changed = retyped
            || recording.edited
            || recording.forced
            || !recording.overridden.is_empty()
            || !recording.expired.is_empty()
            || !recording.expired_pairs.is_empty();
        changed
            && world.colliders.contains(a)
            && world.colliders.contains(b)
            && self.held_rule(world, a, b, || self.resolve(world.bodies, world.colliders, a, b))
                == CollisionRule::NoPair
    }

    /// Why the rule of a live pair changed in this step, the most particular
    /// reason first.
    fn cause(&self, recording: &Recording, key: PairKey, retyped: bool, world: WorldRef<'_>) -> RuleChange {
        let (a, b) = key.colliders();
        let under = |node: Node, c: ColliderHandle| {
            self.decide
                .rules
                .colliders_under(node, world.bodies, world.colliders)
                .contains(&c)
        };
        let expired = recording.expired_pairs.contains(&key)
            || recording.expired.iter().any(|&(n, o)| {
                (under(n, a) && under(o, b)) || (under(n, b) && under(o, a))
            });
        if retyped {
            RuleChange::BodyType
        } else if expired {
            RuleChange::Expiry
        } else if recording.overridden.contains(&key) {
            RuleChange::Override
        } else if recording.edited && !recording.forced {
            RuleChange::Edit
        } else {
            // Forced, or recalculated by the policy or a calculator.
            RuleChange::Recalculation
        }
    }
}
