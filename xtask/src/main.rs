//! Project tasks: `cargo xtask golden` (compare every golden scene with its reference),
//! `cargo xtask bless` (rewrite the references; look at the PNGs it writes first!),
//! `cargo xtask bench` (time the benchmark scenes), `cargo xtask scaling` (peak memory of
//! `heavy-motion` as its sphere count grows) and `cargo xtask study` (regenerate the
//! sampling study's figures in docs/study/), `cargo xtask fuzz` (build the fuzzer with
//! coverage instrumentation and run it; see docs/reliability.md), `cargo xtask geometry`
//! (the coverage of small spheres against their radius, docs/geometry.md), `cargo xtask rate`
//! (micropolygon areas against the shading rate, docs/geometry.md).

mod bench;
mod compare;
mod fuzz;
mod models;
mod rate;
mod study;

use std::process::ExitCode;

use reyes_testkit::golden::{self, Outcome};

fn usage() -> ExitCode {
    eprintln!(
        "usage: cargo xtask <golden | bless [SCENE...] | bench [--runs N] [--threads T] [--baseline BIN] [SCENE...] | scaling [--threads T] [N...] | study [--quick] | geometry [--quick] | compare A B [--diff OUT.png] | fuzz [--execs N] [--renders N] [--targets ron,rib,render] [--seed S] [--save] [--time-limit SECS] | fuzz cmin | models [--bench] | rate [SCENE...]>"
    );
    ExitCode::from(2)
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let root = golden::workspace_root();
    if args.first().map(String::as_str) == Some("bench") {
        return match bench::run(&root, &args[1..]) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("xtask bench: {e}");
                ExitCode::FAILURE
            }
        };
    }
    if args.first().map(String::as_str) == Some("scaling") {
        return match bench::scaling(&root, &args[1..]) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("xtask scaling: {e}");
                ExitCode::FAILURE
            }
        };
    }
    if args.first().map(String::as_str) == Some("rate") {
        return match rate::run(&root, &args[1..]) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("xtask rate: {e}");
                ExitCode::FAILURE
            }
        };
    }
    if args.first().map(String::as_str) == Some("compare") {
        return match compare::run(&args[1..]) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("xtask compare: {e}");
                ExitCode::FAILURE
            }
        };
    }
    if args.first().map(String::as_str) == Some("fuzz") {
        return match fuzz::run(&root, &args[1..]) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("xtask fuzz: {e}");
                ExitCode::FAILURE
            }
        };
    }
    if args.first().map(String::as_str) == Some("textures") {
        // The texture maps of the look-development scenes, made by code (testkit/textures.rs).
        let dir = root.join("scenes/textures");
        let written = std::fs::create_dir_all(&dir).map_err(|e| e.to_string()).and_then(|()| {
            reyes_testkit::textures::scene_maps().into_iter().try_for_each(|(name, image)| {
                let path = dir.join(name);
                image.save(&path).map_err(|e| format!("{}: {e}", path.display()))?;
                println!("wrote {}", path.display());
                Ok(())
            })
        });
        return match written {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("xtask textures: {e}");
                ExitCode::FAILURE
            }
        };
    }
    if args.first().map(String::as_str) == Some("models") {
        return match models::run(&root, args.get(1).map(String::as_str) == Some("--bench")) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("xtask models: {e}");
                ExitCode::FAILURE
            }
        };
    }
    if args.first().map(String::as_str) == Some("geometry") {
        return match study::geometry::run(&root, &args[1..]) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("xtask geometry: {e}");
                ExitCode::FAILURE
            }
        };
    }
    if args.first().map(String::as_str) == Some("study") {
        return match study::run(&root, &args[1..]) {
            Ok(()) => ExitCode::SUCCESS,
            Err(e) => {
                eprintln!("xtask study: {e}");
                ExitCode::FAILURE
            }
        };
    }
    let cases = match golden::manifest(&root) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("xtask: {e}");
            return ExitCode::from(2);
        }
    };
    match args.first().map(String::as_str) {
        Some("golden") => {
            let mut failed = 0;
            for case in &cases {
                match golden::check(&root, case) {
                    Ok(Outcome::Pass(c)) => {
                        println!(
                            "pass {:<16} mean {:.2e} max {:.2e} (tolerance {:.2e} / {:.2e})",
                            case.name(),
                            c.mean.iter().cloned().fold(0.0, f32::max),
                            c.max.iter().cloned().fold(0.0, f32::max),
                            c.mean_tolerance,
                            c.max_tolerance
                        );
                        // A scene with AOVs: every layer against the reference's.
                        match golden::check_aovs(&root, case) {
                            Ok(f) if f.is_empty() => {}
                            Ok(f) => {
                                failed += 1;
                                for line in f {
                                    println!("FAIL {:<16} {line}", case.name());
                                }
                            }
                            Err(e) => {
                                failed += 1;
                                println!("ERROR {:<15} {e}", case.name());
                            }
                        }
                    }
                    Ok(Outcome::Fail(c, path)) => {
                        failed += 1;
                        println!(
                            "FAIL {:<16} mean {:?} max {:?} (tolerance {:.2e} / {:.2e}); wrote {}",
                            case.name(),
                            c.mean,
                            c.max,
                            c.mean_tolerance,
                            c.max_tolerance,
                            path.display()
                        );
                    }
                    Ok(Outcome::Missing(path)) => {
                        failed += 1;
                        println!("MISSING {:<13} no reference {}", case.name(), path.display());
                    }
                    Err(e) => {
                        failed += 1;
                        println!("ERROR {:<15} {e}", case.name());
                    }
                }
            }
            if failed > 0 { ExitCode::FAILURE } else { ExitCode::SUCCESS }
        }
        Some("bless") => {
            let only = &args[1..];
            for case in cases
                .iter()
                .filter(|c| only.is_empty() || only.contains(&c.scene) || only.contains(&c.name()))
            {
                match golden::bless(&root, case) {
                    Ok(png) => println!("blessed {} (look at {})", case.name(), png.display()),
                    Err(e) => {
                        eprintln!("xtask: {}: {e}", case.name());
                        return ExitCode::FAILURE;
                    }
                }
            }
            ExitCode::SUCCESS
        }
        _ => usage(),
    }
}
