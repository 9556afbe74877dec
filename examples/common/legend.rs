//! The row of the rules' colours that the examples' pictures end with: one
//! swatch and name per rule a pair can have, in the palette every picture
//! and the debug view use (`RulePalette`, `docs/semantics.md`, "Seeing the
//! rules"). Each example names its dimension's tree `rules`.

use std::fmt::Write as _;

use crate::rules::{CollisionRule, RulePalette};

/// Writes the row from `x` along the text baseline `y`, in `ink`, and
/// returns where it ends.
pub fn rule_swatches(
    svg: &mut String,
    palette: &RulePalette,
    (x, y): (f32, f32),
    ink: &str,
) -> f32 {
    let mut x = x;
    for rule in [
        CollisionRule::Normal,
        CollisionRule::NoResponse,
        CollisionRule::NoContacts,
        CollisionRule::NoPair,
    ] {
        let name = format!("{rule:?}");
        let _ = writeln!(
            svg,
            r#"<rect x="{x}" y="{}" width="24" height="13" fill="{}"/><text x="{}" y="{y}" font-size="12" fill="{ink}">{name}</text>"#,
            y - 11.0,
            palette.rule(Some(rule)).hex(),
            x + 30.0
        );
        x += 48.0 + name.chars().count() as f32 * 7.3;
    }
    x
}
