//! The lights of every kind: ambient, distant, point, spot (area lights are in the ray-tracing catalogue, trace_errors.rs).

use super::Case;

#[rustfmt::skip]
pub(crate) const CASES: &[Case] = &[
    Case { name: "NaN light intensity", from: "intensity: 0.1", to: "intensity: NaN", field: "lights[0].intensity", at: Some((5, 31)) },
    Case { name: "negative light intensity", from: "intensity: 0.1", to: "intensity: -0.1", field: "lights[0].intensity", at: Some((5, 31)) },
    Case { name: "negative light colour", from: "Ambient(intensity: 0.1)", to: "Ambient(color: (1.0, -1.0, 1.0))", field: "lights[0].color[1]", at: Some((5, 33)) },
    Case { name: "distant light from equals to", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Distant(from: (1.0, 1.0, -1.0), to: (1.0, 1.0, -1.0))", field: "lights[1].to", at: Some((5, 73)) },
    Case { name: "distant light at the default target", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Distant(from: (0.0, 0.0, 0.0))", field: "lights[1].to", at: Some((5, 37)) },
    Case { name: "spot at its target", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Spot(from: (1.0, 1.0, -1.0), to: (1.0, 1.0, -1.0))", field: "lights[1].to", at: Some((5, 70)) },
    Case { name: "spot without to", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Spot(from: (1.0, 1.0, -1.0))", field: "lights[1].to", at: Some((5, 64)) },
    Case { name: "spot NaN to", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Spot(from: (1.0, 1.0, -1.0), to: (0.0, NaN, 0.0))", field: "lights[1].to[1]", at: Some((5, 76)) },
    Case { name: "spot negative intensity", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Spot(from: (1.0, 1.0, -1.0), to: (0.0, 0.0, 0.0), intensity: -2.0)", field: "lights[1].intensity", at: Some((5, 98)) },
    Case { name: "spot cone angle 0", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Spot(from: (1.0, 1.0, -1.0), to: (0.0, 0.0, 0.0), cone_angle: 0.0)", field: "lights[1].cone_angle", at: Some((5, 99)) },
    Case { name: "spot cone angle above 180", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Spot(from: (1.0, 1.0, -1.0), to: (0.0, 0.0, 0.0), cone_angle: 190.0)", field: "lights[1].cone_angle", at: Some((5, 99)) },
    Case { name: "spot cone delta negative", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Spot(from: (1.0, 1.0, -1.0), to: (0.0, 0.0, 0.0), cone_delta: -1.0)", field: "lights[1].cone_delta", at: Some((5, 99)) },
    Case { name: "spot cone delta above the cone angle", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Spot(from: (1.0, 1.0, -1.0), to: (0.0, 0.0, 0.0), cone_angle: 10.0, cone_delta: 12.0)", field: "lights[1].cone_delta", at: Some((5, 117)) },
    Case { name: "spot beam distribution negative", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Spot(from: (1.0, 1.0, -1.0), to: (0.0, 0.0, 0.0), beam_distribution: -1.0)", field: "lights[1].beam_distribution", at: Some((5, 106)) },
    // Added with the hardening of #20.
    Case { name: "point light NaN from", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Point(from: (1.0, NaN, -1.0))", field: "lights[1].from[1]", at: Some((5, 55)) },
    Case { name: "point light negative intensity", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Point(from: (1.0, 1.0, -1.0), intensity: -1.0)", field: "lights[1].intensity", at: Some((5, 78)) },
    Case { name: "point light without from", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Point(intensity: 1.0)", field: "lights[1].from", at: Some((5, 57)) },
    Case { name: "point light infinite colour", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Point(from: (1.0, 1.0, -1.0), color: (inf, 1.0, 1.0))", field: "lights[1].color[0]", at: Some((5, 75)) },
    Case { name: "point light shadows not a bool", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Point(from: (1.0, 1.0, -1.0), shadows: \"yes\")", field: "lights[1].shadows", at: Some((5, 76)) },
    Case { name: "distant light NaN to", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Distant(from: (1.0, 1.0, -1.0), to: (0.0, NaN, 0.0))", field: "lights[1].to[1]", at: Some((5, 79)) },
    Case { name: "distant light infinite intensity", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Distant(from: (1.0, 1.0, -1.0), intensity: inf)", field: "lights[1].intensity", at: Some((5, 80)) },
    Case { name: "distant light without from", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Distant(to: (1.0, 1.0, -1.0))", field: "lights[1].from", at: Some((5, 65)) },
    Case { name: "ambient light unknown field", from: "Ambient(intensity: 0.1)", to: "Ambient(intensity: 0.1, from: (0.0, 0.0, 0.0))", field: "lights[0].from", at: Some((5, 36)) },
    Case { name: "ambient light NaN colour", from: "Ambient(intensity: 0.1)", to: "Ambient(color: (1.0, 1.0, NaN))", field: "lights[0].color[2]", at: Some((5, 38)) },
    Case { name: "unknown light kind", from: "Ambient(intensity: 0.1)", to: "Sun(intensity: 0.1)", field: "lights[0]", at: Some((5, 12)) },
    Case { name: "spot cone angle NaN", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Spot(from: (1.0, 1.0, -1.0), to: (0.0, 0.0, 0.0), cone_angle: NaN)", field: "lights[1].cone_angle", at: Some((5, 99)) },
    Case { name: "spot beam distribution infinite", from: "Distant(from: (1.0, 1.0, -1.0))", to: "Spot(from: (1.0, 1.0, -1.0), to: (0.0, 0.0, 0.0), beam_distribution: inf)", field: "lights[1].beam_distribution", at: Some((5, 106)) },
];

#[test]
fn catalogue() {
    insta::assert_snapshot!("catalogue", super::check(CASES));
}
