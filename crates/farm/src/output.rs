//! Where a frame's images go and how they are written: the output path with the frame
//! number put in, the extra outputs of RIB's `+` `Display` lines beside it, the checks made
//! before any work is done, and the frame's file written as the scene asks.
//!
//! Invariants: names depend only on the output path, the frame number and whether the file
//! has several frames, so a frame renders to the same name whichever frames are chosen. A
//! whole render and a merge write through the same [`FramePicture::write`], so their files
//! agree byte for byte. Files are written atomically ([`reyes_film`]): a directory made for
//! an output is made only when its file is about to be written, never for a render that
//! fails, and never holds a partial file.

use std::borrow::Cow;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use reyes_film::{AovFilm, AovLayer, EarlyBlocks, Film, FilmError, WriteOptions};
use reyes_render::BucketResult;
use reyes_scene::Scene;

use crate::{FarmError, one_line};

/// The output path of frame `number`: a run of `#` (`out.####.exr`) or a `%0Nd`
/// (`out.%04d.exr`) takes the number (1 for a file without `FrameBegin`), zero-padded to
/// the run's length or N; otherwise, when `numbered` (the file has several frames), `.NNNN`
/// is inserted before the extension.
pub fn frame_path(output: &Path, number: Option<i32>, numbered: bool) -> PathBuf {
    let n = number.unwrap_or(1);
    let name = output.file_name().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let with = |name: String| output.with_file_name(name);
    if let Some(start) = name.find('#') {
        let len = name[start..].chars().take_while(|&c| c == '#').count();
        return with(format!("{}{:0len$}{}", &name[..start], n, &name[start + len..]));
    }
    if let Some(start) = name.find('%') {
        let rest = &name[start + 1..];
        let digits: String = rest.chars().take_while(char::is_ascii_digit).collect();
        if rest[digits.len()..].starts_with('d') {
            let width: usize = digits.trim_start_matches('0').parse().unwrap_or(0);
            let end = start + 1 + digits.len() + 1;
            return with(format!("{}{:0width$}{}", &name[..start], n, &name[end..]));
        }
    }
    if !numbered || number.is_none() {
        return output.to_path_buf();
    }
    match name.rfind('.') {
        Some(dot) => with(format!("{}.{n:04}{}", &name[..dot], &name[dot..])),
        None => with(format!("{name}.{n:04}")),
    }
}

/// Where a RIB extra output (`Display "+name"`) goes: beside the main output, with the
/// frame number put in as for the main output. None unless it names an .exr or .png file.
pub fn extra_path(
    output: &Path,
    display: &str,
    number: Option<i32>,
    numbered: bool,
) -> Option<PathBuf> {
    let ext = Path::new(display).extension()?.to_str()?.to_ascii_lowercase();
    if !matches!(ext.as_str(), "exr" | "png") {
        return None;
    }
    let dir = output.parent().unwrap_or(Path::new(""));
    Some(frame_path(&dir.join(display), number, numbered))
}

/// The main output of a RIB frame rendered without `-o`: its main `Display` name, relative
/// to the current directory, as RenderMan renderers write it. A name that is not an .exr or
/// .png file (a `"tiff"` or `"framebuffer"` display) is written as OpenEXR under the same
/// name with `.exr` for its extension, and `warn` says so. None when the frame has no
/// `Display`.
pub fn display_output(
    displays: &[reyes_rib::Display],
    warn: &mut dyn FnMut(String),
) -> Option<PathBuf> {
    let d = displays.iter().find(|d| !d.extra)?;
    let path = PathBuf::from(&d.name);
    path.file_name()?;
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    if matches!(ext.as_deref(), Some("exr" | "png")) {
        return Some(path);
    }
    let written = path.with_extension("exr");
    warn(format!(
        "{}: warning: Display: \"{}\" (driver \"{}\"): only .exr and .png files are written: \
         writing {} (use -o to choose)",
        d.at,
        one_line(&d.name),
        one_line(&d.driver),
        one_line(written.display())
    ));
    Some(written)
}

/// Whether `path` names an OpenEXR file.
pub fn is_exr(path: &Path) -> bool {
    path.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr"))
}

/// The directory a file `path` goes to (`.` for a bare name).
pub fn directory_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

/// Check the output `output` before any work is done: its format (.exr or .png, exit 2),
/// and its directory (exit 1): that it exists or, with `create` (a tile's, a merge's, a
/// farm's output), that it can be made ([`create_directory_of`]): its nearest existing
/// ancestor is a directory.
pub fn check_output(output: &Path, create: bool) -> Result<(), FarmError> {
    let shown = one_line(output.display());
    let ext = output.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    if !matches!(ext.as_deref(), Some("exr" | "png")) {
        return Err(FarmError::invalid(format_args!(
            "{shown}: output: unknown image format, use .exr or .png"
        )));
    }
    let dir = directory_of(output);
    if dir.is_dir() {
        return Ok(());
    }
    if !create {
        return Err(FarmError::failed(format_args!("{shown}: output directory does not exist")));
    }
    // The nearest of it and its ancestors that exists must be a directory to make it in.
    let nearest = dir
        .ancestors()
        .map(|a| if a.as_os_str().is_empty() { Path::new(".") } else { a })
        .find(|a| a.exists());
    match nearest {
        Some(a) if !a.is_dir() => Err(FarmError::failed(format_args!(
            "{shown}: output directory: {} is not a directory",
            one_line(a.display())
        ))),
        _ => Ok(()),
    }
}

/// Make the directory `path` goes to, and any missing above it (`mkdir -p`): a tile, a
/// merge or a farm writes where it is told without the directory made first.
pub fn create_directory_of(path: &Path) -> Result<(), FarmError> {
    let dir = directory_of(path);
    std::fs::create_dir_all(&dir).map_err(|e| {
        FarmError::failed(format_args!(
            "{}: cannot create the output directory {}: {e}",
            one_line(path.display()),
            one_line(dir.display())
        ))
    })
}

/// A frame's pictures as the scene asks them written: its crop window's pixels only, the AOV
/// layers, and the metadata of the scene file.
pub struct FramePicture<'a> {
    /// The scene rendered (after overrides).
    pub scene: &'a Scene,
    /// The scene file as the front end named it (the file's metadata names it).
    pub scene_path: &'a str,
    /// The whole frame's film.
    pub film: &'a Film,
    /// The AOV film and its layers, when the scene writes AOVs.
    pub aovs: Option<(&'a AovFilm, &'a [AovLayer])>,
    /// The render time in seconds, when the scene writes it.
    pub render_time: Option<f32>,
    /// The EXR beauty's blocks compressed while the frame rendered, if they were.
    pub early: Option<&'a EarlyBlocks>,
}

impl FramePicture<'_> {
    /// Write the picture to `path` (.exr or .png), atomically.
    pub fn write(&self, path: &Path, opts: &WriteOptions) -> Result<(), FilmError> {
        let scene = self.scene;
        let mut metadata = reyes_film::Metadata::for_scene(scene, self.scene_path);
        metadata.render_time = self.render_time;
        let image = &scene.image;
        let rect = image.crop_pixels();
        // Only a crop copies the film: the whole frame is written from the render's own (a
        // copy would be the frame's largest allocation, at the peak of its memory).
        let (film, aovs, placement) = if image.crop.is_some() {
            let full = (image.width, image.height);
            let placement = reyes_film::Placement { full, origin: (rect[0], rect[2]) };
            let aovs = self.aovs.map(|(a, l)| (Cow::Owned(a.crop(rect)), l));
            (Cow::Owned(self.film.crop(rect)), aovs, Some(placement))
        } else {
            (Cow::Borrowed(self.film), self.aovs.map(|(a, l)| (Cow::Borrowed(a), l)), None)
        };
        let picture = reyes_film::Picture {
            film: &film,
            aovs: aovs.as_ref().map(|(a, l)| (a.as_ref(), *l)),
            outputs: &scene.outputs,
            metadata: &metadata,
            placement,
            early: self.early,
        };
        reyes_film::write_picture(path, &picture, opts)
    }
}

/// Write to `path` the frame of `scene` that the bucket `results` make, added in raster
/// order (a merge of tiles): the file a whole render writes.
pub fn write_assembled(
    scene: &Scene,
    scene_path: &str,
    results: &BTreeMap<usize, BucketResult>,
    render_time: Option<f32>,
    path: &Path,
    opts: &WriteOptions,
) -> Result<(), FilmError> {
    let aov = reyes_render::aovs::AovSetup::for_scene(scene);
    let channels = aov.as_ref().map(|a| a.plan.channels());
    let (film, aov_film) = reyes_render::buckets::assemble(
        scene.image.width,
        scene.image.height,
        channels,
        results.values(),
    );
    let aovs = aov.as_ref().zip(aov_film.as_ref()).map(|(a, f)| (f, a.layers.as_slice()));
    let picture = FramePicture { scene, scene_path, film: &film, aovs, render_time, early: None };
    picture.write(path, opts)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_numbers_go_where_the_name_asks() {
        let p = |s: &str, n, many| frame_path(Path::new(s), n, many).display().to_string();
        assert_eq!(p("out.exr", None, false), "out.exr");
        assert_eq!(p("out.exr", Some(3), false), "out.exr");
        assert_eq!(p("out.exr", Some(3), true), "out.0003.exr");
        assert_eq!(p("dir/out.###.exr", Some(7), false), "dir/out.007.exr");
        assert_eq!(p("out.%04d.png", Some(12), true), "out.0012.png");
        assert_eq!(p("out_%d.exr", Some(12), true), "out_12.exr");
        assert_eq!(p("noext", Some(2), true), "noext.0002");
        let e = |d: &str| extra_path(Path::new("dir/main.exr"), d, Some(5), true);
        assert_eq!(e("depth.exr").unwrap().display().to_string(), "dir/depth.0005.exr");
        assert_eq!(e("depth.tif"), None);
    }

    #[test]
    fn missing_output_directories_are_refused_or_made() {
        let tmp = tempfile::tempdir().expect("tempdir");
        let out = tmp.path().join("tiles/deep/t1.exr");
        let e = check_output(&out, false).expect_err("no directory");
        assert_eq!(e.exit_code(), 1);
        assert!(e.to_string().ends_with("t1.exr: output directory does not exist"), "{e}");
        check_output(&out, true).expect("can be made");
        assert!(!tmp.path().join("tiles").exists(), "a check makes nothing");
        create_directory_of(&out).expect("made");
        assert!(tmp.path().join("tiles/deep").is_dir());
        check_output(&out, false).expect("there now");
        create_directory_of(&out).expect("made again: nothing to do");
        // A file where a directory would go: refused before any work, by either check.
        std::fs::write(tmp.path().join("file"), b"x").expect("file");
        let under = tmp.path().join("file/sub/t.exr");
        let e = check_output(&under, true).expect_err("a file in the way");
        assert!(e.to_string().ends_with("file is not a directory"), "{e}");
        assert!(create_directory_of(&under).is_err());
        let e = check_output(&tmp.path().join("file/t.exr"), true).expect_err("a file");
        assert!(e.to_string().ends_with("file is not a directory"), "{e}");
        // The format is checked first, with its own exit code.
        assert_eq!(
            check_output(Path::new("nowhere/x.tiff"), true).map_err(|e| e.exit_code()),
            Err(2)
        );
    }
}
