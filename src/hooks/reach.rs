//! How far the rules reach a collider and a live pair: unreached (Rapier
//! alone), planned into Rapier's groups, or hooked. What a user asks when a
//! world costs more than expected (`docs/performance.md`, "Why is my world
//! slow"), and what the debug view tints (`docs/semantics.md`, "Seeing the
//! rules").

use super::super::rapier::prelude::*;

use super::RuleHooks;

/// How the rules reach a collider, as of the plan the last step ran with:
/// what [`RuleHooks::reach`] answers.
///
/// ```
/// use rapier3d::prelude::*;
/// use rapier_collision_rules::{CollisionRule, Reach, RuleHooks};
///
/// let mut world = PhysicsWorld::new();
/// let ground = world.insert_body(RigidBodyBuilder::fixed());
/// let floor = world.insert_collider(ColliderBuilder::cuboid(10.0, 0.5, 10.0), Some(ground));
/// let wall = world.insert_collider(ColliderBuilder::cuboid(0.5, 3.0, 10.0), Some(ground));
/// let ghost = world.insert_body(RigidBodyBuilder::dynamic().translation(Vector::new(0.0, 1.0, 0.0)));
/// let ball = world.insert_collider(ColliderBuilder::ball(0.5), Some(ghost));
/// let mut hooks = RuleHooks::default();
/// // NoContacts needs the hook: the ghost's ball carries it, not the floor.
/// hooks.rules_mut().set_specific(ghost, floor, CollisionRule::NoContacts);
/// hooks.step(&mut world);
/// assert_eq!(hooks.reach(ball), Reach::Hooked);
/// assert_eq!(hooks.reach(floor), Reach::Planned);
/// assert_eq!(hooks.reach(wall), Reach::Unreached);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Reach {
    /// No rule reaches it: Rapier decides its pairs alone, with the
    /// project's own settings.
    Unreached,
    /// The rules reach it and the planner planned it: it carries the
    /// Rapier collision groups, solver groups or collision types its rules
    /// need (Rapier's defaults where they need none, as for a collider
    /// reached only through the parent map), and Rapier decides its pairs,
    /// with its contact recycling.
    Planned,
    /// It carries a hook flag the crate gave it: the hook answers its
    /// pairs (a rule the hook decides), or modifies their contacts (a
    /// one-way surface, a `ManifoldUpdate::Never` setting). Its pairs lose
    /// Rapier's contact recycling.
    Hooked,
}

/// How the rules reach colliders and pairs.
impl RuleHooks {
    /// How the rules reach `collider`, as of the plan the last step (or
    /// [`prepare`](Self::prepare)) ran with. A collider added since is
    /// `Unreached` until then. During a full pass (a calculator, a
    /// pair-created callback, the `Manual` policy, the planner turned off:
    /// [`StepStats::full_pass`](super::StepStats::full_pass)) every
    /// collider is hooked.
    #[must_use]
    pub fn reach(&self, collider: ColliderHandle) -> Reach {
        match self.planned.plan.colliders.get(collider) {
            Some(_) if self.planned.carries_hook(collider, self.modifies_contacts()) => {
                Reach::Hooked
            }
            Some(_) => Reach::Planned,
            None => Reach::Unreached,
        }
    }
}

/// What the debug view asks of the live pairs (feature `debug-render`).
#[cfg(feature = "debug-render")]
mod drawn {
    use super::super::super::rapier::prelude::*;

    use super::super::super::CollisionRule;
    use super::super::super::resolve::Stage;
    use super::super::super::world::filters_pass;
    use super::super::{PairKey, RuleHooks, WorldRef};
    use super::Reach;

    /// What the debug view draws of one live pair the rules reach.
    #[derive(Clone, Copy, Debug, PartialEq, Eq)]
    pub(crate) struct PairReach {
        pub(crate) rule: CollisionRule,
        /// The hook answers it (one of its colliders is hooked, or the hooks
        /// keep state for it).
        pub(crate) hooked: bool,
        /// Its rule was given with `set_pair_rule`.
        pub(crate) overridden: bool,
        /// Its rule ends: an override with an end, or a specific entry with an
        /// end that decides it.
        pub(crate) ending: bool,
    }

    /// The pairs the debug view draws.
    impl RuleHooks {
        /// Whether a calculator or a pair-created callback decides pairs.
        pub(crate) fn calculates(&self) -> bool {
            self.decide.calculator.is_some() || self.decide.on_created.is_some()
        }

        /// Whether the rules reach no collider and no pair: the debug view
        /// then draws what Rapier draws and nothing else.
        pub(crate) fn reaches_nothing(&self) -> bool {
            self.planned.roster.collider_count() == 0 && self.pairs.is_empty()
        }

        /// The live pairs Rapier holds now that the rules reach (a collider of
        /// the pair is planned or hooked, or the hooks keep state for it), with
        /// Rapier's contact pair (none for a sensor pair) and what the debug
        /// view draws of each, in Rapier's graph order: contact pairs, then
        /// sensor pairs. Pairs of two unreached colliders are plain Rapier and
        /// cost two look-ups each.
        pub(crate) fn reached_pairs<'s, 'w>(
            &'s self,
            world: WorldRef<'w>,
        ) -> impl Iterator<
            Item = (
                ColliderHandle,
                ColliderHandle,
                Option<&'w ContactPair>,
                PairReach,
            ),
        > + use<'s, 'w> {
            let ends = self.has_ends();
            let tracked = !self.pairs.is_empty();
            let contacts = world
                .narrow_phase
                .contact_pairs()
                .map(|pair| (pair.collider1, pair.collider2, Some(pair)));
            let sensors = world
                .narrow_phase
                .intersection_pairs()
                .map(|(a, b, _)| (a, b, None));
            contacts.chain(sensors).filter_map(move |(a, b, contact)| {
                let reached = [a, b].map(|c| self.reach(c));
                let state = if tracked {
                    self.pairs.get(PairKey::new(a, b))
                } else {
                    None
                };
                if state.is_none() && reached == [Reach::Unreached; 2] {
                    return None;
                }
                if !filters_pass(world.bodies, world.colliders, world.joints, a, b) {
                    return None;
                }
                let rule = self.held_rule(world, a, b, || {
                    self.resolve(world.bodies, world.colliders, a, b)
                });
                if rule == CollisionRule::NoPair {
                    return None;
                }
                let overridden = state.is_some_and(|s| s.overridden.is_some());
                let ending = ends && self.pair_ends(world, a, b, overridden);
                let hooked = state.is_some_and(|s| !s.absent) || reached.contains(&Reach::Hooked);
                Some((
                    a,
                    b,
                    contact,
                    PairReach {
                        rule,
                        hooked,
                        overridden,
                        ending,
                    },
                ))
            })
        }

        /// Whether the rule of a live pair ends: its override's end, else the
        /// end of the specific entry that decides it (either way round, as the
        /// specific stage reads both).
        fn pair_ends(
            &self,
            world: WorldRef<'_>,
            a: ColliderHandle,
            b: ColliderHandle,
            overridden: bool,
        ) -> bool {
            if overridden {
                return self.pair_ends.contains_key(&PairKey::new(a, b));
            }
            let rules = &self.decide.rules;
            let why = rules.explain(world.bodies, world.colliders, a, b);
            match (why.stage, why.nodes) {
                (Stage::Specific, Some((x, y))) => {
                    rules.specific_until(x, y).is_some() || rules.specific_until(y, x).is_some()
                }
                _ => false,
            }
        }
    }
}

#[cfg(feature = "debug-render")]
pub(crate) use drawn::PairReach;
