//! Where a frame's images go and how they are written: the output path with the frame
//! number put in, the extra outputs of RIB's `+` `Display` lines beside it, the checks made
//! before any work is done, and the frame's file written as the scene asks.
//!
//! Invariants: names depend only on the output path, the frame number and whether the file
//! has several frames, so a frame renders to the same name whichever frames are chosen. A
//! whole render and a merge write through the same [`FramePicture::write`], so their files
//! agree byte for byte. Files are written atomically ([`reyes_film`]).

use std::borrow::Cow;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use reyes_film::{AovFilm, AovLayer, EarlyBlocks, Film, FilmError, WriteOptions};
use reyes_render::BucketResult;
use reyes_scene::Scene;

use crate::{FarmError, one_line};

/// The output path of frame `number`: a run of `#` (`out.####.exr`) or a `%0Nd`
/// (`out.%04d.exr`) takes the number, zero-padded to the run's length or N; otherwise, when
/// `numbered` (the file has several frames), `.NNNN` is inserted before the extension.
pub fn frame_path(output: &Path, number: Option<i32>, numbered: bool) -> PathBuf {
    let Some(n) = number else { return output.to_path_buf() };
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
    if !numbered {
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
/// and that its directory exists (exit 1).
pub fn check_output(output: &Path) -> Result<(), FarmError> {
    let shown = one_line(output.display());
    let ext = output.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    if !matches!(ext.as_deref(), Some("exr" | "png")) {
        return Err(FarmError::invalid(format_args!(
            "{shown}: output: unknown image format, use .exr or .png"
        )));
    }
    if !directory_of(output).is_dir() {
        return Err(FarmError::failed(format_args!("{shown}: output directory does not exist")));
    }
    Ok(())
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
}
