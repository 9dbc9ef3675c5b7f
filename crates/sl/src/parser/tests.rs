//! The parser alone: precedence, casts and lists, formal groups, statements.

use super::*;
use crate::lexer::lex;

fn parse_str(s: &str) -> DResult<File> {
    parse(&lex(s.as_bytes(), 0))
}

fn body_expr(s: &str) -> Expr {
    let f = parse_str(&format!("surface x() {{ {s}; }}")).unwrap();
    let Item::Shader(sh) = &f.items[0] else { panic!() };
    let Stmt::Expr(e) = &sh.body[0] else { panic!("{:?}", sh.body[0]) };
    e.clone()
}

fn show(e: &Expr) -> String {
    match &e.kind {
        ExprKind::Num(v) => format!("{v}"),
        ExprKind::Str(s) => format!("{s:?}"),
        ExprKind::Name(n) => n.clone(),
        ExprKind::Index(a, b) => format!("{}[{}]", show(a), show(b)),
        ExprKind::Call(n, a) => {
            format!("{n}({})", a.iter().map(show).collect::<Vec<_>>().join(","))
        }
        ExprKind::Unary(UnOp::Neg, a) => format!("(-{})", show(a)),
        ExprKind::Unary(UnOp::Not, a) => format!("(!{})", show(a)),
        ExprKind::Binary(op, a, b) => format!("({} {} {})", show(a), op.as_str(), show(b)),
        ExprKind::Assign(op, a, b) => format!("({} {} {})", show(a), op.as_str(), show(b)),
        ExprKind::Cond(c, a, b) => format!("({} ? {} : {})", show(c), show(a), show(b)),
        ExprKind::Cast(t, s, a) => match s {
            Some((s, _)) => format!("({t} {s:?} {})", show(a)),
            None => format!("({t} {})", show(a)),
        },
        ExprKind::Tuple(v) | ExprKind::ArrayLit(v) => {
            format!("<{}>", v.iter().map(show).collect::<Vec<_>>().join(","))
        }
    }
}

#[test]
fn precedence() {
    assert_eq!(show(&body_expr("a = b + c * d . e")), "(a = (b + (c * (d . e))))");
    assert_eq!(show(&body_expr("a ^ b * c + d")), "((a ^ (b * c)) + d)");
    assert_eq!(show(&body_expr("x = a < b && c || d")), "(x = (((a < b) && c) || d))");
    assert_eq!(show(&body_expr("x = c ? a : b ? d : e")), "(x = (c ? a : (b ? d : e)))");
    assert_eq!(show(&body_expr("a = b = c")), "(a = (b = c))");
    assert_eq!(show(&body_expr("x = -a . b")), "(x = ((-a) . b))");
    assert_eq!(show(&body_expr("x = a - b - c")), "(x = ((a - b) - c))");
}

#[test]
fn casts_tuples_channels() {
    assert_eq!(show(&body_expr("c = color \"hsv\" (h, s, v)")), "(c = (color \"hsv\" <h,s,v>))");
    assert_eq!(show(&body_expr("p = point (1, 2, 3)")), "(p = (point <1,2,3>))");
    assert_eq!(show(&body_expr("m = matrix \"shader\" 1")), "(m = (matrix \"shader\" 1))");
    assert_eq!(show(&body_expr("c = color noise(P) * 2")), "(c = ((color noise(P)) * 2))");
    assert_eq!(show(&body_expr("f = texture(\"m\"[1], s, t)")), "(f = texture(\"m\"[1],s,t))");
    assert_eq!(show(&body_expr("a[i] += 2")), "(a[i] += 2)");
}

#[test]
fn formals_with_commas_and_semicolons() {
    let f = parse_str(
        "float f(float a, b; output color c; float d[], e) { return a; } surface s(float Ka = 1; varying color x = 0;) {}",
    )
    .unwrap();
    let Item::Function(func) = &f.items[0] else { panic!() };
    assert_eq!(func.params.len(), 3);
    assert_eq!(func.params[0].vars.len(), 2);
    assert!(func.params[1].output);
    assert_eq!(func.params[2].vars[0].array, Some(ArraySpec::Open));
    let Item::Shader(s) = &f.items[1] else { panic!() };
    assert_eq!(s.params.len(), 2);
    assert_eq!(s.params[1].ty.detail, Some(Detail::Varying));
}

#[test]
fn statements() {
    let f = parse_str(
        "light l() { illuminate(P, N, 1) { Cl = 1; } solar() ; }
         surface s() { float i; for (i = 0; i < 3; i += 1) { if (i > 1) break 1; else continue; }
           while (i > 0) i -= 1; illuminance(\"cat\", P, N, 1) { Ci += Cl; }
           float g(float x) { return x; } Ci = g(1); }",
    )
    .unwrap();
    assert_eq!(f.items.len(), 2);
}
