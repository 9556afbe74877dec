//! Tears heard during Rapier's steps: the pieces of a strain tear made
//! between two Rapier steps of one bracket (several steps between
//! [`prepare`](RuleHooks::prepare) and [`after_step`](RuleHooks::after_step),
//! as bevy_rapier runs substeps and catch-up steps) ask about their new
//! bodies before the hooks can follow the tear. A [`TearListener`] passed
//! to Rapier's step as its event handler writes each torn body's pieces in
//! the hooks' log; until the next
//! [`follow_soft_bodies`](RuleHooks::follow_soft_bodies) gives the pieces
//! their rules, a pair the hook decides reads a piece's new body as the
//! body its source's rules are on (`docs/semantics.md`, "Soft bodies",
//! strain tears between steps).

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use super::super::rapier::prelude::*;

use super::super::Node;
use super::RuleHooks;

/// One body of a soft body that tore in a step: its root or a cluster's
/// proxy, the soft body holding it now and the soft body it came from
/// (itself for the body that kept the handle).
#[derive(Clone, Copy, Debug)]
struct TornBody {
    body: RigidBodyHandle,
    holder: SoftBodyHandle,
    source: SoftBodyHandle,
}

/// The tears heard since the hooks last followed the soft bodies.
#[derive(Debug, Default)]
pub(super) struct TearLog {
    /// Something is logged: the hook's one look while nothing tore.
    any: AtomicBool,
    torn: Mutex<Vec<TornBody>>,
}

impl TearLog {
    fn torn(&self) -> MutexGuard<'_, Vec<TornBody>> {
        self.torn.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// Whether a tear was heard since the last follow.
    #[inline]
    pub(super) fn any(&self) -> bool {
        self.any.load(Ordering::Acquire)
    }

    /// The hooks followed the soft bodies: the pieces have their rules.
    pub(super) fn clear(&self) {
        if self.any() {
            self.torn().clear();
            self.any.store(false, Ordering::Release);
        }
    }

    fn hear(&self, soft_bodies: &SoftBodySet, event: &SoftBodyTearEvent) {
        let mut torn = self.torn();
        // The torn body alone when nothing split off: a cluster it split
        // still has a new proxy, with copies of colliders on it.
        for holder in event.bodies() {
            let Some(body) = soft_bodies.get(holder) else {
                continue;
            };
            let root = body.root_body();
            let bodies = std::iter::once(root).chain(body.live_clusters().map(|(_, c)| c.proxy()).filter(|&p| p != root));
            for handle in bodies {
                torn.push(TornBody {
                    body: handle,
                    holder,
                    source: event.soft_body,
                });
            }
        }
        if !torn.is_empty() {
            self.any.store(true, Ordering::Release);
        }
    }

    /// The soft body `body` belongs to since a tear, and the soft body the
    /// hooks knew that it came from, through the pieces of pieces torn in
    /// the same bracket: `known` says whether the hooks know a soft body.
    pub(super) fn origin(
        &self,
        body: RigidBodyHandle,
        known: impl Fn(SoftBodyHandle) -> bool,
    ) -> Option<SoftBodyHandle> {
        if !self.any() {
            return None;
        }
        let torn = self.torn();
        let mut source = torn.iter().find(|t| t.body == body)?.source;
        // Each round goes one tear back: at most one per entry.
        for _ in 0..=torn.len() {
            if known(source) {
                return Some(source);
            }
            source = torn.iter().find(|t| t.holder == source)?.source;
        }
        None
    }
}

/// An [`EventHandler`] for Rapier's step that tells the hooks of the soft
/// bodies torn during it, and passes every event on to the project's own
/// handler. Needed only where several Rapier steps run between
/// [`prepare`](RuleHooks::prepare) and [`after_step`](RuleHooks::after_step)
/// (a strain tear in the first step makes pieces whose pairs the next steps
/// decide); [`RuleHooks::step`] follows the tears before each step itself.
/// The Bevy plugin installs one on each context.
///
/// ```
/// use rapier3d::prelude::*;
/// use rapier_collision_rules::{CollisionRule, RuleHooks, TearListener};
///
/// let mut world = PhysicsWorld::new();
/// let ground = world.insert_body(RigidBodyBuilder::fixed());
/// world.insert_collider(ColliderBuilder::cuboid(5.0, 0.5, 5.0).active_events(ActiveEvents::COLLISION_EVENTS), Some(ground));
/// let ball = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 1.2, 0.0)));
/// world.insert_collider(ColliderBuilder::ball(0.5), Some(ball));
/// let mut hooks = RuleHooks::default();
/// hooks.rules_mut().set_personal(ball, CollisionRule::NoResponse);
/// // The project's own handler still gets every event.
/// let (collisions, started) = std::sync::mpsc::channel();
/// let (forces, _) = std::sync::mpsc::channel();
/// let (tears, _) = std::sync::mpsc::channel();
/// let project = ChannelEventCollector::new(collisions, forces, tears);
/// let listener: TearListener = hooks.tear_listener().forwarding_to(Box::new(project));
/// for _ in 0..20 {
///     // Three Rapier steps between `prepare` and `after_step`.
///     hooks.follow_soft_bodies(&world.soft_bodies, &world.bodies);
///     hooks.prepare(&world.bodies, &mut world.colliders);
///     hooks.freeze_manifolds(&world.narrow_phase);
///     hooks.wake_edited(&mut world.islands, &mut world.bodies);
///     for _ in 0..3 {
///         world.step_with_events(&hooks, &listener);
///     }
///     hooks.after_step(&world.narrow_phase, &world.bodies, &world.colliders);
/// }
/// assert!(started.try_iter().any(|e| e.started()), "the ball passes through the ground, which still sees it");
/// assert!(world.bodies[ball].translation().y < -1.0);
/// ```
pub struct TearListener {
    log: Arc<TearLog>,
    inner: Option<Box<dyn EventHandler + Send + Sync>>,
}

impl std::fmt::Debug for TearListener {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TearListener")
            .field("forwards", &self.inner.is_some())
            .finish_non_exhaustive()
    }
}

impl TearListener {
    /// The same listener, passing every event on to `inner` as well.
    #[must_use]
    pub fn forwarding_to(mut self, inner: Box<dyn EventHandler + Send + Sync>) -> Self {
        self.inner = Some(inner);
        self
    }

    /// The project's handler it passes events on to, if any.
    pub fn inner(&self) -> Option<&(dyn EventHandler + Send + Sync)> {
        self.inner.as_deref()
    }

    /// Takes the project's handler back.
    pub fn into_inner(self) -> Option<Box<dyn EventHandler + Send + Sync>> {
        self.inner
    }

    /// Whether it writes to `hooks`' log.
    pub fn listens_for(&self, hooks: &RuleHooks) -> bool {
        Arc::ptr_eq(&self.log, hooks.soft.tear_log())
    }
}

impl EventHandler for TearListener {
    fn handle_collision_event(
        &self,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        event: CollisionEvent,
        contact_pair: Option<&ContactPair>,
    ) {
        if let Some(inner) = &self.inner {
            inner.handle_collision_event(bodies, colliders, event, contact_pair);
        }
    }

    fn handle_contact_force_event(
        &self,
        dt: Real,
        bodies: &RigidBodySet,
        colliders: &ColliderSet,
        contact_pair: &ContactPair,
        total_force_magnitude: Real,
    ) {
        if let Some(inner) = &self.inner {
            inner.handle_contact_force_event(dt, bodies, colliders, contact_pair, total_force_magnitude);
        }
    }

    fn handle_soft_body_tear_event(&self, soft_bodies: &SoftBodySet, event: &SoftBodyTearEvent) {
        self.log.hear(soft_bodies, event);
        if let Some(inner) = &self.inner {
            inner.handle_soft_body_tear_event(soft_bodies, event);
        }
    }
}

impl RuleHooks {
    /// A [`TearListener`] writing to these hooks' log, to pass to Rapier's
    /// step as its event handler where several steps run between
    /// [`prepare`](Self::prepare) and [`after_step`](Self::after_step).
    #[must_use]
    pub fn tear_listener(&self) -> TearListener {
        TearListener {
            log: Arc::clone(self.soft.tear_log()),
            inner: None,
        }
    }

    /// Whether `c` is a collider the plan has not met on a body of a soft
    /// body the hooks knew that tore since the last follow: a copy Rapier
    /// made of one of its colliders, the crate's settings with it.
    pub(super) fn torn_copy(&self, colliders: &ColliderSet, c: ColliderHandle) -> bool {
        let log = self.soft.tear_log();
        log.any()
            && self.planned.plan.colliders.get(c).is_none()
            && colliders
                .get(c)
                .and_then(Collider::parent)
                .is_some_and(|body| log.origin(body, |s| self.soft.knows(s)).is_some())
    }

    /// The body whose rules a body of a piece torn since the last follow
    /// stands for: the root the hooks knew of the soft body it came from,
    /// for a body the rules know nothing of (a new root or proxy).
    pub(super) fn torn_alias(&self, body: RigidBodyHandle) -> Option<RigidBodyHandle> {
        let log = self.soft.tear_log();
        if !log.any() {
            return None;
        }
        if self.decide.rules.holds_rules_about(Node::Body(body)) {
            return None;
        }
        let source = log.origin(body, |s| self.soft.knows(s))?;
        self.soft.known_root(source).filter(|&root| root != body)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Bevy plugin installs a listener once per context: hooks that
    /// start over (a quickload) must still read what it hears.
    #[test]
    fn a_listener_writes_to_hooks_that_started_over() {
        let mut hooks = RuleHooks::default();
        let listener = hooks.tear_listener();
        hooks.world_replaced();
        assert!(listener.listens_for(&hooks), "the listener writes to a log the hooks no longer read");
        assert!(!RuleHooks::default().tear_listener().listens_for(&hooks));
    }
}
