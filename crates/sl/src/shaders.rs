//! The Specification's standard shaders, written for this project from its formulas, embedded.

/// Name and source of every standard shader.
pub const STANDARD: &[(&str, &str)] = &[
    ("constant", include_str!("../shaders/constant.sl")),
    ("matte", include_str!("../shaders/matte.sl")),
    ("metal", include_str!("../shaders/metal.sl")),
    ("shinymetal", include_str!("../shaders/shinymetal.sl")),
    ("plastic", include_str!("../shaders/plastic.sl")),
    ("paintedplastic", include_str!("../shaders/paintedplastic.sl")),
    ("ambientlight", include_str!("../shaders/ambientlight.sl")),
    ("distantlight", include_str!("../shaders/distantlight.sl")),
    ("pointlight", include_str!("../shaders/pointlight.sl")),
    ("spotlight", include_str!("../shaders/spotlight.sl")),
    ("bumpy", include_str!("../shaders/bumpy.sl")),
    ("depthcue", include_str!("../shaders/depthcue.sl")),
    ("fog", include_str!("../shaders/fog.sl")),
    ("background", include_str!("../shaders/background.sl")),
    ("clamptoalpha", include_str!("../shaders/clamptoalpha.sl")),
];

/// The source of standard shader `name`.
pub fn standard(name: &str) -> Option<&'static str> {
    STANDARD.iter().find(|(n, _)| *n == name).map(|(_, s)| *s)
}
