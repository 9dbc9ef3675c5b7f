//! `reyes-render measure`: the report through the binary, determinism in the seed, and its
//! usage and scene errors (one line, exit codes).

use std::f64::consts::PI;
use std::process::{Command, Output};

use reyes_testkit::fixtures::measure_scene as scene_text;

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_reyes-render"))
}

/// `value ± error` pairs of one report line, after its label.
fn numbers(out: &str, label: &str) -> Vec<(f64, f64)> {
    let line = out.lines().find(|l| l.starts_with(label)).unwrap_or_else(|| panic!("{out}"));
    let text = line[label.len()..].replace(['(', ')', ','], " ");
    let words: Vec<&str> = text.split_whitespace().collect();
    words
        .split(|w| *w == "±")
        .collect::<Vec<_>>()
        .windows(2)
        .map(|w| (w[0].last().unwrap().parse().unwrap(), w[1][0].parse().unwrap()))
        .collect()
}

#[test]
fn sphere_through_the_binary() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("ball.ron");
    let text = scene_text(
        &["name: \"ball\", shape: Sphere(radius: 1.5), transform: [Translate((1.0, 2.0, 3.0))]"],
        "",
    );
    std::fs::write(&path, text).unwrap();
    let o = bin().args(["measure", path.to_str().unwrap(), "--object", "ball"]).output().unwrap();
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    eprintln!("{out}");
    assert!(out.contains("100 x 100 x 100 strata"), "{out}");
    assert!(out.contains("seed 7"), "the scene's seed by default: {out}");
    let volume = 4.0 / 3.0 * PI * 1.5f64.powi(3);
    let [(v, e)] = numbers(&out, "volume")[..] else { panic!("{out}") };
    assert!((v - volume).abs() <= 3.0 * e && e > 0.0 && e < 0.01, "{v} ± {e} vs {volume}");
    let centre = numbers(&out, "centre");
    assert_eq!(centre.len(), 3, "{out}");
    for (a, ((c, e), want)) in centre.iter().zip([1.0, 2.0, 3.0]).enumerate() {
        assert!((c - want).abs() <= 3.0 * e && *e > 0.0, "axis {a}: {c} ± {e} vs {want}");
    }

    // Deterministic in the seed; another seed gives another estimate.
    let again = bin().args(["measure", path.to_str().unwrap(), "--object", "ball"]).output();
    assert_eq!(again.unwrap().stdout, o.stdout);
    let other = bin()
        .args(["measure", path.to_str().unwrap(), "--object", "ball", "--seed", "8"])
        .output()
        .unwrap();
    assert!(other.status.success());
    assert_ne!(other.stdout, o.stdout);
}

fn one_line_error(o: &Output, code: i32, needle: &str) {
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(code), "{err}");
    assert!(o.stdout.is_empty(), "{}", String::from_utf8_lossy(&o.stdout));
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("reyes-render: error: "), "{err}");
    assert!(err.contains(needle), "{err} lacks {needle}");
}

#[test]
fn usage_errors_exit_2_with_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("scene.ron");
    let open_mesh = "name: \"open\", shape: Mesh(points: [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), \
                     (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)], faces: [[0, 2, 1], [0, 1, 3], [1, 2, 3]])";
    let text = scene_text(
        &[
            "name: \"ball\", shape: Sphere(radius: 1.0)",
            "name: \"lid\", shape: Disk(radius: 1.0)",
            "name: \"cut\", shape: Sphere(radius: 1.0, zmax: Some(0.5))",
            "name: \"half\", shape: Cylinder(radius: 1.0, zmin: 0.0, zmax: 1.0, thetamax: 180.0)",
            "name: \"patch\", shape: BilinearPatch(points: ((0.0, 0.0, 0.0), (1.0, 0.0, 0.0), \
             (0.0, 1.0, 0.0), (1.0, 1.0, 0.0)))",
            open_mesh,
        ],
        "",
    );
    std::fs::write(&path, text).unwrap();
    let scene = path.to_str().unwrap();
    let measure = |args: &[&str]| bin().arg("measure").arg(scene).args(args).output().unwrap();

    let o = measure(&["--object", "x"]);
    one_line_error(&o, 2, "--object: no object or solid named \"x\" in ");
    assert!(String::from_utf8_lossy(&o.stderr).contains("scene.ron"));
    for (name, why) in [
        ("lid", "(Disk)"),
        ("cut", "(Sphere cut at zmax 0.5)"),
        ("half", "(Cylinder with thetamax 180)"),
        ("patch", "(BilinearPatch)"),
        ("open", "belongs to no other face"),
    ] {
        let o = measure(&["--object", name]);
        one_line_error(&o, 2, &format!("--object: object \"{name}\" is not closed "));
        one_line_error(&o, 2, why);
    }
    one_line_error(&measure(&["--object", "ball", "--samples", "0"]), 2, "--samples: ");

    // Scene errors as the render command reports them.
    let bad = dir.path().join("bad.ron");
    std::fs::write(&bad, "Scene(image: (width: 0, height: 1))").unwrap();
    let o = bin().args(["measure", bad.to_str().unwrap(), "--object", "ball"]).output().unwrap();
    one_line_error(&o, 2, "bad.ron");
    let missing = dir.path().join("missing.ron");
    let o =
        bin().args(["measure", missing.to_str().unwrap(), "--object", "ball"]).output().unwrap();
    one_line_error(&o, 1, "cannot read the scene file");

    // The render command is unchanged, and its help mentions `measure`.
    let o = bin().arg("--help").output().unwrap();
    assert!(String::from_utf8_lossy(&o.stdout).contains("reyes-render measure SCENE --object"));
    let o = bin().args(["measure", "--help"]).output().unwrap();
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stdout).contains("Usage: reyes-render measure"));
}

/// A RIB scene is measured like its RON twin: a sphere named by `Attribute "identifier"`, moved
/// by `Translate`; its volume within three standard errors of the exact one. A RIB file of two
/// frames is refused in one line.
#[test]
fn a_rib_scene_is_measured_too() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("ball.rib");
    std::fs::write(
        &path,
        "Projection \"perspective\"\nWorldBegin\nAttributeBegin\n\
         Attribute \"identifier\" \"name\" [\"ball\"]\nTranslate 1 2 3\nSphere 1.5 -1.5 1.5 360\n\
         AttributeEnd\nWorldEnd\n",
    )
    .unwrap();
    let o = bin().args(["measure", path.to_str().unwrap(), "--object", "ball"]).output().unwrap();
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let volume = 4.0 / 3.0 * PI * 1.5f64.powi(3);
    let [(v, e)] = numbers(&out, "volume")[..] else { panic!("{out}") };
    assert!((v - volume).abs() <= 3.0 * e && e > 0.0, "{v} ± {e} vs {volume}");

    let two = dir.path().join("two.rib");
    std::fs::write(&two, "FrameBegin 1\nWorldBegin\nSphere 1 -1 1 360\nWorldEnd\nFrameEnd\nFrameBegin 2\nWorldBegin\nSphere 1 -1 1 360\nWorldEnd\nFrameEnd\n").unwrap();
    let o = bin().args(["measure", two.to_str().unwrap(), "--object", "ball"]).output().unwrap();
    one_line_error(&o, 2, "the file has 2 frames; this command reads a file of one frame");
}
