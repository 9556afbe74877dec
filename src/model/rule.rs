//! The five rules and their severity order. What each means to Rapier's
//! narrow phase is said once, by the hooks' answer
//! (`hooks/answer.rs`, the one place that names `SolverFlags`).

/// What a pair of colliders is allowed to do, from least to most restrictive.
///
/// The derived order is the severity order of the specification:
/// `Defer < Normal < NoResponse < NoContacts < NoPair`, so "the most
/// restrictive of two" is simply their maximum and `Defer` never wins over a
/// real rule.
///
/// ```
/// use rapier_collision_rules::CollisionRule;
///
/// assert!(CollisionRule::Defer < CollisionRule::Normal);
/// assert!(CollisionRule::NoContacts < CollisionRule::NoPair);
/// assert_eq!(
///     CollisionRule::NoResponse.most_restrictive(CollisionRule::Normal),
///     CollisionRule::NoResponse,
/// );
/// assert_eq!(
///     CollisionRule::Defer.most_restrictive(CollisionRule::Normal),
///     CollisionRule::Normal,
/// );
/// ```
#[doc(alias = "filter")]
#[doc(alias = "ignore")]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum CollisionRule {
    /// No decision here: the next, more general stage decides.
    #[default]
    Defer,
    /// Broad phase, contacts and collision response: plain Rapier.
    Normal,
    /// Contacts and collision events, but no impulses: the bodies pass
    /// through each other.
    NoResponse,
    /// The pair exists (it is a live pair), but no contacts are computed.
    NoContacts,
    /// The pair never exists: no contacts, no events, nothing.
    NoPair,
}

impl CollisionRule {
    /// Every rule, least restrictive first.
    pub const ALL: [CollisionRule; 5] = [
        CollisionRule::Defer,
        CollisionRule::Normal,
        CollisionRule::NoResponse,
        CollisionRule::NoContacts,
        CollisionRule::NoPair,
    ];

    /// The more restrictive of `self` and `other` (their maximum).
    #[must_use]
    pub fn most_restrictive(self, other: CollisionRule) -> CollisionRule {
        self.max(other)
    }

    /// `true` for every rule but [`CollisionRule::Defer`].
    #[must_use]
    pub fn is_decided(self) -> bool {
        self != CollisionRule::Defer
    }

    /// Whether the narrow phase computes contacts for a pair with this rule.
    /// A final `Defer` (a `Defer` default rule) behaves as `Normal`: no rule
    /// decided, so the pair is left as plain Rapier would have it.
    #[inline]
    pub(crate) fn computes_contacts(self) -> bool {
        self <= CollisionRule::NoResponse
    }

    /// Whether the solver applies impulses to a pair with this rule.
    #[inline]
    pub(crate) fn responds(self) -> bool {
        self <= CollisionRule::Normal
    }
}

#[cfg(test)]
mod tests {
    use super::CollisionRule::{self, *};

    #[test]
    fn severity_order_is_the_specification_order() {
        let mut shuffled = [NoContacts, Defer, NoPair, Normal, NoResponse];
        shuffled.sort();
        assert_eq!(shuffled, CollisionRule::ALL);
    }

    #[test]
    fn most_restrictive_is_symmetric_and_defer_never_wins() {
        for a in CollisionRule::ALL {
            for b in CollisionRule::ALL {
                assert_eq!(a.most_restrictive(b), b.most_restrictive(a));
                if a != Defer {
                    assert_ne!(a.most_restrictive(b), Defer, "{a:?} with {b:?}");
                }
            }
        }
    }
}
