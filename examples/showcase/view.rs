//! The showcase's picture: one panel per actor, with the actor's trajectory
//! over the whole run in the x-y plane (its centre, sampled every few
//! steps), its shape at the start and at the end, and the other object of
//! the pair it demonstrates outlined. Each panel is zoomed to what it shows;
//! the caption states the rule and the measured outcome. Every rule colour
//! comes from the crate's [`RulePalette`].

use std::fmt::Write as _;

use crate::rules::{CollisionRule, RulePalette};

/// A point of the x-y plane.
pub type P = (f32, f32);

/// An outline in the x-y plane: closed polygons (a rigid collider's
/// silhouette), or open polylines and particles (a soft body's edges).
#[derive(Clone, Default)]
pub struct Figure {
    pub paths: Vec<Vec<P>>,
    pub closed: bool,
    /// A soft body's particles, drawn over the trajectories.
    pub particles: Vec<P>,
}

/// One actor's panel.
pub struct Panel {
    /// The actor's name.
    pub title: String,
    /// The caption's sentences (each wrapped to the panel's width).
    pub caption: Vec<String>,
    /// Whether the measured outcome is what the rule promises.
    pub ok: bool,
    /// The rule of the pair the actor demonstrates: the colour of the panel.
    pub rule: CollisionRule,
    /// The other object of the pair, written by its outline.
    pub other: String,
    /// The actor's centre as `(step, point)`, one track per piece.
    pub tracks: Vec<Vec<(usize, P)>>,
    /// The actor's shapes at the first step and at the last one.
    pub start: Vec<Figure>,
    pub end: Vec<Figure>,
    /// The other object at the first step, and at the last one if it moved.
    pub other_start: Figure,
    pub other_end: Option<Figure>,
}

/// The whole picture: its panels, and what every panel shares.
pub struct Picture<'a> {
    pub title: String,
    pub panels: Vec<Panel>,
    /// Drawn under every panel (the floor).
    pub scenery: Vec<Figure>,
    /// The steps marked on the trajectories (the first and last included).
    pub marks: &'a [usize],
    pub steps_per_second: f32,
}

// Not rule colours: ink, muted text, scenery.
const INK: &str = "#222222";
const MUTED: &str = "#666666";
const FLOOR_FILL: &str = "#ececec";
const FLOOR_LINE: &str = "#b0b0b0";
const FONT: &str = "DejaVu Sans, Helvetica, Arial, sans-serif";

const COLUMNS: usize = 3;
const PANEL_W: f32 = 340.0;
const PLOT_W: f32 = 320.0;
const PLOT_H: f32 = 200.0;
const GAP: f32 = 16.0;
const MARGIN: f32 = 16.0;
const CAPTION_SIZE: f32 = 11.5;
const CAPTION_LINE: f32 = 15.0;
const LABEL_SIZE: f32 = 11.0;
/// The widest and tallest a panel's window grows (world units) to hold
/// where the actor went; beyond it the trajectory leaves the view.
const MAX_SPAN: (f32, f32) = (14.0, 9.0);
/// A figure wider or taller than this (the floor) is cut down to the
/// actor's neighbourhood when a panel is zoomed.
const LARGE: f32 = 10.0;

#[derive(Clone, Copy, Debug)]
struct Rect {
    x0: f32,
    y0: f32,
    x1: f32,
    y1: f32,
}

impl Rect {
    const EMPTY: Rect = Rect {
        x0: f32::MAX,
        y0: f32::MAX,
        x1: f32::MIN,
        y1: f32::MIN,
    };

    fn of(points: impl IntoIterator<Item = P>) -> Rect {
        points.into_iter().fold(Rect::EMPTY, |r, (x, y)| Rect {
            x0: r.x0.min(x),
            y0: r.y0.min(y),
            x1: r.x1.max(x),
            y1: r.y1.max(y),
        })
    }

    fn union(self, o: Rect) -> Rect {
        Rect {
            x0: self.x0.min(o.x0),
            y0: self.y0.min(o.y0),
            x1: self.x1.max(o.x1),
            y1: self.y1.max(o.y1),
        }
    }

    fn is_empty(self) -> bool {
        self.x0 > self.x1 || self.y0 > self.y1
    }

    fn w(self) -> f32 {
        self.x1 - self.x0
    }

    fn h(self) -> f32 {
        self.y1 - self.y0
    }

    fn grow(self, dx: f32, dy: f32) -> Rect {
        Rect {
            x0: self.x0 - dx,
            y0: self.y0 - dy,
            x1: self.x1 + dx,
            y1: self.y1 + dy,
        }
    }

    fn contains(self, (x, y): P) -> bool {
        (self.x0..=self.x1).contains(&x) && (self.y0..=self.y1).contains(&y)
    }

    fn inside(self, o: Rect) -> bool {
        self.x0 >= o.x0 && self.y0 >= o.y0 && self.x1 <= o.x1 && self.y1 <= o.y1
    }

    fn overlaps(self, o: Rect) -> bool {
        self.x0 < o.x1 && o.x0 < self.x1 && self.y0 < o.y1 && o.y0 < self.y1
    }
}

fn bounds(figure: &Figure) -> Rect {
    Rect::of(figure.paths.iter().flatten().copied())
}

/// The part of the world a panel shows, shaped like its plot box: the
/// actor at the start and the other object (cut to the actor's
/// neighbourhood if it is huge), then where the actor went if that fits.
fn window(panel: &Panel) -> Rect {
    let mut core = panel
        .start
        .iter()
        .map(bounds)
        .fold(Rect::EMPTY, Rect::union);
    let near = core.grow(3.0, 3.0);
    for figure in std::iter::once(&panel.other_start).chain(&panel.other_end) {
        let mut b = bounds(figure);
        if b.w() > LARGE {
            (b.x0, b.x1) = (b.x0.max(near.x0), b.x1.min(near.x1));
        }
        if b.h() > LARGE {
            (b.y0, b.y1) = (b.y0.max(near.y0), b.y1.min(near.y1));
        }
        if !b.is_empty() {
            core = core.union(b);
        }
    }
    let fits = |r: Rect| r.w() <= MAX_SPAN.0 && r.h() <= MAX_SPAN.1;
    let extras = panel
        .end
        .iter()
        .map(bounds)
        .chain(panel.tracks.iter().map(|t| Rect::of(t.iter().map(|s| s.1))));
    for extra in extras {
        let with = core.union(extra);
        if fits(with) {
            core = with;
        }
    }
    // Some room around, a least size, and the plot box's shape.
    let mut w = core.grow(0.6, 0.6);
    let (cx, cy) = ((w.x0 + w.x1) / 2.0, (w.y0 + w.y1) / 2.0);
    let aspect = PLOT_W / PLOT_H;
    let (mut hw, mut hh) = (w.w().max(3.0) / 2.0, w.h().max(2.5) / 2.0);
    if hw / hh < aspect {
        hw = hh * aspect;
    } else {
        hh = hw / aspect;
    }
    w = Rect {
        x0: cx - hw,
        y0: cy - hh,
        x1: cx + hw,
        y1: cy + hh,
    };
    w
}

/// Text wrapped to `width` characters, at spaces.
fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut lines = vec![String::new()];
    for word in text.split(' ') {
        let line = lines.last_mut().expect("one line");
        if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > width {
            lines.push(word.to_owned());
        } else {
            if !line.is_empty() {
                line.push(' ');
            }
            line.push_str(word);
        }
    }
    lines
}

/// The rough width of a text in pixels.
fn text_width(text: &str, size: f32) -> f32 {
    text.chars().count() as f32 * size * 0.6
}

fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// Labels of one panel, each at the first of its candidate places that lies
/// in the plot box and clear of the labels and marks already placed.
struct Labels {
    area: Rect,
    taken: Vec<Rect>,
}

impl Labels {
    /// Places `text` near `at` (pixels); candidates are offsets with a text
    /// anchor. Returns whether it found room.
    fn place(
        &mut self,
        svg: &mut String,
        text: &str,
        at: P,
        candidates: &[(f32, f32, &str)],
        style: &str,
    ) -> bool {
        let w = text_width(text, LABEL_SIZE);
        for &(dx, dy, anchor) in candidates {
            let (x, y) = (at.0 + dx, at.1 + dy);
            let x0 = match anchor {
                "start" => x,
                "end" => x - w,
                _ => x - w / 2.0,
            };
            let r = Rect {
                x0,
                y0: y - LABEL_SIZE * 0.85,
                x1: x0 + w,
                y1: y + LABEL_SIZE * 0.25,
            };
            if r.inside(self.area) && !self.taken.iter().any(|t| t.overlaps(r.grow(2.0, 1.0))) {
                self.taken.push(r);
                let _ = writeln!(
                    svg,
                    r##"<text x="{x:.1}" y="{y:.1}" text-anchor="{anchor}" font-size="{LABEL_SIZE}" stroke="#ffffff" stroke-width="3" paint-order="stroke" {style}>{}</text>"##,
                    escape(text)
                );
                return true;
            }
        }
        false
    }

    /// Keeps other labels off a mark of radius `r` at `at`.
    fn reserve(&mut self, at: P, r: f32) {
        self.taken.push(Rect {
            x0: at.0 - r,
            y0: at.1 - r,
            x1: at.0 + r,
            y1: at.1 + r,
        });
    }
}

/// Offsets around a point, for its label.
const AROUND: [(f32, f32, &str); 8] = [
    (8.0, -7.0, "start"),
    (-8.0, -7.0, "end"),
    (8.0, 15.0, "start"),
    (-8.0, 15.0, "end"),
    (0.0, -10.0, "middle"),
    (0.0, 19.0, "middle"),
    (10.0, 4.0, "start"),
    (-10.0, 4.0, "end"),
];

/// Where the segment from `a` (inside `w`) to `b` (outside) leaves `w`,
/// and through which side: 'r', 'l', 't' or 'b'.
fn exit(w: Rect, a: P, b: P) -> (P, char) {
    let mut best = (1.0f32, 'r');
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    for (t, side) in [
        ((w.x1 - a.0) / dx, 'r'),
        ((w.x0 - a.0) / dx, 'l'),
        ((w.y1 - a.1) / dy, 't'),
        ((w.y0 - a.1) / dy, 'b'),
    ] {
        if t.is_finite() && (0.0..best.0).contains(&t) {
            best = (t, side);
        }
    }
    ((a.0 + best.0 * dx, a.1 + best.0 * dy), best.1)
}

/// One panel at `(left, top)`; returns its height.
fn panel(
    svg: &mut String,
    picture: &Picture,
    p: &Panel,
    index: usize,
    (left, top): P,
    palette: &RulePalette,
) -> f32 {
    let color = palette.rule(Some(p.rule)).hex();
    let w = window(p);
    let scale = PLOT_W / w.w();
    let (px0, py0) = (left + (PANEL_W - PLOT_W) / 2.0, top + 26.0);
    let to_px = |(x, y): P| (px0 + (x - w.x0) * scale, py0 + (w.y1 - y) * scale);
    let path = |points: &[P], closed: bool| {
        let mut d = String::new();
        for (i, &q) in points.iter().enumerate() {
            let (x, y) = to_px(q);
            let _ = write!(d, "{}{x:.1},{y:.1}", if i == 0 { "M" } else { " L" });
        }
        if closed {
            d.push_str(" Z");
        }
        d
    };
    // One SVG path a figure (a soft body's edges are its subpaths).
    let figure = |svg: &mut String, f: &Figure, style: &str| {
        if f.paths.is_empty() {
            return;
        }
        let d: Vec<String> = f
            .paths
            .iter()
            .map(|points| path(points, f.closed))
            .collect();
        let _ = writeln!(svg, r#"<path d="{}" {style}/>"#, d.join(" "));
    };

    let _ = writeln!(
        svg,
        r#"<text x="{px0}" y="{}" font-size="14" font-weight="bold" fill="{INK}">{}</text>"#,
        top + 17.0,
        escape(&p.title)
    );
    let _ = writeln!(
        svg,
        r#"<rect x="{}" y="{}" width="10" height="10" fill="{color}"/><text x="{}" y="{}" font-size="11" text-anchor="end" fill="{MUTED}">{:?}</text>"#,
        px0 + PLOT_W - 10.0,
        top + 8.0,
        px0 + PLOT_W - 14.0,
        top + 17.0,
        p.rule
    );
    let _ = writeln!(
        svg,
        r#"<clipPath id="plot{index}"><rect x="{px0}" y="{py0}" width="{PLOT_W}" height="{PLOT_H}"/></clipPath>"#
    );
    let _ = writeln!(svg, r#"<g clip-path="url(#plot{index})">"#);
    for f in &picture.scenery {
        figure(
            svg,
            f,
            &format!(r#"fill="{FLOOR_FILL}" stroke="{FLOOR_LINE}" stroke-width="1""#),
        );
    }
    let other_fill = if p.other_start.closed {
        r##"fill="#ffffff" fill-opacity="0.6""##
    } else {
        r#"fill="none""#
    };
    figure(
        svg,
        &p.other_start,
        &format!(r#"{other_fill} stroke="{INK}" stroke-width="1.6""#),
    );
    if let Some(end) = &p.other_end {
        figure(
            svg,
            end,
            &format!(r#"fill="none" stroke="{INK}" stroke-width="1.2" stroke-dasharray="5 3""#),
        );
    }
    for f in &p.start {
        let style = if f.closed {
            format!(
                r#"fill="{color}" fill-opacity="0.22" stroke="{color}" stroke-width="1.2" stroke-dasharray="3 2""#
            )
        } else {
            format!(r#"fill="none" stroke="{color}" stroke-opacity="0.45" stroke-width="1""#)
        };
        figure(svg, f, &style);
    }
    for f in &p.end {
        let style = if f.closed {
            format!(r#"fill="{color}" fill-opacity="0.8" stroke="{INK}" stroke-width="0.8""#)
        } else {
            format!(r#"fill="none" stroke="{color}" stroke-width="1.4""#)
        };
        figure(svg, f, &style);
    }
    for track in &p.tracks {
        let points: Vec<P> = track.iter().map(|s| s.1).collect();
        let d = path(&points, false);
        let _ = writeln!(
            svg,
            r##"<path d="{d}" fill="none" stroke="#ffffff" stroke-width="5" stroke-linejoin="round" stroke-opacity="0.85"/>"##
        );
        let _ = writeln!(
            svg,
            r#"<path d="{d}" fill="none" stroke="{color}" stroke-width="2.2" stroke-linejoin="round"/>"#
        );
    }
    // A soft body's particles over the trajectories (a rope lies along its own).
    for (figures, fill, opacity) in [(&p.start, "#ffffff", 0.6), (&p.end, color.as_str(), 1.0)] {
        for f in figures.iter() {
            for &q in &f.particles {
                let (x, y) = to_px(q);
                let _ = writeln!(
                    svg,
                    r#"<circle cx="{x:.1}" cy="{y:.1}" r="2.2" fill="{fill}" stroke="{color}" stroke-width="1" opacity="{opacity}"/>"#
                );
            }
        }
    }
    svg.push_str("</g>\n");
    let _ = writeln!(
        svg,
        r##"<rect x="{px0}" y="{py0}" width="{PLOT_W}" height="{PLOT_H}" fill="none" stroke="#999999"/>"##
    );

    // How the other object moved, if it did: an arrow beside its path.
    if let Some(end) = &p.other_end {
        let centre = |r: Rect| to_px(((r.x0 + r.x1) / 2.0, (r.y0 + r.y1) / 2.0));
        let (b0, b1) = (bounds(&p.other_start), bounds(end));
        let (a, b) = (centre(b0), centre(b1));
        let length = (b.0 - a.0).hypot(b.1 - a.1);
        if length > 20.0 {
            let d = ((b.0 - a.0) / length, (b.1 - a.1) / length);
            // Below a horizontal path, right of a vertical one.
            let n = if d.1.abs() < d.0.abs() {
                (-d.1 * d.0.signum(), d.0.abs())
            } else {
                (d.1.abs(), -d.0 * d.1.signum())
            };
            let half = (n.0.abs() * b0.w() + n.1.abs() * b0.h()) * scale / 2.0 + 8.0;
            let (x0, y0) = (a.0 + n.0 * half, a.1 + n.1 * half);
            let (x1, y1) = (b.0 + n.0 * half - d.0 * 4.0, b.1 + n.1 * half - d.1 * 4.0);
            let _ = writeln!(
                svg,
                r#"<g clip-path="url(#plot{index})"><path d="M{x0:.1},{y0:.1} L{x1:.1},{y1:.1}" stroke="{INK}" stroke-width="1.2" stroke-dasharray="5 3" marker-end="url(#arrow)"/></g>"#
            );
        }
    }
    // Marks and labels, inside the plot box.
    let mut labels = Labels {
        area: Rect {
            x0: px0 + 2.0,
            y0: py0 + 2.0,
            x1: px0 + PLOT_W - 2.0,
            y1: py0 + PLOT_H - 2.0,
        },
        taken: Vec::new(),
    };
    let visible = |q: P| w.contains(q);
    let (first, last) = (
        picture.marks.first().copied().unwrap_or(0),
        picture.marks.last().copied().unwrap_or(0),
    );
    let seconds = |step: usize| step as f32 / picture.steps_per_second;
    let mut ends = Vec::new();
    for track in &p.tracks {
        for &(step, q) in track {
            if !picture.marks.contains(&step) || !visible(q) {
                continue;
            }
            let (x, y) = to_px(q);
            if step == first {
                let _ = writeln!(
                    svg,
                    r##"<circle cx="{x:.1}" cy="{y:.1}" r="4.5" fill="#ffffff" stroke="{INK}" stroke-width="1.6"/>"##
                );
            } else if step == last {
                let _ = writeln!(
                    svg,
                    r##"<circle cx="{x:.1}" cy="{y:.1}" r="4.5" fill="{INK}" stroke="#ffffff" stroke-width="1"/>"##
                );
            } else {
                let _ = writeln!(
                    svg,
                    r##"<circle cx="{x:.1}" cy="{y:.1}" r="2.8" fill="{color}" stroke="{INK}" stroke-width="0.8"/>"##
                );
            }
            labels.reserve((x, y), 5.0);
        }
        if let Some(&(_, q)) = track.last() {
            ends.push(q);
        }
    }
    // The other object's name, by its outline.
    let b = bounds(&p.other_start);
    if !b.is_empty() {
        let cx = ((b.x0 + b.x1) / 2.0).clamp(w.x0, w.x1);
        let (top_px, bottom_px) = (to_px((cx, b.y1.min(w.y1))), to_px((cx, b.y0.max(w.y0))));
        let right = to_px((b.x1.min(w.x1), ((b.y0 + b.y1) / 2.0).clamp(w.y0, w.y1)));
        let left = to_px((b.x0.max(w.x0), ((b.y0 + b.y1) / 2.0).clamp(w.y0, w.y1)));
        let style = format!(r#"fill="{INK}" font-style="italic""#);
        let _ = labels.place(svg, &p.other, top_px, &[(0.0, -5.0, "middle")], &style)
            || labels.place(svg, &p.other, right, &[(6.0, 4.0, "start")], &style)
            || labels.place(svg, &p.other, left, &[(-6.0, 4.0, "end")], &style)
            || labels.place(svg, &p.other, bottom_px, &[(0.0, 14.0, "middle")], &style)
            || labels.place(svg, &p.other, top_px, &[(0.0, 14.0, "middle")], &style);
    }
    // Keep the labels off a small other object (a wall, a shield).
    if !b.is_empty() {
        let (a, c) = (to_px((b.x0, b.y1)), to_px((b.x1, b.y0)));
        let r = Rect {
            x0: a.0.max(px0),
            y0: a.1.max(py0),
            x1: c.0.min(px0 + PLOT_W),
            y1: c.1.min(py0 + PLOT_H),
        };
        if !r.is_empty() && r.w() * r.h() < 0.15 * PLOT_W * PLOT_H {
            labels.taken.push(r);
        }
    }
    // Start and end of each track; an end out of view is written where the
    // track leaves the view.
    let bold = format!(r#"fill="{INK}" font-weight="bold""#);
    for (i, track) in p.tracks.iter().enumerate() {
        let Some(&(step0, q0)) = track.first() else {
            continue;
        };
        let &(_, q1) = track.last().expect("a track has a point");
        let still = {
            let (a, b) = (to_px(q0), to_px(q1));
            (a.0 - b.0).hypot(a.1 - b.1) < 12.0
        };
        if i == 0 && step0 == first && visible(q0) {
            let text = if still { "start = end" } else { "start" };
            labels.place(svg, text, to_px(q0), &AROUND, &bold);
        }
        if i == 0 && still {
            continue;
        }
        if step0 != first && visible(q0) {
            // A piece that split off mid-run: its track starts at the split.
            let text = format!("split at {:.2} s", seconds(step0));
            labels.place(svg, &text, to_px(q0), &AROUND, &format!(r#"fill="{INK}""#));
        }
        if visible(q1) {
            labels.place(svg, "end", to_px(q1), &AROUND, &bold);
        } else if let Some(k) = track.iter().rposition(|s| visible(s.1))
            && k + 1 < track.len()
        {
            let (out, side) = exit(w, track[k].1, track[k + 1].1);
            let text = match side {
                'r' => format!("end at x = {:.1} →", q1.0),
                'l' => format!("← end at x = {:.1}", q1.0),
                't' => format!("↑ end at y = {:.1}", q1.1),
                _ => format!("↓ end at y = {:.1}", q1.1),
            };
            let (x, y) = to_px(out);
            // Beside the exit, or further in if the other object is there.
            let (dxs, dys, anchor): (&[f32], &[f32], &str) = match side {
                'r' => (&[-4.0, -40.0, -80.0], &[-8.0, 16.0, -24.0, 32.0], "end"),
                'l' => (&[4.0, 40.0, 80.0], &[-8.0, 16.0, -24.0, 32.0], "start"),
                't' => (&[6.0, -6.0], &[14.0, 30.0, 46.0], "start"),
                _ => (&[6.0, -6.0], &[-6.0, -22.0, -38.0], "start"),
            };
            let candidates: Vec<(f32, f32, &str)> = dxs
                .iter()
                .flat_map(|&dx| {
                    dys.iter().map(move |&dy| {
                        let anchor = if matches!(side, 't' | 'b') && dx < 0.0 {
                            "end"
                        } else {
                            anchor
                        };
                        (dx, dy, anchor)
                    })
                })
                .collect();
            labels.place(svg, &text, (x, y), &candidates, &bold);
        }
    }
    // The caption.
    let width = ((PANEL_W - 8.0) / (CAPTION_SIZE * 0.56)) as usize;
    let mut y = py0 + PLOT_H + 17.0;
    for (i, sentence) in p.caption.iter().enumerate() {
        let weight = if i == 0 { r#" font-weight="bold""# } else { "" };
        for line in wrap(sentence, width) {
            let _ = writeln!(
                svg,
                r#"<text x="{px0}" y="{y:.1}" font-size="{CAPTION_SIZE}" fill="{INK}"{weight}>{}</text>"#,
                escape(&line)
            );
            y += CAPTION_LINE;
        }
    }
    if !p.ok {
        let _ = writeln!(
            svg,
            r#"<text x="{px0}" y="{y:.1}" font-size="{CAPTION_SIZE}" font-weight="bold" fill="{INK}">NOT AS PROMISED</text>"#
        );
        y += CAPTION_LINE;
    }
    y - top
}

/// The legend at `(left, top)`, one entry a line: the palette's rule
/// colours, and what the marks mean (drawn as in the panels). Returns its
/// height.
fn legend(
    svg: &mut String,
    (left, top): P,
    palette: &RulePalette,
    marks: &[usize],
    sps: f32,
) -> f32 {
    let mut y = top + 14.0;
    let _ = writeln!(
        svg,
        r#"<text x="{left}" y="{y}" font-size="13" font-weight="bold" fill="{INK}">The colour of a panel: the rule of its pair</text>"#
    );
    y += 22.0;
    crate::legend::rule_swatches(svg, palette, (left, y), INK);
    y += 30.0;
    let _ = writeln!(
        svg,
        r#"<text x="{left}" y="{y}" font-size="13" font-weight="bold" fill="{INK}">The marks</text>"#
    );
    y += 22.0;
    let middle: Vec<String> = marks[1..marks.len().saturating_sub(1)]
        .iter()
        .map(|&s| format!("{:.2}", s as f32 / sps))
        .collect();
    let x = left;
    let icons: Vec<(String, String)> = vec![
        (
            format!(
                r##"<path d="M{x} CY h24" stroke="{MUTED}" stroke-width="2.2"/><circle cx="{}" cy="CY" r="4.5" fill="#ffffff" stroke="{INK}" stroke-width="1.6"/>"##,
                x + 4.0
            ),
            "the path of the actor's centre, from its start".to_owned(),
        ),
        (
            format!(
                r#"<circle cx="{}" cy="CY" r="2.8" fill="{MUTED}" stroke="{INK}" stroke-width="0.8"/><circle cx="{}" cy="CY" r="4.5" fill="{INK}"/>"#,
                x + 6.0,
                x + 18.0
            ),
            format!("where it was at t = {} s, and its end", middle.join(", ")),
        ),
        (
            format!(
                r#"<rect x="{x}" y="BY" width="10" height="10" fill="{MUTED}" fill-opacity="0.22" stroke="{MUTED}" stroke-dasharray="3 2"/><rect x="{}" y="BY" width="10" height="10" fill="{MUTED}" fill-opacity="0.8" stroke="{INK}" stroke-width="0.8"/>"#,
                x + 14.0
            ),
            "the actor at the start, at the end (in its rule's colour)".to_owned(),
        ),
        (
            format!(
                r#"<rect x="{x}" y="BY" width="10" height="10" fill="none" stroke="{INK}" stroke-width="1.6"/><rect x="{}" y="BY" width="10" height="10" fill="none" stroke="{INK}" stroke-dasharray="5 3"/>"#,
                x + 14.0
            ),
            "the other object of its rule at the start, at the end (arrow: how it moved)"
                .to_owned(),
        ),
        (
            format!(
                r#"<rect x="{x}" y="BY" width="24" height="10" fill="{FLOOR_FILL}" stroke="{FLOOR_LINE}"/>"#
            ),
            "the floor".to_owned(),
        ),
    ];
    for (icon, text) in icons {
        let icon = icon
            .replace("CY", &format!("{}", y - 4.0))
            .replace("BY", &format!("{}", y - 9.0));
        let _ = writeln!(
            svg,
            r#"{icon}<text x="{}" y="{y}" font-size="12" fill="{INK}">{}</text>"#,
            x + 32.0,
            escape(&text)
        );
        y += 21.0;
    }
    y - top
}

/// The panels in a grid, with the legend at the bottom, as one SVG document.
pub fn render(picture: &Picture) -> String {
    let palette = RulePalette::default();
    let width = MARGIN * 2.0 + COLUMNS as f32 * PANEL_W + (COLUMNS - 1) as f32 * GAP;
    let mut body = String::new();
    let _ = writeln!(
        body,
        r#"<text x="{MARGIN}" y="24" font-size="16" font-weight="bold" fill="{INK}">{}</text>"#,
        escape(&picture.title)
    );
    let mut top = 40.0;
    let mut rows = picture.panels.chunks(COLUMNS).peekable();
    let mut row = 0;
    while let Some(panels) = rows.next() {
        let mut height: f32 = 0.0;
        for (col, p) in panels.iter().enumerate() {
            let left = MARGIN + col as f32 * (PANEL_W + GAP);
            let h = panel(
                &mut body,
                picture,
                p,
                row * COLUMNS + col,
                (left, top),
                &palette,
            );
            height = height.max(h);
        }
        // The legend at the bottom: in the last row's empty cells, or under it.
        if rows.peek().is_none() {
            let at = if panels.len() < COLUMNS {
                (
                    MARGIN + panels.len() as f32 * (PANEL_W + GAP) + 10.0,
                    top + 30.0,
                )
            } else {
                (MARGIN, top + height + GAP)
            };
            let h = legend(
                &mut body,
                at,
                &palette,
                picture.marks,
                picture.steps_per_second,
            );
            height = height.max(at.1 - top + h);
        }
        top += height + GAP;
        row += 1;
    }
    let mut svg = String::new();
    let _ = writeln!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{top}" viewBox="0 0 {width} {top}" font-family="{FONT}">"#
    );
    let _ = writeln!(
        svg,
        r##"<rect width="100%" height="100%" fill="#ffffff"/>"##
    );
    let _ = writeln!(
        svg,
        r#"<defs><marker id="arrow" viewBox="0 0 10 10" refX="2" refY="5" markerWidth="7" markerHeight="7" orient="auto"><path d="M0,0 L10,5 L0,10 Z" fill="{INK}"/></marker></defs>"#
    );
    svg.push_str(&body);
    svg.push_str("</svg>\n");
    svg
}
