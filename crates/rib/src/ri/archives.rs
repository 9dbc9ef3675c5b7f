//! Archives in the RI state machine: `ReadArchive` of a file, looked up along
//! `Option "searchpath" "archive"`, and inline archives (`ArchiveBegin "name"` ...
//! `ArchiveEnd`), recorded where they are defined and replayed by `ReadArchive "name"`.
//!
//! Invariants: an inline archive's requests are not run where it is defined (a
//! `ReadArchive` in it is resolved when it is replayed); `ReadArchive` takes an inline
//! archive of its name before a file; an archive, inline or a file, is read to its end where
//! it stands, before the next request of what included it, in the current graphics state
//! and with no block of its own; an archive
//! that reads itself, directly or not, is an error naming the cycle; replays nest at most
//! [`MAX_INSTANCE_NESTING`] deep and add up to at most [`MAX_INSTANCED_REQUESTS`] requests in
//! one world block.

use std::path::{Path, PathBuf};

use super::frame::{MAX_INSTANCE_NESTING, MAX_INSTANCED_REQUESTS, Machine};
use super::search::{Kind, Lookup, SearchPaths};
use crate::error::quote;
use crate::{Location, Reader, Request, RibError, Warning};

impl Machine {
    /// `ArchiveBegin "name"`: records the requests up to the matching `ArchiveEnd`.
    pub(super) fn archive_begin(&mut self, r: &Request) -> Result<(), RibError> {
        let name = r.string(0).ok_or_else(|| r.error("expected an archive name"))?;
        self.archive_recording = Some((name.to_string(), Vec::new(), 0, r.at.clone()));
        Ok(())
    }

    /// The matching `ArchiveEnd`: the archive is defined (a name defined again is replaced).
    pub(super) fn archive_end(&mut self) -> Result<(), RibError> {
        if let Some((name, requests, _, _)) = self.archive_recording.take() {
            self.archives.insert(name, requests);
        }
        Ok(())
    }

    /// `ReadArchive "name"`: the inline archive of that name replayed here, else the file
    /// read here.
    pub(super) fn read_archive(&mut self, r: &Request) -> Result<(), RibError> {
        let name = r.string(0).ok_or_else(|| r.error("expected a file name"))?.to_string();
        if self.archive_replaying.contains(&name) {
            let mut chain: Vec<String> = self.archive_replaying.iter().map(|n| quote(n)).collect();
            chain.push(quote(&name));
            return Err(r.error(format!(
                "inline archives read each other in a cycle: {}",
                chain.join(" -> ")
            )));
        }
        let Some(requests) = self.archives.get(&name).cloned() else {
            return self.read_archive_file(r);
        };
        if self.archive_replaying.len() >= MAX_INSTANCE_NESTING {
            return Err(
                r.error(format!("inline archives nested more than {MAX_INSTANCE_NESTING} deep"))
            );
        }
        self.instanced = self.instanced.saturating_add(requests.len());
        if self.instanced > MAX_INSTANCED_REQUESTS {
            return Err(r.error(format!(
                "object instances and inline archives replay more than {MAX_INSTANCED_REQUESTS} \
                 requests in this world block"
            )));
        }
        self.archive_replaying.push(name);
        let replayed = requests.into_iter().try_for_each(|q| self.request(q));
        self.archive_replaying.pop();
        replayed
    }

    /// `ReadArchive` of a file: looked up along the archive search path, then read in place.
    pub(super) fn read_archive_file(&mut self, r: &Request) -> Result<(), RibError> {
        let name = r.string(0).ok_or_else(|| r.error("expected a file name"))?;
        let path = self.archive_path(name, &r.at)?;
        self.read_file_in_place(&path, &r.at)
    }

    /// Reads the archive file `path`, included at `at`, to its end: each of its requests
    /// handled before the next of the including file (or replay) is.
    pub(super) fn read_file_in_place(
        &mut self,
        path: &Path,
        at: &Location,
    ) -> Result<(), RibError> {
        let depth = self.reader.depth() + 1;
        self.reader.push_archive(path, at)?;
        while let Some(q) = self.reader.next_request_within(depth)? {
            self.warnings.extend(self.reader.take_warnings());
            self.request(q)?;
        }
        self.warnings.extend(self.reader.take_warnings());
        Ok(())
    }

    /// The file of the archive `name` named at `at`: along `Option "searchpath" "archive"`
    /// when one is set, else relative to the file naming it. Not found along a path: the
    /// error of an unreadable archive, naming the path.
    pub(super) fn archive_path(&self, name: &str, at: &Location) -> Result<PathBuf, RibError> {
        let reader = &self.reader;
        match self.frame_options.search.find(Kind::Archive, name, |n| reader.resolve_archive(n, at))
        {
            Lookup::Unsearched(p) | Lookup::Found(p) => Ok(p),
            Lookup::Missing(_, path) => Err(RibError::Archive {
                at: at.clone(),
                file: name.to_string(),
                source: std::io::Error::new(
                    std::io::ErrorKind::NotFound,
                    format!("not found along the archive search path {path:?}"),
                ),
            }),
        }
    }
}

/// The file of the texture `name` named by `request` at `at`: along
/// `Option "searchpath" "texture"` when one is set, else relative to the file naming it. Not
/// found along a path: the default resolution, with a warning naming the path (the texture's
/// loader then says what is wrong with it).
pub(super) fn texture_path(
    search: &SearchPaths,
    reader: &Reader,
    name: &str,
    at: &Location,
    request: &str,
    warnings: &mut Vec<Warning>,
) -> String {
    let path = match search.find(Kind::Texture, name, |n| reader.resolve_archive(n, at)) {
        Lookup::Unsearched(p) | Lookup::Found(p) => p,
        Lookup::Missing(p, path) => {
            warnings.push(Warning {
                at: at.clone(),
                message: format!(
                    "{request}: texture {} is not found along the texture search path {path:?}: {:?} is used",
                    quote(name),
                    p.display().to_string()
                ),
            });
            p
        }
    };
    path.to_string_lossy().into_owned()
}
