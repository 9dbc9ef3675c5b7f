//! A shader's opacity decides occlusion: where a shading-language surface leaves a
//! micropolygon fully opaque, the hider treats it exactly as it treats a native opaque one
//! (its depth is the sample's `Z`, it ends the sample's composite and it occludes what lies
//! behind it); where it leaves it partly transparent, it does none of that.

use reyes_render::{RenderOptions, Rendered};

use super::{Files, ortho};

const SIZE: u32 = 24;
const W: f32 = 1.25;

/// Two opaque spheres, the second wholly behind the first, under `surface` (a RIB `Surface`
/// line).
fn spheres(surface: &str) -> String {
    format!(
        "{}WorldBegin\n{surface}\nAttributeBegin\nTranslate 0 0 4\nSphere 1 -1 1 360\n\
         AttributeEnd\nAttributeBegin\nTranslate 0 0 7\nSphere 0.8 -0.8 0.8 360\nAttributeEnd\n\
         WorldEnd\n",
        ortho(SIZE, W)
    )
}

fn run(files: &Files, rib: &str) -> Rendered {
    reyes_render::render(&files.scene(rib), &RenderOptions::default()).unwrap()
}

/// The same geometry shaded natively (`constant`) and by a shader that is opaque everywhere
/// gives the same depth at every pixel, bit for bit (the geometry, the samples and the depth
/// interpolation are the same; only the colours' origin differs), and the sphere behind is
/// occlusion-culled. (More micropolygons reach the buckets under the shader: the native
/// opaque closed spheres' back faces are dropped before bucketing, which needs the opacity
/// before shading; the shader's back faces are culled by occlusion instead.)
#[test]
fn an_opaque_shader_sets_depth_and_occludes_as_a_native_surface_does() {
    let files = Files::new(&[("flat", "surface flat() { Oi = Os; Ci = Cs * Oi; }")]);
    let native = run(&files, &spheres("Surface \"constant\""));
    let shaded = run(&files, &spheres("Surface \"flat\""));
    assert_eq!(native.film.z(), shaded.film.z(), "depth per pixel");
    let covered = native.film.z().iter().filter(|z| **z < 5.0).count();
    assert!(covered > 100, "the near sphere covers the middle: {covered} pixels");
    let (a, b) = (native.stats.hider.occlusion_culled, shaded.stats.hider.occlusion_culled);
    assert!(a > 0, "the far sphere is hidden behind the near one");
    assert!(b >= a, "micropolygons occlusion-culled: {b} under the shader, {a} native");
}

/// A half-transparent shader occludes nothing: the sphere behind shows through, the depth
/// stays the background's (RenderMan's `Z` is that of opaque surfaces), and no micropolygon
/// is culled.
#[test]
fn a_half_transparent_shader_occludes_nothing() {
    let files = Files::new(&[("half", "surface half() { Oi = 0.5; Ci = Cs * Oi; }")]);
    let r = run(&files, &spheres("Surface \"half\""));
    assert_eq!(r.stats.hider.occlusion_culled, 0);
    let centre = (SIZE / 2) * SIZE + SIZE / 2;
    assert!(r.film.z()[centre as usize] > 1e29, "no opaque depth: {}", r.film.z()[centre as usize]);
    // Four surfaces at the centre (each sphere's front and back, none culled as they are
    // not opaque): alpha 1 - 0.5^4.
    let a = r.film.rgba()[centre as usize][3];
    assert!((a - 0.9375).abs() < 1e-5, "alpha {a}");
}

/// A surface shader that leaves `Oi` (or `Ci`) alone outputs opaque (black): the values
/// Aqsis and PRMan start them at, so that shaders written for them (which often set only
/// `Ci`) render opaque.
#[test]
fn a_shader_that_sets_no_opacity_is_opaque() {
    let files = Files::new(&[
        ("grey", "surface grey() { Ci = 0.5; }"),
        ("nothing", "surface nothing() { }"),
    ]);
    for (name, want) in [("grey", 0.5), ("nothing", 0.0)] {
        let r = run(&files, &spheres(&format!("Surface \"{name}\"")));
        let centre = ((SIZE / 2) * SIZE + SIZE / 2) as usize;
        assert_eq!(r.film.rgba()[centre], [want, want, want, 1.0], "{name}");
        assert!(r.film.z()[centre] < 5.0, "{name}: opaque, so it has a depth");
    }
}
