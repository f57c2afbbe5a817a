//! The error type of every reader.

use std::fmt;

/// A problem found while reading an input file: which file, which line, and what is wrong.
///
/// `line` is 1-based. It is 0 when the problem is not tied to a line (for example the file
/// could not be opened); `Display` then omits it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ParseError {
    /// The file name as given by the caller.
    pub file: String,
    /// The 1-based line number, or 0 for "the whole file".
    pub line: usize,
    /// What is wrong, naming the offending item.
    pub message: String,
}

impl ParseError {
    /// Builds an error for `file` at `line`.
    pub fn new(file: &str, line: usize, message: impl Into<String>) -> Self {
        ParseError {
            file: file.to_string(),
            line,
            message: message.into(),
        }
    }
}

impl fmt::Display for ParseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.line == 0 {
            write!(f, "{}: {}", self.file, self.message)
        } else {
            write!(f, "{}:{}: {}", self.file, self.line, self.message)
        }
    }
}

impl std::error::Error for ParseError {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_has_file_line_and_message() {
        let e = ParseError::new("a.poly", 7, "bad number 'x'");
        assert_eq!(e.to_string(), "a.poly:7: bad number 'x'");
        let e = ParseError::new("a.poly", 0, "cannot open");
        assert_eq!(e.to_string(), "a.poly: cannot open");
    }
}
