//! The error catalogue: each case is a small shader source and the exact one-line message of
//! its error (`file:line:col: message`), for every lexical, preprocessor, syntax, type and
//! uniform/varying error the front end reports. The whole catalogue is also an insta snapshot,
//! so no message drifts unseen.

use reyes_sl::{SlError, compile_str};

/// One bad source and its exact error.
struct Case {
    name: &'static str,
    src: &'static str,
    error: &'static str,
}

fn error_of(src: &str) -> String {
    match compile_str("test.sl", src, &[]) {
        Ok(_) => "(compiles)".to_string(),
        Err(e) => {
            assert_eq!(e.exit_code(), 2, "bad source is exit code 2: {e}");
            assert!(matches!(e, SlError::Source { .. }));
            e.to_string()
        }
    }
}

/// 300 parentheses deep: over the parser's limit of 256.
const NESTED: &str = concat!(
    "surface s() { float x = ",
    "((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((",
    "((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((",
    "((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((((",
    "1",
    "))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))",
    "))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))",
    "))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))))",
    "; }"
);

#[rustfmt::skip]
const CASES: &[Case] = &[
    Case { name: "lexical: malformed number", src: "surface s() { float x = 1x; }", error: "test.sl:1:25: malformed number \"1x\"" },
    Case { name: "lexical: two periods", src: "surface s() { float x = 1.2.3; }", error: "test.sl:1:25: malformed number \"1.2.3\"" },
    Case { name: "lexical: exponent without digits", src: "surface s() { float x = 1e; }", error: "test.sl:1:25: malformed number \"1e\"" },
    Case { name: "lexical: number out of range", src: "surface s() { float x = 1e39; }", error: "test.sl:1:25: number 1e39 is out of range (not a finite 32-bit float)" },
    Case { name: "lexical: unterminated string", src: "surface s() { string x = \"abc; }", error: "test.sl:1:26: unterminated string" },
    Case { name: "lexical: unknown escape", src: "surface s() { string x = \"a\\qb\"; }", error: "test.sl:1:26: unknown escape \\q in a string" },
    Case { name: "lexical: unexpected character", src: "surface s() { float x = 1 @ 2; }", error: "test.sl:1:27: unexpected character '@'" },
    Case { name: "lexical: control byte", src: "surface s() { float x = 1;\u{1} }", error: "test.sl:1:27: unexpected control byte 0x01" },
    Case { name: "lexical: unterminated comment", src: "surface s() { /* never closed }", error: "test.sl:1:15: unterminated comment: '/*' without '*/'" },
    Case { name: "lexical: increment operator", src: "surface s() { float i = 0; i++; }", error: "test.sl:1:29: '++' is not an RSL operator (write x += 1 or x -= 1)" },
    Case { name: "pp: unknown directive", src: "#frobnicate\nsurface s() {}", error: "test.sl:1:2: unknown directive #frobnicate" },
    Case { name: "pp: #if without #endif", src: "#if 1\nsurface s() {}", error: "test.sl:1:1: #if without #endif" },
    Case { name: "pp: #ifdef without #endif", src: "#ifdef X\nsurface s() {}", error: "test.sl:1:1: #ifdef without #endif" },
    Case { name: "pp: #else without #if", src: "#else\nsurface s() {}", error: "test.sl:1:1: #else without #if" },
    Case { name: "pp: #endif without #if", src: "#endif\nsurface s() {}", error: "test.sl:1:1: #endif without #if" },
    Case { name: "pp: #elif without #if", src: "#elif 1\nsurface s() {}", error: "test.sl:1:1: #elif without #if" },
    Case { name: "pp: #elif after #else", src: "#if 0\n#else\n#elif 1\n#endif", error: "test.sl:3:1: #elif after #else" },
    Case { name: "pp: #else after #else", src: "#if 0\n#else\n#else\n#endif", error: "test.sl:3:1: #else after #else" },
    Case { name: "pp: #endif with extra tokens", src: "#if 1\n#endif X\nsurface s() {}", error: "test.sl:2:8: #endif: unexpected \"X\" after #endif" },
    Case { name: "pp: #if without expression", src: "#if\n#endif", error: "test.sl:1:1: #if: expected an expression" },
    Case { name: "pp: #if missing paren", src: "#if (1\n#endif", error: "test.sl:1:6: #if: expected ')', got the end of the line" },
    Case { name: "pp: #if division by zero", src: "#if 1/0\n#endif", error: "test.sl:1:6: #if: division by zero" },
    Case { name: "pp: #if float", src: "#if 1.5\n#endif", error: "test.sl:1:5: #if: 1.5 is not an integer (#if takes integers only)" },
    Case { name: "pp: #if trailing token", src: "#if 1 2\n#endif", error: "test.sl:1:7: #if: unexpected 2 after the expression" },
    Case { name: "pp: defined without name", src: "#if defined\n#endif", error: "test.sl:1:5: #if: \"defined\" takes a macro name: defined NAME or defined(NAME)" },
    Case { name: "pp: #ifdef without name", src: "#ifdef\n#endif", error: "test.sl:1:1: #ifdef: expected a macro name, got the end of the line" },
    Case { name: "pp: #ifdef extra tokens", src: "#ifdef A B\n#endif", error: "test.sl:1:10: #ifdef: unexpected \"B\" after the macro name" },
    Case { name: "pp: #define without name", src: "#define\nsurface s() {}", error: "test.sl:1:1: #define: expected a macro name, got the end of the line" },
    Case { name: "pp: #define number name", src: "#define 3 4\nsurface s() {}", error: "test.sl:1:9: #define: expected a macro name, got the number 3" },
    Case { name: "pp: #define defined", src: "#define defined 1\nsurface s() {}", error: "test.sl:1:9: #define: \"defined\" cannot be a macro name" },
    Case { name: "pp: duplicate macro parameter", src: "#define F(a, a) a\nsurface s() {}", error: "test.sl:1:14: #define F: parameter \"a\" appears twice" },
    Case { name: "pp: bad macro parameter list", src: "#define F(a b) a\nsurface s() {}", error: "test.sl:1:13: #define F: expected ',' or ')' in the parameter list, got \"b\"" },
    Case { name: "pp: stringize non-parameter", src: "#define F(a) #b\nsurface s() {}", error: "test.sl:1:14: #define F: '#' is not followed by a macro parameter" },
    Case { name: "pp: paste at body start", src: "#define F(a) ## a\nsurface s() {}", error: "test.sl:1:14: #define F: '##' cannot begin a macro body" },
    Case { name: "pp: paste at body end", src: "#define F(a) a ##\nsurface s() {}", error: "test.sl:1:16: #define F: '##' cannot end a macro body" },
    Case { name: "pp: paste making no token", src: "#define F(a, b) a ## b\nsurface s() { float x = F(+, /); }", error: "test.sl:2:25: macro \"F\": '##' pasting \"+\" and \"/\" does not give one token" },
    Case { name: "pp: macro argument count", src: "#define F(a, b) a + b\nsurface s() { float x = F(1); }", error: "test.sl:2:25: macro \"F\" takes 2 arguments, got 1" },
    Case { name: "pp: unterminated macro arguments", src: "#define F(a) a\nsurface s() { float x = F(1; }", error: "test.sl:2:25: macro \"F\": unterminated argument list (no ')')" },
    Case { name: "pp: include not found", src: "#include \"missing.h\"\nsurface s() {}", error: "test.sl:1:1: #include \"missing.h\": file not found (no include path given)" },
    Case { name: "pp: include angle not found", src: "#include <missing.h>\nsurface s() {}", error: "test.sl:1:1: #include <missing.h>: file not found (no include path given)" },
    Case { name: "pp: include without name", src: "#include\nsurface s() {}", error: "test.sl:1:1: #include: expected a file name (\"file\" or <file>), got the end of the line" },
    Case { name: "pp: include angle unclosed", src: "#include <x.h\nsurface s() {}", error: "test.sl:1:10: #include: '<' without '>' around the file name" },
    Case { name: "pp: include trailing tokens", src: "#include \"a.h\" x\nsurface s() {}", error: "test.sl:1:16: #include: unexpected \"x\" after the file name" },
    Case { name: "pp: #line not a number", src: "#line x\nsurface s() {}", error: "test.sl:1:7: #line: expected a line number, got \"x\"" },
    Case { name: "pp: #line zero", src: "#line 0\nsurface s() {}", error: "test.sl:1:7: #line: line number 0 is not a positive integer" },
    Case { name: "pp: #line bad file", src: "#line 3 4\nsurface s() {}", error: "test.sl:1:9: #line: expected a file name (a string), got the number 4" },
    Case { name: "pp: #error", src: "#error stop here\nsurface s() {}", error: "test.sl:1:1: #error stop here" },
    Case { name: "pp: directive name a number", src: "# 3\nsurface s() {}", error: "test.sl:1:3: expected a directive name after '#', got the number 3" },
    Case { name: "pp: #undef without name", src: "#undef\nsurface s() {}", error: "test.sl:1:1: #undef: expected a macro name, got the end of the line" },
    Case { name: "syntax: no definition", src: "float x;", error: "test.sl:1:1: expected a shader or function definition, got \"float\"" },
    Case { name: "syntax: missing semicolon", src: "surface s() { Ci = 1 }", error: "test.sl:1:22: expected ';' after the expression, got '}'" },
    Case { name: "syntax: missing paren after shader name", src: "surface s { }", error: "test.sl:1:11: expected '(' after the surface shader name \"s\", got '{'" },
    Case { name: "syntax: missing body", src: "surface s()", error: "test.sl:1:11: expected '{' to begin the body of shader \"s\", got the end of the input" },
    Case { name: "syntax: unclosed body", src: "surface s() { Ci = 1;", error: "test.sl:1:21: expected '}' to close the block, got the end of the input" },
    Case { name: "syntax: keyword as name", src: "surface s() { float if = 1; }", error: "test.sl:1:21: expected a variable name, got the keyword \"if\" (reserved, not a name)" },
    Case { name: "syntax: keyword in expression", src: "surface s() { Ci = while; }", error: "test.sl:1:20: expected an expression, got the keyword \"while\"" },
    Case { name: "syntax: bad parameter", src: "surface s(float) {}", error: "test.sl:1:16: expected a parameter name, got ')'" },
    Case { name: "syntax: void parameter", src: "surface s(void x = 1) {}", error: "test.sl:1:11: a parameter cannot be void" },
    Case { name: "syntax: void variable", src: "surface s() { void x; }", error: "test.sl:1:15: a variable cannot be void" },
    Case { name: "syntax: array without size", src: "surface s() { float a[]; }", error: "test.sl:1:22: an array here needs a size: '[]' is for function parameters only" },
    Case { name: "syntax: array size zero", src: "surface s() { float a[0]; }", error: "test.sl:1:23: array size must be a positive integer, got 0" },
    Case { name: "syntax: array size fractional", src: "surface s() { float a[1.5]; }", error: "test.sl:1:23: array size must be a positive integer, got 1.5" },
    Case { name: "syntax: else without if", src: "surface s() { else Ci = 1; }", error: "test.sl:1:15: \"else\" without \"if\"" },
    Case { name: "syntax: declaration in for", src: "surface s() { for (float i = 0; i < 1; i += 1) ; }", error: "test.sl:1:20: a declaration cannot begin a \"for\" (declare the variable before the loop)" },
    Case { name: "syntax: missing closing paren of if", src: "surface s() { if (1 < 2 Ci = 1; }", error: "test.sl:1:25: expected ')' to close the condition of \"if\", got \"Ci\"" },
    Case { name: "syntax: break count not integer", src: "surface s() { while (1 < 2) break 1.5; }", error: "test.sl:1:35: \"break\" takes a loop count (a positive integer), got 1.5" },
    Case { name: "syntax: output local", src: "surface s() { output float x; }", error: "test.sl:1:15: \"output\" is for parameters only" },
    Case { name: "syntax: array literal in expression", src: "surface s() { float a[2]; a = {1, 2}; }", error: "test.sl:1:31: an array initialiser {…} is allowed only in a declaration" },
    Case { name: "syntax: unclosed call", src: "surface s() { Ci = diffuse(N; }", error: "test.sl:1:29: expected ')' or ',' in the arguments of \"diffuse\", got ';'" },
    Case { name: "syntax: missing index bracket", src: "surface s() { float a[2]; Ci = a[0; }", error: "test.sl:1:35: expected ']' to close the index, got ';'" },
    Case { name: "syntax: shader inside shader", src: "surface s() { surface t() {} }", error: "test.sl:1:15: a surface shader cannot be defined inside another definition" },
    Case { name: "syntax: cast to void", src: "surface s() { Ci = void 1; }", error: "test.sl:1:20: cannot cast to void" },
    Case { name: "syntax: expression expected", src: "surface s() { Ci = ; }", error: "test.sl:1:20: expected an expression, got ';'" },
    Case { name: "syntax: missing colon", src: "surface s() { Ci = 1 < 2 ? 1 ; }", error: "test.sl:1:30: expected ':' of '?:', got ';'" },
    Case { name: "syntax: missing array bracket", src: "surface s() { float a[2; }", error: "test.sl:1:24: expected ']' after the array size, got ';'" },
    Case { name: "check: transformation shader", src: "transformation t() {}", error: "test.sl:1:1: transformation shaders are not supported (RenderMan Interface 3.2 reserves them; no renderer runs them)" },
    Case { name: "check: two shaders", src: "surface a() {} surface b() {}", error: "test.sl:1:24: a second shader \"b\" in one file (the first is \"a\" at line 1)" },
    Case { name: "check: only functions", src: "float f() { return 1; }", error: "test.sl:1:23: no shader definition (surface, displacement, light, volume or imager) in the file" },
    Case { name: "check: parameter without default", src: "surface s(float Kd) {}", error: "test.sl:1:17: shader parameter \"Kd\" needs a default value" },
    Case { name: "check: undeclared variable", src: "surface s() { Ci = foo; }", error: "test.sl:1:20: undeclared variable \"foo\"" },
    Case { name: "check: redeclared variable", src: "surface s() { float x; float x; }", error: "test.sl:1:30: \"x\" is already declared in this scope" },
    Case { name: "check: function used as variable", src: "surface s() { Ci = diffuse; }", error: "test.sl:1:20: \"diffuse\" is a function: call it as diffuse(...)" },
    Case { name: "check: unknown function", src: "surface s() { Ci = frobnicate(1); }", error: "test.sl:1:20: unknown function \"frobnicate\"" },
    Case { name: "check: variable called", src: "surface s() { float x = 1; Ci = x(1); }", error: "test.sl:1:33: \"x\" is a variable, not a function" },
    Case { name: "check: wrong argument types", src: "surface s() { float x = sin(\"a\"); }", error: "test.sl:1:25: no \"sin\" takes (string); it takes float sin(float)" },
    Case { name: "check: wrong argument count", src: "surface s() { float x = sin(1, 2); }", error: "test.sl:1:25: no \"sin\" takes (float, float); it takes float sin(float)" },
    Case { name: "check: assign colour to float", src: "surface s() { float x = Cs; }", error: "test.sl:1:25: the initial value of \"x\" must be float, got color" },
    Case { name: "check: assign point to colour", src: "surface s() { Ci = P; }", error: "test.sl:1:20: the value assigned to \"Ci\" must be color, got point (write a cast: color (...))" },
    Case { name: "check: assign string to float", src: "surface s() { float x; x = \"a\"; }", error: "test.sl:1:28: the value assigned to \"x\" must be float, got string" },
    Case { name: "check: add colour and point", src: "surface s() { Ci = Cs + P; }", error: "test.sl:1:23: operator '+' cannot take color and point" },
    Case { name: "check: compare colours with less", src: "surface s() { if (Cs < Cs) Ci = 1; }", error: "test.sl:1:22: operator '<' cannot take color and color" },
    Case { name: "check: dot of colours", src: "surface s() { float d = Cs . Cs; }", error: "test.sl:1:28: operator '.' cannot take color and color" },
    Case { name: "check: cross of floats", src: "surface s() { vector v = 1 ^ 2; }", error: "test.sl:1:28: operator '^' cannot take float and float" },
    Case { name: "check: matrix plus matrix", src: "surface s() { matrix m = 1; m = m + m; }", error: "test.sl:1:35: operator '+' cannot take matrix and matrix" },
    Case { name: "check: string arithmetic", src: "surface s() { string a = \"x\"; a = a + a; }", error: "test.sl:1:37: operator '+' cannot take string and string" },
    Case { name: "check: condition of if is a colour", src: "surface s() { if (Cs) Ci = 1; }", error: "test.sl:1:19: the condition of \"if\" must be a relation or a float, got color" },
    Case { name: "check: not of a colour", src: "surface s() { if (!Cs) Ci = 1; }", error: "test.sl:1:20: the operand of '!' must be a relation or a float, got color" },
    Case { name: "check: and of strings", src: "surface s() { if (\"a\" && \"b\") Ci = 1; }", error: "test.sl:1:19: the left operand of '&&' must be a relation or a float, got string" },
    Case { name: "check: ternary branch types", src: "surface s() { Ci = 1 < 2 ? Cs : \"a\"; }", error: "test.sl:1:26: the branches of '?:' have different types: color and string" },
    Case { name: "check: negate a string", src: "surface s() { string a = -\"x\"; }", error: "test.sl:1:26: unary '-' takes a float, colour, point, vector, normal or matrix, got string" },
    Case { name: "check: tuple of two", src: "surface s() { Ci = (1, 2); }", error: "test.sl:1:20: a color is made of 3 floats, got a list of 2" },
    Case { name: "check: tuple component not float", src: "surface s() { Ci = color (1, Cs, 2); }", error: "test.sl:1:30: a component of a color must be a float, got color" },
    Case { name: "check: unknown colour space", src: "surface s() { Ci = color \"cmyk\" (1, 0, 0); }", error: "test.sl:1:26: unknown colour space \"cmyk\" (rgb, hsv, hsl, xyz, xyY, YIQ)" },
    Case { name: "check: cast colour to float", src: "surface s() { float f = float Cs; }", error: "test.sl:1:25: cannot cast color to float" },
    Case { name: "check: cast to string", src: "surface s() { string x = string 1; }", error: "test.sl:1:26: no cast to string" },
    Case { name: "check: space for a float", src: "surface s() { float f = float \"world\" 1; }", error: "test.sl:1:31: a float has no space" },
    Case { name: "check: index a non-array", src: "surface s() { float f = 1; f = f[0]; }", error: "test.sl:1:33: indexing a float, which is not an array" },
    Case { name: "check: index a string outside texture", src: "surface s() { string m = \"a\"; Ci = m[1]; }", error: "test.sl:1:37: indexing a string, which is not an array (a channel [n] follows only the map name of texture, environment and shadow)" },
    Case { name: "check: index out of range", src: "surface s() { float a[3]; a[3] = 1; }", error: "test.sl:1:29: index 3 is out of range for float[3] (0 to 2)" },
    Case { name: "check: array index not float", src: "surface s() { float a[3]; a[\"x\"] = 1; }", error: "test.sl:1:29: an array index must be a float, got string" },
    Case { name: "check: array initialiser for a scalar", src: "surface s() { float a = {1, 2}; }", error: "test.sl:1:25: an array initialiser {…} for \"a\", a float" },
    Case { name: "check: array initialiser length", src: "surface s() { float a[3] = {1, 2}; }", error: "test.sl:1:28: the initialiser has 2 values for \"a\", a float[3]" },
    Case { name: "check: assign to a function call", src: "surface s() { diffuse(N) = 1; }", error: "test.sl:1:15: '=': only a variable or an array element can be assigned" },
    Case { name: "check: assign to read-only global", src: "surface s() { I = 0; }", error: "test.sl:1:15: \"I\" is read-only in surface shaders" },
    Case { name: "check: global not in shader type", src: "displacement d() { Ci = 1; }", error: "test.sl:1:20: displacement shaders have no predefined variable \"Ci\"" },
    Case { name: "check: L outside illuminance", src: "surface s() { Ci = Cl; }", error: "test.sl:1:20: \"Cl\" is defined only inside an illuminance statement" },
    Case { name: "check: Ps in a surface", src: "surface s() { Ci = Ps; }", error: "test.sl:1:20: surface shaders have no predefined variable \"Ps\"" },
    Case { name: "check: assign a function", src: "surface s() { texture = 1; }", error: "test.sl:1:15: '=': \"texture\" is a function, not a variable" },
    Case { name: "check: compound assign type", src: "surface s() { float f = 1; f *= Cs; }", error: "test.sl:1:30: '*=' on a float with a color gives a color" },
    Case { name: "check: break outside loop", src: "surface s() { break; }", error: "test.sl:1:15: \"break\" outside a loop" },
    Case { name: "check: break too many", src: "surface s() { while (1 < 2) break 2; }", error: "test.sl:1:29: \"break 2\" leaves 2 loops, but only 1 enclose it" },
    Case { name: "check: continue outside loop", src: "surface s() { continue; }", error: "test.sl:1:15: \"continue\" outside a loop" },
    Case { name: "check: return outside function", src: "surface s() { return; }", error: "test.sl:1:15: \"return\" outside a function (a shader body does not return)" },
    Case { name: "check: return value from void", src: "void f() { return 1; } surface s() { f(); }", error: "test.sl:1:19: function \"f\" returns void, but \"return\" has a value" },
    Case { name: "check: return without value", src: "float f() { return; } surface s() {}", error: "test.sl:1:13: \"return\" without a value in function \"f\", which returns float" },
    Case { name: "check: function without return", src: "float f() { float x = 1; } surface s() {}", error: "test.sl:1:7: function \"f\" returns float but has no return statement" },
    Case { name: "check: return type mismatch", src: "float f() { return Cs; } surface s() {}", error: "test.sl:1:20: the return value of \"f\" must be float, got color" },
    Case { name: "check: function parameter default", src: "float f(float x = 1) { return x; } surface s() {}", error: "test.sl:1:15: function parameter \"x\" cannot have a default" },
    Case { name: "check: function with global name", src: "float P() { return 1; } surface s() {}", error: "test.sl:1:7: function \"P\" has the name of a predefined variable" },
    Case { name: "check: function redefined", src: "float f(float x) { return x; } float f(float y) { return y; } surface s() {}", error: "test.sl:1:38: function \"f\" is already defined with these parameter types (line 1)" },
    Case { name: "check: recursion", src: "float f(float x) { return f(x); } surface s() {}", error: "test.sl:1:27: function \"f\" calls itself: recursion is not allowed in RSL" },
    Case { name: "check: mutual recursion", src: "float f(float x) { float g(float y) { return f(y); } return g(x); } surface s() {}", error: "test.sl:1:46: recursion is not allowed in RSL: f calls g calls f" },
    Case { name: "check: outer variable without extern", src: "surface s(float Kd = 1) { float f() { return Kd; } Ci = f(); }", error: "test.sl:1:46: \"Kd\" belongs to an enclosing scope: a function reaches it only through \"extern\" (declare extern float Kd;)" },
    Case { name: "check: extern of nothing", src: "surface s() { float f() { extern float nothing; return 1; } Ci = f(); }", error: "test.sl:1:40: extern \"nothing\": no variable of that name in an enclosing scope" },
    Case { name: "check: extern type mismatch", src: "surface s(float Kd = 1) { float f() { extern color Kd; return 1; } Ci = f(); }", error: "test.sl:1:52: extern \"Kd\" is declared color, but the variable it names is float" },
    Case { name: "check: extern initialiser", src: "surface s(float Kd = 1) { float f() { extern float Kd = 2; return 1; } Ci = f(); }", error: "test.sl:1:52: extern \"Kd\" cannot have an initialiser" },
    Case { name: "check: user call argument types", src: "float f(float x) { return x; } surface s() { float y = f(\"a\"); }", error: "test.sl:1:56: no \"f\" takes (string); it takes float f(float)" },
    Case { name: "check: output argument not a variable", src: "void f(output float x) { x = 1; } surface s() { f(1); }", error: "test.sl:1:49: no \"f\" takes (float); it takes void f(output float)" },
    Case { name: "check: illuminance in a light", src: "light l() { illuminance(P) { Cl = 1; } }", error: "test.sl:1:13: \"illuminance\" is for surface and volume shaders, not light shaders" },
    Case { name: "check: illuminate in a surface", src: "surface s() { illuminate(P) { Ci = 1; } }", error: "test.sl:1:15: \"illuminate\" is for light shaders, not surface shaders" },
    Case { name: "check: illuminance without position", src: "surface s() { illuminance() { Ci = 1; } }", error: "test.sl:1:15: \"illuminance\" needs a position: illuminance ([category,] P [, axis, angle]) statement" },
    Case { name: "check: illuminance axis without angle", src: "surface s() { illuminance(P, N) { Ci = 1; } }", error: "test.sl:1:30: \"illuminance\": an axis needs an angle after it" },
    Case { name: "check: illuminate nested", src: "light l() { illuminate(P) { solar() { Cl = 1; } } }", error: "test.sl:1:29: \"solar\" inside another illuminate or solar" },
    Case { name: "check: illuminate with options", src: "light l() { illuminate(P, N, 1, \"x\", 1) { Cl = 1; } }", error: "test.sl:1:13: \"illuminate\" takes no options, got \"x\"" },
    Case { name: "check: texture option type", src: "surface s() { Ci = texture(\"m\", s, t, \"blur\", \"x\"); }", error: "test.sl:1:47: \"texture\": option \"blur\" takes a float, got string" },
    Case { name: "check: texture option without value", src: "surface s() { Ci = texture(\"m\", s, t, \"blur\"); }", error: "test.sl:1:39: \"texture\": option \"blur\" has no value" },
    Case { name: "check: texture channel not float", src: "surface s() { Ci = texture(\"m\"[\"x\"], s, t); }", error: "test.sl:1:32: the channel of a texture map must be a float, got string" },
    Case { name: "check: varying to uniform", src: "surface s() { uniform float x = s; }", error: "test.sl:1:33: cannot assign a varying value to uniform variable \"x\"" },
    Case { name: "check: varying to uniform by assignment", src: "surface s() { uniform float x = 0; x = u; }", error: "test.sl:1:38: cannot assign a varying value to uniform variable \"x\"" },
    Case { name: "check: uniform under varying condition", src: "surface s() { uniform float x = 0; if (s > 0.5) x = 1; }", error: "test.sl:1:51: cannot assign to uniform variable \"x\" under varying control (the condition at 1:42 is varying)" },
    Case { name: "check: uniform in varying loop", src: "surface s() { uniform float x = 0; while (s > x) x += 1; }", error: "test.sl:1:52: cannot assign to uniform variable \"x\" under varying control (the condition at 1:45 is varying)" },
    Case { name: "check: uniform after varying break", src: "surface s() { uniform float i = 0; uniform float x = 0; while (i < 3) { if (t > 0.5) break; x = 1; i += 1; } }", error: "test.sl:1:95: cannot assign to uniform variable \"x\" under varying control (the condition at 1:66 is varying)" },
    Case { name: "check: varying default of uniform parameter", src: "surface s(float k = s) {}", error: "test.sl:1:21: the default of uniform parameter \"k\" is varying (declare it varying)" },
    Case { name: "check: varying argument to uniform formal", src: "float f(uniform float x) { return x; } surface s() { float y = f(s); }", error: "test.sl:1:66: argument 1 of \"f\" is varying, but parameter \"x\" is declared uniform" },
    Case { name: "check: uniform function returns varying", src: "uniform float f() { return s; } surface s() { float y = f(); }", error: "test.sl:1:15: function \"f\" is declared uniform but returns a varying value" },
    Case { name: "check: uniform output parameter written varying", src: "void f(output varying float x) { x = s; } surface s() { uniform float y = 0; f(y); }", error: "test.sl:1:80: cannot assign a varying value to uniform variable \"y\"" },
    Case { name: "check: uniform output of builtin", src: "surface s() { uniform float kr = 0, kt = 0; fresnel(I, N, 1.5, kr, kt); }", error: "test.sl:1:64: cannot assign a varying value to uniform variable \"kr\"" },
    Case { name: "check: void used as value", src: "void f() {} surface s() { float x = f(); }", error: "test.sl:1:37: the initial value of \"x\" must be float, got void" },
    Case { name: "pp: #else with extra tokens", src: "#if 0\n#else X\n#endif\nsurface s() {}", error: "test.sl:2:7: #else: unexpected \"X\" after #else" },
    Case { name: "pp: #line extra tokens", src: "#line 3 \"f.sl\" x\nsurface s() {}", error: "test.sl:1:16: #line: unexpected \"x\" after the file name" },
    Case { name: "pp: include extra string", src: "#include \"a.h\" \"b\"\nsurface s() {}", error: "test.sl:1:16: #include: unexpected string \"b\" after the file name" },
    Case { name: "lexical: octal escape too large", src: "surface s() { string x = \"\\777\"; }", error: "test.sl:1:26: octal escape \\777 is above \\377" },
    Case { name: "syntax: missing paren after while", src: "surface s() { while s > 0 Ci = 1; }", error: "test.sl:1:21: expected '(' after \"while\", got \"s\"" },
    Case { name: "syntax: function without body", src: "float f() return 1;", error: "test.sl:1:11: expected '{' to begin the body of function \"f\", got \"return\"" },
    Case { name: "syntax: nesting too deep", src: NESTED, error: "test.sl:1:280: nesting deeper than 256 levels" },
    Case { name: "check: array element type", src: "surface s() { float a[2] = {1, Cs}; }", error: "test.sl:1:32: an element of \"a\" must be float, got color" },
    Case { name: "check: cast an array", src: "surface s() { float a[2]; color c = color a; }", error: "test.sl:1:37: cannot cast an array (float[2]) to color" },
    Case { name: "check: index a scalar in an assignment", src: "surface s() { float f; f[0] = 1; }", error: "test.sl:1:25: indexing \"f\", a float, which is not an array" },
    Case { name: "check: illuminance axis type", src: "surface s() { illuminance(P, Cs, 1) { Ci = 1; } }", error: "test.sl:1:30: the axis of \"illuminance\" must be vector, got color (write a cast: vector (...))" },
    Case { name: "check: illuminance angle type", src: "surface s() { illuminance(P, N, Cs) { Ci = 1; } }", error: "test.sl:1:33: the angle of \"illuminance\" must be float, got color" },
    Case { name: "check: right operand of and", src: "surface s() { if (s > 0 && Cs) Ci = 1; }", error: "test.sl:1:28: the right operand of '&&' must be a relation or a float, got color" },
];

#[test]
fn each_case_gives_its_exact_message() {
    assert!(CASES.len() >= 150);
    let mut wrong = Vec::new();
    for c in CASES {
        let got = error_of(c.src);
        assert!(!got.contains('\n'), "{}: not one line: {got}", c.name);
        assert!(got.starts_with("test.sl:"), "{}: no position: {got}", c.name);
        if got != c.error {
            wrong.push(format!("{}: expected\n  {}\ngot\n  {}", c.name, c.error, got));
        }
    }
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

#[test]
fn names_are_unique() {
    let mut names: Vec<&str> = CASES.iter().map(|c| c.name).collect();
    names.sort_unstable();
    names.dedup();
    assert_eq!(names.len(), CASES.len());
}

#[test]
fn catalogue_snapshot() {
    let text: String = CASES
        .iter()
        .map(|c| format!("{}\n  {:?}\n  {}\n", c.name, c.src, error_of(c.src)))
        .collect();
    insta::assert_snapshot!("catalogue", text);
}
