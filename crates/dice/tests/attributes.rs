//! Per-object attributes in the dicer: an object's own shading rate (RenderMan's
//! `ShadingRate` attribute) drives its split and dice decisions.

mod common;

use common::*;
use reyes_scene::Transform;

/// An object's own shading rate replaces the scene's in its dicing: a quarter of the rate
/// halves the micropolygons' side, so about four times as many; the other objects do not
/// change, and writing the scene's rate explicitly changes nothing.
#[test]
fn an_objects_shading_rate_drives_its_dicing() {
    let ball = |x: f32, rate: Option<f32>| {
        let mut o = object(sphere(1.0), vec![Transform::Translate([x, 0.0, 8.0])]);
        o.shading_rate = rate;
        o
    };
    let count = |rate: Option<f32>| {
        let mut s = scene_ahead(320, 240, 40.0, vec![ball(-1.5, rate), ball(1.5, None)]);
        // The rate's own rule: crack-free dicing rounds each count to a multiple of its
        // sides' polyline floors (split/edge.rs), which the bound below does not model.
        s.hider.crack_free = false;
        let (d, _) = dice(&s);
        // The left ball's micropolygons lie left of the image centre, the right ball's right.
        let left = d.mpolys.iter().filter(|m| m.v[0][0] < 160.0).count() as f64;
        let right = d.mpolys.iter().filter(|m| m.v[0][0] >= 160.0).count() as f64;
        (left, right, d)
    };
    let (base_left, base_right, base) = count(None);
    let (same_left, _, same) = count(Some(1.0));
    assert_eq!(base.mpolys, same.mpolys, "the scene's own rate, written out, changes nothing");
    assert_eq!(base_left, same_left);
    let (fine_left, fine_right, _) = count(Some(0.25));
    let ratio = fine_left / base_left;
    eprintln!("micropolygons of the ball: {base_left} at rate 1, {fine_left} at rate 0.25");
    // Each side's count is ceil(length / sqrt(rate)), and ceil(2x) <= 2 ceil(x): at most 4x,
    // a little less where a side's count rounds up at the coarser rate.
    assert!((3.0..=4.0).contains(&ratio), "a quarter of the rate: {ratio:.2}x micropolygons");
    assert_eq!(fine_right, base_right, "the other ball is diced as before");
    let (coarse_left, _, _) = count(Some(4.0));
    let ratio = base_left / coarse_left;
    assert!((3.0..=4.0).contains(&ratio), "four times the rate: 1/{ratio:.2} of them");
}
