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
    Case { name: "max grid size 0", from: "(4, 4),", to: "(4, 4), max_grid_size: 0,", field: "hider.max_grid_size", at: Some((4, 49)) },
];

#[test]
fn catalogue() {
    insta::assert_snapshot!("catalogue", super::check(CASES));
}
