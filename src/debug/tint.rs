//! The user's own debug backend, with the shapes of the colliders the rules
//! reach drawn in the palette's tint.

use super::super::rapier::prelude::*;

use super::super::RuleHooks;
use super::{RuleDebugFilter, RulePalette};

/// A `DebugRenderBackend` that passes everything to the user's backend,
/// recolouring the lines of a collider's shape when the rules reach it: the
/// tint's hue and saturation, Rapier's lightness and alpha (so a sleeping
/// or disabled collider stays as dim as Rapier draws it). Only the shapes
/// pass through it (see `RuleDebugRender::render`).
pub(crate) struct Tinted<'a, B> {
    pub(crate) backend: &'a mut B,
    pub(crate) hooks: &'a RuleHooks,
    pub(crate) bodies: &'a RigidBodySet,
    pub(crate) colliders: &'a ColliderSet,
    pub(crate) palette: &'a RulePalette,
    pub(crate) filter: &'a RuleDebugFilter,
    /// Only the shapes of colliders that get a tint are drawn.
    pub(crate) only_reached: bool,
}

impl<B: DebugRenderBackend> Tinted<'_, B> {
    /// The tint of a collider's shape, if it gets one.
    fn tint(&self, object: DebugRenderObject<'_>) -> Option<DebugColor> {
        let DebugRenderObject::Collider(handle, _) = object else {
            return None;
        };
        let reach = self.hooks.reach(handle);
        let tinted = self.filter.tints(reach)
            && self
                .filter
                .holds(self.hooks.rules(), self.bodies, self.colliders, handle);
        self.palette
            .reach(reach)
            .filter(|_| tinted)
            .map(|tint| tint.hsla(1.0))
    }

    fn color(&self, object: DebugRenderObject<'_>, color: DebugColor) -> DebugColor {
        match self.tint(object) {
            Some([hue, saturation, _, _]) => [hue, saturation, color[2], color[3]],
            None => color,
        }
    }
}

impl<B: DebugRenderBackend> DebugRenderBackend for Tinted<'_, B> {
    fn filter_object(&self, object: DebugRenderObject) -> bool {
        (!self.only_reached || self.tint(object).is_some()) && self.backend.filter_object(object)
    }

    fn draw_line(&mut self, object: DebugRenderObject, a: Vector, b: Vector, color: DebugColor) {
        let color = self.color(object, color);
        self.backend.draw_line(object, a, b, color);
    }

    fn draw_polyline(
        &mut self,
        object: DebugRenderObject,
        vertices: &[Vector],
        indices: &[[u32; 2]],
        transform: &Pose,
        scale: Vector,
        color: DebugColor,
    ) {
        let color = self.color(object, color);
        self.backend
            .draw_polyline(object, vertices, indices, transform, scale, color);
    }

    fn draw_line_strip(
        &mut self,
        object: DebugRenderObject,
        vertices: &[Vector],
        transform: &Pose,
        scale: Vector,
        color: DebugColor,
        closed: bool,
    ) {
        let color = self.color(object, color);
        self.backend
            .draw_line_strip(object, vertices, transform, scale, color, closed);
    }
}
