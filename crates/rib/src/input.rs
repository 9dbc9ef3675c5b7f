//! One entry for every scene file: RON or RIB, chosen by the file's extension, or by its
//! content when the extension says nothing (or the scene comes from standard input, `-`).
//! Both front-ends end in the same validated [`reyes_scene::Scene`]s.
//!
//! Invariant: the format decision depends only on the name and the first bytes; errors keep
//! their front-end's one-line form and exit code (2 for a bad scene, 1 for I/O).

use std::io::Read;
use std::path::Path;

use crate::{Frame, Loaded, Permissions, RiOptions, RibError, Source, Warning};

/// The two scene formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// The project's own RON scene format (docs/scene-format.md).
    Ron,
    /// RenderMan RIB, ASCII or binary, possibly gzipped (docs/rib.md).
    Rib,
}

/// Why a scene file could not be loaded.
#[derive(Debug, thiserror::Error)]
pub enum InputError {
    /// A RON scene failed.
    #[error(transparent)]
    Ron(#[from] reyes_scene::LoadError),
    /// A RIB scene failed.
    #[error(transparent)]
    Rib(#[from] RibError),
    /// Standard input could not be read.
    #[error("<stdin>: cannot read: {0}")]
    Stdin(std::io::Error),
}

impl InputError {
    /// Exit code: 1 for I/O failures, 2 for bad scenes.
    pub fn exit_code(&self) -> u8 {
        match self {
            InputError::Ron(e) => e.exit_code(),
            InputError::Rib(RibError::Io { .. } | RibError::Archive { .. }) => 1,
            InputError::Rib(_) => 2,
            InputError::Stdin(_) => 1,
        }
    }
}

/// A scene file refused: why, and the warnings gathered before the error (in file order), to
/// be shown before it: what the reader tolerated often explains the refusal (a light ignored
/// with a warning, then used by handle).
#[derive(Debug, thiserror::Error)]
#[error("{error}")]
pub struct Refusal {
    /// The error that stopped the load (boxed: a RON error is large, and a refusal travels
    /// up the `Result` of every load).
    #[source]
    pub error: Box<InputError>,
    /// The warnings raised before it.
    pub warnings: Vec<Warning>,
}

impl Refusal {
    /// Exit code: 1 for I/O failures, 2 for bad scenes.
    pub fn exit_code(&self) -> u8 {
        self.error.exit_code()
    }
}

impl From<InputError> for Refusal {
    fn from(error: InputError) -> Self {
        Refusal { error: Box::new(error), warnings: Vec::new() }
    }
}

impl From<RibError> for Refusal {
    fn from(error: RibError) -> Self {
        InputError::from(error).into()
    }
}

impl From<reyes_scene::LoadError> for Refusal {
    fn from(error: reyes_scene::LoadError) -> Self {
        InputError::from(error).into()
    }
}

/// The format of the file `path` whose first bytes are `head`: `.ron` is RON; `.rib` and
/// `.rib.gz` (and any gzip data) are RIB; otherwise RON when the text starts (after white
/// space) with a `//` or `/*` comment or with `Scene`, else RIB.
pub fn detect(path: &Path, head: &[u8]) -> Format {
    let name =
        path.file_name().map(|n| n.to_string_lossy().to_ascii_lowercase()).unwrap_or_default();
    if name.ends_with(".ron") {
        return Format::Ron;
    }
    if name.ends_with(".rib") || name.ends_with(".rib.gz") || head.starts_with(&[0x1f, 0x8b]) {
        return Format::Rib;
    }
    let text = head.strip_prefix(b"\xef\xbb\xbf").unwrap_or(head);
    let start = text.iter().position(|b| !b.is_ascii_whitespace()).unwrap_or(text.len());
    let rest = &text[start..];
    if rest.starts_with(b"//")
        || rest.starts_with(b"/*")
        || rest.starts_with(b"Scene")
        || rest.starts_with(b"(")
    {
        Format::Ron
    } else {
        Format::Rib
    }
}

/// Loads the scene file `path` (`-`: standard input) in whichever format it is, into its
/// frames (a RON scene is one frame without a number) and the warnings to show.
///
/// # Errors
///
/// A [`Refusal`]: the first error, with the warnings raised before it.
pub fn load_scene_file(path: &Path, options: &RiOptions) -> Result<Loaded, Refusal> {
    load_scene_file_with(path, options, Permissions::default())
}

/// [`load_scene_file`] with `permissions` (running a RIB file's `RunProgram` procedurals:
/// the CLI's `--allow-run-program`).
///
/// # Errors
///
/// As [`load_scene_file`].
pub fn load_scene_file_with(
    path: &Path,
    options: &RiOptions,
    permissions: Permissions,
) -> Result<Loaded, Refusal> {
    if path == Path::new("-") {
        let mut bytes = Vec::new();
        std::io::stdin().read_to_end(&mut bytes).map_err(InputError::Stdin)?;
        return match detect(path, &bytes) {
            Format::Ron => {
                let text = String::from_utf8_lossy(&bytes);
                Ok(ron_frames(&text, Path::new("<stdin>"), options)?)
            }
            Format::Rib => load_rib(Source::from_bytes("<stdin>", bytes), options, permissions),
        };
    }
    let mut head = [0u8; 256];
    let n = std::fs::File::open(path)
        .and_then(|mut f| f.read(&mut head))
        .map_err(|source| reyes_scene::LoadError::Io { path: path.to_path_buf(), source })?;
    match detect(path, &head[..n]) {
        Format::Ron => {
            let text = reyes_scene::read_text(path)?;
            Ok(ron_frames(&text, path, options)?)
        }
        Format::Rib => {
            let source = Source::open(path).map_err(|source| RibError::Io {
                file: path.display().to_string().into(),
                source,
            })?;
            load_rib(source, options, permissions)
        }
    }
}

fn load_rib(
    source: Source,
    options: &RiOptions,
    permissions: Permissions,
) -> Result<Loaded, Refusal> {
    crate::ri::load_reporting(source, options, permissions)
        .map_err(|(e, warnings)| Refusal { error: Box::new(e.into()), warnings })
}

/// The frames of the RON scene `text`: one without a number, unless frames are chosen
/// (`options.frames`), when each chosen number is a frame, with the scene's `${...}`
/// expressions evaluated for it ([`reyes_scene::animate`]). An animated scene needs frames.
fn ron_frames(
    text: &str,
    file: &Path,
    options: &RiOptions,
) -> Result<Loaded, reyes_scene::LoadError> {
    let numbers: Vec<i32> = match &options.frames {
        Some(ranges) => {
            let mut v: Vec<i32> = ranges.iter().flat_map(|&(a, b)| a..=b).collect();
            v.sort_unstable();
            v.dedup();
            v
        }
        None if reyes_scene::animate::is_animated(text) => {
            return Err(reyes_scene::SceneError {
                file: file.to_path_buf(),
                line: None,
                col: None,
                field: "${...}".into(),
                message:
                    "the scene is animated: choose its frames with --frames (e.g. --frames 1-24)"
                        .into(),
            }
            .into());
        }
        None => {
            let scene = reyes_scene::parse_files(text, file)?;
            let frames =
                vec![Frame { number: None, scene, displays: Vec::new(), makes: Vec::new() }];
            return Ok(Loaded {
                makes_after: Vec::new(),
                frames,
                warnings: Vec::new(),
                several_frames: false,
                display_repeats: false,
            });
        }
    };
    let mut frames = Vec::with_capacity(numbers.len());
    for n in numbers {
        let text = reyes_scene::animate::substitute(text, n, file)?;
        let scene = reyes_scene::parse_files(&text, file)?;
        frames.push(Frame { number: Some(n), scene, displays: Vec::new(), makes: Vec::new() });
    }
    let several_frames = reyes_scene::animate::is_animated(text);
    Ok(Loaded {
        frames,
        makes_after: Vec::new(),
        warnings: Vec::new(),
        several_frames,
        display_repeats: false,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_by_name_then_content() {
        let p = Path::new;
        assert_eq!(detect(p("a.ron"), b"Display"), Format::Ron);
        assert_eq!(detect(p("a.RIB"), b"Scene("), Format::Rib);
        assert_eq!(detect(p("a.rib.gz"), b""), Format::Rib);
        assert_eq!(detect(p("scene"), &[0x1f, 0x8b, 8]), Format::Rib);
        assert_eq!(detect(p("scene"), b"  // a RON scene\nScene("), Format::Ron);
        assert_eq!(detect(p("-"), b"\nScene(image: (width: 1, height: 1))"), Format::Ron);
        assert_eq!(detect(p("-"), b"##RenderMan RIB\nFormat 64 64 1"), Format::Rib);
        assert_eq!(detect(p("scene.txt"), b"WorldBegin"), Format::Rib);
    }
}
