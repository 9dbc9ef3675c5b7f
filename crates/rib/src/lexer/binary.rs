//! Lexical stage, binary encoding (Spec 3.2 Appendix C.2, "Binary encoding"): a byte with the
//! top bit set, outside a string, starts an encoded token; the encodings mix freely with ASCII.
//!
//! Invariants: every decode consumes its code byte, so a caller always progresses; lengths read
//! from the input never size an allocation up front (data are appended as they arrive, so a
//! lying length costs at most the input's size); positions advance one column per byte and
//! never a line (encoded bytes are not text).
//!
//! Codes (octal, as the spec writes them):
//! - `0200 + 4d + w`: a signed big-endian integer of `w + 1` bytes, the last `d` of them after
//!   the binary point (an integer when `d = 0`);
//! - `0220 + n`: a string of `n < 16` bytes; `0240 + l`: a string whose length takes `l + 1`
//!   bytes; no escapes in either;
//! - `0244`, `0245`: an IEEE single or double (big-endian);
//! - `0246 c`: the request bound to code `c`; `0314 c s`: binds request name `s` to `c`;
//! - `0310 + l`: an array of floats whose count takes `l + 1` bytes, then the floats;
//! - `0315 + w t s`: binds string `s` to token `t` of `w + 1` bytes; `0317 + w t`: that string;
//! - everything else (`0247`-`0307`, `0321`-`0377`) is reserved: [`LexError::Binary`], after
//!   which the stream cannot be resynchronised.

use std::io;

use super::{LexError, Lexer, Num, Pending, Tok};
use crate::error::Pos;
use crate::signature::RequestKind;

fn truncated(at: Pos) -> LexError {
    LexError::Syntax(at, "truncated binary token".into())
}

impl Lexer {
    /// Ensures `n` bytes are buffered at `pos`; false if the input ends first.
    fn have(&mut self, n: usize) -> io::Result<bool> {
        while self.end - self.pos < n {
            if !self.refill()? {
                return Ok(false);
            }
        }
        Ok(true)
    }

    /// Reads an unsigned big-endian integer of `n <= 8` bytes.
    fn be(&mut self, n: usize, at: Pos) -> Result<u64, LexError> {
        if !self.have(n)? {
            let rest = self.end - self.pos;
            self.take(rest);
            return Err(truncated(at));
        }
        let v = self.buf[self.pos..self.pos + n].iter().fold(0u64, |v, &b| (v << 8) | u64::from(b));
        self.take(n);
        Ok(v)
    }

    /// Reads `n` raw bytes as a string (no escapes).
    fn raw_string(&mut self, n: u64, at: Pos) -> Result<String, LexError> {
        let mut out = Vec::new();
        let mut left = n;
        while left > 0 {
            if self.pos == self.end && !self.refill()? {
                return Err(truncated(at));
            }
            let k = (self.end - self.pos).min(usize::try_from(left).unwrap_or(usize::MAX));
            out.extend_from_slice(&self.buf[self.pos..self.pos + k]);
            self.take(k);
            left -= k as u64;
        }
        Ok(self.utf8(at, out))
    }

    /// A finite float, or the out-of-range error.
    fn finite(f: f32, at: Pos) -> Result<Num, LexError> {
        if f.is_finite() {
            Ok(Num { f, i: None, int_form: false })
        } else {
            Err(LexError::Syntax(at, "binary float is not a finite 32-bit float".into()))
        }
    }

    /// The string of a definition: quoted ASCII, encoded, or a defined one.
    fn definition_string(&mut self, at: Pos) -> Result<String, LexError> {
        self.skip_blank()?;
        let here = self.here();
        match self.peek()? {
            Some(b'"') => self.string(),
            Some(0o220..=0o243 | 0o317..=0o320) => match self.binary(here)? {
                Some(Tok::Str(s)) => Ok(s),
                _ => Err(LexError::Syntax(at, "binary definition without a string".into())),
            },
            _ => Err(LexError::Syntax(at, "binary definition without a string".into())),
        }
    }

    /// Decodes the encoded token whose code byte is at `pos` (it has the top bit set).
    /// Returns `None` for a definition, which is no token.
    pub(super) fn binary(&mut self, at: Pos) -> Result<Option<Tok>, LexError> {
        let Some(code) = self.peek()? else { return Err(truncated(at)) };
        self.take(1);
        let tok = match code {
            0o200..=0o217 => {
                let w = usize::from(code & 3) + 1;
                let d = i32::from((code >> 2) & 3);
                let raw = self.be(w, at)?;
                let shift = 64 - 8 * w as u32;
                let v = ((raw << shift) as i64) >> shift;
                if d == 0 {
                    Tok::Num(Num { f: v as f32, i: i32::try_from(v).ok(), int_form: true })
                } else {
                    Tok::Num(Num {
                        f: (v as f64 / 256f64.powi(d)) as f32,
                        i: None,
                        int_form: false,
                    })
                }
            }
            0o220..=0o237 => Tok::Str(self.raw_string(u64::from(code - 0o220), at)?),
            0o240..=0o243 => {
                let n = self.be(usize::from(code - 0o240) + 1, at)?;
                Tok::Str(self.raw_string(n, at)?)
            }
            0o244 => Tok::Num(Self::finite(f32::from_bits(self.be(4, at)? as u32), at)?),
            0o245 => Tok::Num(Self::finite(f64::from_bits(self.be(8, at)?) as f32, at)?),
            0o246 => {
                let c = self.be(1, at)? as usize;
                match self.requests.get(c).cloned().flatten() {
                    Some(t) => t,
                    None => {
                        return Err(LexError::Syntax(
                            at,
                            format!("binary request code {c} is not defined"),
                        ));
                    }
                }
            }
            0o310..=0o313 => {
                let n = self.be(usize::from(code - 0o310) + 1, at)?;
                let mut values = Vec::new();
                for _ in 0..n {
                    let f = f32::from_bits(self.be(4, at)? as u32);
                    values.push(Self::finite(f, at)?.f);
                }
                self.pending = Some(Pending { at, values, next: 0 });
                Tok::Open
            }
            0o314 => {
                let c = self.be(1, at)? as usize;
                let name = self.definition_string(at)?;
                let tok = match RequestKind::from_name(name.as_bytes()) {
                    Some(k) => Tok::Request(k),
                    None => Tok::Unknown(name),
                };
                if let Some(slot) = self.requests.get_mut(c) {
                    *slot = Some(tok);
                }
                return Ok(None);
            }
            0o315 | 0o316 => {
                let t = self.be(usize::from(code - 0o315) + 1, at)? as u16;
                let s = self.definition_string(at)?;
                self.strings.insert(t, s);
                return Ok(None);
            }
            0o317 | 0o320 => {
                let t = self.be(usize::from(code - 0o317) + 1, at)? as u16;
                match self.strings.get(&t) {
                    Some(s) => Tok::Str(s.clone()),
                    None => {
                        return Err(LexError::Syntax(
                            at,
                            format!("binary string token {t} is not defined"),
                        ));
                    }
                }
            }
            reserved => return Err(LexError::Binary(at, reserved)),
        };
        Ok(Some(tok))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn toks(bytes: &[u8]) -> Result<Vec<Tok>, String> {
        let mut l = Lexer::new(Box::new(io::Cursor::new(bytes.to_vec())), false);
        let mut out = Vec::new();
        loop {
            match l.next() {
                Ok((_, Tok::Eof)) => return Ok(out),
                Ok((_, t)) => out.push(t),
                Err(LexError::Syntax(p, m)) => return Err(format!("{p}: {m}")),
                Err(e) => return Err(format!("{e:?}")),
            }
        }
    }

    fn int(i: i32) -> Tok {
        Tok::Num(Num { f: i as f32, i: Some(i), int_form: true })
    }

    fn float(f: f32) -> Tok {
        Tok::Num(Num { f, i: None, int_form: false })
    }

    #[test]
    fn integers_and_fixed_point() {
        assert_eq!(toks(&[0o200, 5]), Ok(vec![int(5)]));
        assert_eq!(toks(&[0o200, 0xff]), Ok(vec![int(-1)]));
        assert_eq!(toks(&[0o201, 0x01, 0x00]), Ok(vec![int(256)]));
        assert_eq!(toks(&[0o203, 0x80, 0, 0, 0]), Ok(vec![int(i32::MIN)]));
        // d = 1, w = 1: 0x0180 / 256 = 1.5
        assert_eq!(toks(&[0o205, 0x01, 0x80]), Ok(vec![float(1.5)]));
        // d = 2, w = 1: 0x8000 as signed / 65536 = -0.5
        assert_eq!(toks(&[0o211, 0x80, 0x00]), Ok(vec![float(-0.5)]));
    }

    #[test]
    fn strings_floats_and_arrays() {
        assert_eq!(toks(b"\x93abc"), Ok(vec![Tok::Str("abc".into())]));
        assert_eq!(toks(&[0o220]), Ok(vec![Tok::Str(String::new())]));
        let mut long = vec![0o240, 20];
        long.extend_from_slice(&[b'x'; 20]);
        assert_eq!(toks(&long), Ok(vec![Tok::Str("x".repeat(20))]));
        let mut f = vec![0o244];
        f.extend_from_slice(&2.5f32.to_be_bytes());
        assert_eq!(toks(&f), Ok(vec![float(2.5)]));
        let mut d = vec![0o245];
        d.extend_from_slice(&0.25f64.to_be_bytes());
        assert_eq!(toks(&d), Ok(vec![float(0.25)]));
        let mut a = vec![0o310, 2];
        a.extend_from_slice(&1.0f32.to_be_bytes());
        a.extend_from_slice(&(-2.0f32).to_be_bytes());
        assert_eq!(toks(&a), Ok(vec![Tok::Open, float(1.0), float(-2.0), Tok::Close]));
    }

    #[test]
    fn defined_requests_and_strings() {
        let mut b = vec![0o314, 7, 0o226];
        b.extend_from_slice(b"Sphere");
        b.extend_from_slice(&[0o246, 7, 0o315, 1]);
        b.extend_from_slice(b"\"plastic\"");
        b.extend_from_slice(&[0o317, 1, 0o314, 8]);
        b.extend_from_slice(b"\"Frob\" \xa6\x08");
        assert_eq!(
            toks(&b),
            Ok(vec![
                Tok::Request(RequestKind::Sphere),
                Tok::Str("plastic".into()),
                Tok::Unknown("Frob".into())
            ])
        );
    }

    #[test]
    fn binary_errors() {
        assert_eq!(toks(&[0o246, 3]), Err("1:1: binary request code 3 is not defined".into()));
        assert_eq!(toks(&[0o317, 9]), Err("1:1: binary string token 9 is not defined".into()));
        assert_eq!(toks(&[0o201, 1]), Err("1:1: truncated binary token".into()));
        assert_eq!(toks(&[0o240, 10, b'a']), Err("1:1: truncated binary token".into()));
        assert_eq!(toks(&[0o310, 0xff]), Err("1:1: truncated binary token".into()));
        let mut f = vec![b' ', 0o244];
        f.extend_from_slice(&f32::INFINITY.to_be_bytes());
        assert_eq!(toks(&f), Err("1:2: binary float is not a finite 32-bit float".into()));
        assert_eq!(
            toks(&[0o314, 1, 0o200, 1]),
            Err("1:1: binary definition without a string".into())
        );
        assert!(matches!(
            Lexer::new(Box::new(io::Cursor::new(vec![0o377])), false).next(),
            Err(LexError::Binary(Pos { line: 1, col: 1 }, 0o377))
        ));
    }

    #[test]
    fn positions_count_encoded_bytes_as_columns() {
        // A newline byte inside an encoded integer is data, not a line break.
        let mut l =
            Lexer::new(Box::new(io::Cursor::new(vec![0o200, b'\n', b' ', b'[', b']'])), false);
        assert_eq!(l.next().unwrap(), (Pos { line: 1, col: 1 }, int(10)));
        assert_eq!(l.next().unwrap(), (Pos { line: 1, col: 4 }, Tok::Open));
    }
}
