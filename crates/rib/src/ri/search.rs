//! `Option "searchpath"` (Spec 3.2, 4.1.4): where archives, textures, shaders and procedural
//! programs are looked for.
//!
//! A path is a `:`-separated list of directories; `&` stands for the path as it was before
//! (the default when none was set) and `@` for the default, which here is the directory of
//! the RIB file that names the file (the current directory for standard input and memory
//! sources), as names resolve when no path is set. A relative directory in a path is taken
//! relative to the directory of the file holding the `Option` request, as a relative name is.
//!
//! Invariants: a name is looked for in the path's directories in order and the first
//! existing file wins; an absolute name is taken as written; without a path for its kind a
//! name resolves as before (the default alone), so setting no path changes nothing.

use std::path::{Path, PathBuf};

/// The kinds of file a search path is set for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    /// `ReadArchive` and `DelayedReadArchive` files.
    Archive,
    /// Texture maps named in shader parameters.
    Texture,
    /// Compiled shaders (kept; this renderer's shaders are built in, so none is read).
    Shader,
    /// `RunProgram` and `DynamicLoad` programs (kept; neither is run).
    Procedural,
}

impl Kind {
    /// The kind an `Option "searchpath"` parameter names.
    pub(crate) fn of(name: &str) -> Option<Kind> {
        Some(match name {
            "archive" => Kind::Archive,
            "texture" => Kind::Texture,
            "shader" => Kind::Shader,
            "procedural" => Kind::Procedural,
            _ => return None,
        })
    }
}

/// One directory of a path.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Entry {
    /// `@`: the directory of the file naming the file.
    Default,
    /// A directory (made absolute, or relative to the current directory, when set).
    Dir(PathBuf),
}

/// The search paths in force (an option: restored at `FrameEnd`).
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct SearchPaths {
    paths: [Option<Vec<Entry>>; 4],
}

/// Where a name was found.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Lookup {
    /// No path is set for the kind: the default resolution.
    Unsearched(PathBuf),
    /// The first existing file along the path.
    Found(PathBuf),
    /// No directory of the path holds it: the default resolution, and the path as shown.
    Missing(PathBuf, String),
}

impl SearchPaths {
    /// Sets the path of `kind` from the option's value: `:`-separated directories, `&` the
    /// previous path, `@` the default; `dir` makes a relative directory absolute (relative
    /// to the file holding the option).
    pub(crate) fn set(&mut self, kind: Kind, value: &str, dir: impl Fn(&str) -> PathBuf) {
        let previous = self.paths[kind as usize].clone().unwrap_or_else(|| vec![Entry::Default]);
        let mut path = Vec::new();
        for part in value.split(':') {
            match part {
                "" => {}
                "&" => path.extend(previous.iter().cloned()),
                "@" => path.push(Entry::Default),
                d => path.push(Entry::Dir(dir(d))),
            }
        }
        self.paths[kind as usize] = Some(path);
    }

    /// The directories of the path of `kind` (not `@`), in order; none when no path is set.
    pub(crate) fn dirs(&self, kind: Kind) -> Vec<PathBuf> {
        let entries = self.paths[kind as usize].iter().flatten();
        entries.filter_map(|e| if let Entry::Dir(d) = e { Some(d.clone()) } else { None }).collect()
    }

    /// The path of `kind`, if one is set.
    #[cfg(test)]
    pub(crate) fn get(&self, kind: Kind) -> Option<&[Entry]> {
        self.paths[kind as usize].as_deref()
    }

    /// Looks `name` up along the path of `kind`; `default` resolves it the default way
    /// (against the directory of the file naming it).
    pub(crate) fn find(&self, kind: Kind, name: &str, default: impl Fn(&str) -> PathBuf) -> Lookup {
        let Some(path) = &self.paths[kind as usize] else {
            return Lookup::Unsearched(default(name));
        };
        if Path::new(name).is_absolute() {
            return Lookup::Found(PathBuf::from(name));
        }
        for entry in path {
            let candidate = match entry {
                Entry::Default => default(name),
                Entry::Dir(d) => d.join(name),
            };
            if candidate.is_file() {
                return Lookup::Found(candidate);
            }
        }
        let shown: Vec<String> = path
            .iter()
            .map(|e| match e {
                Entry::Default => "@".to_string(),
                Entry::Dir(d) => d.display().to_string(),
            })
            .collect();
        Lookup::Missing(default(name), shown.join(":"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ampersand_is_the_previous_path_and_at_the_default() {
        let mut s = SearchPaths::default();
        let dir = |d: &str| PathBuf::from("/base").join(d);
        s.set(Kind::Texture, "maps:&", dir);
        assert_eq!(
            s.get(Kind::Texture),
            Some(&[Entry::Dir("/base/maps".into()), Entry::Default][..])
        );
        s.set(Kind::Texture, "/abs::&:@", dir);
        assert_eq!(
            s.get(Kind::Texture),
            Some(
                &[
                    Entry::Dir("/abs".into()),
                    Entry::Dir("/base/maps".into()),
                    Entry::Default,
                    Entry::Default
                ][..]
            )
        );
        assert_eq!(s.get(Kind::Archive), None, "each kind has its own path");
        assert_eq!(
            s.find(Kind::Archive, "a.rib", |n| PathBuf::from("/here").join(n)),
            Lookup::Unsearched("/here/a.rib".into())
        );
        assert_eq!(
            s.find(Kind::Texture, "no-such-map.tx", |n| PathBuf::from("/here").join(n)),
            Lookup::Missing("/here/no-such-map.tx".into(), "/abs:/base/maps:@:@".into())
        );
    }
}
