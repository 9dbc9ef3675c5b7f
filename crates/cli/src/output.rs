//! Where a frame's images go: the output path with the frame number put in, and the extra
//! outputs of RIB's `+` `Display` lines beside it.
//!
//! Invariant: names depend only on the output path, the frame number and whether the file has
//! several frames, so a frame renders to the same name whichever frames are chosen.

use std::path::{Path, PathBuf};

/// The output path of frame `number`: a run of `#` (`out.####.exr`) or a `%0Nd`
/// (`out.%04d.exr`) takes the number, zero-padded to the run's length or N; otherwise, when
/// `numbered` (the file has several frames), `.NNNN` is inserted before the extension.
pub(crate) fn frame_path(output: &Path, number: Option<i32>, numbered: bool) -> PathBuf {
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
pub(crate) fn extra_path(
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
