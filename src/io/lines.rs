//! Line tokenizer shared by every text reader (Triangle, TetGen and the surface formats).
//!
//! All the formats treat `#` as the start of a comment, skip blank lines, and separate fields
//! by ASCII whitespace. A *record* is a non-blank line after comment removal; each record keeps
//! its line number so that errors can point at it.
//!
//! Speed matters here: a million-point `.node` file is tens of megabytes, and users time the
//! whole command. The whole file is read once into memory (no copy when it is valid UTF-8),
//! the tokenizer makes a single pass over its bytes without allocating per line (a record's
//! field list is reused), and floats are parsed by `fast-float2`, which rounds correctly, so
//! every number reads exactly as Rust's own parser (and `strtod`) reads it.

use super::error::ParseError;

/// The records of one file, in order.
pub(crate) struct Records<'a> {
    file: &'a str,
    text: &'a str,
    /// Byte offset of the first unread line.
    pos: usize,
    line_no: usize,
}

/// Vertex lines of a `.node` section (`<#> <D coordinates> [attributes] [marker]`) as read,
/// in file order: for Triangle's files `D` = 2, for TetGen's 3.
#[derive(Default)]
pub(crate) struct VertexRows<const D: usize> {
    pub points: Vec<[f64; D]>,
    pub attributes: Vec<f64>,
    pub markers: Vec<i32>,
}

impl<const D: usize> VertexRows<D> {
    /// Reads one vertex line with `na` attributes, and a marker when `markers`.
    pub fn push(&mut self, rec: &Record<'_>, na: usize, markers: bool) -> Result<(), ParseError> {
        const WHAT: [&str; 3] = ["x coordinate", "y coordinate", "z coordinate"];
        let mut p = [0.0; D];
        for (k, x) in p.iter_mut().enumerate() {
            *x = rec.f64(1 + k, WHAT[k])?;
        }
        self.points.push(p);
        for a in 0..na {
            self.attributes
                .push(rec.opt_f64(1 + D + a, "attribute")?.unwrap_or(0.0));
        }
        if markers {
            self.markers
                .push(rec.marker(1 + D + na, "boundary marker")?.unwrap_or(0));
        }
        Ok(())
    }

    /// Appends `other`'s rows after these.
    pub fn append(&mut self, mut other: VertexRows<D>) {
        self.points.append(&mut other.points);
        self.attributes.append(&mut other.attributes);
        self.markers.append(&mut other.markers);
    }

    /// Reads the `n` vertex lines after the header `rec` (which holds the header on entry),
    /// each with `na` attributes and a marker when `markers`. The first line's number fixes
    /// the numbering base (`base_of`, as each tool decides it), which names the vertices in
    /// messages. With `rest` the vertices are the rest of the file (a `.node` file), and a big
    /// one is read on all threads ([`Records::rest_in_parts`]).
    #[allow(clippy::too_many_arguments)]
    pub fn read<'a>(
        recs: &mut Records<'a>,
        rec: &mut Record<'a>,
        n: usize,
        na: usize,
        markers: bool,
        text: &str,
        rest: bool,
        base_of: impl Fn(i64) -> u32,
    ) -> Result<(Self, u32), ParseError> {
        // Vertex ids are u32 below NONE.
        if n >= crate::NONE as usize {
            return Err(rec.error(format!(
                "too many vertices ({n}); at most {} are supported",
                crate::NONE - 1
            )));
        }
        check_attribute_count(rec, n, na, text)?;
        let mut rows = VertexRows::<D> {
            points: Vec::with_capacity(capacity(n, text)),
            attributes: Vec::with_capacity(capacity(n.saturating_mul(na), text)),
            markers: Vec::with_capacity(if markers { capacity(n, text) } else { 0 }),
        };
        let mut base = 0;
        for k in 0..n {
            recs.require(rec, || format!("vertex {} of {n}", k + 1))?;
            if k == 0 {
                base = base_of(rec.int(0, "vertex number")?);
            }
            rec.item = Some(("vertex", base as i64 + k as i64));
            rows.push(rec, na, markers)?;
            if k == 0 && rest {
                let threads = crate::threads::count().unwrap_or(1);
                let parts = recs.rest_in_parts(n - 1, threads, |r, part: &mut VertexRows<D>| {
                    part.push(r, na, markers)
                });
                if let Some(parts) = parts {
                    for part in parts {
                        rows.append(part);
                    }
                    recs.skip_to_end();
                    break;
                }
            }
        }
        Ok((rows, base))
    }
}

/// The size of text from which [`Records::rest_in_parts`] splits the work (a million-point
/// `.node` file is about 45 MB; below a few megabytes the threads cost more than they save).
pub(crate) const PARALLEL_BYTES: usize = 4 << 20;

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

/// Bytes that end a field: ASCII whitespace (as `u8::is_ascii_whitespace`: space, tab, line
/// feed, form feed, carriage return) and the comment sign.
const fn separators() -> [bool; 256] {
    let mut t = [false; 256];
    t[b' ' as usize] = true;
    t[b'\t' as usize] = true;
    t[b'\n' as usize] = true;
    t[0x0C] = true;
    t[b'\r' as usize] = true;
    t[b'#' as usize] = true;
    t
}
static SEPARATOR: [bool; 256] = separators();

/// The end of the field that starts at `i`: the first separator at or after `i`, or the end.
///
/// Numbers are most of the bytes of a large file, so this looks at eight bytes at a time: a
/// word has a candidate when one of its bytes is at most `b' '` or is `b'#'` (the classic
/// "has a byte less than n" and "has a zero byte" bit tricks; the lowest flagged byte is
/// exact, borrows only spill upwards). A candidate that is a control character but not
/// whitespace is part of the field, so it is checked byte by byte.
#[inline]
fn field_end(bytes: &[u8], mut i: usize) -> usize {
    const ONES: u64 = u64::from_ne_bytes([0x01; 8]);
    const HIGHS: u64 = u64::from_ne_bytes([0x80; 8]);
    const HASH: u64 = u64::from_ne_bytes([b'#'; 8]);
    while let Some(chunk) = bytes.get(i..i + 8) {
        let v = u64::from_le_bytes(chunk.try_into().expect("eight bytes"));
        let low = v.wrapping_sub(ONES * 0x21) & !v & HIGHS;
        let x = v ^ HASH;
        let hash = x.wrapping_sub(ONES) & !x & HIGHS;
        let candidates = low | hash;
        if candidates == 0 {
            i += 8;
            continue;
        }
        let k = i + (candidates.trailing_zeros() / 8) as usize;
        if SEPARATOR[bytes[k] as usize] {
            return k;
        }
        i = k + 1;
    }
    while i < bytes.len() && !SEPARATOR[bytes[i] as usize] {
        i += 1;
    }
    i
}

impl<'a> Records<'a> {
    /// Tokenizes `text`, the contents of `file` (the name is only used in errors).
    pub fn new(text: &'a str, file: &'a str) -> Self {
        Records {
            file,
            text,
            pos: 0,
            line_no: 0,
        }
    }

    /// The next record, or `None` at the end of the file. Reuses `rec`'s field buffer so that
    /// million-line files do not allocate per line.
    pub fn next_into(&mut self, rec: &mut Record<'a>) -> bool {
        let text = self.text;
        let bytes = text.as_bytes();
        let n = bytes.len();
        let mut i = self.pos;
        while i < n {
            self.line_no += 1;
            rec.fields.clear();
            // One line: fields until the line feed; a comment sign skips to it.
            loop {
                while i < n && SEPARATOR[bytes[i] as usize] && bytes[i] != b'\n' && bytes[i] != b'#'
                {
                    i += 1;
                }
                if i == n {
                    break;
                }
                match bytes[i] {
                    b'\n' => {
                        i += 1;
                        break;
                    }
                    b'#' => {
                        i = match bytes[i..].iter().position(|&b| b == b'\n') {
                            Some(k) => i + k + 1,
                            None => n,
                        };
                        break;
                    }
                    _ => {}
                }
                let start = i;
                i = field_end(bytes, i);
                // Both ends are at ASCII bytes (or the end), hence on character boundaries.
                rec.fields.push(&text[start..i]);
            }
            if !rec.fields.is_empty() {
                self.pos = i;
                rec.line = self.line_no;
                rec.file = self.file;
                rec.item = None;
                return true;
            }
        }
        self.pos = n;
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

    /// The records after the last one read, parsed on `threads` threads when the rest of the
    /// text is big (at least [`PARALLEL_BYTES`]) and more than one thread is allowed: it is
    /// cut at line feeds into one part per thread, `parse` reads each record of a part into
    /// that part's `T`, and the parts come back in file order. For the rest of a file whose
    /// every remaining record is of one kind (the vertex lines of a `.node` file). `None`
    /// when the text is small, when a record fails, or when the records are not `expected`
    /// in all: the caller then reads them one by one as before, which names any error with
    /// its line (here nothing is reported, and nothing is consumed).
    pub fn rest_in_parts<T: Default + Send>(
        &self,
        expected: usize,
        threads: usize,
        parse: impl Fn(&Record<'a>, &mut T) -> Result<(), ParseError> + Sync,
    ) -> Option<Vec<T>> {
        let bytes = self.text.as_bytes();
        let (start, end) = (self.pos, bytes.len());
        if threads < 2 || end - start < PARALLEL_BYTES {
            return None;
        }
        // Part boundaries: just after the first line feed at or past each even cut.
        let mut cuts = vec![start];
        for k in 1..threads {
            let at = start + (end - start) * k / threads;
            let cut = match bytes[at..].iter().position(|&b| b == b'\n') {
                Some(i) => at + i + 1,
                None => end,
            };
            cuts.push(cut.max(*cuts.last().expect("start")));
        }
        cuts.push(end);
        let parts = crate::threads::chunks(threads, threads, 1, |range, stop| {
            let mut out = Vec::new();
            for k in range {
                // Each part is a tokenizer over the text up to its end, from its start.
                let mut recs = Records {
                    file: self.file,
                    text: &self.text[..cuts[k + 1]],
                    pos: cuts[k],
                    line_no: 0,
                };
                let mut rec = recs.record();
                let mut part = T::default();
                let mut count = 0usize;
                while recs.next_into(&mut rec) {
                    if crate::threads::stopped(count, stop) {
                        return Err(());
                    }
                    parse(&rec, &mut part).map_err(|_| ())?;
                    count += 1;
                }
                out.push((part, count));
            }
            Ok(out)
        });
        let mut all = Vec::with_capacity(threads);
        let mut total = 0;
        for part in parts {
            for (t, count) in part.ok()? {
                total += count;
                all.push(t);
            }
        }
        (total == expected).then_some(all)
    }

    /// Marks the whole text read (after [`Records::rest_in_parts`] took the rest).
    pub fn skip_to_end(&mut self) {
        self.pos = self.text.len();
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
        // Valid UTF-8 (the usual case) is taken over without a copy.
        Ok(bytes) => Ok(String::from_utf8(bytes)
            .unwrap_or_else(|e| String::from_utf8_lossy(e.as_bytes()).into_owned())),
        Err(e) => Err(ParseError::new(
            &path.display().to_string(),
            0,
            format!("cannot read: {e}"),
        )),
    }
}

/// Caps pre-allocation by what the text can possibly hold, so that a corrupt count cannot
/// request gigabytes before the short file is noticed.
pub(crate) fn capacity(count: usize, text: &str) -> usize {
    count.min(text.len() / 2 + 1)
}

/// Refuses an attribute count that the text cannot hold. Missing attributes read as 0 (as in
/// Triangle and TetGen), so a corrupt count such as 10^12 would otherwise have every row push
/// that many zeros; a real file spends at least a byte on each value it declares.
pub(crate) fn check_attribute_count(
    rec: &Record<'_>,
    rows: usize,
    per_row: usize,
    text: &str,
) -> Result<(), ParseError> {
    if per_row > 0 && rows.saturating_mul(per_row) > text.len() {
        return Err(rec.error(format!(
            "{rows} rows of {per_row} attributes cannot fit in a file of {} bytes",
            text.len()
        )));
    }
    Ok(())
}

/// Parses a float exactly as `str::parse::<f64>` does (same accepted syntax, same correctly
/// rounded value, so the same as `strtod` on well-formed input), several times faster.
pub(crate) fn parse_f64(s: &str) -> Option<f64> {
    match fast_float2::parse::<f64, _>(s.as_bytes()) {
        // The sign of a NaN is the only thing the two parsers may disagree on; NaN is rare
        // enough to ask the standard parser.
        Ok(x) if x.is_nan() => s.parse::<f64>().ok(),
        Ok(x) => Some(x),
        Err(_) => None,
    }
}

/// Parses an integer; integral floats (`"3.0"`, `"1e2"`) are accepted.
pub(crate) fn parse_int(s: &str) -> Option<i64> {
    if let Ok(v) = s.parse::<i64>() {
        return Some(v);
    }
    let f = parse_f64(s)?;
    // 2^63 is exactly representable, so this range check keeps the cast lossless.
    const LIMIT: f64 = 9_223_372_036_854_775_808.0;
    if f.fract() == 0.0 && (-LIMIT..LIMIT).contains(&f) {
        Some(f as i64)
    } else {
        None
    }
}

/// What [`parse_bounds`] reads: the file's extension, the element in singular and plural,
/// and the bounded quantity (for messages).
pub(crate) struct BoundsFile {
    pub ext: &'static str,
    pub one: &'static str,
    pub many: &'static str,
    pub quantity: &'static str,
}

/// Parses a file of one bound per element, TetGen's `.vol` and Triangle's `.area`:
/// `<#elements>`, then `<#> <maximum>` per element (-1 or 0: no bound; the number is not
/// checked, as in both tools). It must have `num` lines; errors give the file and line.
pub(crate) fn parse_bounds(
    text: &str,
    file: &str,
    num: usize,
    kind: &BoundsFile,
) -> Result<Vec<f64>, ParseError> {
    let BoundsFile {
        ext,
        one,
        many,
        quantity,
    } = *kind;
    let mut recs = Records::new(text, file);
    let mut rec = recs.record();
    recs.require(&mut rec, || format!("the header line '<#{many}>'"))?;
    rec.at_most(1, &format!("the {ext} header"))?;
    let n = rec.count(0, &format!("{one} count"))?;
    if n != num {
        return Err(rec.error(format!("{n} {quantity} bounds for {num} {many}")));
    }
    let mut out = Vec::with_capacity(capacity(n, text));
    for k in 0..n {
        recs.require(&mut rec, || format!("{one} {} of {n}", k + 1))?;
        rec.at_most(2, &format!("a {ext} line"))?;
        out.push(rec.f64(1, &format!("maximum {quantity}"))?);
    }
    if recs.next_into(&mut rec) {
        return Err(rec.error(format!(
            "unexpected data after the {many} declared in the header (is a count wrong?)"
        )));
    }
    Ok(out)
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

    /// A small deterministic generator for the randomized comparisons below.
    fn rng(seed: u64) -> impl FnMut(usize) -> usize {
        let mut state = seed;
        move |m| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            ((state >> 33) as usize) % m
        }
    }

    #[test]
    fn tokenizer_matches_lines_and_split_ascii_whitespace() {
        // The reference is the obvious implementation: `str::lines`, cut at '#', split on
        // ASCII whitespace. Pieces include every separator, control characters that are not
        // separators (vertical tab, NUL), and long fields that cross the eight-byte words.
        let pieces = [
            " ",
            "\t",
            "\n",
            "\r\n",
            "\r",
            "\x0c",
            "\x0b",
            "\0",
            "#",
            "# c\n",
            "1",
            "-2.5e-3",
            "0.12345678901234567",
            "abcdefghijklmnopq",
            "é",
            "ü\x0b9",
        ];
        let mut next = rng(7);
        for _ in 0..3000 {
            let text: String = (0..next(40)).map(|_| pieces[next(pieces.len())]).collect();
            let mut want = Vec::new();
            for (k, line) in text.lines().enumerate() {
                let content = line.split('#').next().unwrap_or("");
                let fields: Vec<String> = content
                    .split_ascii_whitespace()
                    .map(str::to_string)
                    .collect();
                if !fields.is_empty() {
                    want.push((k + 1, fields));
                }
            }
            assert_eq!(all(&text), want, "{text:?}");
            let mut r = Records::new(&text, "t");
            let mut rec = r.record();
            while r.next_into(&mut rec) {}
            assert_eq!(r.eof("x").line, text.lines().count().max(1), "{text:?}");
        }
    }

    fn same(a: Option<f64>, b: Option<f64>) -> bool {
        match (a, b) {
            (None, None) => true,
            (Some(x), Some(y)) => x.to_bits() == y.to_bits(),
            _ => false,
        }
    }

    #[test]
    fn floats_parse_exactly_as_the_standard_parser() {
        let tricky = [
            "0",
            "-0",
            "+0",
            "-0.0",
            "0e0",
            "1",
            "-1",
            "+1.5",
            ".5",
            "5.",
            "-.5e-1",
            "1e",
            "1e+",
            "e5",
            ".",
            "-",
            "+",
            "",
            "1.0.0",
            "1e5.0",
            "0x10",
            "1_000",
            " 1",
            "1 ",
            // Halfway and near-halfway cases, many digits, exponents at the edges.
            "9007199254740993",
            "9007199254740992.9999999999999999999999999999",
            "2.2250738585072011e-308",
            "2.2250738585072012e-308",
            "4.9406564584124654e-324",
            "2.4703282292062327e-324",
            "2.4703282292062328e-324",
            "1e-400",
            "-1e-400",
            "1.7976931348623157e308",
            "1.7976931348623158e308",
            "1.7976931348623159e308",
            "1e309",
            "-1e309",
            "0.1000000000000000055511151231257827021181583404541015625",
            "0.1000000000000000055511151231257827021181583404541015624",
            "0.1000000000000000055511151231257827021181583404541015626",
            "123456789012345678901234567890e-20",
            "0.000000000000000000000000000000000000000000001e45",
            "1E22",
            "1e23",
            "8.98846567431158e307",
            "3.0e-5",
            "1.e5",
            "00000000001.5",
            // Non-finite values, in the spellings the standard parser accepts.
            "inf",
            "-inf",
            "+inf",
            "Inf",
            "INF",
            "infinity",
            "-Infinity",
            "infinit",
            "infinityy",
            "nan",
            "NaN",
            "-nan",
            "+NAN",
            "nana",
            "in",
            "na",
        ];
        for s in tricky {
            let want = s.parse::<f64>().ok();
            let got = parse_f64(s);
            let nan = |v: Option<f64>| v.is_some_and(f64::is_nan);
            assert!(
                same(want, got) || (nan(want) && nan(got)),
                "{s:?}: {want:?} vs {got:?}"
            );
        }
        // Random strings over the characters of the syntax, and random bit patterns printed
        // with many digits (17) and too many (25).
        let alphabet = [
            "0",
            "1",
            "5",
            "9",
            ".",
            "e",
            "E",
            "+",
            "-",
            "i",
            "n",
            "f",
            "a",
            "y",
            "N",
            "F",
            "inity",
            "00000000000",
            "99999999999",
        ];
        let mut next = rng(11);
        let mut accepted = 0;
        for _ in 0..200_000 {
            let s: String = (0..1 + next(8))
                .map(|_| alphabet[next(alphabet.len())])
                .collect();
            let want = s.parse::<f64>().ok();
            accepted += want.is_some() as usize;
            let got = parse_f64(&s);
            assert!(
                same(want, got) || want.is_some_and(f64::is_nan) && got.is_some_and(f64::is_nan),
                "{s:?}: {want:?} vs {got:?}"
            );
        }
        assert!(
            accepted > 5000,
            "only {accepted} of the random strings were numbers"
        );
        for _ in 0..100_000 {
            let bits = (next(1 << 31) as u64) << 33 ^ (next(1 << 31) as u64) << 2 ^ next(4) as u64;
            let x = f64::from_bits(bits);
            for s in [format!("{x:.16e}"), format!("{x:.24e}"), format!("{x:e}")] {
                assert!(same(s.parse().ok(), parse_f64(&s)), "{s}");
            }
        }
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
    fn rest_in_parts_gives_the_records_in_order_for_any_thread_count() {
        let mut text = String::from("header\n");
        let n = 400_000;
        for i in 0..n {
            text.push_str(&format!(
                "{i} {}.5{}",
                i * 3,
                if i % 9 == 0 { " # c\n\n" } else { "\n" }
            ));
        }
        assert!(text.len() > PARALLEL_BYTES);
        let mut recs = Records::new(&text, "t");
        let mut rec = recs.record();
        assert!(recs.next_into(&mut rec));
        let read = |r: &Record<'_>, out: &mut Vec<f64>| {
            out.push(r.f64(1, "value")?);
            Ok(())
        };
        assert!(
            recs.rest_in_parts(n, 1, read).is_none(),
            "one thread: line by line"
        );
        for threads in [2, 3, 4, 7] {
            let parts = recs.rest_in_parts(n, threads, read).unwrap();
            assert_eq!(parts.len(), threads);
            let all: Vec<f64> = parts.into_iter().flatten().collect();
            assert_eq!(all.len(), n);
            assert!(all
                .iter()
                .enumerate()
                .all(|(i, &x)| x == (i * 3) as f64 + 0.5));
            assert!(
                recs.rest_in_parts(n + 1, threads, read).is_none(),
                "a count off"
            );
        }
        // A bad record anywhere: no parts (the caller reads line by line and names it).
        let bad = text.replacen("\n399990 ", "\n399990 x", 1);
        let mut recs = Records::new(&bad, "t");
        assert!(recs.next_into(&mut rec));
        assert!(recs.rest_in_parts(n, 2, read).is_none());
        // Nothing was consumed.
        assert!(recs.next_into(&mut rec));
        assert_eq!(rec.fields[0], "0");
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
