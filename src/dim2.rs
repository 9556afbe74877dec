//! The rules for `rapier2d` (feature `dim2`): the same API as the 3D one,
//! over `rapier2d`'s types. The README's 2D quick start shows it at work.

dimension!(rapier2d);

/// A rotation as numbers, for fingerprints of poses: a unit complex's two.
#[inline]
fn rotation_words(rotation: rapier::math::Rotation) -> [f32; 2] {
    [rotation.re, rotation.im]
}
