//! `reyes-render shader check|info` (reyes_sl::tool) end to end: what each prints, where, and
//! with which exit code.

use std::process::{Command, Output};

fn run_in(dir: &std::path::Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_reyes-render"))
        .current_dir(dir)
        .args(args)
        .output()
        .expect("run reyes-render")
}

#[test]
fn check_reports_each_file_and_fails_on_a_bad_one() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("ok.sl"), "surface ok(float Kd = 1) { Ci = Kd * Cs; }\n")
        .unwrap();
    std::fs::write(dir.path().join("bad.sl"), "surface bad() {\n  Ci = 1 +;\n}\n").unwrap();
    let o = run_in(dir.path(), &["shader", "check", "ok.sl"]);
    assert_eq!(o.status.code(), Some(0));
    assert_eq!(String::from_utf8_lossy(&o.stdout), "ok.sl: ok: surface \"ok\", 1 parameter\n");
    assert!(o.stderr.is_empty());
    let o = run_in(dir.path(), &["shader", "check", "ok.sl", "bad.sl"]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("reyes-render: error: bad.sl:2:"), "{err}");
    let o = run_in(dir.path(), &["shader", "check", "missing.sl"]);
    assert_eq!(o.status.code(), Some(1));
    let o = run_in(dir.path(), &["shader"]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn info_prints_the_parameters_of_a_builtin_and_of_a_file() {
    let dir = tempfile::tempdir().unwrap();
    let o = run_in(dir.path(), &["shader", "info", "matte"]);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(
        String::from_utf8_lossy(&o.stdout),
        "surface \"matte\"\n    \"Ka\" \"uniform float\"\n        default 1\n    \"Kd\" \"uniform float\"\n        default 1\n"
    );
    std::fs::write(
        dir.path().join("glow.sl"),
        "surface glow(color tint = color(1, 0.5, 0)) { Ci = tint; }\n",
    )
    .unwrap();
    let o = run_in(dir.path(), &["shader", "info", "glow"]);
    assert_eq!(
        String::from_utf8_lossy(&o.stdout),
        "surface \"glow\"\n    \"tint\" \"uniform color\"\n        default [1 0.5 0]\n"
    );
}
