//! Number formatting and buffered text output for the writers.
//!
//! Floats are written as the shortest decimal that reads back to the same bits, in the layout
//! of Rust's `{}` for magnitudes in `[1e-5, 1e16)` and zero, of `{:e}` otherwise (see
//! [`Real`]). The digits come from `ryu` (shortest round trip, several times faster than the
//! standard formatter), laid out here. Where two shortest decimals are equally close to the
//! value (for example 1208899598058064.25, between ...64.2 and ...64.3), `ryu` picks the
//! even one and the standard formatter the one above; the exact midpoint test below keeps
//! today's output, so files do not change with the speed-up.
//!
//! [`Out`] buffers a text file in memory and hands it to the underlying writer in large
//! blocks; fields are appended without formatting machinery or per-number allocation.

use std::fmt;
use std::io::{self, Write};

/// Formats an `f64` as the shortest decimal that reads back to the same bits (with Rust's
/// parser, `strtod` or Python's `float`).
///
/// Plain notation (`{}`) is used for magnitudes in `[1e-5, 1e16)` and for zero; scientific
/// notation (`{:e}`) otherwise, so that tiny or huge values do not print hundreds of digits.
#[derive(Debug, Clone, Copy)]
pub struct Real(pub f64);

impl fmt::Display for Real {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut buf = [0u8; REAL_MAX];
        let n = format_real(self.0, &mut buf);
        // Only ASCII is written.
        f.write_str(std::str::from_utf8(&buf[..n]).map_err(|_| fmt::Error)?)
    }
}

/// The longest text of [`format_real`]: sign, "0.0000", 17 digits (plain), or sign, 17
/// digits, point, "e-324" (scientific).
const REAL_MAX: usize = 32;

/// Writes `x` as [`Real`] does into `buf`, returning the length.
fn format_real(x: f64, buf: &mut [u8; REAL_MAX]) -> usize {
    if !x.is_finite() || x == 0.0 {
        let s: &[u8] = if x.is_nan() {
            b"NaN"
        } else if x.is_infinite() {
            if x > 0.0 {
                b"inf"
            } else {
                b"-inf"
            }
        } else if x.is_sign_negative() {
            b"-0"
        } else {
            b"0"
        };
        buf[..s.len()].copy_from_slice(s);
        return s.len();
    }
    let mut ryu = ryu::Buffer::new();
    let text = ryu.format_finite(x).as_bytes();
    if !may_be_midpoint(x) {
        // ryu's layout is the standard one but for the ".0" it gives integral values.
        let text = text.strip_suffix(b".0").unwrap_or(text);
        copy_small(buf, text);
        return text.len();
    }
    let (mut digits, mut exp) = decimal(text);
    while digits % 10 == 0 {
        digits /= 10;
        exp += 1;
    }
    if is_upper_midpoint(x.abs(), digits, exp) {
        // ryu's digits end in an even digit here, so adding one never carries.
        digits += 1;
    } else {
        let text = text.strip_suffix(b".0").unwrap_or(text);
        copy_small(buf, text);
        return text.len();
    }
    let mut ds = [0u8; 20];
    let mut nd = 0;
    let mut d = digits;
    while d > 0 {
        ds[19 - nd] = b'0' + (d % 10) as u8;
        d /= 10;
        nd += 1;
    }
    let ds = &ds[20 - nd..];
    let mut n = 0;
    let mut put = |bytes: &[u8]| {
        buf[n..n + bytes.len()].copy_from_slice(bytes);
        n += bytes.len();
    };
    if x < 0.0 {
        put(b"-");
    }
    // The value is 0.d1d2... × 10^point.
    let point = nd as i32 + exp;
    if (1e-5..1e16).contains(&x.abs()) {
        if exp >= 0 {
            put(ds);
            for _ in 0..exp {
                put(b"0");
            }
        } else if point > 0 {
            put(&ds[..point as usize]);
            put(b".");
            put(&ds[point as usize..]);
        } else {
            put(b"0.");
            for _ in 0..-point {
                put(b"0");
            }
            put(ds);
        }
    } else {
        put(&ds[..1]);
        if nd > 1 {
            put(b".");
            put(&ds[1..]);
        }
        put(b"e");
        let mut e = [0u8; 4];
        let mut ne = 0;
        let mut v = (point - 1).unsigned_abs();
        loop {
            e[3 - ne] = b'0' + (v % 10) as u8;
            v /= 10;
            ne += 1;
            if v == 0 {
                break;
            }
        }
        if point - 1 < 0 {
            put(b"-");
        }
        put(&e[4 - ne..]);
    }
    n
}

/// Copies a few bytes; a plain loop is cheaper than a call to `memcpy` for these sizes.
#[inline]
fn copy_small(to: &mut [u8], from: &[u8]) {
    for (t, f) in to.iter_mut().zip(from) {
        *t = *f;
    }
}

/// `a = m × 2^e` with `m` an integer below 2^53 (`a` finite, nonzero, sign ignored).
fn mantissa_exponent(a: f64) -> (u64, i32) {
    let bits = a.to_bits() & !(1 << 63);
    let biased = (bits >> 52) as i32;
    let fraction = bits & ((1 << 52) - 1);
    if biased == 0 {
        (fraction, -1074)
    } else {
        (fraction | 1 << 52, biased - 1075)
    }
}

/// A quick filter for [`is_upper_midpoint`]: a midpoint `(2d + 1) × 10^k / 2` with
/// `|k| <= 25` is an odd integer times `2^(k-1)`, so the power of two left when the odd part
/// of `x`'s mantissa is taken out lies in `[-26, 24]`. Coordinates with full mantissas (powers
/// near -53 for values near 1) fail this at once.
#[inline]
fn may_be_midpoint(x: f64) -> bool {
    let (m, e) = mantissa_exponent(x);
    (-26..=24).contains(&(e + m.trailing_zeros() as i32))
}

/// Reads ryu's text of a finite nonzero float back as `digits × 10^exp` (at most 17 digits;
/// the sign is dropped).
fn decimal(s: &[u8]) -> (u64, i32) {
    let mut digits = 0u64;
    let mut fraction = 0i32;
    let mut after_point = false;
    let mut exp = 0i32;
    let mut i = 0;
    while i < s.len() {
        match s[i] {
            b'0'..=b'9' => {
                digits = digits * 10 + (s[i] - b'0') as u64;
                fraction += after_point as i32;
            }
            b'.' => after_point = true,
            b'e' | b'E' => {
                let (neg, rest) = match s[i + 1] {
                    b'-' => (true, &s[i + 2..]),
                    b'+' => (false, &s[i + 2..]),
                    _ => (false, &s[i + 1..]),
                };
                let e = rest.iter().fold(0i32, |e, &c| e * 10 + (c - b'0') as i32);
                exp = if neg { -e } else { e };
                break;
            }
            _ => {}
        }
        i += 1;
    }
    (digits, exp - fraction)
}

/// Whether `a` (positive, finite) is exactly `(digits + 1/2) × 10^exp`: then the standard
/// formatter writes `digits + 1` where ryu writes `digits`.
///
/// With `a = m × 2^e` (`m` an integer below 2^53) the test is
/// `m × 5^-exp × 2^(e+1-exp) = (2 digits + 1) × 5^exp` for the relevant sign of `exp`,
/// compared exactly in 128-bit integers through odd parts and powers of two. Outside
/// `|exp| <= 25` no such equality is possible (an odd part would exceed 2^58), so the common
/// case costs one comparison.
fn is_upper_midpoint(a: f64, digits: u64, exp: i32) -> bool {
    if !(-25..=25).contains(&exp) {
        return false;
    }
    let (m, e) = mantissa_exponent(a);
    let five = |k: i32| 5u128.pow(k.unsigned_abs());
    let (left, right) = if exp < 0 {
        (m as u128 * five(exp), 2 * digits as u128 + 1)
    } else {
        (m as u128, (2 * digits as u128 + 1) * five(exp))
    };
    // left × 2^(e + 1 - exp) == right, with `right` odd.
    let tz = left.trailing_zeros() as i32;
    left >> tz == right && tz + e + 1 - exp == 0
}

/// A buffered text writer for the output files: fields are appended to the current line,
/// separated by single spaces; [`Out::end_line`] ends it.
///
/// Numbers are formatted straight into a fixed block, which is handed to the underlying writer
/// when full. A write error is kept and returned by the next [`Out::end_line`] (or
/// [`Out::finish`]), so that appending fields stays infallible and chainable.
pub(crate) struct Out<W: Write> {
    inner: W,
    buf: Box<[u8]>,
    len: usize,
    line_start: bool,
    error: Option<io::Error>,
}

/// How much text is handed to the underlying writer at once.
const BLOCK: usize = 1 << 18;
/// Room kept after a block for one more field (a float is at most [`REAL_MAX`] bytes).
const SLACK: usize = 64;

impl<W: Write> Out<W> {
    /// A writer into `inner`.
    pub fn new(inner: W) -> Self {
        Out {
            inner,
            buf: vec![0; BLOCK + SLACK].into_boxed_slice(),
            len: 0,
            line_start: true,
            error: None,
        }
    }

    /// Hands a full block on; then writes the field separator if the line has a field.
    #[inline]
    fn field(&mut self) -> &mut [u8] {
        if self.len >= BLOCK {
            self.drain();
        }
        if !self.line_start {
            self.buf[self.len] = b' ';
            self.len += 1;
        }
        self.line_start = false;
        &mut self.buf[self.len..]
    }

    fn drain(&mut self) {
        if self.error.is_none() {
            if let Err(e) = self.inner.write_all(&self.buf[..self.len]) {
                self.error = Some(e);
            }
        }
        self.len = 0;
    }

    /// Appends an unsigned integer field.
    pub fn uint(&mut self, v: u64) -> &mut Self {
        self.integer(v)
    }

    /// Appends a signed integer field.
    pub fn int(&mut self, v: i64) -> &mut Self {
        self.integer(v)
    }

    fn integer(&mut self, v: impl itoa::Integer) -> &mut Self {
        let mut b = itoa::Buffer::new();
        let text = b.format(v).as_bytes();
        copy_small(self.field(), text);
        self.len += text.len();
        self
    }

    /// Appends a float field, formatted as [`Real`].
    pub fn real(&mut self, x: f64) -> &mut Self {
        let to: &mut [u8; REAL_MAX] = (&mut self.field()[..REAL_MAX])
            .try_into()
            .expect("SLACK leaves room for a float");
        self.len += format_real(x, to);
        self
    }

    /// Ends the current line; reports a write error met since the last call.
    pub fn end_line(&mut self) -> io::Result<()> {
        if self.len >= BLOCK + SLACK - 1 {
            self.drain();
        }
        self.buf[self.len] = b'\n';
        self.len += 1;
        self.line_start = true;
        match self.error.take() {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }

    /// Writes what is buffered and flushes the underlying writer.
    pub fn finish(mut self) -> io::Result<()> {
        self.drain();
        if let Some(e) = self.error.take() {
            return Err(e);
        }
        self.inner.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_bit_for_bit() {
        let samples = [
            0.0,
            -0.0,
            1.0,
            0.1,
            1.0 / 3.0,
            -2.5e-7,
            1e-300,
            f64::MIN_POSITIVE,
            5e-324,
            1.7976931348623157e308,
            123_456_789.123_456_79,
            1e16,
            9.999999999999998e15,
            -0.6000000000000001,
        ];
        for x in samples {
            let s = Real(x).to_string();
            let back: f64 = s.parse().unwrap();
            assert_eq!(back.to_bits(), x.to_bits(), "{x:e} printed as {s}");
            assert!(s.len() <= 25, "{x:e} printed too long: {s}");
        }
    }

    #[test]
    fn uses_plain_notation_for_ordinary_values() {
        assert_eq!(Real(0.25).to_string(), "0.25");
        assert_eq!(Real(-3.0).to_string(), "-3");
        assert_eq!(Real(1e-7).to_string(), "1e-7");
    }

    /// The text the writers produced before the fast formatter: the standard formatter.
    fn reference(x: f64) -> String {
        let a = x.abs();
        if a == 0.0 || !a.is_finite() || (1e-5..1e16).contains(&a) {
            format!("{x}")
        } else {
            format!("{x:e}")
        }
    }

    #[test]
    fn matches_the_standard_formatter_exactly() {
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let check = |x: f64| {
            let got = Real(x).to_string();
            assert_eq!(got, reference(x), "{:#x}", x.to_bits());
            if x.is_finite() {
                assert_eq!(got.parse::<f64>().unwrap().to_bits(), x.to_bits(), "{got}");
            }
        };
        let specials = [
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MAX,
            f64::MIN,
            f64::MIN_POSITIVE,
            f64::EPSILON,
            1e-5,
            1e16,
            1e15,
            1e23,
            0.3,
            2.0f64.powi(-1074),
            // Midpoints between two shortest decimals, where ryu and the standard formatter
            // pick different digits.
            4835598392232257.0 / 4.0,
            -1612498777800701.0 / 8.0,
            0.5,
            2.5,
            1.25e-3,
        ];
        for x in specials {
            check(x);
            check(f64::from_bits(x.to_bits() + 1));
            check(f64::from_bits(x.to_bits().wrapping_sub(1)));
        }
        for _ in 0..300_000 {
            let r = next();
            // Random bits; values near the notation thresholds; quarter-integers, the
            // midpoint cases; short decimals such as coordinates typed by hand.
            check(f64::from_bits(r));
            check((r >> 11) as f64 * 2f64.powi((r % 64) as i32 - 53 - 20));
            check((r >> 12) as f64 / 4.0 * 10f64.powi((r % 3) as i32 - 1));
            check((r % 100_000) as f64 / 1000.0 - 50.0);
        }
    }

    #[test]
    fn out_separates_fields_and_lines() {
        let mut v = Vec::new();
        let mut o = Out::new(&mut v);
        o.uint(3).int(-1).real(0.5).end_line().unwrap();
        o.real(-2e20).end_line().unwrap();
        o.finish().unwrap();
        assert_eq!(String::from_utf8(v).unwrap(), "3 -1 0.5\n-2e20\n");
    }

    #[test]
    fn out_matches_formatted_text_across_blocks_and_long_lines() {
        // Many lines, and one line of many fields, both far longer than a block.
        let mut v = Vec::new();
        let mut want = String::new();
        let mut o = Out::new(&mut v);
        for i in 0..100_000u64 {
            let x = i as f64 / 7.0 - 3e4;
            o.uint(i)
                .int(-(i as i64))
                .real(x)
                .uint(u64::MAX)
                .end_line()
                .unwrap();
            want.push_str(&format!("{i} {} {} {}\n", -(i as i64), Real(x), u64::MAX));
        }
        for i in 0..50_000u64 {
            o.real(i as f64 * 1e-9);
            want.push_str(&format!(
                "{}{}",
                if i > 0 { " " } else { "" },
                Real(i as f64 * 1e-9)
            ));
        }
        o.end_line().unwrap();
        want.push('\n');
        o.finish().unwrap();
        assert!(want.len() > 4 * BLOCK);
        assert_eq!(String::from_utf8(v).unwrap(), want);
    }

    #[test]
    fn out_reports_write_errors() {
        struct Full;
        impl Write for Full {
            fn write(&mut self, _: &[u8]) -> io::Result<usize> {
                Err(io::Error::other("disk full"))
            }
            fn flush(&mut self) -> io::Result<()> {
                Ok(())
            }
        }
        let mut o = Out::new(Full);
        let mut failed = None;
        for i in 0..100_000 {
            if let Err(e) = o.uint(i).real(0.1).end_line() {
                failed = Some((i, e.to_string()));
                break;
            }
        }
        let (line, message) = failed.expect("a full block must reach the writer and fail");
        assert!(line > 1000, "failed at line {line}");
        assert_eq!(message, "disk full");
        let mut o = Out::new(Full);
        o.uint(1).end_line().unwrap();
        assert!(
            o.finish().is_err(),
            "the last block's error is reported too"
        );
    }
}
