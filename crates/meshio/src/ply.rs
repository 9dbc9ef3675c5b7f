//! Stanford PLY, ASCII and binary of either byte order: a header of text lines
//! (`element NAME COUNT`, `property TYPE NAME`, `property list CTYPE ITYPE NAME`), then the
//! elements in header order.
//!
//! From `vertex` elements we take `x y z`, optional `nx ny nz` and optional `u v` (also named
//! `s t` or `texture_u texture_v`); from `face` elements the list `vertex_indices` (or
//! `vertex_index`). Other properties and elements are read past. Header and ASCII faults name
//! the line; binary faults name the element (its kind and 0-based index among its kind).
//! An ASCII file holds one element per non-blank line (as every writer we know of does).

use std::path::Path;

use crate::{MeshData, MeshError};

#[derive(Clone, Copy, Debug, PartialEq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(name: &str) -> Option<Scalar> {
        Some(match name {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    fn is_float(self) -> bool {
        matches!(self, Scalar::F32 | Scalar::F64)
    }
}

#[derive(Clone, Copy, Debug)]
enum Kind {
    Scalar(Scalar),
    List(Scalar, Scalar),
}

struct Element {
    /// The header line that declares it.
    line: usize,
    name: String,
    count: usize,
    props: Vec<(String, Kind)>,
}

#[derive(Clone, Copy, PartialEq)]
enum Encoding {
    Ascii,
    Little,
    Big,
}

/// What a vertex property feeds: a slot of the position, normal or uv, or nothing.
#[derive(Clone, Copy)]
enum Slot {
    P(usize),
    N(usize),
    T(usize),
    Skip,
}

pub(crate) fn read(path: &Path, bytes: &[u8]) -> Result<MeshData, MeshError> {
    let at = |line: usize, what: String| MeshError::Line { path: path.to_path_buf(), line, what };
    // The header.
    let mut pos = 0;
    let mut line = 0;
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    loop {
        line += 1;
        let Some(nl) = bytes[pos..].iter().position(|&b| b == b'\n') else {
            return Err(at(line, "the header has no end_header line".into()));
        };
        let raw = &bytes[pos..pos + nl];
        pos += nl + 1;
        let text =
            std::str::from_utf8(raw).map_err(|_| at(line, "header line is not text".into()))?;
        let text = text.trim_end_matches('\r');
        let words: Vec<&str> = text.split_ascii_whitespace().collect();
        if line == 1 {
            if text != "ply" {
                return Err(at(line, "not a PLY file (the first line is not 'ply')".into()));
            }
            continue;
        }
        match words.as_slice() {
            ["format", f, "1.0"] => {
                encoding = Some(match *f {
                    "ascii" => Encoding::Ascii,
                    "binary_little_endian" => Encoding::Little,
                    "binary_big_endian" => Encoding::Big,
                    _ => return Err(at(line, format!("unknown PLY format '{f}'"))),
                })
            }
            ["format", ..] => {
                return Err(at(
                    line,
                    "expected 'format ascii|binary_little_endian|binary_big_endian 1.0'".into(),
                ));
            }
            ["comment", ..] | ["obj_info", ..] | [] => {}
            ["element", name, count] => {
                let count = count
                    .parse()
                    .map_err(|_| at(line, format!("element count '{count}' is not a number")))?;
                elements.push(Element { line, name: name.to_string(), count, props: Vec::new() });
            }
            ["property", rest @ ..] => {
                let Some(el) = elements.last_mut() else {
                    return Err(at(line, "property before any element".into()));
                };
                let ty = |t: &str| {
                    Scalar::parse(t).ok_or_else(|| at(line, format!("unknown property type '{t}'")))
                };
                let (name, kind) = match rest {
                    ["list", c, i, name] => {
                        let (c, i) = (ty(c)?, ty(i)?);
                        if c.is_float() {
                            return Err(at(line, "a list count must be an integer type".into()));
                        }
                        (name, Kind::List(c, i))
                    }
                    [t, name] => (name, Kind::Scalar(ty(t)?)),
                    _ => {
                        return Err(at(
                            line,
                            "expected 'property TYPE NAME' or 'property list CTYPE ITYPE NAME'"
                                .into(),
                        ));
                    }
                };
                el.props.push((name.to_string(), kind));
            }
            ["end_header"] => break,
            _ => return Err(at(line, format!("unexpected header line '{text}'"))),
        }
    }
    let Some(encoding) = encoding else {
        return Err(at(line, "the header has no format line".into()));
    };
    let header_lines = line;

    let n_vertices = elements.iter().filter(|e| e.name == "vertex").map(|e| e.count).sum::<usize>();
    if n_vertices > u32::MAX as usize {
        return Err(at(header_lines, "more than u32::MAX vertices".into()));
    }
    // Capacities from the header are capped by the file's size (every vertex or face takes
    // at least a byte), so a lying count cannot ask for more memory than the file is big.
    let cap = |count: usize| count.min(bytes.len());
    let mut mesh = MeshData::default();
    mesh.points.reserve(cap(n_vertices));
    let mut normals: Vec<[f32; 3]> = Vec::new();
    let mut uvs: Vec<[f32; 2]> = Vec::new();
    let mut has_normals = false;
    let mut has_uvs = false;

    let mut data = Data { bytes, pos, encoding, line: header_lines, words: None };
    for el in &elements {
        if el.props.is_empty() {
            // Nothing to read (and a binary file could claim any count of these).
            continue;
        }
        let mut slots = Vec::new();
        let mut list = None;
        if el.name == "vertex" {
            let find =
                |names: &[&str]| el.props.iter().position(|(n, _)| names.contains(&n.as_str()));
            let xyz = [find(&["x"]), find(&["y"]), find(&["z"])];
            let nxyz = [find(&["nx"]), find(&["ny"]), find(&["nz"])];
            let uv = [find(&["u", "s", "texture_u"]), find(&["v", "t", "texture_v"])];
            if xyz.iter().any(Option::is_none) {
                return Err(at(el.line, "the vertex element lacks x, y or z".into()));
            }
            has_normals = nxyz.iter().all(Option::is_some);
            has_uvs = uv.iter().all(Option::is_some);
            slots = vec![Slot::Skip; el.props.len()];
            for (k, p) in xyz.iter().enumerate() {
                slots[p.unwrap_or(0)] = Slot::P(k);
            }
            if has_normals {
                for (k, p) in nxyz.iter().enumerate() {
                    slots[p.unwrap_or(0)] = Slot::N(k);
                }
                normals.reserve(cap(el.count));
            }
            if has_uvs {
                for (k, p) in uv.iter().enumerate() {
                    slots[p.unwrap_or(0)] = Slot::T(k);
                }
                uvs.reserve(cap(el.count));
            }
            if let Some((name, _)) = el.props.iter().zip(&slots).find_map(|(p, s)| {
                matches!(s, Slot::P(_) | Slot::N(_) | Slot::T(_))
                    .then_some(p)
                    .filter(|p| matches!(p.1, Kind::List(..)))
            }) {
                return Err(at(el.line, format!("vertex property '{name}' is a list")));
            }
        } else if el.name == "face" {
            list = el.props.iter().position(|(n, _)| n == "vertex_indices" || n == "vertex_index");
            match list.map(|k| el.props[k].1) {
                Some(Kind::List(..)) => {}
                _ => {
                    return Err(at(el.line, "the face element lacks a vertex_indices list".into()));
                }
            }
            mesh.ends.reserve(cap(el.count));
        }
        for index in 0..el.count {
            let fail = |data: &Data, what: String| match encoding {
                Encoding::Ascii => {
                    MeshError::Line { path: path.to_path_buf(), line: data.line, what }
                }
                _ => MeshError::Element {
                    path: path.to_path_buf(),
                    element: el.name.clone(),
                    index,
                    what,
                },
            };
            data.start_record().map_err(|what| fail(&data, what))?;
            if el.name == "vertex" {
                let (mut p, mut n, mut t) = ([0f32; 3], [0f32; 3], [0f32; 2]);
                for ((name, kind), slot) in el.props.iter().zip(&slots) {
                    let x = match *kind {
                        Kind::Scalar(s) => data.scalar(s).map_err(|what| fail(&data, what))?,
                        Kind::List(c, i) => {
                            data.skip_list(c, i).map_err(|what| fail(&data, what))?;
                            continue;
                        }
                    } as f32;
                    if !matches!(slot, Slot::Skip) && !x.is_finite() {
                        return Err(fail(&data, format!("{name} is not finite")));
                    }
                    match *slot {
                        Slot::P(k) => p[k] = x,
                        Slot::N(k) => n[k] = x,
                        Slot::T(k) => t[k] = x,
                        Slot::Skip => {}
                    }
                }
                mesh.points.push(p);
                if has_normals {
                    normals.push(n);
                }
                if has_uvs {
                    uvs.push(t);
                }
            } else {
                for (k, (_, kind)) in el.props.iter().enumerate() {
                    match *kind {
                        Kind::Scalar(s) => {
                            data.scalar(s).map_err(|what| fail(&data, what))?;
                        }
                        Kind::List(c, i) if Some(k) == list => {
                            let count = data.count(c).map_err(|what| fail(&data, what))?;
                            if count < 3 {
                                return Err(fail(
                                    &data,
                                    format!("face has {count} vertices (at least 3 needed)"),
                                ));
                            }
                            if i.is_float() {
                                return Err(fail(&data, "vertex indices are not integers".into()));
                            }
                            for _ in 0..count {
                                let v = data.scalar(i).map_err(|what| fail(&data, what))?;
                                if v < 0.0 || v >= n_vertices as f64 || v.fract() != 0.0 {
                                    return Err(fail(
                                        &data,
                                        format!(
                                            "vertex index {v} out of range ({n_vertices} vertices)"
                                        ),
                                    ));
                                }
                                mesh.indices.push(v as u32);
                            }
                            if mesh.indices.len() > u32::MAX as usize {
                                return Err(fail(&data, "more than u32::MAX face indices".into()));
                            }
                            mesh.ends.push(mesh.indices.len() as u32);
                        }
                        Kind::List(c, i) => {
                            data.skip_list(c, i).map_err(|what| fail(&data, what))?
                        }
                    }
                }
            }
            data.end_record().map_err(|what| fail(&data, what))?;
        }
    }
    if has_normals {
        mesh.normals = Some(normals);
    }
    if has_uvs {
        mesh.uvs = Some(uvs);
    }
    Ok(mesh)
}

/// The element data after the header: a byte cursor (binary) or a line cursor (ASCII).
struct Data<'a> {
    bytes: &'a [u8],
    pos: usize,
    encoding: Encoding,
    /// The current line (ASCII).
    line: usize,
    /// The words of the current ASCII record left to read.
    words: Option<std::str::SplitAsciiWhitespace<'a>>,
}

const TRUNCATED: &str = "the file ends inside this element (truncated)";

impl<'a> Data<'a> {
    fn start_record(&mut self) -> Result<(), String> {
        if self.encoding != Encoding::Ascii {
            return Ok(());
        }
        // One record per non-blank line.
        loop {
            if self.pos >= self.bytes.len() {
                self.line += 1;
                return Err("the file ends before this element (truncated)".into());
            }
            let rest = &self.bytes[self.pos..];
            let nl = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
            self.pos += nl + 1;
            self.line += 1;
            let text =
                std::str::from_utf8(&rest[..nl]).map_err(|_| "the line is not text".to_string())?;
            if !text.trim().is_empty() {
                self.words = Some(text.split_ascii_whitespace());
                return Ok(());
            }
        }
    }

    fn end_record(&mut self) -> Result<(), String> {
        match self.words.as_mut().and_then(Iterator::next) {
            Some(w) => Err(format!("unexpected value '{w}' after the element's properties")),
            None => Ok(()),
        }
    }

    fn take<const N: usize>(&mut self) -> Result<[u8; N], String> {
        let b = self.bytes.get(self.pos..self.pos + N).ok_or(TRUNCATED)?;
        self.pos += N;
        let mut a: [u8; N] = b.try_into().map_err(|_| TRUNCATED)?;
        if self.encoding == Encoding::Big {
            a.reverse();
        }
        Ok(a)
    }

    fn scalar(&mut self, s: Scalar) -> Result<f64, String> {
        if self.encoding == Encoding::Ascii {
            let w = self
                .words
                .as_mut()
                .and_then(Iterator::next)
                .ok_or("the line ends before the element's last property")?;
            let x: f64 = w.parse().map_err(|_| format!("'{w}' is not a number"))?;
            if !s.is_float() && x.fract() != 0.0 {
                return Err(format!("'{w}' is not an integer"));
            }
            return Ok(x);
        }
        // Bytes are in little-endian order after `take`.
        Ok(match s {
            Scalar::I8 => i8::from_le_bytes(self.take()?) as f64,
            Scalar::U8 => u8::from_le_bytes(self.take()?) as f64,
            Scalar::I16 => i16::from_le_bytes(self.take()?) as f64,
            Scalar::U16 => u16::from_le_bytes(self.take()?) as f64,
            Scalar::I32 => i32::from_le_bytes(self.take()?) as f64,
            Scalar::U32 => u32::from_le_bytes(self.take()?) as f64,
            Scalar::F32 => f32::from_le_bytes(self.take()?) as f64,
            Scalar::F64 => f64::from_le_bytes(self.take()?),
        })
    }

    fn count(&mut self, c: Scalar) -> Result<usize, String> {
        let n = self.scalar(c)?;
        if n < 0.0 {
            return Err(format!("negative list length {n}"));
        }
        Ok(n as usize)
    }

    fn skip_list(&mut self, c: Scalar, i: Scalar) -> Result<(), String> {
        let n = self.count(c)?;
        if self.encoding == Encoding::Ascii {
            for _ in 0..n {
                self.scalar(i)?;
            }
        } else {
            let len = n.checked_mul(i.size()).ok_or(TRUNCATED)?;
            if self.bytes.len() - self.pos.min(self.bytes.len()) < len {
                return Err(TRUNCATED.into());
            }
            self.pos += len;
        }
        Ok(())
    }
}
