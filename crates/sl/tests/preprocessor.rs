//! The C preprocessor: includes on a search path, macros (object- and function-like, `#`, `##`,
//! variadic), conditionals, `#line`, line continuation, and the position every token keeps.

use std::fs;
use std::path::PathBuf;

use reyes_sl::{Options, SlError, Source, compile_file, compile_str, preprocess};

/// The spellings of the preprocessed tokens, space-separated.
fn text(src: &str) -> String {
    spellings(preprocess(Source::Text { name: "t.sl", text: src }, &Options::default()).unwrap())
}

fn spellings(toks: Vec<(String, String)>) -> String {
    toks.into_iter().map(|t| t.0).collect::<Vec<_>>().join(" ")
}

/// Each token with its position.
fn positioned(src: &str) -> Vec<(String, String)> {
    preprocess(Source::Text { name: "t.sl", text: src }, &Options::default()).unwrap()
}

fn error(src: &str) -> String {
    preprocess(Source::Text { name: "t.sl", text: src }, &Options::default())
        .unwrap_err()
        .to_string()
}

#[test]
fn object_and_function_macros() {
    assert_eq!(text("#define N 3\nN + N"), "3 + 3");
    assert_eq!(text("#define SQ(x) ((x)*(x))\nSQ(a+1)"), "( ( a + 1 ) * ( a + 1 ) )");
    assert_eq!(text("#define F(a, b) b a\nF((1, 2), g(3, 4))"), "g ( 3 , 4 ) ( 1 , 2 )");
    assert_eq!(text("#define E() 7\nE()"), "7");
    // A function-like macro's name without '(' is left alone.
    assert_eq!(text("#define F(x) x\nF + 1"), "F + 1");
    // Nested: arguments are expanded before substitution, and the result is rescanned.
    assert_eq!(text("#define A 1\n#define ID(x) x\n#define B ID(A)\nB"), "1");
    assert_eq!(text("#define N 3\n#undef N\nN"), "N");
}

#[test]
fn recursive_macros_stop() {
    assert_eq!(text("#define X X + 1\nX"), "X + 1");
    assert_eq!(text("#define A B\n#define B A\nA B"), "A B");
    assert_eq!(text("#define F(x) F(x) * 2\nF(3)"), "F ( 3 ) * 2");
}

#[test]
fn stringizing_pasting_and_variadic() {
    assert_eq!(text("#define S(x) #x\nS(a  +   \"b\")"), "\"a + \\\"b\\\"\"");
    assert_eq!(text("#define CAT(a, b) a ## b\nCAT(Ka, mb) CAT(1, 5)"), "Kamb 15");
    assert_eq!(text("#define V(f, ...) f(__VA_ARGS__)\nV(max, 1, 2, 3)"), "max ( 1 , 2 , 3 )");
    assert_eq!(text("#define V(...) [__VA_ARGS__]\nV()"), "[ ]");
    // Pasted operands are not expanded first.
    assert_eq!(text("#define N 1\n#define CAT(a, b) a ## b\nCAT(N, 2)"), "N2");
}

#[test]
fn conditionals() {
    let src = "#define A 2\n#if A > 1 && defined(A) && !defined B\nyes\n#elif 1\nno1\n#else\nno2\n#endif\n";
    assert_eq!(text(src), "yes");
    assert_eq!(text("#if 0\na\n#elif 0\nb\n#elif 1\nc\n#else\nd\n#endif"), "c");
    assert_eq!(text("#ifdef U\na\n#else\nb\n#endif"), "b");
    assert_eq!(text("#ifndef U\na\n#endif"), "a");
    assert_eq!(text("#if 0\n#if 1\nx\n#endif\n#else\ny\n#endif"), "y");
    // Skipped text may hold what would not lex, and unknown directives.
    assert_eq!(text("#if 0\ndon't @ 1x \"open\n#frobnicate\n#endif\nok"), "ok");
    // Operands that && || ?: skip are not evaluated.
    assert_eq!(text("#if 0 && 1 / 0\na\n#elif 1 || 1 / 0\nb\n#endif"), "b");
    assert_eq!(text("#if 1 ? 2 : 1 / 0\nc\n#endif"), "c");
    // Integer arithmetic, unknown names are 0.
    assert_eq!(
        text(
            "#if (1 << 3) == 8 && 7 % 4 == 3 && -1 < 0 && UNKNOWN == 0 && (1 ? 2 : 3) == 2\nok\n#endif"
        ),
        "ok"
    );
}

#[test]
fn line_continuation_and_comments() {
    assert_eq!(text("#define LONG(a) a + \\\n  a\nLONG(x) /* c */ // d\ny"), "x + x y");
    let p = positioned("a \\\n b\nc");
    assert_eq!(p[1].1, "t.sl:2:2");
    assert_eq!(p[2].1, "t.sl:3:1");
}

#[test]
fn macro_tokens_take_the_expansion_site() {
    let p = positioned("#define TWO 1 + 1\n#define ID(x) x\nfloat y = TWO;\n  z = ID(  w);");
    let at: Vec<(&str, &str)> = p.iter().map(|(a, b)| (a.as_str(), b.as_str())).collect();
    assert_eq!(
        at,
        [
            ("float", "t.sl:3:1"),
            ("y", "t.sl:3:7"),
            ("=", "t.sl:3:9"),
            ("1", "t.sl:3:11"),
            ("+", "t.sl:3:11"),
            ("1", "t.sl:3:11"),
            (";", "t.sl:3:14"),
            ("z", "t.sl:4:3"),
            ("=", "t.sl:4:5"),
            // An argument keeps its own position.
            ("w", "t.sl:4:12"),
            (";", "t.sl:4:14"),
        ]
    );
}

#[test]
fn line_and_file_macros() {
    assert_eq!(text("\n  __LINE__ __FILE__"), "2 \"t.sl\"");
}

#[test]
fn line_directive() {
    let p = positioned("a\n#line 100\nb\nc\n#line 7 \"orig.sl\"\nd");
    assert_eq!(p[1].1, "t.sl:100:1");
    assert_eq!(p[2].1, "t.sl:101:1");
    assert_eq!(p[3].1, "orig.sl:7:1");
    // Errors after #line report the given file and line.
    let e =
        compile_str("t.sl", "#line 40 \"gen.sl\"\nsurface s() { Ci = nope; }", &[]).unwrap_err();
    assert_eq!(e.to_string(), "gen.sl:40:20: undeclared variable \"nope\"");
}

#[test]
fn error_macro_and_defines_option() {
    assert_eq!(
        error("#ifndef X\n#error X is not defined\n#endif"),
        "t.sl:2:1: #error X is not defined"
    );
    let opts = Options { defines: vec![("X".into(), "2".into())], ..Options::default() };
    let toks =
        preprocess(Source::Text { name: "t.sl", text: "#if X == 2\nok\n#endif" }, &opts).unwrap();
    assert_eq!(spellings(toks), "ok");
}

/// A folder with `shader.sl` including headers from its own folder and from an include path.
fn tree() -> (tempfile::TempDir, PathBuf, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("src");
    let inc = dir.path().join("inc");
    fs::create_dir_all(&src).unwrap();
    fs::create_dir_all(&inc).unwrap();
    // The including file's folder is searched first for quoted names.
    fs::write(src.join("local.h"), "#define FROM_LOCAL 1\n").unwrap();
    fs::write(inc.join("local.h"), "#define FROM_INC 1\n").unwrap();
    fs::write(
        inc.join("lib.h"),
        "#include \"nested.h\"\nfloat half(float x) { return x * HALF; }\n",
    )
    .unwrap();
    fs::write(inc.join("nested.h"), "#define HALF 0.5\n").unwrap();
    fs::write(
        src.join("shader.sl"),
        "#include \"local.h\"\n#include <lib.h>\n#if FROM_LOCAL && !defined(FROM_INC)\nsurface s() { Ci = half(1); }\n#endif\n",
    )
    .unwrap();
    (dir, src, inc)
}

#[test]
fn includes_search_the_including_folder_then_the_path() {
    let (_dir, src, inc) = tree();
    let s = compile_file(&src.join("shader.sl"), std::slice::from_ref(&inc)).unwrap();
    assert_eq!(s.name, "s");
    assert_eq!(s.functions[0].name, "half");
    // The function's position is in the header.
    let file = s.sources.name(s.functions[0].pos.file);
    assert!(file.ends_with("inc/lib.h"), "{file}");
    assert_eq!((s.functions[0].pos.line, s.functions[0].pos.col), (2, 7));
    // Without the include path, <lib.h> is not found.
    let e = compile_file(&src.join("shader.sl"), &[]).unwrap_err();
    assert!(
        e.to_string().ends_with(
            "src/shader.sl:2:1: #include <lib.h>: file not found (no include path given)"
        ),
        "{e}"
    );
    assert_eq!(e.exit_code(), 2);
}

#[test]
fn errors_in_headers_name_the_header() {
    let (_dir, src, inc) = tree();
    fs::write(inc.join("bad.h"), "\n  float f() { return 1 +; }\n").unwrap();
    fs::write(src.join("b.sl"), "#include \"bad.h\"\nsurface s() {}\n").unwrap();
    let e = compile_file(&src.join("b.sl"), std::slice::from_ref(&inc)).unwrap_err();
    let msg = e.to_string();
    assert!(msg.ends_with("inc/bad.h:2:25: expected an expression, got ';'"), "{msg}");
    // A macro from a header used in the shader reports the use, in the shader.
    fs::write(inc.join("m.h"), "#define BAD (1 +)\n").unwrap();
    fs::write(src.join("m.sl"), "#include <m.h>\nsurface s() {\n  Ci = BAD;\n}\n").unwrap();
    let e = compile_file(&src.join("m.sl"), &[inc]).unwrap_err().to_string();
    assert!(e.ends_with("src/m.sl:3:8: expected an expression, got ')'"), "{e}");
}

#[test]
fn include_names_may_come_from_macros() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("h.h"), "float h() { return 2; }\n").unwrap();
    let src = "#define HEADER \"h.h\"\n#include HEADER\nsurface s() { Ci = h(); }\n";
    fs::write(dir.path().join("s.sl"), src).unwrap();
    assert_eq!(compile_file(&dir.path().join("s.sl"), &[]).unwrap().functions[0].name, "h");
    let src = "#define SYS <h.h>\n#include SYS\nsurface s() { Ci = h(); }\n";
    fs::write(dir.path().join("t.sl"), src).unwrap();
    let inc = vec![dir.path().to_path_buf()];
    assert_eq!(compile_file(&dir.path().join("t.sl"), &inc).unwrap().functions[0].name, "h");
}

#[test]
fn self_inclusion_is_stopped() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(dir.path().join("loop.h"), "#include \"loop.h\"\n").unwrap();
    fs::write(dir.path().join("s.sl"), "#include \"loop.h\"\nsurface s() {}\n").unwrap();
    let e = compile_file(&dir.path().join("s.sl"), &[]).unwrap_err().to_string();
    assert!(e.contains("loop.h:1:1: #include \"loop.h\": includes nested more than 64 deep (does a file include itself?)"), "{e}");
}

#[test]
fn include_guards_work() {
    let dir = tempfile::tempdir().unwrap();
    fs::write(
        dir.path().join("g.h"),
        "#ifndef G_H\n#define G_H\nfloat g() { return 1; }\n#endif\n",
    )
    .unwrap();
    fs::write(
        dir.path().join("s.sl"),
        "#include \"g.h\"\n#include \"g.h\"\nsurface s() { Ci = g(); }\n",
    )
    .unwrap();
    let s = compile_file(&dir.path().join("s.sl"), &[]).unwrap();
    assert_eq!(s.functions.len(), 1);
}

#[test]
fn unreadable_shader_is_an_io_error() {
    let e = compile_file(std::path::Path::new("/nonexistent/dir/x.sl"), &[]).unwrap_err();
    assert_eq!(e.exit_code(), 1);
    assert!(matches!(e, SlError::Io { .. }));
    let msg = e.to_string();
    assert!(msg.starts_with("/nonexistent/dir/x.sl: cannot read the shader: "), "{msg}");
    assert!(!msg.contains('\n'));
}

/// A macro whose parameter appears 64 times, nested five deep in its own arguments, would
/// make 64^5 (1e9) tokens: it is one error at the use, once a million tokens are made (the
/// budget is checked as each body is built, so the last level is never built whole; fuzz
/// regression `sl-nested-macro-blowup`, which took 19.5 GB before).
#[test]
fn an_exponential_expansion_is_one_error() {
    let body = vec!["(b) * (x)"; 64].join(" + ");
    let src = format!(
        "#define M(a, b, x) ((a) * (1 - (x)) + {body})\nf = M(1, M(1, M(1, M(1, M(1, 0.5, s), t), s), t), s);\n"
    );
    let e = error(&src);
    assert!(e.starts_with("t.sl:2:"), "{e}");
    assert!(e.contains("macro \"M\": expansion makes more than 1000000 tokens"), "{e}");
    // The body is 525 tokens (13 before the sum, 64 terms of 7, 63 '+', one ')'); two levels
    // put the inner body's 525 in place of each of the 64 one-token `b`s.
    let two = format!("#define M(a, b, x) ((a) * (1 - (x)) + {body})\nM(1, M(1, 0.5, s), t)\n");
    assert_eq!(text(&two).split(' ').count(), 525 + 64 * 524);
}
