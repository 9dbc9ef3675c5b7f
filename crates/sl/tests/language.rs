//! Each construct of RSL 1 parsed and checked: the IR's types, details, resolved overloads and
//! conversions are what the Specification says.

use reyes_sl::globals::{Access, GLOBALS};
use reyes_sl::ir::{BinOp, Callee, CheckedShader, Expr, ExprKind, Stmt, Var, VarKind};
use reyes_sl::library::library;
use reyes_sl::{BaseType, Detail, ShaderKind, Type, compile_str};

fn ok(src: &str) -> CheckedShader {
    compile_str("t.sl", src, &[]).unwrap_or_else(|e| panic!("{e}\n{src}"))
}

fn surface(body: &str) -> CheckedShader {
    ok(&format!("surface s() {{ {body} }}"))
}

fn var<'a>(s: &'a CheckedShader, name: &str) -> &'a Var {
    s.vars.iter().find(|v| v.name == name).unwrap_or_else(|| panic!("no variable {name}"))
}

/// The initialiser of local `name`.
fn init<'a>(s: &'a CheckedShader, name: &str) -> &'a Expr {
    fn find<'a>(stmts: &'a [Stmt], s: &CheckedShader, name: &str) -> Option<&'a Expr> {
        for st in stmts {
            match st {
                Stmt::Local { var, init: Some(e) } if s.vars[*var].name == name => return Some(e),
                Stmt::Block(b) | Stmt::Loop { body: b, .. } => {
                    if let Some(e) = find(b, s, name) {
                        return Some(e);
                    }
                }
                Stmt::If { then, els, .. } => {
                    if let Some(e) = find(then, s, name).or_else(|| find(els, s, name)) {
                        return Some(e);
                    }
                }
                _ => {}
            }
        }
        None
    }
    find(&s.body, s, name).unwrap_or_else(|| panic!("no initialiser of {name}"))
}

/// The type of local `name`'s initialiser, before conversion to the variable's type.
fn raw_type(s: &CheckedShader, name: &str) -> Type {
    match &init(s, name).kind {
        ExprKind::Convert(e) => e.ty,
        _ => init(s, name).ty,
    }
}

fn call_ret(e: &Expr) -> (String, Type) {
    match &e.kind {
        ExprKind::Convert(x) => call_ret(x),
        ExprKind::Call { callee: Callee::Builtin { name, .. }, .. } => (name.to_string(), e.ty),
        ExprKind::Binary(_, a, _) => call_ret(a),
        other => panic!("not a call: {other:?}"),
    }
}

#[test]
fn shader_types_and_transformation() {
    for (kw, kind) in [
        ("surface", ShaderKind::Surface),
        ("displacement", ShaderKind::Displacement),
        ("light", ShaderKind::Light),
        ("volume", ShaderKind::Volume),
        ("imager", ShaderKind::Imager),
    ] {
        assert_eq!(ok(&format!("{kw} x() {{}}")).kind, kind);
    }
    assert!(compile_str("t.sl", "transformation t() {}", &[]).is_err());
}

#[test]
fn every_global_per_shader_type() {
    for kind in ShaderKind::ALL {
        for g in GLOBALS {
            let read = format!("{kind} x() {{ {} v = {}; }}", g.ty.base, g.name);
            let read = if g.in_illuminance && kind == ShaderKind::Surface {
                format!("surface x() {{ illuminance(P) {{ {} v = {}; }} }}", g.ty.base, g.name)
            } else {
                read
            };
            let write = format!("{kind} x() {{ {} = {}; }}", g.name, g.name);
            let r = compile_str("t.sl", &read, &[]);
            let w = compile_str("t.sl", &write, &[]);
            match g.access(kind) {
                Access::None => assert!(r.is_err(), "{} readable in {kind}", g.name),
                Access::Read => {
                    assert!(r.is_ok(), "{} not readable in {kind}: {:?}", g.name, r.err());
                    let e = w.unwrap_err().to_string();
                    assert!(e.contains("is read-only"), "{e}");
                }
                Access::ReadWrite => {
                    assert!(r.is_ok(), "{} not readable in {kind}", g.name);
                    assert!(w.is_ok(), "{} not writable in {kind}: {:?}", g.name, w.err());
                }
            }
        }
    }
    let s = surface("Ci = Cs; Oi = Os;");
    assert_eq!(s.globals_read, ["Cs", "Os"]);
    assert_eq!(s.globals_written, ["Ci", "Oi"]);
}

#[test]
fn declarations_types_details_arrays() {
    let s = ok("surface s(float a = 1; varying color b = 0; output float o = 0; float arr[3] = {1, 2, 3}; string m = \"x\";) {
        uniform float u = 1; varying float v = 0; float w = 1, x = s; point p; vector q; normal n; matrix mm = 1;
        float loc[2] = {u, x}; float y = arr[1] + loc[0];
    }");
    assert_eq!(var(&s, "a").detail, Detail::Uniform);
    assert_eq!(var(&s, "b").detail, Detail::Varying);
    assert!(matches!(var(&s, "o").kind, VarKind::Param { output: true, .. }));
    assert_eq!(var(&s, "arr").ty, Type { base: BaseType::Float, array: Some(3) });
    assert_eq!(var(&s, "m").ty, Type::STRING);
    assert_eq!(var(&s, "u").detail, Detail::Uniform);
    assert_eq!(var(&s, "v").detail, Detail::Varying);
    // Undeclared detail is inferred: uniform unless it takes a varying value.
    assert_eq!(var(&s, "w").detail, Detail::Uniform);
    assert_eq!(var(&s, "x").detail, Detail::Varying);
    assert_eq!(var(&s, "loc").detail, Detail::Varying);
    assert_eq!(var(&s, "y").detail, Detail::Varying);
    assert_eq!(var(&s, "mm").ty, Type::MATRIX);
    assert_eq!(var(&s, "n").ty, Type::NORMAL);
    let VarKind::Param { default: Some(d), .. } = &var(&s, "arr").kind else { panic!() };
    assert!(matches!(&d.kind, ExprKind::Array(v) if v.len() == 3));
}

#[test]
fn parameter_defaults_can_call_functions_and_use_spaces() {
    let s = ok(
        "light l(float angle = radians(30); point from = point \"shader\" (0, 0, 0);) { solar() Cl = 1; }",
    );
    let VarKind::Param { default: Some(d), .. } = &var(&s, "from").kind else { panic!() };
    assert!(
        matches!(&d.kind, ExprKind::Construct { space: Some(sp), parts } if sp == "shader" && parts.len() == 3)
    );
}

#[test]
fn operators_follow_the_specification() {
    let s = surface(
        "vector d = P - P; point p = P + d; float f = N . I; vector c = N ^ I; color k = Cs * 2;
         color m = Cs * Cs; vector vv = d * d; matrix a = 1; matrix b = a * a; matrix q = a / a;
         matrix r = 2 * a; float neg = -f; point pp = P * 2 + 1; vector nv = N + d;",
    );
    assert_eq!(raw_type(&s, "d"), Type::VECTOR);
    assert_eq!(raw_type(&s, "p"), Type::POINT);
    assert_eq!(raw_type(&s, "f"), Type::FLOAT);
    assert_eq!(raw_type(&s, "c"), Type::VECTOR);
    assert_eq!(raw_type(&s, "k"), Type::COLOR);
    assert_eq!(raw_type(&s, "vv"), Type::VECTOR);
    assert_eq!(raw_type(&s, "b"), Type::MATRIX);
    assert_eq!(raw_type(&s, "q"), Type::MATRIX);
    assert_eq!(raw_type(&s, "r"), Type::MATRIX);
    assert_eq!(raw_type(&s, "pp"), Type::POINT);
    assert_eq!(raw_type(&s, "nv"), Type::VECTOR);
    // The float of colour * float is promoted explicitly.
    let ExprKind::Binary(BinOp::Mul, l, r) = &init(&s, "k").kind else { panic!() };
    assert_eq!((l.ty, r.ty), (Type::COLOR, Type::COLOR));
    assert!(matches!(r.kind, ExprKind::Convert(_)));
}

#[test]
fn relations_and_logic_give_booleans() {
    let s = surface(
        "if (s < 0.5 && t >= 0.2 || !(u == v) && Cs != 0 && \"a\" == \"b\" && P == N) Ci = 1;",
    );
    let Stmt::If { cond, .. } = &s.body[0] else { panic!() };
    assert_eq!(cond.ty, Type::BOOL);
    assert_eq!(cond.detail, Detail::Varying);
    // A float condition is compared with 0 (an extension both peers accept).
    let s = surface("float f = 1; if (f) Ci = 1; while (f) f -= 1;");
    let Stmt::If { cond, .. } = &s.body[1] else { panic!() };
    assert!(matches!(cond.kind, ExprKind::Convert(_)) && cond.ty == Type::BOOL);
}

#[test]
fn return_type_overloads_take_the_expected_type() {
    let s = surface(
        "float f = noise(P); color c = noise(P); point p = noise(P); vector v = noise(P);
         color k = Cs * noise(P); color g = noise(P) * 2; float r = random(); color rc = random();
         color tc = texture(\"m\"); float tf = texture(\"m\"[1], s, t, \"blur\", 0.1);
         color ce = color environment(\"e\", I); float sh = shadow(\"s\", P, \"bias\", 0.01);
         float cn = cellnoise(P, 1); color pn = pnoise(P, point(1, 1, 1));",
    );
    assert_eq!(call_ret(init(&s, "f")), ("noise".into(), Type::FLOAT));
    assert_eq!(call_ret(init(&s, "c")), ("noise".into(), Type::COLOR));
    assert_eq!(call_ret(init(&s, "p")), ("noise".into(), Type::POINT));
    assert_eq!(call_ret(init(&s, "v")), ("noise".into(), Type::VECTOR));
    // In an expression, the other operand decides; with a float, float is the default.
    let ExprKind::Binary(_, _, n) = &init(&s, "k").kind else { panic!() };
    assert_eq!(call_ret(n), ("noise".into(), Type::COLOR));
    assert_eq!(call_ret(init(&s, "g")), ("noise".into(), Type::FLOAT));
    assert_eq!(call_ret(init(&s, "rc")), ("random".into(), Type::COLOR));
    assert_eq!(call_ret(init(&s, "tc")), ("texture".into(), Type::COLOR));
    let ExprKind::Call { channel, options, args, .. } = &init(&s, "tf").kind else { panic!() };
    assert!(channel.is_some());
    assert_eq!(args.len(), 3);
    assert_eq!(options[0].0, "blur");
    assert_eq!(call_ret(init(&s, "ce")), ("environment".into(), Type::COLOR));
    assert_eq!(call_ret(init(&s, "pn")), ("pnoise".into(), Type::COLOR));
    assert_eq!(init(&s, "tf").detail, Detail::Varying);
}

#[test]
fn constructors_and_casts() {
    let s = surface(
        "point a = point \"world\" (1, 2, 3); color h = color \"hsv\" (0.5, 1, 1); matrix m = matrix \"shader\" 1;
         matrix sixteen = (1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1); color c = (1, 0, 0);
         vector v = vector N; color g = color 0.5; point w = point \"world\" P; Ci = (color(N) + 1) / 2;
         color mixed = mix((1, 0, 0), (0, 1, 0), 0.5);",
    );
    assert!(
        matches!(&init(&s, "a").kind, ExprKind::Construct { space: Some(sp), .. } if sp == "world")
    );
    assert!(
        matches!(&init(&s, "h").kind, ExprKind::Construct { space: Some(sp), .. } if sp == "hsv")
    );
    assert!(matches!(&init(&s, "m").kind, ExprKind::SpaceCast { space, .. } if space == "shader"));
    assert!(
        matches!(&init(&s, "sixteen").kind, ExprKind::Construct { parts, .. } if parts.len() == 16)
    );
    assert_eq!(init(&s, "c").ty, Type::COLOR);
    assert!(matches!(&init(&s, "w").kind, ExprKind::SpaceCast { .. }));
    assert_eq!(call_ret(init(&s, "mixed")), ("mix".into(), Type::COLOR));
}

#[test]
fn control_flow_and_break_levels() {
    let s = surface(
        "float i, j; for (i = 0; i < 3; i += 1) { for (j = 0; j < 3; j += 1) { if (j > 1) continue 2; if (i > 1) break 2; } }
         while (i > 0) { i -= 1; if (i < 1) break; } for (;;) break; Ci = 1 < 2 ? Cs : 0;",
    );
    let loops: Vec<&Stmt> = s.body.iter().filter(|st| matches!(st, Stmt::Loop { .. })).collect();
    assert_eq!(loops.len(), 3);
    // All uniform: no mask needed.
    assert!(loops.iter().all(|l| matches!(l, Stmt::Loop { varying: false, .. })));
}

#[test]
fn varying_control_flow_makes_variables_varying() {
    let s = surface(
        "float a = 0; if (s > 0.5) a = 1;
         float b = 0; float k = 0; while (k < 3) { if (t > 0.5) break; b = 1; k += 1; }
         float c = 0; c = c + 1;
         float d = 0; illuminance(P) { d += 1; }
         uniform float e = 0; illuminance(P) { uniform float inner = 1; inner += 1; }",
    );
    assert_eq!(var(&s, "a").detail, Detail::Varying);
    // A break under a varying condition leaves some points behind: the loop is varying.
    assert_eq!(var(&s, "b").detail, Detail::Varying);
    assert_eq!(var(&s, "k").detail, Detail::Varying);
    let Stmt::Loop { varying, .. } =
        s.body.iter().find(|st| matches!(st, Stmt::Loop { .. })).unwrap()
    else {
        panic!()
    };
    assert!(varying);
    assert_eq!(var(&s, "c").detail, Detail::Uniform);
    assert_eq!(var(&s, "d").detail, Detail::Varying);
    // A uniform declared inside varying control flow is assigned there freely.
    assert_eq!(var(&s, "inner").detail, Detail::Uniform);
}

#[test]
fn varying_reaches_through_later_assignments() {
    // x is read before it becomes varying: the fixpoint makes the earlier read varying too.
    let s = surface("float x = 0; float i; for (i = 0; i < 2; i += 1) { Ci = x; x = s; }");
    assert_eq!(var(&s, "x").detail, Detail::Varying);
}

#[test]
fn random_in_a_uniform_variable_is_one_value_for_the_grid() {
    let s = surface("uniform color c = color(random(), random(), random()); float r = random();");
    assert_eq!(init(&s, "c").detail, Detail::Uniform);
    assert_eq!(var(&s, "r").detail, Detail::Varying);
}

#[test]
fn user_functions() {
    let s = ok("
        float twice(float x) { return 2 * x; }
        color twice(color x) { return 2 * x; }
        void split(color c; output float r, g) { r = comp(c, 0); g = comp(c, 1); }
        float sum(float a[]) { return a[0] + a[1]; }
        float noise(point p) { return 0.5; }
        surface s(float Kd = 1;) {
            float local(float y) { extern float Kd; extern point P; return Kd * y + xcomp(P); }
            float r, g; float arr[2] = {1, 2};
            split(Cs, r, g);
            float f = twice(1); color c = twice(Cs); float l = local(u); float z = sum(arr); float n = noise(P);
        }");
    let names: Vec<&str> = s.functions.iter().map(|f| f.name.as_str()).collect();
    assert_eq!(names, ["twice", "twice", "split", "sum", "noise", "local"]);
    let ExprKind::Call { callee: Callee::User(i), .. } = &init(&s, "c").kind else { panic!() };
    assert_eq!(s.functions[*i].ret, Type::COLOR);
    // Output arguments written with varying values make the actuals varying.
    assert_eq!(var(&s, "r").detail, Detail::Varying);
    // A formal is as varying as its arguments.
    let twice_float = &s.functions[0];
    assert_eq!(s.vars[twice_float.params[0]].detail, Detail::Uniform);
    assert_eq!(var(&s, "l").detail, Detail::Varying);
    // A user function hides the library's function of the same name.
    assert!(matches!(&init(&s, "n").kind, ExprKind::Call { callee: Callee::User(_), .. }));
}

#[test]
fn lighting_statements() {
    let s = surface(
        "color C = 0; illuminance(\"specular\", P, N, PI / 2) { C += Cl * (normalize(L) . N); }
         illuminance(P, N, 1, \"send:L\", 1) { C += Cl; } illuminance(P) { C += Ol; } Ci = C;",
    );
    let Stmt::Illuminance { category, cone, .. } = &s.body[1] else { panic!("{:?}", s.body[1]) };
    assert!(category.is_some() && cone.is_some());
    let Stmt::Illuminance { options, .. } = &s.body[2] else { panic!() };
    assert_eq!(options.len(), 1);
    let l = ok("light l() { illuminate(P) Cl = 1; } ");
    assert!(matches!(l.body[0], Stmt::Illuminate { cone: None, .. }));
    let l = ok(
        "light l(point from = 0;) { illuminate(from, vector (0, 0, 1), 0.5) { Cl = 1 / (L . L); } }",
    );
    assert!(matches!(l.body[0], Stmt::Illuminate { cone: Some(_), .. }));
    let l = ok("light l() { solar(vector (0, 0, 1), 0) Cl = 1; solar() Cl = 2; }");
    assert!(matches!(l.body[0], Stmt::Solar { cone: Some(_), .. }));
    assert!(matches!(l.body[1], Stmt::Solar { cone: None, .. }));
}

#[test]
fn library_calls_resolve() {
    let s = surface(
        "float kr, kt; vector R, T; fresnel(normalize(I), N, 1.5, kr, kt); fresnel(I, N, 1.5, kr, kt, R, T);
         color lc = 0; float got = lightsource(\"__nonspecular\", lc); float res[2];
         float ti = textureinfo(\"m\", \"resolution\", res); float at = attribute(\"identifier:name\", lc);
         string cat = concat(\"a\", \"b\", \"c\"); printf(\"%f %c\\n\", s, Cs); string fm = format(\"%d\", 1);
         float sp = spline(t, 0, 1, 2, 3); color csp = spline(\"catmull-rom\", t, Cs, Cs, Cs, Cs);
         float m = max(1, 2, 3, s); color mc = min(Cs, Ci); float cl = clamp(s, 0, 1);
         point tp = transform(\"world\", P); vector tv = vtransform(\"object\", \"world\", I); normal tn = ntransform(\"world\", N);
         color ct = ctransform(\"hsv\", Cs); matrix mx = 1; float det = determinant(mx); mx = translate(mx, vector(1, 0, 0));
         mx = rotate(mx, 1, vector(0, 0, 1)); mx = scale(mx, point(1, 2, 3)); float cm = comp(mx, 0, 1); setcomp(mx, 0, 1, 2);
         setxcomp(P, 1); float x = xcomp(P) + ycomp(N) + zcomp(I); float dd = Du(s) + Dv(t) + Deriv(s, t) + area(P) + depth(P);
         normal cn = calculatenormal(P); float fs = filterstep(0.5, s); float fs2 = filterstep(0.5, s, t, \"width\", 2);
         float kd = 0; float got2 = surface(\"Kd\", kd) + displacement(\"amp\", kd) + atmosphere(\"d\", kd)
             + incident(\"x\", kd) + opposite(\"x\", kd) + option(\"limits:bucketsize\", res) + rendererinfo(\"version\", res);
         color amb = ambient() + diffuse(N) + specular(N, -I, 0.1) + phong(N, -I, 10) + specularbrdf(-I, N, -I, 0.1);",
    );
    let _ = s;
}

#[test]
fn every_library_function_has_a_signature_and_a_callable_form() {
    // Each entry of the table parses into signatures that show in one line.
    for name in library().names() {
        for sig in library().get(name).unwrap() {
            let shown = sig.show(name);
            assert!(!shown.contains('\n') && shown.contains(name), "{shown}");
        }
    }
    assert!(library().names().len() >= 90, "{}", library().names().len());
}

#[test]
fn untyped_functions_are_void() {
    let s = ok(
        "setit(output float x) { x = 1; } surface s() { float y; setit(y); inner() { Ci = 0; } inner(); }",
    );
    assert_eq!(s.functions[0].ret, Type::VOID);
    assert_eq!(s.functions[1].name, "inner");
}

#[test]
fn message_passing_outputs_keep_uniform_variables_uniform() {
    let s = surface(
        "color C = 0; illuminance(P) { uniform float nonspec = 0; lightsource(\"__nonspecular\", nonspec); C += (1 - nonspec) * Cl; } Ci = C;",
    );
    assert_eq!(var(&s, "nonspec").detail, Detail::Uniform);
}

#[test]
fn geometric_results_have_their_own_types() {
    let s = surface("vector a = transform(\"world\", I); normal b = transform(\"world\", N); point c = transform(\"world\", P);
                     vector d = Du(P); normal n = calculatenormal(P); float e = Du(s);");
    assert_eq!(call_ret(init(&s, "a")).1, Type::VECTOR);
    assert_eq!(call_ret(init(&s, "b")).1, Type::NORMAL);
    assert_eq!(call_ret(init(&s, "c")).1, Type::POINT);
    assert_eq!(call_ret(init(&s, "d")).1, Type::VECTOR);
    assert_eq!(call_ret(init(&s, "n")).1, Type::NORMAL);
    assert_eq!(call_ret(init(&s, "e")).1, Type::FLOAT);
}

#[test]
fn adjacent_strings_join() {
    let s = surface("string a = \"tex\" \"ture\" \".tx\";");
    assert!(matches!(&init(&s, "a").kind, ExprKind::Str(t) if t == "texture.tx"));
}
