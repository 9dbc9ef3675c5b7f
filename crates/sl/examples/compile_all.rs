//! Compiles every `.sl` file under the folders named on the command line (public shaders,
//! which are not in this repository; docs/shading.md, "Public shaders"), with each folder's
//! `include` (or `shaders/include`) folder on the include path; files under an `include`
//! folder are headers and are not compiled alone. Prints how many compile and each failure;
//! exits 1 if any fails, 2 without a folder.
//!
//! `cargo run --release -p reyes-sl --example compile_all -- /tmp/shaders/shaders`

use std::path::{Path, PathBuf};
use std::process::ExitCode;

fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(rd) = std::fs::read_dir(dir) else { return };
    let mut entries: Vec<PathBuf> = rd.flatten().map(|e| e.path()).collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            walk(&p, out);
        } else if p.extension().is_some_and(|e| e == "sl")
            && !p.components().any(|c| c.as_os_str() == "include")
        {
            out.push(p);
        }
    }
}

fn main() -> ExitCode {
    let dirs: Vec<PathBuf> = std::env::args_os().skip(1).map(PathBuf::from).collect();
    if dirs.is_empty() {
        eprintln!("usage: compile_all FOLDER...");
        return ExitCode::from(2);
    }
    let mut files = Vec::new();
    let mut includes = Vec::new();
    for d in &dirs {
        walk(d, &mut files);
        for sub in ["include", "shaders/include"] {
            let p = d.join(sub);
            if p.is_dir() {
                includes.push(p);
            }
        }
    }
    let failed: Vec<String> = files
        .iter()
        .filter_map(|f| reyes_sl::compile_file(f, &includes).err().map(|e| e.to_string()))
        .collect();
    println!("{} of {} compile", files.len() - failed.len(), files.len());
    for f in &failed {
        println!("FAIL {f}");
    }
    if failed.is_empty() { ExitCode::SUCCESS } else { ExitCode::from(1) }
}
