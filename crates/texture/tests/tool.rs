//! `reyes-render texture make|info` (issue #32), through the library function the CLI calls:
//! what it writes, what it prints, and its exit codes (0; 2 bad input or usage; 1 I/O).

use reyes_texture::Wrap;
use reyes_texture::prepared::{MapKind, PreparedFile, SampleType};
use reyes_texture::tool::run;

fn ok<T, E: std::fmt::Display>(r: Result<T, E>) -> T {
    r.unwrap_or_else(|e| panic!("{e}"))
}

fn args(a: &[&str]) -> Vec<String> {
    a.iter().map(|s| s.to_string()).collect()
}

#[test]
fn make_and_info_write_and_describe_prepared_maps() {
    let dir = ok(tempfile::tempdir());
    let src = dir.path().join("pic.png");
    ok(image::RgbImage::from_fn(20, 12, |x, y| image::Rgb([x as u8 * 10, y as u8 * 20, 7]))
        .save(&src));
    let (s, out) = (src.to_string_lossy().into_owned(), dir.path().join("pic.tex"));
    let o = out.to_string_lossy().into_owned();
    let (stdout, errors, code) =
        run(&args(&["make", "--swrap", "clamp", "--twrap", "black", "--half", &s, &o]));
    assert_eq!((stdout.as_str(), errors.len(), code), ("", 0, 0), "{errors:?}");
    let p = ok(PreparedFile::open(&out));
    assert_eq!(p.header.wrap, Some([Wrap::Clamp, Wrap::Black]));
    assert_eq!((p.header.sample, p.header.channels), (SampleType::Float(16), 3));
    let sizes: Vec<(u32, u32)> = p.header.levels.iter().map(|l| (l.width, l.height)).collect();
    assert_eq!(sizes, [(20, 12), (10, 6), (5, 3), (3, 2), (2, 1), (1, 1)]);
    let (stdout, _, code) = run(&args(&["info", &o]));
    assert_eq!(code, 0);
    for line in [
        "texture format: Plain Texture",
        "channels: 3, 16-bit float",
        "wrap: clamp black",
        "tiles: 32 x 32",
        "20x12 10x6 5x3 3x2 2x1 1x1",
    ] {
        assert!(stdout.contains(line), "{line:?} not in {stdout}");
    }
    let env = dir.path().join("pic.env").to_string_lossy().into_owned();
    assert_eq!(run(&args(&["make", "--latlong", &s, &env])).2, 0);
    assert_eq!(ok(PreparedFile::open(std::path::Path::new(&env))).header.kind, MapKind::LatLong);
    // Usage errors, bad input, I/O: one line each, exit 2, 2, 1.
    for (a, want) in [
        (vec!["make", &s], 2),
        (vec!["make", "--wrap", "sideways", &s, &o], 2),
        (vec!["make", "--filter", "fuzzy", &s, &o], 2),
        (vec!["frobnicate"], 2),
        (vec!["info", "/no/such/file.tex"], 1),
        (vec!["make", "/no/such/pic.png", &o], 1),
    ] {
        let (_, errors, code) = run(&args(&a));
        assert_eq!(code, want, "{a:?}: {errors:?}");
        assert!(errors.len() == 1 && !errors[0].contains('\n'), "{a:?}: {errors:?}");
    }
    let junk = dir.path().join("junk.tex");
    ok(std::fs::write(&junk, b"MM\0*not a tiff at all"));
    let (_, errors, code) = run(&args(&["info", &junk.to_string_lossy()]));
    assert_eq!(code, 2, "{errors:?}");
}
