//! Level of detail: `Detail` and `DetailRange` choose among three levels by the raster area of
//! the bound, at three camera distances, and blend two levels by opacity in a transition.

use reyes_render::{RenderOptions, render};
use reyes_scene::{Material, Scene};

use super::scene;

/// Three levels of a unit disk facing the camera at distance `d` (64 x 64 pixels, fov 40): red for small
/// areas, green for middle ones, blue for large ones, each a `constant` disk (one layer, so that opacities composite simply) on the same
/// `Detail` bound, the unit cube around it.
fn levels(d: f64) -> String {
    format!(
        "Format 64 64 1
Projection \"perspective\" \"fov\" [40]
PixelSamples 4 4
WorldBegin
Translate 0 0 {d}
Surface \"constant\"
AttributeBegin
  Detail [-1 1 -1 1 -1 1]
  AttributeBegin
    DetailRange [0 0 100 200]
    Color [1 0 0]
    Disk 0 1 360
  AttributeEnd
  AttributeBegin
    DetailRange [100 200 1000 2000]
    Color [0 1 0]
    Disk 0 1 360
  AttributeEnd
  AttributeBegin
    DetailRange [1000 2000 1e30 1e30]
    Color [0 0 1]
    Disk 0 1 360
  AttributeEnd
AttributeEnd
WorldEnd
"
    )
}

/// The bound's raster area at distance `d`: its nearest face, at depth `d - 1`, spans
/// `2 / tan(20 deg) / (d - 1)` screen units, 32 pixels each, both ways.
fn area(d: f64) -> f64 {
    let side = 2.0 / 20f64.to_radians().tan() / (d - 1.0) * 32.0;
    side * side
}

/// Linear ramps of a level.
fn weight([a, b, c, e]: [f64; 4], x: f64) -> f64 {
    if x < a || x > e {
        0.0
    } else if x < b {
        (x - a) / (b - a)
    } else if x > c {
        (e - x) / (e - c)
    } else {
        1.0
    }
}

/// (colour, opacity) of each object drawn.
fn drawn(s: &Scene) -> Vec<([f32; 3], f32)> {
    s.objects
        .iter()
        .map(|o| match o.material {
            Material::Constant { color, opacity } => (color, opacity[0]),
            ref m => panic!("{m:?}"),
        })
        .collect()
}

#[test]
fn one_level_is_drawn_at_each_distance() {
    // Areas 36.7, 381.6 and 3433 pixels: inside red's, green's and blue's full range.
    for (d, want) in [(30.0, [1.0, 0.0, 0.0]), (10.0, [0.0, 1.0, 0.0]), (4.0, [0.0, 0.0, 1.0])] {
        let text = levels(d);
        assert_eq!(drawn(&scene(&text)), vec![(want, 1.0)], "distance {d}, area {}", area(d));
        // In the picture every pixel shows that level's colour or the background only.
        let film = render(&scene(&text), &RenderOptions::default()).unwrap().film;
        let mut covered = 0;
        for p in film.rgba() {
            for c in 0..3 {
                if want[c] == 0.0 {
                    assert_eq!(p[c], 0.0, "distance {d}: {p:?}");
                }
            }
            covered += usize::from(p[3] > 0.99);
        }
        assert!(covered > 0, "distance {d}: nothing drawn");
    }
}

#[test]
fn levels_blend_by_opacity_where_their_ranges_overlap() {
    // At distance 5.54 the area is about 1500 pixels: green is fading out and blue in.
    let d = 5.54;
    let a = area(d);
    let (green, blue) =
        (weight([100.0, 200.0, 1000.0, 2000.0], a), weight([1000.0, 2000.0, 1e30, 1e30], a));
    assert!(green > 0.4 && blue > 0.4, "{green} {blue}");
    let s = scene(&levels(d));
    let got = drawn(&s);
    assert_eq!(got.len(), 2, "{got:?}");
    // The areas agree to rounding of the f32 corners (relative 1e-6 of ~1500 pixels).
    assert_eq!(got[0].0, [0.0, 1.0, 0.0]);
    assert!((f64::from(got[0].1) - green).abs() < 1e-4, "{got:?} {green}");
    assert_eq!(got[1].0, [0.0, 0.0, 1.0]);
    assert!((f64::from(got[1].1) - blue).abs() < 1e-4, "{got:?} {blue}");
    // In the picture, the middle of the disk composites both coincident levels, front one
    // first (which one is in front varies with the sample): alpha is exactly
    // 1 - (1 - g)(1 - b), and each colour between its weight times the other's
    // transmittance and its weight. Pixels are exact; 1e-4 is float rounding.
    let film = render(&s, &RenderOptions::default()).unwrap().film;
    let p = film.pixel(32, 32).unwrap().map(f64::from);
    let (g, b) = (green, blue);
    assert!((p[3] - (1.0 - (1.0 - g) * (1.0 - b))).abs() < 1e-4, "{p:?}");
    assert!(p[0].abs() < 1e-6, "{p:?}");
    assert!(p[1] >= g * (1.0 - b) - 1e-4 && p[1] <= g + 1e-4, "{p:?}");
    assert!(p[2] >= b * (1.0 - g) - 1e-4 && p[2] <= b + 1e-4, "{p:?}");
}

#[test]
fn bad_ranges_and_bounds_are_one_line_errors() {
    let cases = [
        (
            "Detail [-1 1 -1 1 -1 1] DetailRange [3 2 1 0]",
            "DetailRange: the range must be in increasing order, got [3 2 1 0]",
        ),
        ("Detail [-1 1 -1 1 -1 1] DetailRange [1 2]", "DetailRange"),
        ("Detail [-1 1 -1 1]", "Detail"),
        ("RelativeDetail -1", "RelativeDetail"),
    ];
    for (body, want) in cases {
        let text = if body.starts_with("RelativeDetail") {
            format!("{body}\n{}", super::world(""))
        } else {
            super::world(body)
        };
        let e = super::rib(&text).unwrap_err().to_string();
        assert!(e.starts_with("test.rib:") && e.contains(want) && !e.contains('\n'), "{body}: {e}");
    }
    // Without a Detail bound the level is drawn, with a warning.
    let loaded = super::rib(&super::world("DetailRange [0 0 10 20] Sphere 1 -1 1 360")).unwrap();
    assert_eq!(loaded.frames[0].scene.objects.len(), 1);
    assert!(loaded.warnings.iter().any(|w| w.to_string().contains("no Detail bound")));
}
