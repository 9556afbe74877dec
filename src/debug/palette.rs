//! The one palette of the rules, shared by the debug view and the pictures
//! (`docs/semantics.md`, "Seeing the rules").

use super::super::CollisionRule;
use super::super::hooks::Reach;

/// A colour of the palette, in sRGB with 8 bits a channel.
///
/// ```
/// use rapier_collision_rules::RuleColor;
///
/// let orange = RuleColor(245, 133, 24);
/// assert_eq!(orange.hex(), "#f58518");
/// let [hue, saturation, lightness, alpha] = orange.hsla(1.0);
/// assert!((hue - 29.6).abs() < 0.1 && saturation > 0.9 && (lightness - 0.53).abs() < 0.01);
/// assert_eq!(alpha, 1.0);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct RuleColor(pub u8, pub u8, pub u8);

impl RuleColor {
    /// `#rrggbb`, for SVG and HTML.
    #[must_use]
    pub fn hex(self) -> String {
        format!("#{:02x}{:02x}{:02x}", self.0, self.1, self.2)
    }

    /// The colour as Rapier's debug rendering takes it: `[hue 0..360,
    /// saturation 0..=1, lightness 0..=1, alpha]`.
    #[must_use]
    pub fn hsla(self, alpha: f32) -> [f32; 4] {
        let [r, g, b] = [self.0, self.1, self.2].map(|c| f32::from(c) / 255.0);
        let (max, min) = (r.max(g).max(b), r.min(g).min(b));
        let lightness = (max + min) / 2.0;
        let chroma = max - min;
        if chroma == 0.0 {
            return [0.0, 0.0, lightness, alpha];
        }
        let saturation = chroma / (1.0 - (2.0 * lightness - 1.0).abs());
        let sector = if max == r {
            ((g - b) / chroma).rem_euclid(6.0)
        } else if max == g {
            (b - r) / chroma + 2.0
        } else {
            (r - g) / chroma + 4.0
        };
        [sector * 60.0, saturation, lightness, alpha]
    }
}

/// The colours the rules are drawn in: one per rule, one per way the rules
/// reach a collider, and the marks of a pair's override and end. The
/// debug view ([`RuleDebugRender`](super::RuleDebugRender), feature
/// `debug-render`), the Bevy debug plugin and the pictures under `docs/`
/// use [`RulePalette::default`].
///
/// ```
/// use rapier_collision_rules::{CollisionRule, Reach, RulePalette};
///
/// let palette = RulePalette::default();
/// assert_eq!(palette.rule(Some(CollisionRule::NoResponse)).hex(), "#f58518");
/// assert_eq!(palette.rule(None), palette.not_live, "no live pair");
/// assert_eq!(palette.reach(Reach::Unreached), None, "Rapier's own colour");
/// assert_eq!(palette.reach(Reach::Hooked), Some(palette.hooked));
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct RulePalette {
    /// A `Normal` pair: blue.
    pub normal: RuleColor,
    /// A `NoResponse` pair: orange.
    pub no_response: RuleColor,
    /// A `NoContacts` pair: green.
    pub no_contacts: RuleColor,
    /// A `NoPair` rule (no live pair is drawn with it; the pictures and the
    /// group matrix use it): purple.
    pub no_pair: RuleColor,
    /// No live pair (the objects are apart): grey.
    pub not_live: RuleColor,
    /// `Defer`, a table cell or entry that lets a later stage decide: light grey.
    pub defer: RuleColor,
    /// A collider the planner gave Rapier groups or types ([`Reach::Planned`]): teal.
    pub planned: RuleColor,
    /// A collider that carries a hook flag the crate gave it (it is hooked,
    /// or a one-way surface: [`Reach::Hooked`]): violet, a hue
    /// far from Rapier's own collider colours (red to orange).
    pub hooked: RuleColor,
    /// The mark of a pair whose rule was given with `set_pair_rule`: yellow.
    pub overridden: RuleColor,
    /// The mark of a pair whose rule ends ([`Until`](super::super::Until)): pink.
    pub ending: RuleColor,
}

impl Default for RulePalette {
    fn default() -> RulePalette {
        RulePalette {
            normal: RuleColor(0x4c, 0x78, 0xa8),
            no_response: RuleColor(0xf5, 0x85, 0x18),
            no_contacts: RuleColor(0x54, 0xa2, 0x4b),
            no_pair: RuleColor(0xb2, 0x79, 0xa2),
            not_live: RuleColor(0x9d, 0x9d, 0x9d),
            defer: RuleColor(0xd9, 0xd9, 0xd9),
            planned: RuleColor(0x72, 0xb7, 0xb2),
            hooked: RuleColor(0x94, 0x67, 0xbd),
            overridden: RuleColor(0xee, 0xca, 0x3b),
            ending: RuleColor(0xff, 0x9d, 0xa6),
        }
    }
}

impl RulePalette {
    /// The colour of a pair's rule; `None` (no live pair) is
    /// [`not_live`](Self::not_live).
    #[must_use]
    pub fn rule(&self, rule: Option<CollisionRule>) -> RuleColor {
        match rule {
            Some(CollisionRule::Normal) => self.normal,
            Some(CollisionRule::NoResponse) => self.no_response,
            Some(CollisionRule::NoContacts) => self.no_contacts,
            Some(CollisionRule::NoPair) => self.no_pair,
            Some(CollisionRule::Defer) => self.defer,
            None => self.not_live,
        }
    }

    /// The tint of a collider the rules reach; `None` for an unreached one,
    /// which keeps Rapier's own colour.
    #[must_use]
    pub fn reach(&self, reach: Reach) -> Option<RuleColor> {
        match reach {
            Reach::Unreached => None,
            Reach::Planned => Some(self.planned),
            Reach::Hooked => Some(self.hooked),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grey_primaries_and_hues_convert_as_hsl_says() {
        assert_eq!(RuleColor(128, 128, 128).hsla(1.0)[..2], [0.0, 0.0]);
        let hue = |c: RuleColor| c.hsla(1.0)[0];
        assert_eq!(hue(RuleColor(255, 0, 0)), 0.0);
        assert_eq!(hue(RuleColor(0, 255, 0)), 120.0);
        assert_eq!(hue(RuleColor(0, 0, 255)), 240.0);
        assert_eq!(hue(RuleColor(255, 0, 255)), 300.0);
        let [_, s, l, a] = RuleColor(255, 0, 0).hsla(0.5);
        assert_eq!((s, l, a), (1.0, 0.5, 0.5));
    }

    #[test]
    fn every_rule_and_reach_has_its_own_colour() {
        let p = RulePalette::default();
        let mut colours: Vec<RuleColor> = CollisionRule::ALL
            .iter()
            .map(|&r| p.rule(Some(r)))
            .collect();
        colours.extend([p.not_live, p.planned, p.hooked, p.overridden, p.ending]);
        let mut unique = colours.clone();
        unique.sort_by_key(|c| (c.0, c.1, c.2));
        unique.dedup();
        assert_eq!(unique.len(), colours.len(), "{colours:?}");
    }
}
