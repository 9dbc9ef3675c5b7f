//! The hider: method, pixel samples, jitter and patterns, the filter of every kind, bucket and grid sizes, shading rate, seed, the `original` switches, and the filter table the film builds from them.

use super::Case;

#[rustfmt::skip]
pub(crate) const CASES: &[Case] = &[
    Case { name: "unknown variant", from: "Gaussian", to: "Gauss", field: "hider.filter.kind", at: Some((4, 49)) },
    Case { name: "pixel samples 0", from: "(4, 4)", to: "(4, 0)", field: "hider.pixel_samples[1]", at: Some((4, 30)) },
    Case { name: "pixel samples too many", from: "(4, 4)", to: "(65, 4)", field: "hider.pixel_samples[0]", at: Some((4, 27)) },
    Case { name: "filter width 0", from: "width: 2.0", to: "width: 0.0", field: "hider.filter.width", at: Some((4, 66)) },
    Case { name: "filter width negative", from: "width: 2.0", to: "width: -2.0", field: "hider.filter.width", at: Some((4, 66)) },
    Case { name: "filter width too wide", from: "width: 2.0", to: "width: 17.0", field: "hider.filter.width", at: Some((4, 66)) },
    Case { name: "filter height 0", from: "width: 2.0)", to: "width: 2.0, height: Some(0.0))", field: "hider.filter.height", at: Some((4, 79)) },
    Case { name: "filter height negative", from: "width: 2.0)", to: "width: 2.0, height: Some(-1.0))", field: "hider.filter.height", at: Some((4, 79)) },
    Case { name: "filter height too tall", from: "width: 2.0)", to: "width: 2.0, height: Some(17.0))", field: "hider.filter.height", at: Some((4, 79)) },
    Case { name: "filter height NaN", from: "width: 2.0)", to: "width: 2.0, height: Some(NaN))", field: "hider.filter.height", at: Some((4, 79)) },
    Case { name: "filter height without Some", from: "width: 2.0)", to: "width: 2.0, height: 1.0)", field: "hider.filter.height", at: Some((4, 79)) },
    Case { name: "RenderMan filter width negative", from: "kind: Gaussian, width: 2.0", to: "kind: RiGaussian, width: -2.0", field: "hider.filter.width", at: Some((4, 68)) },
    Case { name: "unknown RenderMan filter", from: "Gaussian", to: "RiLanczos", field: "hider.filter.kind", at: Some((4, 49)) },
    Case { name: "bucket size 0", from: "(4, 4),", to: "(4, 4), bucket_size: (0, 16),", field: "hider.bucket_size[0]", at: Some((4, 48)) },
    Case { name: "shading rate 0", from: "(4, 4),", to: "(4, 4), shading_rate: 0.0,", field: "hider.shading_rate", at: Some((4, 48)) },
    Case { name: "flatness negative", from: "(4, 4),", to: "(4, 4), flatness: -0.1,", field: "hider.flatness", at: Some((4, 44)) },
    Case { name: "flatness NaN", from: "(4, 4),", to: "(4, 4), flatness: NaN,", field: "hider.flatness", at: Some((4, 44)) },
    Case { name: "relative flatness above 1", from: "(4, 4),", to: "(4, 4), relative_flatness: 2.0,", field: "hider.relative_flatness", at: Some((4, 53)) },
    Case { name: "motion factor negative", from: "(4, 4),", to: "(4, 4), motion_factor: -1.0,", field: "hider.motion_factor", at: Some((4, 49)) },
    Case { name: "motion factor NaN", from: "(4, 4),", to: "(4, 4), motion_factor: NaN,", field: "hider.motion_factor", at: Some((4, 49)) },
    Case { name: "focus factor negative", from: "(4, 4),", to: "(4, 4), focus_factor: -0.5,", field: "hider.focus_factor", at: Some((4, 48)) },
    Case { name: "focus factor infinite", from: "(4, 4),", to: "(4, 4), focus_factor: inf,", field: "hider.focus_factor", at: Some((4, 48)) },
    Case { name: "max grid size 0", from: "(4, 4),", to: "(4, 4), max_grid_size: 0,", field: "hider.max_grid_size", at: Some((4, 49)) },
    // Added with the hardening of #20.
    Case { name: "jitter not a bool", from: "(4, 4),", to: "(4, 4), jitter: 1,", field: "hider.jitter", at: Some((4, 42)) },
    Case { name: "unknown spatial pattern", from: "(4, 4),", to: "(4, 4), pattern: Fig8,", field: "hider.pattern", at: Some((4, 43)) },
    Case { name: "unknown time pattern", from: "(4, 4),", to: "(4, 4), time_pattern: Fig16,", field: "hider.time_pattern", at: Some((4, 48)) },
    Case { name: "bucket size too large", from: "(4, 4),", to: "(4, 4), bucket_size: (16, 1025),", field: "hider.bucket_size[1]", at: Some((4, 52)) },
    Case { name: "shading rate NaN", from: "(4, 4),", to: "(4, 4), shading_rate: NaN,", field: "hider.shading_rate", at: Some((4, 48)) },
    Case { name: "shading rate infinite", from: "(4, 4),", to: "(4, 4), shading_rate: inf,", field: "hider.shading_rate", at: Some((4, 48)) },
    Case { name: "seed negative", from: "(4, 4),", to: "(4, 4), seed: -1,", field: "hider.seed", at: Some((4, 40)) },
    Case { name: "seed too large", from: "(4, 4),", to: "(4, 4), seed: 18446744073709551616,", field: "hider.seed", at: Some((4, 40)) },
    Case { name: "cull back faces not a bool", from: "(4, 4),", to: "(4, 4), cull_back_faces: 0,", field: "hider.cull_back_faces", at: Some((4, 51)) },
    Case { name: "unknown original switch", from: "(4, 4),", to: "(4, 4), original: (permute: true, zbuffer: true),", field: "hider.original.zbuffer", at: Some((4, 60)) },
    Case { name: "original switch not a bool", from: "(4, 4),", to: "(4, 4), original: (matte: 1),", field: "hider.original.matte", at: Some((4, 52)) },
    Case { name: "original without brackets", from: "(4, 4),", to: "(4, 4), original: true,", field: "hider.original", at: Some((4, 44)) },
    Case { name: "unknown field in the hider", from: "(4, 4),", to: "(4, 4), samples: 3,", field: "hider.samples", at: Some((4, 34)) },
    Case { name: "unknown field in the filter", from: "width: 2.0)", to: "width: 2.0, radius: 1.0)", field: "hider.filter.radius", at: Some((4, 71)) },
    Case { name: "filter without a kind", from: "kind: Gaussian, ", to: "", field: "hider.filter.kind", at: Some((4, 53)) },
    Case { name: "filter width NaN", from: "width: 2.0)", to: "width: NaN)", field: "hider.filter.width", at: Some((4, 66)) },
    Case { name: "pixel samples with 3 values", from: "(4, 4)", to: "(4, 4, 4)", field: "hider.pixel_samples[2]", at: Some((4, 33)) },
    Case { name: "narrow box filter", from: "kind: Gaussian, width: 2.0", to: "kind: Box, width: 0.1", field: "hider.filter", at: Some((4, 42)) },
    Case { name: "narrow gaussian filter", from: "kind: Gaussian, width: 2.0", to: "kind: Gaussian, width: 0.1", field: "hider.filter", at: Some((4, 42)) },
    Case { name: "sinc filter width NaN", from: "kind: Gaussian, width: 2.0", to: "kind: Sinc, width: NaN", field: "hider.filter.width", at: Some((4, 62)) },
    Case { name: "narrow bartlett filter", from: "kind: Gaussian, width: 2.0", to: "kind: Bartlett, width: 0.1", field: "hider.filter", at: Some((4, 42)) },
    Case { name: "bessel filter too wide", from: "kind: Gaussian, width: 2.0", to: "kind: Bessel, width: 16.5", field: "hider.filter.width", at: Some((4, 64)) },
    Case { name: "narrow RenderMan box filter", from: "kind: Gaussian, width: 2.0", to: "kind: RiBox, width: 1e-20", field: "hider.filter", at: Some((4, 42)) },
    Case { name: "narrow RenderMan triangle filter", from: "kind: Gaussian, width: 2.0", to: "kind: RiTriangle, width: 0.1", field: "hider.filter", at: Some((4, 42)) },
    Case { name: "narrow RenderMan catmull-rom filter", from: "kind: Gaussian, width: 2.0", to: "kind: RiCatmullRom, width: 0.1", field: "hider.filter", at: Some((4, 42)) },
    Case { name: "narrow RenderMan gaussian filter", from: "kind: Gaussian, width: 2.0", to: "kind: RiGaussian, width: 0.1", field: "hider.filter", at: Some((4, 42)) },
    Case { name: "narrow RenderMan sinc filter", from: "kind: Gaussian, width: 2.0", to: "kind: RiSinc, width: 0.1", field: "hider.filter", at: Some((4, 42)) },
    Case { name: "narrow RenderMan disk filter", from: "kind: Gaussian, width: 2.0", to: "kind: RiDisk, width: 0.1", field: "hider.filter", at: Some((4, 42)) },
    Case { name: "narrow RenderMan bessel filter", from: "kind: Gaussian, width: 2.0", to: "kind: RiBessel, width: 0.1", field: "hider.filter", at: Some((4, 42)) },
    Case { name: "narrow RenderMan mitchell filter", from: "kind: Gaussian, width: 2.0", to: "kind: RiMitchell, width: 0.1", field: "hider.filter", at: Some((4, 42)) },
    Case { name: "narrow RenderMan blackman-harris filter", from: "kind: Gaussian, width: 2.0", to: "kind: RiBlackmanHarris, width: 0.1", field: "hider.filter", at: Some((4, 42)) },
    Case { name: "filter narrow in y only", from: "width: 2.0)", to: "width: 2.0, height: Some(0.1))", field: "hider.filter", at: Some((4, 42)) },
    Case { name: "disk filter between the strata", from: "(4, 4), filter: (kind: Gaussian, width: 2.0)", to: "(2, 2), filter: (kind: RiDisk, width: 0.6)", field: "hider.filter", at: Some((4, 42)) },
    // Added with adaptive sampling (#14).
    Case { name: "adaptive level too deep", from: "(4, 4),", to: "(4, 4), adaptive: (max_level: 5),", field: "hider.adaptive.max_level", at: Some((4, 56)) },
    Case { name: "adaptive threshold negative", from: "(4, 4),", to: "(4, 4), adaptive: (threshold: -1.0),", field: "hider.adaptive.threshold", at: Some((4, 56)) },
    Case { name: "adaptive with the ray-tracing hider", from: "(4, 4),", to: "(4, 4), method: RayTrace, adaptive: (max_level: 1),", field: "hider.adaptive.max_level", at: Some((4, 74)) },
    Case { name: "unknown adaptive field", from: "(4, 4),", to: "(4, 4), adaptive: (levels: 2),", field: "hider.adaptive.levels", at: Some((4, 45)) },
    Case { name: "filter missed by the original stratum pairing", from: "(4, 4), filter: (kind: Gaussian, width: 2.0)", to: "(3, 4), filter: (kind: RiDisk, width: 0.2), original: (permute: true)", field: "hider.filter", at: Some((4, 42)) },
    // Added with occlusion culling (#13).
    Case { name: "occlusion cull not a bool", from: "(4, 4),", to: "(4, 4), occlusion_cull: 0,", field: "hider.occlusion_cull", at: Some((4, 50)) },
];

#[test]
fn catalogue() {
    insta::assert_snapshot!("catalogue", super::check(CASES));
}
