//! The showcase's side views: every collider's extent in the x-y plane,
//! coloured by the rule of its actor's pair, one frame per instant.

use std::fmt::Write as _;

use crate::rules::CollisionRule;

/// One drawable box: its x-y extent and its colour.
pub struct Shape {
    pub min: (f32, f32),
    pub max: (f32, f32),
    pub color: &'static str,
}

/// The colour of a pair's rule (grey: the pair is not live).
pub fn color(rule: Option<CollisionRule>) -> &'static str {
    match rule {
        Some(CollisionRule::Normal) | Some(CollisionRule::Defer) => "#4c78a8",
        Some(CollisionRule::NoResponse) => "#f58518",
        Some(CollisionRule::NoContacts) => "#54a24b",
        Some(CollisionRule::NoPair) => "#b279a2",
        None => "#9d9d9d",
    }
}

/// The frames stacked top to bottom, with a legend, as one SVG document.
pub fn render(frames: &[(usize, Vec<Shape>)], labels: &[(&str, f32)]) -> String {
    let (x0, x1, y0, y1) = (-36.0f32, 36.0f32, -1.0f32, 6.0f32);
    let scale = 18.0;
    let (w, h) = ((x1 - x0) * scale, (y1 - y0) * scale);
    let mut svg = String::new();
    let total = h * frames.len() as f32 + 40.0;
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{total}" font-family="sans-serif" font-size="12">"#
    );
    let _ = writeln!(
        svg,
        r##"<rect width="100%" height="100%" fill="#ffffff"/>"##
    );
    for (i, (step, shapes)) in frames.iter().enumerate() {
        let top = i as f32 * h;
        let _ = writeln!(
            svg,
            r#"<text x="6" y="{}">t = {:.2} s</text>"#,
            top + 14.0,
            *step as f32 / 60.0
        );
        for s in shapes {
            // Clip what left the view (bullets, debris far below).
            let (ax, bx) = (s.min.0.max(x0), s.max.0.min(x1));
            let (ay, by) = (s.min.1.max(y0), s.max.1.min(y1));
            if ax >= bx || ay >= by {
                continue;
            }
            let (px, py) = ((ax - x0) * scale, top + (y1 - by) * scale);
            let _ = writeln!(
                svg,
                r##"<rect x="{px:.1}" y="{py:.1}" width="{:.1}" height="{:.1}" fill="{}" fill-opacity="0.75" stroke="#333" stroke-width="0.5"/>"##,
                (bx - ax) * scale,
                (by - ay) * scale,
                s.color
            );
        }
        let _ = writeln!(
            svg,
            r##"<line x1="0" y1="{0}" x2="{w}" y2="{0}" stroke="#ccc"/>"##,
            top + h
        );
        if i == 0 {
            for &(name, x) in labels {
                let (lx, ly) = ((x - x0) * scale, top + 30.0);
                let _ = writeln!(
                    svg,
                    r#"<text x="{lx:.1}" y="{ly:.1}" text-anchor="middle">{name}</text>"#
                );
            }
        }
    }
    let legend = [
        ("Normal", color(Some(CollisionRule::Normal))),
        ("NoResponse", color(Some(CollisionRule::NoResponse))),
        ("NoContacts", color(Some(CollisionRule::NoContacts))),
        ("NoPair", color(Some(CollisionRule::NoPair))),
        ("pair not live", color(None)),
    ];
    for (i, (name, fill)) in legend.iter().enumerate() {
        let x = 10.0 + i as f32 * 120.0;
        let y = total - 26.0;
        let _ = writeln!(
            svg,
            r#"<rect x="{x}" y="{y}" width="14" height="14" fill="{fill}"/><text x="{}" y="{}">{name}</text>"#,
            x + 18.0,
            y + 12.0
        );
    }
    svg.push_str("</svg>\n");
    svg
}
