//! Input stage: where RIB bytes come from ([`Source`]: a file, stdin or memory), and transparent
//! gzip decompression.
//!
//! Invariant: a `Source` is read once, front to back, in bounded chunks; nothing here holds the
//! whole input. Gzip is recognised by its magic bytes (0x1f 0x8b), never by the file name.

use std::fs::File;
use std::io::{self, Read};
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A stream of RIB bytes with the name that messages use for it.
pub struct Source {
    pub(crate) name: Arc<str>,
    pub(crate) path: Option<PathBuf>,
    pub(crate) read: Box<dyn Read>,
}

impl std::fmt::Debug for Source {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Source").field("name", &self.name).field("path", &self.path).finish()
    }
}

impl Source {
    /// Opens a file, or standard input when `path` is `-`. The display name is the path as given
    /// (`<stdin>` for `-`).
    pub fn open(path: impl AsRef<Path>) -> io::Result<Source> {
        let path = path.as_ref();
        if path.as_os_str() == "-" {
            return Ok(Source::stdin());
        }
        let file = File::open(path)?;
        if file.metadata()?.is_dir() {
            return Err(io::Error::new(io::ErrorKind::InvalidInput, "is a directory"));
        }
        Ok(Source {
            name: Arc::from(path.display().to_string()),
            path: Some(path.to_path_buf()),
            read: Box::new(file),
        })
    }

    /// Standard input, named `<stdin>`. Archives it includes resolve against the current
    /// directory.
    pub fn stdin() -> Source {
        Source { name: Arc::from("<stdin>"), path: None, read: Box::new(io::stdin()) }
    }

    /// Bytes in memory (plain or gzipped), with a name for messages.
    pub fn from_bytes(name: &str, bytes: impl Into<Vec<u8>>) -> Source {
        Source::from_reader(name, io::Cursor::new(bytes.into()))
    }

    /// Any reader, with a name for messages. It is read in chunks, never all at once.
    pub fn from_reader(name: &str, read: impl Read + 'static) -> Source {
        Source { name: Arc::from(name), path: None, read: Box::new(read) }
    }

    /// Sets the path that relative `ReadArchive` names resolve against (its directory) and that
    /// include-cycle detection compares; `from_bytes` and `from_reader` sources have none.
    pub fn with_path(mut self, path: impl Into<PathBuf>) -> Source {
        self.path = Some(path.into());
        self
    }

    /// The display name used in messages.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The file path, if the source is a file.
    pub fn path(&self) -> Option<&Path> {
        self.path.as_deref()
    }

    /// The byte stream with gzip removed: peeks at the first two bytes and, on the gzip magic,
    /// wraps the rest in a decoder (concatenated gzip members are read as one stream).
    pub(crate) fn into_plain_reader(self) -> io::Result<Box<dyn Read>> {
        let mut read = self.read;
        let mut head = [0u8; 2];
        let mut got = 0;
        while got < 2 {
            match read.read(&mut head[got..]) {
                Ok(0) => break,
                Ok(n) => got += n,
                Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
                Err(e) => return Err(e),
            }
        }
        let rest = io::Cursor::new(head[..got].to_vec()).chain(read);
        if got == 2 && head == [0x1f, 0x8b] {
            Ok(Box::new(flate2::read::MultiGzDecoder::new(rest)))
        } else {
            Ok(Box::new(rest))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    fn all(source: Source) -> Vec<u8> {
        let mut out = Vec::new();
        source.into_plain_reader().unwrap().read_to_end(&mut out).unwrap();
        out
    }

    #[test]
    fn plain_bytes_pass_through() {
        assert_eq!(all(Source::from_bytes("m", b"WorldBegin".to_vec())), b"WorldBegin");
        assert_eq!(all(Source::from_bytes("m", b"W".to_vec())), b"W");
        assert_eq!(all(Source::from_bytes("m", Vec::new())), b"");
    }

    #[test]
    fn gzip_is_decompressed_by_magic() {
        let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
        enc.write_all(b"Sphere 1 -1 1 360\n").unwrap();
        let gz = enc.finish().unwrap();
        assert_eq!(all(Source::from_bytes("m.rib", gz)), b"Sphere 1 -1 1 360\n");
    }

    #[test]
    fn names() {
        assert_eq!(Source::stdin().name(), "<stdin>");
        assert_eq!(Source::from_bytes("mem", Vec::new()).name(), "mem");
        assert!(Source::open("/nonexistent/x.rib").is_err());
    }
}
