//! Tolerant RON scanner that maps field paths (`objects[0].shape.radius`) to source positions.
//!
//! Invariants: never panics and never recurses, whatever the input (malformed RON, unclosed
//! strings, comments or brackets included); positions are 1-based lines split on `'\n'` and
//! 1-based columns counted in `char`s, exactly as ron counts them, so the two can be compared.
//! Path rules: struct fields by name, list and tuple elements by index, a named body
//! (`Sphere(..)`, `Some(..)`) is transparent, and a named body holding exactly one positional
//! element (a newtype variant such as `Translate((..))`) gives that element its own path.
//!
//! The tokens come from `scan`; this module builds the tree of values from them and answers
//! the path and position queries.

mod scan;

pub(crate) use scan::Pos;
use scan::{Tok, Token, Tokens, tokenize};

/// One step of a path.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Seg<'a> {
    /// A top-level value.
    Root,
    /// A struct field.
    Field(&'a str),
    /// A list or tuple element.
    Index(usize),
}

/// One value in the source.
#[derive(Debug, Clone)]
struct Node<'a> {
    parent: Option<usize>,
    seg: Seg<'a>,
    /// First character of the value.
    start: Pos,
    /// Last character of the value (its closing bracket), or end of input if unclosed.
    end: Pos,
    depth: usize,
    /// A named body with exactly one positional element: that element shares this path.
    newtype: bool,
}

/// Where the next token goes in an open group.
#[derive(Debug, Clone, Copy)]
enum Expect<'a> {
    /// A new element (after the opener or a comma).
    Item,
    /// The value of the named field.
    Value(&'a str),
    /// A comma or the closer (an element was just read).
    Separator,
}

/// The place of one token in the tree: which value a value written there would be.
#[derive(Debug, Clone, Copy)]
struct Slot<'a> {
    /// The innermost open group (its node), if any.
    frame: Option<usize>,
    kind: SlotKind<'a>,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum SlotKind<'a> {
    /// The value of the named field (the token follows `name:`).
    Field(&'a str),
    /// Element `i` of a list or tuple (the token follows its opener or a comma).
    Element(usize),
    /// No value's place: a field name, or where a separator is due.
    Between,
}

const NO_SLOT: Slot<'static> = Slot { frame: None, kind: SlotKind::Between };

/// The slot of the next token in `frame` (the innermost open group).
fn slot_in<'a>(frame: Option<&Frame<'a>>) -> Slot<'a> {
    let Some(f) = frame else { return NO_SLOT };
    let kind = match f.expect {
        Expect::Value(name) => SlotKind::Field(name),
        // A list, or a group that has held elements but no fields: a tuple.
        Expect::Item
            if f.closer == ']' || (f.closer == ')' && f.fields == 0 && f.positional > 0) =>
        {
            SlotKind::Element(f.positional)
        }
        Expect::Item | Expect::Separator => SlotKind::Between,
    };
    Slot { frame: Some(f.node), kind }
}

/// An open `(..)`, `[..]` or `{..}`.
struct Frame<'a> {
    node: usize,
    closer: char,
    named: bool,
    positional: usize,
    fields: usize,
    expect: Expect<'a>,
}

/// The values of a RON text, with their paths and positions.
pub(crate) struct SourceMap<'a> {
    nodes: Vec<Node<'a>>,
    tokens: Vec<Token<'a>>,
    /// Per token, its slot (tokens read together with the one before have [`NO_SLOT`]).
    slots: Vec<Slot<'a>>,
    /// Where a block comment that never ends starts.
    pub unclosed_comment: Option<Pos>,
}

impl<'a> SourceMap<'a> {
    /// Scans `src` tolerantly: malformed input yields a best-effort map, never a failure.
    pub(crate) fn scan(src: &'a str) -> Self {
        let Tokens { tokens, eof, unclosed_comment } = tokenize(src);
        let mut nodes: Vec<Node<'a>> = Vec::new();
        let mut stack: Vec<Frame<'a>> = Vec::new();
        // Open frames per closer kind, so a stray closer costs O(1), not a scan of the stack.
        let mut open = OpenCounts::default();
        let mut slots = vec![NO_SLOT; tokens.len()];
        let mut k = 0;
        while let Some(token) = tokens.get(k) {
            if let Some(slot) = slots.get_mut(k) {
                *slot = slot_in(stack.last());
            }
            k += 1;
            let next = tokens.get(k).map(|t| t.tok);
            match token.tok {
                // `#![enable(..)]` attributes before the top-level value: skip them.
                Tok::Other('#') if stack.is_empty() => {
                    k = skip_attribute(&tokens, k);
                }
                Tok::Ident(name)
                    if next == Some(Tok::Colon)
                        && stack.last().is_some_and(|f| {
                            f.closer == ')' && !matches!(f.expect, Expect::Value(_))
                        }) =>
                {
                    k += 1;
                    if let Some(frame) = stack.last_mut() {
                        frame.expect = Expect::Value(name);
                    }
                }
                Tok::Ident(_) if next == Some(Tok::Open(')')) => {
                    k += 1;
                    let node = push_value(&mut nodes, &mut stack, token.start);
                    open.add(')');
                    stack.push(open_frame(node, ')', true));
                }
                Tok::Open(closer) => {
                    let node = push_value(&mut nodes, &mut stack, token.start);
                    open.add(closer);
                    stack.push(open_frame(node, closer, false));
                }
                Tok::Ident(_) | Tok::Atom | Tok::Number(_) => {
                    let node = push_value(&mut nodes, &mut stack, token.start);
                    if let Some(n) = nodes.get_mut(node) {
                        n.end = token.end;
                    }
                }
                // Every frame above the matching one is popped with it, so the scan is
                // amortised over the pops and the whole loop stays linear.
                Tok::Close(c) if open.has(c) => {
                    while let Some(frame) = stack.pop() {
                        open.remove(frame.closer);
                        if frame.closer == c {
                            close_frame(&mut nodes, &frame, token.end);
                            break;
                        }
                        close_frame(&mut nodes, &frame, token.start);
                    }
                }
                Tok::Close(_) => {}
                Tok::Comma => {
                    if let Some(frame) = stack.last_mut() {
                        frame.expect = Expect::Item;
                    }
                }
                Tok::Colon | Tok::Other(_) => {}
            }
        }
        while let Some(frame) = stack.pop() {
            close_frame(&mut nodes, &frame, eof);
        }
        SourceMap { nodes, tokens, slots, unclosed_comment }
    }

    /// The path of node `index`, e.g. `objects[0].shape.radius` (empty for the top level).
    fn path_of(&self, index: usize) -> String {
        let mut segs = Vec::new();
        let mut at = Some(index);
        while let Some(i) = at {
            let Some(node) = self.nodes.get(i) else { break };
            let transparent =
                node.parent.and_then(|p| self.nodes.get(p)).is_some_and(|parent| parent.newtype);
            if !transparent {
                segs.push(node.seg);
            }
            at = node.parent;
        }
        let mut path = String::new();
        for seg in segs.iter().rev() {
            push_seg(&mut path, *seg);
        }
        path
    }

    /// Position of the value at `path`, else of its nearest ancestor that is written in the
    /// source (the top level excluded), else `None`.
    pub(crate) fn find(&self, path: &str) -> Option<Pos> {
        let mut paths: Vec<String> = Vec::with_capacity(self.nodes.len());
        for node in &self.nodes {
            let parent = node.parent.and_then(|p| paths.get(p).map(|s| (s, p)));
            let path = match parent {
                None => {
                    let mut s = String::new();
                    push_seg(&mut s, node.seg);
                    s
                }
                Some((base, p)) => {
                    let mut s = base.clone();
                    if !self.nodes.get(p).is_some_and(|n| n.newtype) {
                        push_seg(&mut s, node.seg);
                    }
                    s
                }
            };
            paths.push(path);
        }
        let mut want = path;
        while !want.is_empty() {
            if let Some(i) = paths.iter().position(|p| p == want) {
                return self.nodes.get(i).map(|n| n.start);
            }
            want = parent_path(want);
        }
        None
    }

    /// The path of the innermost value whose extent contains `pos` (empty if none).
    pub(crate) fn path_at(&self, pos: Pos) -> String {
        let mut best: Option<(usize, usize)> = None;
        for (i, node) in self.nodes.iter().enumerate() {
            if node.start <= pos && pos <= node.end && best.is_none_or(|(d, _)| node.depth > d) {
                best = Some((node.depth, i));
            }
        }
        best.map(|(_, i)| self.path_of(i)).unwrap_or_default()
    }

    /// The path of what stands at `pos` (a token start): the innermost value containing it,
    /// except where no value starts there but one is due (after `name:`, or after the opener
    /// or a comma of a list or tuple): then the path of the value due, e.g. `image.width` for
    /// the second colon of `(width: : 640)` and `eye[1]` for the colon of `eye: (0.0, :)`.
    pub(crate) fn path_for(&self, pos: Pos) -> String {
        let Some(k) = self.tokens.iter().position(|t| t.start == pos) else {
            return self.path_at(pos);
        };
        if self.nodes.iter().any(|n| n.start == pos) {
            return self.path_at(pos);
        }
        let (Some(slot), Some(token)) = (self.slots.get(k), self.tokens.get(k)) else {
            return self.path_at(pos);
        };
        let Some(frame) = slot.frame else { return self.path_at(pos) };
        let base = self.path_of(frame);
        let newtype = self.nodes.get(frame).is_some_and(|n| n.newtype);
        match slot.kind {
            SlotKind::Field(name) => join(&base, name),
            // A closer after a comma ends the group: no element is due.
            SlotKind::Element(_) if matches!(token.tok, Tok::Close(_)) || newtype => base,
            SlotKind::Element(i) => {
                let mut path = base;
                push_seg(&mut path, Seg::Index(i));
                path
            }
            SlotKind::Between => self.path_at(pos),
        }
    }

    /// `struct.name` for the field name just before `pos`, when it is an identifier inside a
    /// group (a field name missing its colon, `(width 640)`); `None` otherwise.
    pub(crate) fn field_before(&self, pos: Pos) -> Option<String> {
        let token = self.tokens.iter().rev().find(|t| t.end < pos)?;
        let Tok::Ident(name) = token.tok else { return None };
        let node = self.nodes.iter().find(|n| n.start == token.start)?;
        let parent = node.parent?;
        Some(join(&self.path_of(parent), name))
    }

    /// The number written at `pos`, if `pos` lies on one: its first character's position
    /// and its text.
    pub(crate) fn number_around(&self, pos: Pos) -> Option<(Pos, &'a str)> {
        let token = self.tokens.iter().find(|t| t.start <= pos && pos <= t.end)?;
        match token.tok {
            Tok::Number(text) => Some((token.start, text)),
            _ => None,
        }
    }

    /// True if no token ends at or after `pos` (only whitespace and comments remain).
    pub(crate) fn is_past_last_token(&self, pos: Pos) -> bool {
        self.tokens.last().is_none_or(|t| t.end < pos)
    }

    /// Moves `start` forward over whitespace and comments to the next token, without passing
    /// `limit` (when `limit` is after `start`). A position inside a token is kept.
    pub(crate) fn snap(&self, start: Pos, limit: Pos) -> Pos {
        let first_after = self.tokens.iter().find(|t| t.end >= start);
        match first_after {
            Some(t) if t.start <= start => start,
            Some(t) if t.start <= limit.max(start) => t.start,
            _ => start,
        }
    }
}

/// Skips the rest of an attribute whose `#` was just read: `!`, then one bracketed group.
/// Returns the index of the first token after it.
fn skip_attribute(tokens: &[Token<'_>], mut k: usize) -> usize {
    if tokens.get(k).map(|t| t.tok) == Some(Tok::Other('!')) {
        k += 1;
    }
    if tokens.get(k).map(|t| t.tok) != Some(Tok::Open(']')) {
        return k;
    }
    let mut depth = 0usize;
    while let Some(t) = tokens.get(k) {
        k += 1;
        match t.tok {
            Tok::Open(_) => depth += 1,
            Tok::Close(_) => {
                depth = depth.saturating_sub(1);
                if depth == 0 {
                    break;
                }
            }
            _ => {}
        }
    }
    k
}

/// How many frames of each kind are open.
#[derive(Default)]
struct OpenCounts {
    paren: usize,
    bracket: usize,
    brace: usize,
}

impl OpenCounts {
    fn slot(&mut self, closer: char) -> &mut usize {
        match closer {
            ')' => &mut self.paren,
            ']' => &mut self.bracket,
            _ => &mut self.brace,
        }
    }

    fn add(&mut self, closer: char) {
        *self.slot(closer) += 1;
    }

    fn remove(&mut self, closer: char) {
        let n = self.slot(closer);
        *n = n.saturating_sub(1);
    }

    fn has(&mut self, closer: char) -> bool {
        *self.slot(closer) > 0
    }
}

fn open_frame<'a>(node: usize, closer: char, named: bool) -> Frame<'a> {
    Frame { node, closer, named, positional: 0, fields: 0, expect: Expect::Item }
}

fn close_frame(nodes: &mut [Node<'_>], frame: &Frame<'_>, end: Pos) {
    if let Some(node) = nodes.get_mut(frame.node) {
        node.end = end.max(node.start);
        node.newtype = frame.named && frame.positional == 1 && frame.fields == 0;
    }
}

/// Records a value starting at `start` as the next element of the innermost open group.
fn push_value<'a>(nodes: &mut Vec<Node<'a>>, stack: &mut [Frame<'a>], start: Pos) -> usize {
    let (parent, seg, depth) = match stack.last_mut() {
        None => (None, Seg::Root, 0),
        Some(frame) => {
            let seg = match frame.expect {
                Expect::Value(name) => {
                    frame.fields += 1;
                    Seg::Field(name)
                }
                Expect::Item | Expect::Separator => {
                    frame.positional += 1;
                    Seg::Index(frame.positional - 1)
                }
            };
            frame.expect = Expect::Separator;
            let depth = nodes.get(frame.node).map_or(0, |n| n.depth + 1);
            (Some(frame.node), seg, depth)
        }
    };
    nodes.push(Node { parent, seg, start, end: start, depth, newtype: false });
    nodes.len() - 1
}

fn push_seg(path: &mut String, seg: Seg<'_>) {
    match seg {
        Seg::Root => {}
        Seg::Field(name) => {
            if !path.is_empty() {
                path.push('.');
            }
            path.push_str(name);
        }
        Seg::Index(i) => {
            path.push('[');
            path.push_str(&i.to_string());
            path.push(']');
        }
    }
}

/// `a.b[2]` -> `a.b`, `a.b` -> `a`, `a` -> ``.
pub(crate) fn parent_path(path: &str) -> &str {
    let cut = if path.ends_with(']') { path.rfind('[') } else { path.rfind('.') };
    cut.and_then(|i| path.get(..i)).unwrap_or("")
}

/// Appends a field name to a path (`""` + `a` is `a`).
pub(crate) fn join(base: &str, field: &str) -> String {
    if base.is_empty() { field.to_string() } else { format!("{base}.{field}") }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(line: usize, col: usize) -> Option<Pos> {
        Some(Pos { line, col })
    }

    #[test]
    fn fields_lists_tuples_and_variants() {
        let src = "Scene(\n  image: (width: 1, height: 2),\n  objects: [(shape: Sphere(radius: -1.0)),\n    (shape: Mesh(faces: [[0, 1, 2], [3, 4, 5, 6, 7]]))],\n  hider: (pixel_samples: (4, 0)),\n)";
        let map = SourceMap::scan(src);
        assert_eq!(map.find("image.height"), at(2, 29));
        assert_eq!(map.find("objects[0].shape.radius"), at(3, 36));
        assert_eq!(map.find("objects[1].shape.faces[1][4]"), at(4, 50));
        assert_eq!(map.find("hider.pixel_samples[1]"), at(5, 30));
        // Missing: the nearest ancestor written in the source.
        assert_eq!(map.find("objects[0].shape.zmin"), at(3, 21));
        assert_eq!(map.find("camera.fov"), None);
    }

    #[test]
    fn newtypes_are_transparent() {
        let src = "(t: [Translate((1, 2, 3)), Scale((1, 0, 1))], lens: Some((f_stop: 2)))";
        let map = SourceMap::scan(src);
        assert_eq!(map.find("t[0]"), at(1, 6));
        assert_eq!(map.find("t[1][1]"), at(1, 38));
        assert_eq!(map.find("lens.f_stop"), at(1, 67));
    }

    /// CSG trees: variant names are transparent, `Union([..])` and `Object("..")` share their
    /// path with their one value, and `Difference(a, b)` indexes its two operands.
    #[test]
    fn csg_operands_are_indexed() {
        let src = "(tree: Difference(Union([Object(\"a\"), Object(\"b\")]), Object(\"c\")))";
        let map = SourceMap::scan(src);
        assert_eq!(map.find("tree"), at(1, 8));
        assert_eq!(map.find("tree[0]"), at(1, 19));
        assert_eq!(map.find("tree[0][1]"), at(1, 39));
        assert_eq!(map.find("tree[1]"), at(1, 54));
        assert_eq!(map.path_at(Pos { line: 1, col: 46 }), "tree[0][1]");
    }

    /// The paths of the ray-tracing fields: an area light's shape and motion keys, `Some(..)`
    /// around `reflect`, `refract`, `pattern` and `roll` (transparent), the roll's path keys,
    /// and the `hider.method` and `raytrace` values.
    #[test]
    fn ray_tracing_paths() {
        let src = "(hider: (method: RayTrace),
 lights: [Point(from: (0.0, 1.0, 0.0), shadows: true),
  Area(shape: Sphere(center: (0.0, 9.0, 0.0), radius: -1.0),
       motion: [(time: 0.0), (time: 2.0, offset: (1.0, 0.0, 0.0))])],
 objects: [(reflect: Some((color: (1.0, 1.0, 1.0), gloss: -5.0)),
            refract: Some(Refract(ior: -1.0, blur: 1.0)),
            pattern: Some(PoolBall(color: (2.0, 0.0, 0.0))),
            roll: Some((radius: 1.0, path: [(time: 0.0, position: (0.0, 1.0, 0.0)),
                                             (time: 0.5, position: (1.0, 1.0, 0.0)),
                                             (time: 0.4, position: (2.0, 1.0, 0.0))]))),
 ],
 raytrace: (max_depth: 0))";
        let map = SourceMap::scan(src);
        assert_eq!(map.find("hider.method"), at(1, 18));
        assert_eq!(map.find("lights[0].shadows"), at(2, 49));
        assert_eq!(map.find("lights[1].shape.radius"), at(3, 55));
        assert_eq!(map.find("lights[1].shape.center[1]"), at(3, 36));
        assert_eq!(map.find("lights[1].motion[1].time"), at(4, 37));
        assert_eq!(map.find("lights[1].motion[1].offset[0]"), at(4, 51));
        // Absent: the key itself.
        assert_eq!(map.find("lights[1].motion[0].intensity"), at(4, 17));
        assert_eq!(map.find("objects[0].reflect.gloss"), at(5, 59));
        assert_eq!(map.find("objects[0].refract.ior"), at(6, 40));
        // Absent: the nearest value written, `Some(..)`, which shares the path of its content.
        assert_eq!(map.find("objects[0].refract.color[0]"), at(6, 22));
        assert_eq!(map.find("objects[0].pattern.color[0]"), at(7, 44));
        assert_eq!(map.find("objects[0].roll"), at(8, 19));
        assert_eq!(map.find("objects[0].roll.radius"), at(8, 33));
        assert_eq!(map.find("objects[0].roll.path[2].time"), at(10, 53));
        assert_eq!(map.find("objects[0].roll.path[1].position[0]"), at(9, 69));
        assert_eq!(map.find("objects[0].roll.steps"), at(8, 19));
        assert_eq!(map.find("raytrace.max_depth"), at(12, 24));
        assert_eq!(map.find("raytrace.vertex_rays"), at(12, 12));
    }

    #[test]
    fn strings_comments_and_raw_literals_are_skipped() {
        let src = "#![enable(implicit_some)]\n( /* a: (1) /* nested */ */ a: \"x:(\\\"\", // b: 9\n b: r#\"]\"#, c: 'x', d: r#e, f: [1e-3, -inf])";
        let map = SourceMap::scan(src);
        assert_eq!(map.find("a"), at(2, 32));
        assert_eq!(map.find("b"), at(3, 5));
        assert_eq!(map.find("c"), at(3, 16));
        assert_eq!(map.find("d"), at(3, 24));
        assert_eq!(map.find("f[1]"), at(3, 39));
        assert_eq!(map.find("e"), None);
    }

    #[test]
    fn innermost_value_at_a_position() {
        let src = "(a: (b: [1, 2], c: 3), d: 4)";
        let map = SourceMap::scan(src);
        assert_eq!(map.path_at(Pos { line: 1, col: 13 }), "a.b[1]");
        assert_eq!(map.path_at(Pos { line: 1, col: 14 }), "a.b");
        assert_eq!(map.path_at(Pos { line: 1, col: 15 }), "a");
        assert_eq!(map.path_at(Pos { line: 1, col: 17 }), "a");
        assert_eq!(map.path_at(Pos { line: 1, col: 2 }), "");
    }

    /// Where no value starts but one is due, the path is that of the value due; elsewhere it
    /// is the innermost value's.
    #[test]
    fn the_value_due_at_punctuation() {
        let src = "(a: (b: : 1, c: [:, 2], d: (1.0, :), e:), f: (g 1))";
        let map = SourceMap::scan(src);
        let p = |col| map.path_for(Pos { line: 1, col });
        assert_eq!(p(9), "a.b");
        assert_eq!(p(18), "a.c[0]");
        assert_eq!(p(34), "a.d[1]");
        assert_eq!(p(40), "a.e");
        // A value starts here: its own path (the colon before it held no element).
        assert_eq!(p(21), "a.c[0]");
        // A field name: the struct.
        assert_eq!(p(14), "a");
        assert_eq!(map.field_before(Pos { line: 1, col: 49 }).as_deref(), Some("f.g"));
        assert_eq!(
            map.number_around(Pos { line: 1, col: 31 }),
            Some((Pos { line: 1, col: 29 }, "1.0"))
        );
        assert_eq!(map.number_around(Pos { line: 1, col: 28 }), None);
    }

    #[test]
    fn malformed_input_is_tolerated() {
        for src in ["", "(", ")", "((a: [", "\"unclosed", "/* open", "r#\"x", "a: : ,, ]] (", "#"] {
            let map = SourceMap::scan(src);
            let _ = map.find("a.b[0]");
            let _ = map.path_at(Pos { line: 1, col: 1 });
        }
    }

    #[test]
    fn parent_paths() {
        assert_eq!(parent_path("a.b[2]"), "a.b");
        assert_eq!(parent_path("a.b"), "a");
        assert_eq!(parent_path("a"), "");
        assert_eq!(join("", "x"), "x");
        assert_eq!(join("a", "x"), "a.x");
    }
}
