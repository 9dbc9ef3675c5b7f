//! `ReadArchive` machinery: paths resolve against the including file's folder, positions name
//! the file they are in, include cycles and unreadable archives are one-line errors naming the
//! including request, and the include stack unwinds at each archive's end.

use std::fs;
use std::path::Path;

use reyes_rib::{Reader, ReaderOptions, RequestKind, RibError, Source};

fn write(dir: &Path, name: &str, text: &str) {
    let path = dir.join(name);
    fs::create_dir_all(path.parent().unwrap()).unwrap();
    fs::write(path, text).unwrap();
}

/// Reads `root`, following archives through `read_archive` as the state machine would;
/// returns (file:line:col request) lines and the error lines.
fn trace(root: &Path) -> (Vec<String>, Vec<String>) {
    let mut r = Reader::open(root).unwrap();
    let (mut seen, mut errors) = (Vec::new(), Vec::new());
    for _ in 0..1000 {
        match r.next_request() {
            Ok(Some(q)) => {
                seen.push(format!("{} {}", q.at, q.name()));
                if q.kind == RequestKind::ReadArchive
                    && let Err(e) = r.read_archive(&q)
                {
                    errors.push(e.to_string());
                }
            }
            Ok(None) => return (seen, errors),
            Err(e) => errors.push(e.to_string()),
        }
    }
    panic!("did not finish");
}

/// Writes `files` (`(path, text)`) to a new temporary folder and [`trace`]s the first; the
/// folder, then what was seen and the errors.
fn trace_files(files: &[(&str, &str)]) -> (tempfile::TempDir, Vec<String>, Vec<String>) {
    let tmp = tempfile::tempdir().unwrap();
    for (name, text) in files {
        write(tmp.path(), name, text);
    }
    let (seen, errors) = trace(&tmp.path().join(files[0].0));
    (tmp, seen, errors)
}

#[test]
fn archives_resolve_relative_to_the_including_file() {
    let (tmp, seen, errors) = trace_files(&[
        ("scene/main.rib", "WorldBegin\nReadArchive \"parts/ball.rib\"\nWorldEnd\n"),
        ("scene/parts/ball.rib", "AttributeBegin\n  ReadArchive \"shape.rib\"\nAttributeEnd\n"),
        ("scene/parts/shape.rib", "Sphere 1 -1 1 360"),
    ]);
    assert_eq!(errors, Vec::<String>::new());
    let d = tmp.path();
    let m = d.join("scene/main.rib").display().to_string();
    let b = d.join("scene/parts/ball.rib").display().to_string();
    let s = d.join("scene/parts/shape.rib").display().to_string();
    assert_eq!(
        seen,
        vec![
            format!("{m}:1:1 WorldBegin"),
            format!("{m}:2:1 ReadArchive"),
            format!("{b}:1:1 AttributeBegin"),
            format!("{b}:2:3 ReadArchive"),
            format!("{s}:1:1 Sphere"),
            format!("{b}:3:1 AttributeEnd"),
            format!("{m}:3:1 WorldEnd"),
        ]
    );
}

#[test]
fn errors_inside_an_archive_name_the_archive() {
    let (tmp, _, errors) = trace_files(&[
        ("a.rib", "ReadArchive \"b.rib\"\nSphere 1 -1 1 360\n"),
        ("b.rib", "# archive\nTranslate 1 2\n"),
    ]);
    assert_eq!(
        errors,
        vec![format!(
            "{}:2:1: Translate: missing argument dz (a number) in Translate dx dy dz",
            tmp.path().join("b.rib").display()
        )]
    );
}

#[test]
fn include_cycles_are_reported_with_the_chain() {
    let (tmp, seen, errors) = trace_files(&[
        ("a.rib", "ReadArchive \"b.rib\"\n"),
        ("b.rib", "Sphere 1 -1 1 360\nReadArchive \"a.rib\"\n"),
    ]);
    let d = tmp.path();
    let (a, b) = (d.join("a.rib").display().to_string(), d.join("b.rib").display().to_string());
    assert_eq!(errors, vec![format!("{b}:2:1: ReadArchive: include cycle {a} -> {b} -> {a}")]);
    assert_eq!(seen.len(), 3);
    // A file including itself.
    let (tmp, _, errors) = trace_files(&[("self.rib", "ReadArchive \"self.rib\"")]);
    let s = tmp.path().join("self.rib").display().to_string();
    assert_eq!(errors, vec![format!("{s}:1:1: ReadArchive: include cycle {s} -> {s}")]);
}

#[test]
fn a_missing_archive_names_the_file_and_the_including_request() {
    let (tmp, seen, errors) =
        trace_files(&[("main.rib", "WorldBegin\n  ReadArchive \"nowhere.rib\"\nWorldEnd\n")]);
    let d = tmp.path();
    assert_eq!(errors.len(), 1);
    let want = format!(
        "{}:2:3: ReadArchive: cannot read \"{}\": ",
        d.join("main.rib").display(),
        d.join("nowhere.rib").display()
    );
    assert!(errors[0].starts_with(&want), "{}", errors[0]);
    // The including stream goes on.
    assert_eq!(seen.last().map(|s| s.ends_with("WorldEnd")), Some(true));
}

#[test]
fn the_reader_can_follow_archives_itself() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    write(d, "main.rib", "WorldBegin ReadArchive \"x.rib\" WorldEnd");
    write(d, "x.rib", "Declare \"q\" \"float\"\nSurface \"s\" \"q\" 1");
    let options = ReaderOptions { follow_archives: true, ..ReaderOptions::default() };
    let mut r = Reader::with_options(Source::open(d.join("main.rib")).unwrap(), options);
    let kinds: Vec<_> = (&mut r).map(|q| q.unwrap().kind).collect();
    assert_eq!(
        kinds,
        vec![
            RequestKind::WorldBegin,
            RequestKind::Declare,
            RequestKind::Surface,
            RequestKind::WorldEnd
        ]
    );
    // Declarations made in an archive stay (Declare is not scoped).
    assert!(r.declarations().get("q").is_some());
    assert!(r.warnings().is_empty());
}

#[test]
fn nesting_is_bounded() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    for i in 0..70 {
        write(d, &format!("n{i}.rib"), &format!("ReadArchive \"n{}.rib\"", i + 1));
    }
    let (_, errors) = trace(&d.join("n0.rib"));
    assert_eq!(errors.len(), 1);
    assert!(errors[0].ends_with("ReadArchive: archives nested deeper than 64"), "{}", errors[0]);
}

#[test]
fn memory_sources_can_be_pushed_and_stdin_is_named() {
    let mut r = Reader::new(Source::from_bytes("main", "WorldBegin\nWorldEnd"));
    let first = r.next_request().unwrap().unwrap();
    r.push_source(Source::from_bytes("inline", "Sphere 1 -1 1 360"), &first.at).unwrap();
    assert_eq!(r.depth(), 2);
    let q = r.next_request().unwrap().unwrap();
    assert_eq!(q.at.to_string(), "inline:1:1");
    assert_eq!(r.next_request().unwrap().unwrap().kind, RequestKind::WorldEnd);
    assert_eq!(r.current_file(), Some("main"));
    assert_eq!(Source::stdin().name(), "<stdin>");
    assert!(matches!(Reader::open("/nonexistent/dir/x.rib"), Err(RibError::Io { .. })));
    assert_eq!(
        Reader::open("/nonexistent/dir/x.rib").unwrap_err().to_string(),
        "/nonexistent/dir/x.rib: cannot read: No such file or directory (os error 2)"
    );
}
