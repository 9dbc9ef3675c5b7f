//! The filter's y width and the RenderMan kernels in the scene model: absent `height` keeps
//! every existing scene's meaning, a given one reads back, and every `Ri` kind knows its
//! RenderMan name.

use std::path::Path;

use reyes_scene::{Filter, FilterKind, Scene, parse};

fn ok(hider: &str) -> Scene {
    let text = format!(
        "Scene(image: (width: 8, height: 6),
               camera: (eye: (0.0, 0.0, -5.0), look_at: (0.0, 0.0, 0.0)), hider: {hider})"
    );
    parse(&text, Path::new("filter.ron")).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_filter_without_height_is_as_tall_as_it_is_wide() {
    let f = ok("(filter: (kind: Gaussian, width: 2.0))").hider.filter;
    assert_eq!(f, Filter::new(FilterKind::Gaussian, 2.0));
    assert_eq!(f.height, None);
    assert_eq!(f.y_width(), 2.0);
    assert_eq!(f.max_width(), 2.0);
    assert_eq!(Filter::default(), f, "the default is Appendix A's Gaussian of width 2");
}

#[test]
fn a_filter_with_height_keeps_both_widths() {
    let f = ok("(filter: (kind: RiGaussian, width: 4.0, height: Some(1.0)))").hider.filter;
    assert_eq!(f, Filter { kind: FilterKind::RiGaussian, width: 4.0, height: Some(1.0) });
    assert_eq!((f.width, f.y_width(), f.max_width()), (4.0, 1.0, 4.0));
    let tall = ok("(filter: (kind: RiBox, width: 1.0, height: Some(3.0)))").hider.filter;
    assert_eq!(tall.max_width(), 3.0);
}

#[test]
fn filters_read_back_from_what_ron_writes() {
    for hider in [
        "(filter: (kind: Sinc, width: 3.0))",
        "(filter: (kind: RiCatmullRom, width: 4.0, height: Some(3.0)))",
    ] {
        let scene = ok(hider);
        let text = ron::ser::to_string(&scene).unwrap_or_else(|e| panic!("{e}"));
        // An absent height stays absent, so old scenes are written as they were.
        assert_eq!(text.contains("height:Some"), scene.hider.filter.height.is_some(), "{text}");
        assert_eq!(parse(&text, Path::new("back.ron")).unwrap_or_else(|e| panic!("{e}")), scene);
    }
}

#[test]
fn every_renderman_kind_parses_and_names_itself() {
    let renderman: Vec<FilterKind> =
        FilterKind::ALL.into_iter().filter(|k| k.is_renderman()).collect();
    assert_eq!(renderman.len(), 9);
    for kind in FilterKind::ALL {
        let scene = ok(&format!("(filter: (kind: {kind:?}, width: 2.0, height: Some(3.0)))"));
        assert_eq!(scene.hider.filter.kind, kind);
        match kind.renderman_name() {
            Some(name) => {
                assert_eq!(FilterKind::from_renderman_name(name), Some(kind));
                assert_eq!(FilterKind::from_renderman_name(&name.to_uppercase()), Some(kind));
                assert!(format!("{kind:?}").starts_with("Ri"), "{kind:?}");
            }
            None => assert!(!format!("{kind:?}").starts_with("Ri"), "{kind:?}"),
        }
    }
    assert_eq!(FilterKind::from_renderman_name("catmull-rom"), Some(FilterKind::RiCatmullRom));
    assert_eq!(FilterKind::from_renderman_name("lanczos"), None);
    assert_eq!(FilterKind::from_renderman_name("separable-catmull-rom"), None);
}
