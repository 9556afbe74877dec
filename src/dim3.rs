//! The rules for `rapier3d` (feature `dim3`, on by default). Everything
//! here is also at the crate's root.

dimension!(rapier3d);

/// A rotation as numbers, for fingerprints of poses: a quaternion's four.
#[inline]
fn rotation_words(rotation: rapier::math::Rotation) -> [f32; 4] {
    rotation.to_array()
}
