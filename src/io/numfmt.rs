//! Float formatting for output files.

use std::fmt;

/// Formats an `f64` as the shortest decimal that reads back to the same bits (with Rust's
/// parser, `strtod` or Python's `float`).
///
/// Plain notation (`{}`) is used for magnitudes in `[1e-5, 1e16)` and for zero; scientific
/// notation (`{:e}`) otherwise, so that tiny or huge values do not print hundreds of digits.
#[derive(Debug, Clone, Copy)]
pub struct Real(pub f64);

impl fmt::Display for Real {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let a = self.0.abs();
        if a == 0.0 || !a.is_finite() || (1e-5..1e16).contains(&a) {
            write!(f, "{}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
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
}
