//! The texture commands of `reyes-render texture`, in the manner of `txmake`:
//!
//! ```text
//! reyes-render texture make [OPTIONS] IN OUT        a prepared texture from a picture
//!     --wrap periodic|clamp|black  (both; --swrap, --twrap each)
//!     --filter NAME  --width W (both; --swidth, --twidth)
//!     --byte | --short | --half | --float           sample storage
//!     --latlong                                      a latitude-longitude environment map
//!     --shadow                                       a shadow map from a depth map
//! reyes-render texture make --cube PX NX PY NY PZ NZ OUT [--fov DEGREES]
//! reyes-render texture info FILE                    what a texture file holds
//! ```
//!
//! Exit codes are the renderer's: 0 success, 2 bad input (a file that is not a usable image,
//! a usage error), 1 a file that cannot be read or written. Every error is one line.

use std::fmt::Write as _;
use std::path::Path;

use crate::make::{MakeOptions, make_cube, make_latlong, make_shadow, make_texture};
use crate::prepared::{PreparedFile, SampleType, is_tiff, wrap_of};
use crate::write::{Depth, wrap_word};

const USAGE: &str = "usage: reyes-render texture make [--wrap W] [--filter F] [--width W] \
                     [--byte|--short|--half|--float] [--latlong|--shadow] IN OUT | \
                     reyes-render texture make --cube PX NX PY NY PZ NZ OUT [--fov D] | \
                     reyes-render texture info FILE";

/// Runs `texture ARGS...` (the arguments after `texture`): standard output, the lines for
/// standard error, and the exit code.
pub fn run(args: &[String]) -> (String, Vec<String>, u8) {
    match args.first().map(String::as_str) {
        Some("make") => make(&args[1..]),
        Some("info") => match &args[1..] {
            [file] => info(Path::new(file)),
            _ => usage("info: give one file"),
        },
        Some("-h" | "--help") => (format!("{USAGE}\n"), Vec::new(), 0),
        Some(other) => usage(&format!("unknown texture command {other:?}")),
        None => usage("no texture command"),
    }
}

fn usage(what: &str) -> (String, Vec<String>, u8) {
    (String::new(), vec![format!("error: {what} ({USAGE})")], 2)
}

fn make(args: &[String]) -> (String, Vec<String>, u8) {
    let mut opts = MakeOptions::default();
    let (mut latlong, mut shadow, mut cube) = (false, false, false);
    let mut files = Vec::new();
    let mut it = args.iter();
    while let Some(a) = it.next() {
        let mut value = |name: &str| it.next().cloned().ok_or(format!("{name} needs a value"));
        let r: Result<(), String> = (|| {
            match a.as_str() {
                "--wrap" | "--swrap" | "--twrap" => {
                    let v = value(a)?;
                    let w = wrap_of(&v).ok_or(format!("unknown wrap mode {v:?}"))?;
                    if a != "--twrap" {
                        opts.wrap[0] = w;
                    }
                    if a != "--swrap" {
                        opts.wrap[1] = w;
                    }
                }
                "--filter" => opts.filter = value(a)?,
                "--width" | "--swidth" | "--twidth" => {
                    let v = value(a)?;
                    let w: f32 = v.parse().map_err(|_| format!("{a}: {v:?} is not a number"))?;
                    if a != "--twidth" {
                        opts.width[0] = w;
                    }
                    if a != "--swidth" {
                        opts.width[1] = w;
                    }
                }
                "--fov" => {
                    let v = value(a)?;
                    opts.fov = v.parse().map_err(|_| format!("--fov: {v:?} is not a number"))?;
                }
                "--byte" => opts.depth = Some(Depth::Byte),
                "--short" => opts.depth = Some(Depth::Short),
                "--half" => opts.depth = Some(Depth::Half),
                "--float" => opts.depth = Some(Depth::Float),
                "--latlong" => latlong = true,
                "--shadow" => shadow = true,
                "--cube" => cube = true,
                _ if a.starts_with('-') && a.len() > 1 => {
                    return Err(format!("unknown option {a}"));
                }
                _ => files.push(a.clone()),
            }
            Ok(())
        })();
        if let Err(e) = r {
            return usage(&e);
        }
    }
    let result = match (cube, latlong, shadow, files.as_slice()) {
        (true, false, false, [px, nx, py, ny, pz, nz, out]) => {
            let faces = [px, nx, py, ny, pz, nz].map(|f| Path::new(f.as_str()));
            make_cube(faces, Path::new(out), &opts)
        }
        (true, ..) => {
            return usage("make --cube takes six faces and the output, and no other kind");
        }
        (false, true, true, _) => return usage("make: --latlong or --shadow, not both"),
        (false, l, s, [src, out]) => {
            let (src, out) = (Path::new(src), Path::new(out));
            if s {
                make_shadow(src, out)
            } else if l {
                make_latlong(src, out, &opts)
            } else {
                make_texture(src, out, &opts)
            }
        }
        _ => return usage("make: give the input and the output file"),
    };
    match result {
        Ok(()) => (String::new(), Vec::new(), 0),
        Err(e) => (String::new(), vec![format!("error: {e}")], e.exit_code()),
    }
}

/// What `file` holds, as `texture info` prints it.
///
/// # Errors
///
/// The file cannot be read (exit 1) or is not a TIFF texture (exit 2): the one-line error.
pub fn describe(file: &Path) -> Result<String, crate::TextureError> {
    let mut head = [0u8; 4];
    let n = std::fs::File::open(file)
        .and_then(|mut f| std::io::Read::read(&mut f, &mut head))
        .map_err(|source| crate::TextureError::Io { file: file.to_path_buf(), source })?;
    if !is_tiff(&head[..n]) {
        let image = crate::load::decode(file, crate::ColorSpace::Linear)?;
        return Ok(format!(
            "{}: picture (not prepared), {} x {}, RGBA float after decoding\n",
            file.display(),
            image.width,
            image.height
        ));
    }
    let p = PreparedFile::open(file)?;
    let h = &p.header;
    let mut s = String::new();
    let sample = match h.sample {
        SampleType::Uint(b) => format!("{b}-bit unsigned"),
        SampleType::Int(b) => format!("{b}-bit signed"),
        SampleType::Float(b) => format!("{b}-bit float"),
    };
    let _ = writeln!(s, "{}", file.display());
    let format = if h.format.is_empty() { "(none)" } else { h.format.as_str() };
    let _ = writeln!(s, "  texture format: {format} ({:?})", h.kind);
    let _ = writeln!(s, "  channels: {}, {sample}", h.channels);
    let wrap = match h.wrap {
        Some([a, b]) => format!("{} {}", wrap_word(a), wrap_word(b)),
        None => format!("(not given: {:?})", h.wrap_text),
    };
    let _ = writeln!(s, "  wrap: {wrap}");
    let l0 = h.levels[0];
    let chunk = if l0.tiled { "tiles" } else { "strips" };
    let _ = writeln!(s, "  {chunk}: {} x {}", l0.chunk_w, l0.chunk_h);
    let sizes: Vec<String> = h.levels.iter().map(|l| format!("{}x{}", l.width, l.height)).collect();
    let _ = writeln!(
        s,
        "  levels ({} of {} directories): {}",
        h.levels.len(),
        h.directories,
        sizes.join(" ")
    );
    if let Some(f) = h.fov_cot {
        let _ = writeln!(s, "  field of view: {} degrees", 2.0 * (1.0 / f).atan().to_degrees());
    }
    for (name, m) in
        [("world to screen", h.world_to_screen), ("world to camera", h.world_to_camera)]
    {
        if let Some(m) = m {
            let rows: Vec<String> = m
                .chunks(4)
                .map(|r| r.iter().map(|v| format!("{v}")).collect::<Vec<_>>().join(" "))
                .collect();
            let _ = writeln!(s, "  {name}: [{}]", rows.join(" | "));
        }
    }
    Ok(s)
}

fn info(file: &Path) -> (String, Vec<String>, u8) {
    match describe(file) {
        Ok(s) => (s, Vec::new(), 0),
        Err(e) => (String::new(), vec![format!("error: {e}")], e.exit_code()),
    }
}
