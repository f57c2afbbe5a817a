//! Line tokenizer shared by the Triangle (and later TetGen) readers.
//!
//! Both formats treat `#` as the start of a comment, skip blank lines, and separate fields by
//! any whitespace. A *record* is a non-blank line after comment removal; each record keeps its
//! line number so that errors can point at it.

use super::error::ParseError;

/// The records of one file, in order.
pub(crate) struct Records<'a> {
    file: &'a str,
    lines: std::str::Lines<'a>,
    line_no: usize,
}

/// One record: its 1-based line number and its whitespace-separated fields.
///
/// `item` names what the record describes (for example `("vertex", 3)`, numbered as in the
/// file); errors are then prefixed with it. Setting it is free, unlike formatting a label for
/// every line of a million-line file.
pub(crate) struct Record<'a> {
    pub file: &'a str,
    pub line: usize,
    pub fields: Vec<&'a str>,
    pub item: Option<(&'static str, i64)>,
}

impl<'a> Records<'a> {
    /// Tokenizes `text`, the contents of `file` (the name is only used in errors).
    pub fn new(text: &'a str, file: &'a str) -> Self {
        Records {
            file,
            lines: text.lines(),
            line_no: 0,
        }
    }

    /// The next record, or `None` at the end of the file. Reuses `rec`'s field buffer so that
    /// million-line files do not allocate per line.
    pub fn next_into(&mut self, rec: &mut Record<'a>) -> bool {
        for line in self.lines.by_ref() {
            self.line_no += 1;
            let content = match line.find('#') {
                Some(i) => &line[..i],
                None => line,
            };
            rec.fields.clear();
            rec.fields.extend(content.split_ascii_whitespace());
            if !rec.fields.is_empty() {
                rec.line = self.line_no;
                rec.file = self.file;
                rec.item = None;
                return true;
            }
        }
        false
    }

    /// The next record, or an "unexpected end of file" error saying what was `expected`
    /// (built only on failure).
    pub fn require(
        &mut self,
        rec: &mut Record<'a>,
        expected: impl FnOnce() -> String,
    ) -> Result<(), ParseError> {
        if self.next_into(rec) {
            Ok(())
        } else {
            Err(self.eof(&expected()))
        }
    }

    /// An "unexpected end of file" error at the last line read.
    pub fn eof(&self, expected: &str) -> ParseError {
        ParseError::new(
            self.file,
            self.line_no.max(1),
            format!("unexpected end of file: expected {expected}"),
        )
    }

    /// An empty record to pass to [`Records::next_into`].
    pub fn record(&self) -> Record<'a> {
        Record {
            file: self.file,
            line: 0,
            fields: Vec::with_capacity(8),
            item: None,
        }
    }
}

impl<'a> Record<'a> {
    /// An error at this record's line, prefixed with the record's item when set.
    pub fn error(&self, message: impl Into<String>) -> ParseError {
        let message = message.into();
        match self.item {
            Some((kind, number)) => {
                ParseError::new(self.file, self.line, format!("{kind} {number}: {message}"))
            }
            None => ParseError::new(self.file, self.line, message),
        }
    }

    /// Field `i` (0-based) if present.
    pub fn get(&self, i: usize) -> Option<&'a str> {
        self.fields.get(i).copied()
    }

    /// Field `i` as a float; `what` names it in errors ("x coordinate of vertex 3").
    pub fn f64(&self, i: usize, what: &str) -> Result<f64, ParseError> {
        let s = self
            .get(i)
            .ok_or_else(|| self.error(format!("missing {what}")))?;
        parse_f64(s).ok_or_else(|| self.error(format!("bad number '{s}' for {what}")))
    }

    /// Field `i` as a float, or `None` when the line has no such field.
    pub fn opt_f64(&self, i: usize, what: &str) -> Result<Option<f64>, ParseError> {
        match self.get(i) {
            None => Ok(None),
            Some(_) => self.f64(i, what).map(Some),
        }
    }

    /// Field `i` as an integer (an integral float such as `3.0` is accepted, as `strtol`-based
    /// readers accept it too, but `3.5` is not).
    pub fn int(&self, i: usize, what: &str) -> Result<i64, ParseError> {
        let s = self
            .get(i)
            .ok_or_else(|| self.error(format!("missing {what}")))?;
        parse_int(s).ok_or_else(|| self.error(format!("bad integer '{s}' for {what}")))
    }

    /// Field `i` as an integer, or `None` when the line has no such field.
    pub fn opt_int(&self, i: usize, what: &str) -> Result<Option<i64>, ParseError> {
        match self.get(i) {
            None => Ok(None),
            Some(_) => self.int(i, what).map(Some),
        }
    }

    /// Field `i` as an `i32` marker.
    pub fn marker(&self, i: usize, what: &str) -> Result<Option<i32>, ParseError> {
        match self.opt_int(i, what)? {
            None => Ok(None),
            Some(v) => i32::try_from(v)
                .map(Some)
                .map_err(|_| self.error(format!("{what} {v} does not fit in a 32-bit integer"))),
        }
    }

    /// Field `i` as a non-negative count.
    pub fn count(&self, i: usize, what: &str) -> Result<usize, ParseError> {
        let v = self.int(i, what)?;
        usize::try_from(v).map_err(|_| self.error(format!("{what} is negative ({v})")))
    }

    /// Fails when the record has more than `max` fields: used on count lines, where extra
    /// fields almost always mean that a preceding count is wrong.
    pub fn at_most(&self, max: usize, what: &str) -> Result<(), ParseError> {
        if self.fields.len() > max {
            Err(self.error(format!(
                "{what} has {} fields, expected at most {max} (is a count above wrong?)",
                self.fields.len()
            )))
        } else {
            Ok(())
        }
    }
}

/// Reads a whole file as text; invalid UTF-8 (say, Latin-1 in a comment) is replaced, not
/// rejected, because only ASCII matters to the formats. Errors name the file.
pub(crate) fn read_text(path: &std::path::Path) -> Result<String, ParseError> {
    match std::fs::read(path) {
        Ok(bytes) => Ok(String::from_utf8_lossy(&bytes).into_owned()),
        Err(e) => Err(ParseError::new(
            &path.display().to_string(),
            0,
            format!("cannot read: {e}"),
        )),
    }
}

/// Parses a float as `strtod` would for well-formed input (Rust's parser rounds correctly).
pub(crate) fn parse_f64(s: &str) -> Option<f64> {
    s.parse::<f64>().ok()
}

/// Parses an integer; integral floats (`"3.0"`, `"1e2"`) are accepted.
pub(crate) fn parse_int(s: &str) -> Option<i64> {
    if let Ok(v) = s.parse::<i64>() {
        return Some(v);
    }
    let f = s.parse::<f64>().ok()?;
    // 2^63 is exactly representable, so this range check keeps the cast lossless.
    const LIMIT: f64 = 9_223_372_036_854_775_808.0;
    if f.fract() == 0.0 && (-LIMIT..LIMIT).contains(&f) {
        Some(f as i64)
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn all(text: &str) -> Vec<(usize, Vec<String>)> {
        let mut r = Records::new(text, "t");
        let mut rec = r.record();
        let mut out = Vec::new();
        while r.next_into(&mut rec) {
            out.push((rec.line, rec.fields.iter().map(|s| s.to_string()).collect()));
        }
        out
    }

    #[test]
    fn skips_comments_and_blank_lines_and_keeps_line_numbers() {
        let got = all("# head\n\n  1 2\t3  # tail\r\n   # only comment\n4\n");
        assert_eq!(got.len(), 2);
        assert_eq!(got[0].0, 3);
        assert_eq!(got[0].1, vec!["1", "2", "3"]);
        assert_eq!(got[1].0, 5);
        assert_eq!(got[1].1, vec!["4"]);
    }

    #[test]
    fn integers_accept_integral_floats_only() {
        assert_eq!(parse_int("42"), Some(42));
        assert_eq!(parse_int("-3"), Some(-3));
        assert_eq!(parse_int("3.0"), Some(3));
        assert_eq!(parse_int("3.5"), None);
        assert_eq!(parse_int("x"), None);
        assert_eq!(parse_int("1e300"), None);
    }

    #[test]
    fn eof_error_points_at_last_line() {
        let mut r = Records::new("1\n2\n", "f.node");
        let mut rec = r.record();
        assert!(r.next_into(&mut rec));
        assert!(r.next_into(&mut rec));
        let e = r
            .require(&mut rec, || "the segment count".into())
            .unwrap_err();
        assert_eq!(e.line, 2);
        assert!(e.message.contains("unexpected end of file"), "{e}");
    }
}
