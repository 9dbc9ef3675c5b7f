//! Every failure the fuzzer found, as a test: one input file per bug in
//! `crates/fuzz/regressions/`, named after the bug, with a comment at its top saying what it
//! did; one test per file here, named the same, replaying it through the target it failed
//! (`reyes-fuzz replay`, so that an abort or a hang fails the test instead of killing the test
//! process). A bug in code owned elsewhere and not fixed yet is `#[ignore]`d with its owner;
//! removing the `ignore` is part of the fix.

use std::path::Path;
use std::process::Command;

/// Replays `regressions/FILE` through `target`: it must load, render or be rejected cleanly,
/// a render within the fuzzer's limits (10 s of CPU, 2 GiB).
fn replay(target: &str, file: &str) {
    replay_with(target, file, &[]);
}

/// [`replay`] with other limits (`--timeout SECS`, `--memory MIB`).
fn replay_with(target: &str, file: &str, limits: &[&str]) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("regressions").join(file);
    assert!(path.is_file(), "{} is missing", path.display());
    let out = Command::new(env!("CARGO_BIN_EXE_reyes-fuzz"))
        .arg("replay")
        .arg(target)
        .args(limits)
        .arg(&path)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success() && !stdout.contains("FAILED"),
        "{file} still fails:\n{stdout}{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Every file in `regressions/` has its test here, named after it (`a-b.ron`: `fn a_b`).
#[test]
fn every_regression_file_has_its_test() {
    let source = include_str!("regression.rs");
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("regressions");
    for entry in std::fs::read_dir(&dir).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        let stem = name.split('.').next().unwrap().replace('-', "_");
        assert!(source.contains(&format!("fn {stem}()")), "regressions/{name} has no test");
        assert!(source.contains(&format!("\"{name}\"")), "no test replays regressions/{name}");
    }
}

#[test]
fn dice_split_endless_huge_patch_point() {
    replay("render", "dice-split-endless-huge-patch-point.ron");
}

#[test]
fn dice_fast_motion_memory() {
    replay("render", "dice-fast-motion-memory.rib");
}

#[test]
fn dice_csg_huge_operand_slow() {
    replay_with("render", "dice-csg-huge-operand-slow.ron", &["--timeout", "2"]);
}

#[test]
fn dice_dof_near_eye_slow() {
    replay_with("render", "dice-dof-near-eye-slow.rib", &["--timeout", "2"]);
}

#[test]
fn dice_split_endless_huge_moving_mesh_point() {
    replay("render", "dice-split-endless-huge-moving-mesh-point.ron");
}

#[test]
fn budget_tiny_fov_lens() {
    replay_with("render", "budget-tiny-fov-lens.ron", &["--timeout", "5"]);
}

#[test]
fn budget_huge_patch_point() {
    replay_with("render", "budget-huge-patch-point.rib", &["--timeout", "5"]);
}

#[test]
fn render_far_camera_slow() {
    replay_with("render", "render-far-camera-slow.rib", &["--timeout", "2"]);
}

#[test]
fn render_mesh_point_1e15_slow() {
    replay_with("render", "render-mesh-point-1e15-slow.ron", &["--timeout", "2"]);
}

#[test]
fn render_camera_swing_slow() {
    replay_with("render", "render-camera-swing-slow.ron", &["--timeout", "2"]);
}

#[test]
fn render_dof_huge_axis_slow() {
    replay_with("render", "render-dof-huge-axis-slow.rib", &["--timeout", "2"]);
}

#[test]
fn sl_no_shader_names_the_file() {
    replay("sl", "sl-no-shader-names-the-file.sl");
}

#[test]
fn sl_control_character_in_run_error() {
    replay("sl", "sl-control-character-in-run-error.sl");
}

#[test]
fn render_shrunk_lens_huge_floor_slow() {
    replay_with("render", "render-shrunk-lens-huge-floor-slow.ron", &["--timeout", "2"]);
}

#[test]
fn sl_nested_macro_blowup() {
    // The sl target runs in process, without the child's limits: the bound on time and
    // memory is the preprocessor's budget, tested in crates/sl/tests/preprocessor.rs.
    replay("sl", "sl-nested-macro-blowup.sl");
}
