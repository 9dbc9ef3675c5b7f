//! Animation of a RON scene by frame-number substitution (docs/scene-format.md,
//! "Animation"): before parsing, every `${EXPR}` in the text is replaced by the value of the
//! arithmetic expression EXPR for the frame being rendered.
//!
//! EXPR has numbers, the variable `frame`, `+ - * /`, unary minus, parentheses and the
//! functions `sin(x)`, `cos(x)` (radians), `min(a, b)`, `max(a, b)`, `clamp(x, lo, hi)`,
//! `mix(a, b, t)` (`a + (b - a) t`) and `key(f0, v0, f1, v1, ...)` (the value at `frame` of
//! the keys `(f, v)` given in increasing `f`, linear between keys, held beyond the ends).
//! It is evaluated in `f64`; an integral value is written as an integer (so it can fill an
//! integer field such as `seed`), any other as the shortest decimal that reads back as the
//! same `f64`.
//!
//! Invariant: substitution keeps the text's lines (an expression cannot span lines), so
//! parse and validation errors name the right line; an error in an expression names the
//! line and column of its `${`.

use std::path::Path;

use crate::SceneError;

/// Whether the scene text is animated (has a `${`).
pub fn is_animated(text: &str) -> bool {
    text.contains("${")
}

/// The text of frame `frame`: every `${EXPR}` replaced by its value.
///
/// # Errors
///
/// A [`SceneError`] at the `${` of an unterminated or invalid expression (field `${...}`).
pub fn substitute(text: &str, frame: i32, file: &Path) -> Result<String, SceneError> {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    let mut offset = 0;
    while let Some(start) = rest.find("${") {
        out.push_str(&rest[..start]);
        let at = offset + start;
        let fail = |message: String| {
            let before = &text[..at];
            let line = before.matches('\n').count() + 1;
            let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
            SceneError {
                file: file.to_path_buf(),
                line: Some(line),
                col: Some(col),
                field: "${...}".into(),
                message,
            }
        };
        let body = &rest[start + 2..];
        let end = body
            .find(['}', '\n'])
            .filter(|&e| body.as_bytes()[e] == b'}')
            .ok_or_else(|| fail("no closing } on this line".into()))?;
        let value = Parser { s: &body.as_bytes()[..end], at: 0, frame: f64::from(frame) }
            .whole()
            .map_err(|m| fail(format!("{m} in '{}'", &body[..end])))?;
        if !value.is_finite() {
            return Err(fail(format!("'{}' is {value} at frame {frame}", &body[..end])));
        }
        if value.fract() == 0.0 && value.abs() < 9.0e15 {
            out.push_str(&format!("{}", value as i64));
        } else {
            out.push_str(&format!("{value:?}"));
        }
        let consumed = start + 2 + end + 1;
        offset += consumed;
        rest = &rest[consumed..];
    }
    out.push_str(rest);
    Ok(out)
}

/// A recursive-descent parser and evaluator of one expression.
struct Parser<'a> {
    s: &'a [u8],
    at: usize,
    frame: f64,
}

impl Parser<'_> {
    fn whole(mut self) -> Result<f64, String> {
        let v = self.sum()?;
        self.space();
        match self.s.get(self.at) {
            None => Ok(v),
            Some(&c) => Err(format!("unexpected '{}'", c as char)),
        }
    }

    fn space(&mut self) {
        while self.s.get(self.at).is_some_and(u8::is_ascii_whitespace) {
            self.at += 1;
        }
    }

    fn eat(&mut self, c: u8) -> bool {
        self.space();
        let hit = self.s.get(self.at) == Some(&c);
        self.at += usize::from(hit);
        hit
    }

    fn sum(&mut self) -> Result<f64, String> {
        let mut v = self.product()?;
        loop {
            if self.eat(b'+') {
                v += self.product()?;
            } else if self.eat(b'-') {
                v -= self.product()?;
            } else {
                return Ok(v);
            }
        }
    }

    fn product(&mut self) -> Result<f64, String> {
        let mut v = self.unary()?;
        loop {
            if self.eat(b'*') {
                v *= self.unary()?;
            } else if self.eat(b'/') {
                v /= self.unary()?;
            } else {
                return Ok(v);
            }
        }
    }

    fn unary(&mut self) -> Result<f64, String> {
        if self.eat(b'-') {
            return Ok(-self.unary()?);
        }
        if self.eat(b'+') {
            return self.unary();
        }
        self.atom()
    }

    fn atom(&mut self) -> Result<f64, String> {
        self.space();
        if self.eat(b'(') {
            let v = self.sum()?;
            return if self.eat(b')') { Ok(v) } else { Err("expected ')'".into()) };
        }
        let start = self.at;
        let c = *self.s.get(start).ok_or("expected a number, frame or a function")?;
        if c.is_ascii_digit() || c == b'.' {
            while self.s.get(self.at).is_some_and(|c| c.is_ascii_digit() || *c == b'.') {
                self.at += 1;
            }
            if matches!(self.s.get(self.at), Some(b'e' | b'E')) {
                self.at += 1;
                if matches!(self.s.get(self.at), Some(b'+' | b'-')) {
                    self.at += 1;
                }
                while self.s.get(self.at).is_some_and(u8::is_ascii_digit) {
                    self.at += 1;
                }
            }
            let text = std::str::from_utf8(&self.s[start..self.at]).unwrap_or_default();
            return text.parse().map_err(|_| format!("bad number '{text}'"));
        }
        if !c.is_ascii_alphabetic() {
            return Err(format!("unexpected '{}'", c as char));
        }
        while self.s.get(self.at).is_some_and(|c| c.is_ascii_alphanumeric() || *c == b'_') {
            self.at += 1;
        }
        let name = std::str::from_utf8(&self.s[start..self.at]).unwrap_or_default().to_string();
        if name == "frame" {
            return Ok(self.frame);
        }
        if !self.eat(b'(') {
            return Err(format!("unknown name '{name}' (the variable is 'frame')"));
        }
        let mut args = vec![self.sum()?];
        while self.eat(b',') {
            args.push(self.sum()?);
        }
        if !self.eat(b')') {
            return Err(format!("expected ')' after the arguments of {name}"));
        }
        call(&name, &args, self.frame)
    }
}

fn call(name: &str, a: &[f64], frame: f64) -> Result<f64, String> {
    let arity = |n: usize| {
        if a.len() == n {
            Ok(())
        } else {
            Err(format!("{name} takes {n} arguments, got {}", a.len()))
        }
    };
    match name {
        "sin" => arity(1).map(|()| a[0].sin()),
        "cos" => arity(1).map(|()| a[0].cos()),
        "min" => arity(2).map(|()| a[0].min(a[1])),
        "max" => arity(2).map(|()| a[0].max(a[1])),
        "clamp" => arity(3).map(|()| a[0].max(a[1]).min(a[2])),
        "mix" => arity(3).map(|()| a[0] + (a[1] - a[0]) * a[2]),
        "key" => key(a, frame),
        _ => Err(format!("unknown function '{name}' (sin, cos, min, max, clamp, mix, key)")),
    }
}

/// `key(f0, v0, f1, v1, ...)` at `frame`.
fn key(a: &[f64], frame: f64) -> Result<f64, String> {
    if a.is_empty() || !a.len().is_multiple_of(2) {
        return Err("key takes pairs of frame and value: key(f0, v0, f1, v1, ...)".into());
    }
    let keys: Vec<(f64, f64)> = a.chunks(2).map(|p| (p[0], p[1])).collect();
    if keys.windows(2).any(|w| w[1].0 <= w[0].0) {
        return Err("key: the frames of the keys must increase".into());
    }
    let (first, last) = (keys[0], keys[keys.len() - 1]);
    if frame <= first.0 {
        return Ok(first.1);
    }
    if frame >= last.0 {
        return Ok(last.1);
    }
    let i = keys.partition_point(|k| k.0 <= frame);
    let ((f0, v0), (f1, v1)) = (keys[i - 1], keys[i]);
    Ok(v0 + (v1 - v0) * (frame - f0) / (f1 - f0))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(text: &str, frame: i32) -> Result<String, String> {
        substitute(text, frame, Path::new("s.ron")).map_err(|e| e.to_string())
    }

    #[test]
    fn expressions_take_the_frame_number() {
        assert_eq!(
            at("seed: ${frame}, x: ${frame * 0.5 - 1}", 3).as_deref(),
            Ok("seed: 3, x: 0.5")
        );
        assert_eq!(at("${key(1, 0, 11, 2)} ${key(1, 0, 11, 2)}", 6).as_deref(), Ok("1 1"));
        assert_eq!(at("${key(1, 0, 11, 2)}", 0).as_deref(), Ok("0"));
        assert_eq!(at("${key(1, 0, 11, 2, 21, -2)}", 16).as_deref(), Ok("0"));
        assert_eq!(at("${key(1, 0, 11, 2)}", 30).as_deref(), Ok("2"));
        assert_eq!(
            at("${mix(1, 3, 0.25)} ${clamp(frame, 0, 2)} ${-(1 + 2) * 2}", 7).as_deref(),
            Ok("1.5 2 -6")
        );
        assert_eq!(at("${0.1 + 0.2}", 1).as_deref(), Ok("0.30000000000000004"));
        assert_eq!(
            at("${2 * sin(0)} ${cos(0)} ${min(frame, 4)} ${max(1e1, 2)}", 9).as_deref(),
            Ok("0 1 4 10")
        );
        assert_eq!(at("no expressions", 1).as_deref(), Ok("no expressions"));
    }

    #[test]
    fn bad_expressions_name_their_place() {
        let e = |t: &str| at(t, 1).err().unwrap_or_default();
        assert_eq!(
            e("a\n  x: ${frame +}"),
            "s.ron:2:6: ${...}: expected a number, frame or a function in 'frame +'"
        );
        assert_eq!(e("x: ${frame\n}"), "s.ron:1:4: ${...}: no closing } on this line");
        assert_eq!(
            e("${time}"),
            "s.ron:1:1: ${...}: unknown name 'time' (the variable is 'frame') in 'time'"
        );
        assert_eq!(
            e("${tan(1)}"),
            "s.ron:1:1: ${...}: unknown function 'tan' (sin, cos, min, max, clamp, mix, key) in 'tan(1)'"
        );
        assert_eq!(
            e("${1 / (frame - 1)}"),
            "s.ron:1:1: ${...}: '1 / (frame - 1)' is inf at frame 1"
        );
        assert_eq!(
            e("${key(2, 0, 1, 1)}"),
            "s.ron:1:1: ${...}: key: the frames of the keys must increase in 'key(2, 0, 1, 1)'"
        );
        assert_eq!(e("${min(1)}"), "s.ron:1:1: ${...}: min takes 2 arguments, got 1 in 'min(1)'");
        assert_eq!(e("${1 2}"), "s.ron:1:1: ${...}: unexpected '2' in '1 2'");
    }
}
