//! Public shaders (not in this repository): set SL_SHADERS to folders of `.sl` files (separated
//! by ':'); every `.sl` file under them is compiled, with each file's folder and an `include`
//! folder beside it on the include path (files under an `include` folder are headers and
//! are not compiled alone), and the failures are listed. Without SL_SHADERS this
//! test does nothing. SL_SHADERS_STRICT=1 makes any failure fail the test.

use std::path::{Path, PathBuf};

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

#[test]
fn public_shaders_compile() {
    let Ok(dirs) = std::env::var("SL_SHADERS") else { return };
    let mut files = Vec::new();
    let mut includes = Vec::new();
    for d in dirs.split(':').filter(|d| !d.is_empty()) {
        walk(Path::new(d), &mut files);
        for sub in ["include", "shaders/include"] {
            let p = Path::new(d).join(sub);
            if p.is_dir() {
                includes.push(p);
            }
        }
    }
    let mut failed = Vec::new();
    for f in &files {
        match reyes_sl::compile_file(f, &includes) {
            Ok(_) => {}
            Err(e) => failed.push(e.to_string()),
        }
    }
    println!("{} of {} compile", files.len() - failed.len(), files.len());
    for f in &failed {
        println!("FAIL {f}");
    }
    if std::env::var("SL_SHADERS_STRICT").is_ok_and(|v| v == "1") {
        assert!(failed.is_empty());
    }
}
