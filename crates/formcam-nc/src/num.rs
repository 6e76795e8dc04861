//! The output buffer of the writers and the one fixed-decimal number
//! formatter every writer uses: `decimals` places, rounded half away from
//! zero, never `-0`; trailing zeros stripped ([`push`], the posts and
//! templates) or kept ([`push_fixed`], the toolpath writer, which then
//! follows the program's own style).

use crate::NcError;

/// Decimals for mm values.
pub(crate) const MM: u32 = 3;
/// Decimals for degree values.
pub(crate) const DEG: u32 = 4;
/// Decimals for per-minute feeds given by the program.
pub(crate) const FEED: u32 = 1;
/// Decimals for computed feeds (inverse-time F, feeds converted from block times).
pub(crate) const FEED_FINE: u32 = 3;

const POW10: [f64; 10] = [1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9];

/// Bytes collected on the stack before they go to the vector in one copy.
const CAP: usize = 4096;
/// The most bytes a number takes (sign, 19 digits, point, 9 decimals, slack).
const NUM_MAX: usize = 40;

/// The bytes of a program being written. Small pieces (words, numbers) are
/// gathered in a stack buffer and moved to the vector a few kilobytes at a
/// time, which is much faster than many tiny `memcpy`s; the vector is checked
/// as UTF-8 once at the end ([`with_out`]).
pub(crate) struct Out {
    vec: Vec<u8>,
    buf: [u8; CAP],
    len: usize,
}

impl Out {
    /// A buffer appending to `vec`.
    pub(crate) fn new(vec: Vec<u8>) -> Self {
        Self {
            vec,
            buf: [0; CAP],
            len: 0,
        }
    }

    /// Moves the buffered bytes to the vector.
    #[inline]
    fn flush(&mut self) {
        self.vec.extend_from_slice(&self.buf[..self.len]);
        self.len = 0;
    }

    /// Makes room for `n` buffered bytes (`n <= CAP`).
    #[inline(always)]
    fn room(&mut self, n: usize) {
        if self.len + n > CAP {
            self.flush();
        }
    }

    /// Reserves room in the vector for `n` more bytes.
    pub(crate) fn reserve(&mut self, n: usize) {
        self.vec.reserve(n + self.len);
    }

    /// Appends a string.
    #[inline(always)]
    pub(crate) fn s(&mut self, s: &str) {
        let b = s.as_bytes();
        if b.len() > 64 {
            self.flush();
            self.vec.extend_from_slice(b);
            return;
        }
        self.room(b.len());
        for (d, x) in self.buf[self.len..self.len + b.len()].iter_mut().zip(b) {
            *d = *x;
        }
        self.len += b.len();
    }

    /// Appends a short word (at most 8 bytes, padded with anything) in one
    /// 8-byte store.
    #[inline(always)]
    pub(crate) fn word(&mut self, w: &Word) {
        self.room(8);
        let at = self.len & (CAP - 1);
        if let Some(dst) = self.buf.get_mut(at..at + 8) {
            dst.copy_from_slice(&w.bytes);
        }
        self.len += w.len;
    }

    /// Appends one ASCII byte.
    #[inline(always)]
    pub(crate) fn byte(&mut self, b: u8) {
        self.room(1);
        self.buf[self.len] = b;
        self.len += 1;
    }

    /// Appends a character.
    #[inline]
    pub(crate) fn c(&mut self, c: char) {
        if c.is_ascii() {
            self.byte(c as u8);
        } else {
            let mut b = [0u8; 4];
            self.s(c.encode_utf8(&mut b));
        }
    }

    /// Appends bytes written elsewhere.
    pub(crate) fn append(&mut self, b: &[u8]) {
        self.flush();
        self.vec.extend_from_slice(b);
    }

    /// Takes the bytes out, flushed.
    pub(crate) fn finish(mut self) -> Vec<u8> {
        self.flush();
        self.vec
    }

    /// Takes the bytes written so far out as a string, leaving the buffer
    /// empty (and reusable).
    pub(crate) fn take_string(&mut self) -> String {
        self.flush();
        let bytes = std::mem::take(&mut self.vec);
        // Only whole `&str`s and ASCII bytes were pushed: this is valid UTF-8.
        match String::from_utf8(bytes) {
            Ok(s) => s,
            Err(e) => String::from_utf8_lossy(e.as_bytes()).into_owned(),
        }
    }
}

/// A word of at most 8 bytes for [`Out::word`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct Word {
    bytes: [u8; 8],
    len: usize,
}

impl Word {
    /// `s` as a word, or `None` when it is longer than 8 bytes.
    pub(crate) fn new(s: &str) -> Option<Self> {
        let b = s.as_bytes();
        let mut bytes = [0u8; 8];
        bytes.get_mut(..b.len())?.copy_from_slice(b);
        Some(Self {
            bytes,
            len: b.len(),
        })
    }
}

/// Runs `f` on the bytes of `out` and makes them a `String` again; on an error
/// `out` is left as it was.
pub(crate) fn with_out(
    out: &mut String,
    f: impl FnOnce(&mut Out) -> Result<(), NcError>,
) -> Result<(), NcError> {
    let start = out.len();
    let mut o = Out::new(std::mem::take(out).into_bytes());
    let r = f(&mut o);
    let mut bytes = o.finish();
    if r.is_err() {
        bytes.truncate(start);
    }
    // Only whole `&str`s and ASCII bytes were pushed: this is valid UTF-8.
    *out = match String::from_utf8(bytes) {
        Ok(s) => s,
        Err(e) => String::from_utf8_lossy(e.as_bytes()).into_owned(),
    };
    r
}

/// `v` scaled by `10^decimals` and rounded (half away from zero, exactly as
/// `f64::round`); `None` when it does not fit an `i64` comfortably (or is not
/// finite).
#[inline(always)]
pub(crate) fn scaled(v: f64, decimals: u32) -> Option<i64> {
    let s = v * POW10[decimals.min(9) as usize];
    if s.is_nan() || s.abs() >= 9.0e18 {
        return None;
    }
    // `as` truncates towards zero and the fraction it drops is exact, so
    // this rounds as `round` does without a call to it (not an instruction
    // on baseline x86-64).
    let t = s as i64;
    let frac = s - t as f64;
    Some(t + i64::from(frac >= 0.5) - i64::from(frac <= -0.5))
}

/// `v` rounded to `decimals` places: the value [`push_fixed`] prints.
pub(crate) fn rounded(v: f64, decimals: u32) -> f64 {
    let k = 10f64.powi(decimals as i32);
    (v * k).round() / k
}

/// `a` and `b` print the same with `decimals` places.
pub(crate) fn same_printed(a: f64, b: f64, decimals: u32) -> bool {
    let k = 10f64.powi(decimals as i32);
    (a * k).round() == (b * k).round()
}

/// Writes `v` with exactly `decimals` places (trailing zeros kept, no point
/// for `decimals = 0`), never `-0`.
pub(crate) fn push_fixed(out: &mut Out, v: f64, decimals: u32) {
    match scaled(v, decimals) {
        Some(s) if decimals <= 9 && s.unsigned_abs() < 9_000_000_000_000_000 => {
            push_digits(out, s, decimals, false, false);
        }
        _ => {
            let d = decimals as usize;
            out.s(&format!("{v:.d$}"));
        }
    }
}

/// Writes `v` with at most `decimals` places. `keep_point` writes a decimal
/// point even for whole numbers (`12.`), as Fanuc-style controls want.
#[inline]
pub(crate) fn push(out: &mut Out, v: f64, decimals: u32, keep_point: bool) {
    match scaled(v, decimals) {
        Some(s) => push_scaled(out, s, decimals, keep_point),
        None => out.s(&format!("{v:.0}")),
    }
}

/// Two-digit pairs "00".."99".
const PAIRS: [[u8; 2]; 100] = {
    let mut t = [[0u8; 2]; 100];
    let mut i = 0;
    while i < 100 {
        t[i] = [b'0' + (i / 10) as u8, b'0' + (i % 10) as u8];
        i += 1;
    }
    t
};

/// Writes the scaled integer `s` (value `s / 10^decimals`), trailing zeros
/// stripped.
#[inline(always)]
pub(crate) fn push_scaled(out: &mut Out, s: i64, decimals: u32, keep_point: bool) {
    push_digits(out, s, decimals, keep_point, true);
}

/// Writes the scaled integer `s` (value `s / 10^decimals`): digits in place,
/// right to left, two at a time; `trim` strips trailing zeros of the
/// fraction.
#[inline(always)]
fn push_digits(out: &mut Out, s: i64, decimals: u32, keep_point: bool, trim: bool) {
    // Every index below is under `start + NUM_MAX <= CAP`; masking with
    // `CAP - 1` (a power of two) only tells the compiler so.
    const M: usize = CAP - 1;
    macro_rules! two {
        ($buf:expr, $p:expr, $u:expr) => {{
            let r = PAIRS[($u % 100) as usize];
            $u /= 100;
            $p -= 2;
            $buf[$p & M] = r[0];
            $buf[($p + 1) & M] = r[1];
        }};
    }
    macro_rules! one {
        ($buf:expr, $p:expr, $b:expr) => {{
            $p -= 1;
            $buf[$p & M] = $b;
        }};
    }
    let mut u = s.unsigned_abs();
    let d = decimals.min(9) as usize;
    let digits = if u == 0 { 1 } else { u.ilog10() as usize + 1 };
    let int_digits = digits.saturating_sub(d).max(1);
    let total = usize::from(s < 0)
        + int_digits
        + if d > 0 {
            1 + d
        } else {
            usize::from(keep_point)
        };
    out.room(NUM_MAX);
    let start = out.len;
    let buf = &mut out.buf;
    let mut p = start + total;
    if d > 0 {
        let mut k = d;
        while k >= 2 {
            two!(buf, p, u);
            k -= 2;
        }
        if k == 1 {
            one!(buf, p, b'0' + (u % 10) as u8);
            u /= 10;
        }
        one!(buf, p, b'.');
    } else if keep_point {
        one!(buf, p, b'.');
    }
    while u >= 100 {
        two!(buf, p, u);
    }
    if u >= 10 {
        let r = PAIRS[(u % 100) as usize];
        p -= 2;
        buf[p & M] = r[0];
        buf[(p + 1) & M] = r[1];
    } else {
        one!(buf, p, b'0' + u as u8);
    }
    if s < 0 {
        one!(buf, p, b'-');
    }
    debug_assert_eq!(p, start);
    // Trailing zeros of the fraction go, and its point when nothing is left
    // (unless `keep_point`).
    let mut end = start + total;
    if d > 0 && trim {
        let point = end - d - 1;
        while end > point + 1 && buf[(end - 1) & M] == b'0' {
            end -= 1;
        }
        if end == point + 1 && !keep_point {
            end = point;
        }
    }
    out.len = end;
}

/// Writes an unsigned integer.
#[inline]
pub(crate) fn push_uint(out: &mut Out, n: u64) {
    push_scaled(out, n.min(i64::MAX as u64) as i64, 0, false);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn f(v: f64, d: u32, k: bool) -> String {
        let mut s = Out::new(Vec::new());
        push(&mut s, v, d, k);
        String::from_utf8(s.finish()).unwrap_or_default()
    }

    #[test]
    fn formats() {
        assert_eq!(f(12.5, 3, false), "12.5");
        assert_eq!(f(12.0, 3, false), "12");
        assert_eq!(f(12.0, 3, true), "12.");
        assert_eq!(f(0.0, 3, false), "0");
        assert_eq!(f(0.0, 3, true), "0.");
        assert_eq!(f(-0.0001, 3, false), "0");
        assert_eq!(f(-0.0004, 4, false), "-0.0004");
        assert_eq!(f(0.05, 3, false), "0.05");
        assert_eq!(f(-1.23456, 3, false), "-1.235");
        assert_eq!(f(1200.0, 1, false), "1200");
        assert_eq!(f(100.0, 0, false), "100");
        assert_eq!(f(3600.12345, 4, false), "3600.1235");
        assert_eq!(f(0.5, 0, false), "1");
        assert_eq!(f(-0.5, 0, false), "-1");
        assert_eq!(f(-2.5, 0, true), "-3.");
        assert_eq!(f(-1234567.891, 3, false), "-1234567.891");
        assert_eq!(f(1234567.8912, 4, true), "1234567.8912");
        assert_eq!(f(0.001, 3, true), "0.001");
        assert_eq!(f(10.0, 4, false), "10");
        assert_eq!(f(100.10, 4, false), "100.1");
        assert_eq!(f(9.99999, 3, false), "10");
        assert_eq!(f(123456789.0, 0, false), "123456789");
        assert_eq!(f(1e300, 3, false).len(), 301);
        let mut s = Out::new(Vec::new());
        push_uint(&mut s, 10);
        assert_eq!(s.finish(), b"10");
    }

    fn fixed(v: f64, d: u32) -> String {
        let mut s = Out::new(Vec::new());
        push_fixed(&mut s, v, d);
        s.take_string()
    }

    #[test]
    fn fixed_places() {
        assert_eq!(fixed(-0.0004, 3), "0.000");
        assert_eq!(fixed(12.0, 0), "12");
        assert_eq!(fixed(-4.56789, 4), "-4.5679");
        assert_eq!(fixed(0.05, 3), "0.050");
        assert_eq!(fixed(1e300, 2).len(), 304);
        assert_eq!(rounded(-4.56789, 4), -4.5679);
        assert!(same_printed(1.0004, 1.0, 3) && !same_printed(1.0005, 1.0, 3));
    }

    #[test]
    fn rounding_is_round_half_away_from_zero() {
        // The largest double below 0.5, and odd integers above 2^52, where
        // adding 0.5 before truncating rounds the wrong way.
        for v in [
            0.499_999_999_999_999_94,
            -0.499_999_999_999_999_94,
            4_503_599_627_370_497.0,
            -4_503_599_627_370_497.0,
            2.5,
            -2.5,
            1e-300,
        ] {
            assert_eq!(scaled(v, 0), Some(v.round() as i64), "{v}");
        }
        let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
        for _ in 0..100_000 {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let r = (seed >> 11) as f64 / (1u64 << 53) as f64;
            let v = (r - 0.5) * 10f64.powi((seed % 24) as i32 - 2);
            for d in [0, 3, 4] {
                let want = (v * POW10[d as usize]).round();
                let got = scaled(v, d);
                if want.abs() < 9.0e18 {
                    assert_eq!(got, Some(want as i64), "{v} {d}");
                } else {
                    assert_eq!(got, None, "{v} {d}");
                }
            }
        }
    }

    #[test]
    fn close_to_the_value_and_short() {
        let mut seed: u64 = 88172645463325252;
        for _ in 0..100_000 {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            let r = (seed >> 11) as f64 / (1u64 << 53) as f64;
            let v = (r - 0.5) * 10f64.powi((seed % 12) as i32);
            for d in [0, 1, 3, 4] {
                let t = f(v, d, false);
                let back: f64 = t.parse().unwrap_or(f64::NAN);
                assert!(
                    (back - v).abs() <= 0.5 / 10f64.powi(d as i32) * (1.0 + 1e-9) + v.abs() * 1e-15,
                    "{v} {d} {t}"
                );
                assert!(
                    !t.contains('.') || !t.ends_with('0') && !t.ends_with('.'),
                    "{t}"
                );
                assert!(t != "-0", "{v}");
            }
        }
    }
}
