//! The text of a drawn pair's label: its rule and what decided it, as
//! `explain` tells.

use std::fmt::Write as _;

use super::super::rapier::prelude::Vector;

use super::super::hooks::PairReach;
use super::super::{Explanation, Node, Stage};

/// A backend that can draw text: [`RuleDebugRender::render_labels`](super::RuleDebugRender::render_labels)
/// hands it one label per drawn pair, at the middle of the pair's line, in
/// the colour of the pair's rule (HSLA, as Rapier's debug colours).
///
/// ```
/// use rapier3d::prelude::*;
/// use rapier_collision_rules::RuleLabelBackend;
///
/// /// Keeps the labels, for a UI to draw.
/// #[derive(Default)]
/// struct Labels(Vec<(Vector, String)>);
///
/// impl RuleLabelBackend for Labels {
///     fn draw_label(&mut self, at: Vector, text: &str, _color: [f32; 4]) {
///         self.0.push((at, text.to_owned()));
///     }
/// }
/// ```
pub trait RuleLabelBackend {
    /// Draws `text` at `at`.
    fn draw_label(&mut self, at: Vector, text: &str, color: [f32; 4]);
}

/// A node as a label names it: `collider 3`, `body 7` (the handle's index).
fn node_name(node: Node) -> String {
    match node {
        Node::Collider(h) => format!("collider {}", h.into_raw_parts().0),
        Node::Body(h) => format!("body {}", h.into_raw_parts().0),
    }
}

/// `NoResponse: specific body 2 / collider 5, ends`: the pair's rule, then
/// the override, or the calculator (where one, or a pair-created callback,
/// is installed and the rule is not the default calculation's), or `kept`
/// (a rule the rules no longer give, kept by the `Manual` policy), or the
/// stage with its nodes (and groups), as `explain` gives them; then the
/// marks.
pub(crate) fn label_text(reach: &PairReach, why: &Explanation, calculated: bool) -> String {
    let mut text = format!("{:?}: ", reach.rule);
    let nodes = |text: &mut String| {
        if let Some((a, b)) = why.nodes {
            let _ = write!(text, " {} / {}", node_name(a), node_name(b));
        }
    };
    if reach.overridden {
        text.push_str("override");
    } else if why.rule != reach.rule && calculated {
        text.push_str("calculator");
    } else if why.rule != reach.rule {
        // The pair keeps the rule it had (the `Manual` policy).
        text.push_str("kept");
    } else {
        match why.stage {
            Stage::Specific => {
                text.push_str("specific");
                nodes(&mut text);
            }
            Stage::Personal => {
                text.push_str("personal");
                nodes(&mut text);
            }
            Stage::Group => {
                text.push_str("group");
                if let Some((a, b)) = why.groups {
                    let _ = write!(text, " {} / {}", a.id(), b.id());
                }
                nodes(&mut text);
            }
            Stage::Default => text.push_str("default rule"),
        }
    }
    if reach.ending {
        text.push_str(", ends");
    }
    if reach.hooked {
        text.push_str(", hooked");
    }
    text
}
