//! A multipass RIB file through the `reyes-render` binary (issue #32): the first frame renders
//! the light's view to a depth map (`Display "zfile"`), `MakeShadow` turns it into a shadow
//! map between the frames, and the second frame's light reads it with `shadow()`.
//!
//! The scene, in RenderMan's world: a light at the origin looking down +z, a sphere of radius
//! 1 at depth 5, a wall at depth 10 facing it. The sphere's shadow on the wall is the disk of
//! radius `10 tan(asin(1/5)) = 2.0412` about the wall's centre. The camera stands 3 to the
//! right of the light, looking down +z too, so the wall is parallel to its picture: wall point
//! `(x, y, 10)` is at raster `(80 + 8 (x - 3) / tan 30°, 80 - 8 y / tan 30°)` of the 160 x 160
//! picture (fov 60), and the part of the shadow right of the sphere's image is in view.

use std::process::Command;

/// The light: its intensity, unshadowed where `shadow()` says so.
const LIGHT: &str = r#"light shadowlight(float intensity = 1; string shadowname = "";
    float bias = 0.05; float blur = 0) {
    illuminate(point "shader" (0, 0, 0)) {
        Cl = intensity * (1 - shadow(shadowname, Ps, "bias", bias, "blur", blur));
    }
}
"#;

/// The two frames, the second's light reading the map with `blur`.
fn multipass(blur: f32) -> String {
    let world = "AttributeBegin\nTranslate 0 0 5\nSphere 1 -1 1 360\nAttributeEnd\n\
                 Polygon \"P\" [-8 -8 10  8 -8 10  8 8 10  -8 8 10]\n";
    format!(
        "FrameBegin 1\nDisplay \"shadow.z\" \"zfile\" \"z\"\nFormat 256 256 1\nPixelSamples 2 2\n\
         Projection \"perspective\" \"fov\" [40]\nWorldBegin\n{world}WorldEnd\nFrameEnd\n\
         MakeShadow \"shadow.z\" \"shadow.shd\"\n\
         FrameBegin 2\nDisplay \"beauty.exr\" \"file\" \"rgba\"\nFormat 160 160 1\n\
         PixelSamples 4 4\nProjection \"perspective\" \"fov\" [60]\nTranslate -3 0 0\n\
         WorldBegin\nLightSource \"shadowlight\" 1 \"shadowname\" [\"shadow.shd\"] \"blur\" [{blur}]\n\
         ShadingInterpolation \"smooth\"\nSurface \"matte\" \"Ka\" [0] \"Kd\" [1]\n\
         {world}WorldEnd\nFrameEnd\n"
    )
}

/// Renders the file, written into a fresh directory, from another working directory, and
/// returns the picture's red channel, row by row. The depth map and the shadow map are
/// written beside the RIB file (its maps' names resolve there); the picture, as every
/// `Display` picture, in the working directory.
fn render(blur: f32) -> (tempfile::TempDir, Vec<f32>) {
    let dir = tempfile::tempdir().unwrap();
    let cwd = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("shadowlight.sl"), LIGHT).unwrap();
    let rib = dir.path().join("multipass.rib");
    std::fs::write(&rib, multipass(blur)).unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_reyes-render"))
        .current_dir(cwd.path())
        .arg("-q")
        .arg(&rib)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(err.is_empty(), "{err}");
    for f in ["shadow.z", "shadow.shd"] {
        assert!(dir.path().join(f).is_file(), "{f} not written");
    }
    let film = reyes_film::read_exr(&cwd.path().join("beauty.exr")).unwrap();
    let red = (0..160 * 160).map(|k| film.pixel(k % 160, k / 160).unwrap()[0]).collect();
    (dir, red)
}

/// Raster per wall unit: 80 pixels per `tan 30°` at depth 10.
const K: f64 = 80.0 / (10.0 * 0.577_350_269_189_625_8);

/// The shadow's radius on the wall.
fn radius() -> f64 {
    let s: f64 = 0.2;
    10.0 * s / (1.0 - s * s).sqrt()
}

/// The matte wall lit from the origin: `N.L` at wall point `(x, y)`.
fn lit(x: f64, y: f64) -> f64 {
    10.0 / (x * x + y * y + 100.0).sqrt()
}

/// Where a run of pixels `values` (at raster positions `at(i)`), going from shadow into light,
/// crosses half its local lit level `light(i)`: linearly between the two pixel centres.
fn crossing(values: &[f32], at: impl Fn(usize) -> f64, light: impl Fn(usize) -> f64) -> f64 {
    let f = |i: usize| f64::from(values[i]) / light(i);
    let i = (0..values.len() - 1).find(|&i| f(i) < 0.5 && f(i + 1) >= 0.5).expect("an edge");
    let t = (0.5 - f(i)) / (f(i + 1) - f(i));
    at(i) + t * (at(i + 1) - at(i))
}

#[test]
fn a_depth_pass_shadows_the_beauty_pass_where_the_silhouette_projects() {
    let (_dir, red) = render(0.0);
    let px = |x: usize, y: usize| red[y * 160 + x];
    // Raster <-> wall.
    let wall_x = |rx: f64| 3.0 + (rx - 80.0) / K;
    let wall_y = |ry: f64| (80.0 - ry) / K;
    // One texel of the 256-texel map (fov 40: 2 tan 20° x 10 across) on the wall, in raster
    // pixels (0.39): the edge may be that far from where it projects. The picture's own
    // estimate of the edge (16 samples a pixel, the Gaussian filter, smooth shading, the
    // crossing interpolated between pixel centres) is good to a tenth of a pixel or better
    // on a straight edge, so the texel is the bound.
    let texel = 20.0 * 0.363_970_234_266_202_4 / 256.0 * K;
    let tol = texel;
    // The beauty pass interpolates its shading smoothly: with RenderMan's default constant
    // shading every micropolygon takes its first vertex's colour, and the edge would move by
    // half a micropolygon (0.34 to 0.48 pixels here) wherever the lookups were made.
    // Along the middle row, rightwards out of the shadow (centre row 79.5 + 0.5).
    let row: Vec<f32> = (40..80).map(|x| px(x, 79)).chain((40..80).map(|x| px(x, 80))).collect();
    let mid: Vec<f32> = (0..40).map(|i| 0.5 * (row[i] + row[40 + i])).collect();
    let rx = crossing(&mid, |i| 40.5 + i as f64, |i| lit(wall_x(40.5 + i as f64), 0.0));
    let exact = 80.0 + K * (radius() - 3.0);
    println!("right edge at raster x {rx:.3}, exact {exact:.3}, tolerance {tol:.3}");
    assert!((rx - exact).abs() <= tol, "right edge at {rx}, exact {exact}");
    // Down the column through the shadow's centre (wall x = 0), from the centre downwards.
    let cx = (80.0 - 3.0 * K).round() as usize;
    let col: Vec<f32> = (80..130).map(|y| px(cx, y)).collect();
    let x0 = wall_x(cx as f64 + 0.5);
    let ry = crossing(&col, |i| 80.5 + i as f64, |i| lit(x0, wall_y(80.5 + i as f64)));
    let exact_y = 80.0 + K * (radius() * radius() - x0 * x0).sqrt();
    println!("lower edge at raster y {ry:.3}, exact {exact_y:.3}");
    // And upwards from the centre.
    let up: Vec<f32> = (30..80).rev().map(|y| px(cx, y)).collect();
    let ry = crossing(&up, |i| 79.5 - i as f64, |i| lit(x0, wall_y(79.5 - i as f64)));
    let exact_y = 160.0 - exact_y;
    println!("upper edge at raster y {ry:.3}, exact {exact_y:.3}");
    assert!((ry - exact_y).abs() <= tol, "upper edge at {ry}, exact {exact_y}");
    assert!((ry - exact_y).abs() <= tol, "lower edge at {ry}, exact {exact_y}");
    // Deep in the shadow nothing is lit; away from the edge the wall is lit exactly as the
    // matte model says (no self-shadowing acne at the bias), to the filter's smoothing, up
    // to two pixels from the wall's own edge (raster x 149.3, where the filter meets the
    // black beyond).
    for x in 45..=(exact as usize - 3) {
        assert!(px(x, 80) < 0.01, "pixel ({x}, 80) in shadow reads {}", px(x, 80));
    }
    for x in (exact as usize + 3)..147 {
        for y in [30, 80, 130] {
            let want = lit(wall_x(x as f64 + 0.5), wall_y(y as f64 + 0.5));
            let got = f64::from(px(x, y));
            assert!((got - want).abs() < 0.01 * want, "lit pixel ({x}, {y}): {got} vs {want}");
        }
    }
}

/// The width over which the shadow's edge rises from 10% to 90% of the light, along the
/// middle row, in raster pixels.
fn edge_width(red: &[f32]) -> f64 {
    let wall_x = |rx: f64| 3.0 + (rx - 80.0) / K;
    let row: Vec<f64> =
        (40..90).map(|x| f64::from(red[80 * 160 + x]) / lit(wall_x(x as f64 + 0.5), 0.0)).collect();
    let at = |level: f64| {
        let i = (0..row.len() - 1).find(|&i| row[i] < level && row[i + 1] >= level).unwrap();
        i as f64 + (level - row[i]) / (row[i + 1] - row[i])
    };
    at(0.9) - at(0.1)
}

#[test]
fn blur_widens_the_penumbra_as_the_filter_predicts() {
    // `blur` widens the filtered region by that much of the map (texture coordinates): 0.05
    // of the map's 7.28 wall units is 0.364 (5.04 pixels), which a box of percentage-closer
    // samples turns into a linear ramp whose 10-90% width is 0.8 of it (4.03 pixels). The
    // picture's own edge (its filter, the sharp map's texel) widens it further; two such
    // blurs of an edge add about in quadrature, so the blur's part is sqrt(w1^2 - w0^2).
    // Its 16 samples are a 4 x 4 grid of strata: the ramp is four jittered steps, whose
    // 10-90% width may be off by a quarter of the box.
    let (_d0, sharp) = render(0.0);
    let (_d1, blurred) = render(0.05);
    let (w0, w1) = (edge_width(&sharp), edge_width(&blurred));
    let predicted = 0.8 * 0.05 * 20.0 * 0.363_970_234_266_202_4 * K;
    let blur = (w1 * w1 - w0 * w0).sqrt();
    println!(
        "10-90% edge: {w0:.2} px sharp, {w1:.2} px at blur 0.05: {blur:.2} px of blur, predicted {predicted:.2}"
    );
    assert!(
        (blur - predicted).abs() <= 0.25 * predicted,
        "blur's ramp {blur} px, predicted {predicted}"
    );
}
