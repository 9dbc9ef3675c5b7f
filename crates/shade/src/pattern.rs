//! Procedural patterns: Appendix B's pool ball (3.9 of the notes).
//!
//! Invariant: a pattern is a pure function of the object-space point (so it moves, turns and
//! rolls with its object) and replaces the material colour.

use glam::Vec3;
use reyes_scene::Pattern;

/// Appendix B's `ivorycolor`: the outside of striped balls, the ring of solid balls and the
/// number disks.
pub const IVORY: Vec3 = Vec3::new(0.85, 0.85, 0.8);
/// Appendix B's `blackcolor` (0.05): the ring line of striped balls.
pub const BLACK: Vec3 = Vec3::splat(0.05);

/// Half-width of the stripe band, in units of the radius.
const HALF_STRIPE: f32 = 0.4722;
/// Where the ring line starts.
const HALF_RING: f32 = 0.85;
/// Where the ring line ends and the number disk starts.
const DISK: f32 = 0.90;

/// The colour of `pattern` at the object-space point `p_object`.
pub fn pattern_color(pattern: &Pattern, p_object: Vec3) -> Vec3 {
    match *pattern {
        Pattern::PoolBall { color, striped } => pool_ball(Vec3::from(color), striped, p_object),
    }
}

/// Appendix B's pool ball around the object's z axis, at the object-space point `p_object`
/// taken to the unit sphere (`z = |p_z| / |p|`, so the pattern does not depend on the
/// ball's radius):
///
/// | `z` | striped ball | solid ball |
/// |---|---|---|
/// | `< 0.4722` (band) | `color` | `color` |
/// | `< 0.85` | ivory | `color` |
/// | `< 0.90` (ring line) | black (0.05) | ivory |
/// | `>= 0.90` (number disk) | ivory | ivory |
///
/// The number disk has no picture map (Appendix B reads the ball's number from a frame
/// buffer; there is no image texture here), so it is plain ivory, as Appendix B's branch
/// without a map. Appendix B's per-region reflectivities and Phong exponents are not
/// carried: reflection is the object's `reflect`, the highlight its material's.
/// The point at the centre (`p = 0`) counts as being in the band.
pub fn pool_ball(color: Vec3, striped: bool, p_object: Vec3) -> Vec3 {
    let z = p_object.normalize_or_zero().z.abs();
    if z < HALF_STRIPE {
        color
    } else if z < HALF_RING {
        if striped { IVORY } else { color }
    } else if z < DISK {
        if striped { BLACK } else { IVORY }
    } else {
        IVORY
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn regions_by_height() {
        let red = Vec3::new(1.0, 0.0, 0.0);
        let at = |z: f32| Vec3::new((1.0 - z * z).sqrt(), 0.0, z) * 3.0;
        for (z, striped, want) in [
            (0.0, true, red),
            (-0.47, true, red),
            (0.48, true, IVORY),
            (0.48, false, red),
            (-0.86, true, BLACK),
            (0.86, false, IVORY),
            (0.95, true, IVORY),
            (-1.0, false, IVORY),
        ] {
            assert_eq!(pool_ball(red, striped, at(z)), want, "z {z} striped {striped}");
        }
        assert_eq!(pool_ball(red, true, Vec3::ZERO), red);
    }
}
