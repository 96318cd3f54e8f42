//! Errors with `file:line:col` and the source map that turns byte spans into line:column.

/// A byte range `start..end` in the source text.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Span {
    /// First byte.
    pub start: usize,
    /// One past the last byte.
    pub end: usize,
}

/// A located error in a PDDL (or plan) file: `file:line:col: message`.
///
/// `line` and `col` are 1-based; `col` counts characters (not bytes) from the start of the line.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{file}:{line}:{col}: {message}")]
pub struct PddlError {
    /// The file name as given by the caller.
    pub file: String,
    /// 1-based line.
    pub line: usize,
    /// 1-based column, in characters.
    pub col: usize,
    /// What is wrong, naming the offending construct.
    pub message: String,
}

/// A named text: a file's name, as error locations give it, and its contents.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Source {
    /// The file name (`domain.pddl`, a path, `<stdin>`).
    pub file: String,
    /// The text.
    pub text: String,
}

impl Source {
    /// A text under a file name.
    pub fn new(file: impl Into<String>, text: impl Into<String>) -> Self {
        Source {
            file: file.into(),
            text: text.into(),
        }
    }

    /// Reads a file as UTF-8 text ([`read_source`]), named by its path.
    pub fn read(path: impl AsRef<std::path::Path>) -> Result<Source, PddlError> {
        let path = path.as_ref();
        Ok(Source::new(path.display().to_string(), read_source(path)?))
    }
}

/// A source text with its file name and line index, to locate byte spans.
#[derive(Clone, Debug, Default)]
pub(crate) struct SourceMap {
    pub(crate) file: String,
    pub(crate) text: String,
    line_starts: Vec<usize>,
}

impl SourceMap {
    pub(crate) fn new(text: &str, file: &str) -> Self {
        let mut line_starts = vec![0];
        line_starts.extend(
            text.bytes()
                .enumerate()
                .filter(|&(_, b)| b == b'\n')
                .map(|(i, _)| i + 1),
        );
        SourceMap {
            file: file.to_string(),
            text: text.to_string(),
            line_starts,
        }
    }

    /// 1-based (line, column in characters) of byte offset `pos` (clamped to the text).
    pub(crate) fn line_col(&self, pos: usize) -> (usize, usize) {
        let pos = pos.min(self.text.len());
        let line = match self.line_starts.binary_search(&pos) {
            Ok(i) => i,
            Err(i) => i - 1,
        };
        let start = self.line_starts[line];
        let mut end = pos;
        while !self.text.is_char_boundary(end) {
            end -= 1;
        }
        let col = self.text[start..end].chars().count() + 1;
        (line + 1, col)
    }

    /// An error located at the start of `span`.
    pub(crate) fn error(&self, span: Span, message: impl Into<String>) -> PddlError {
        let (line, col) = self.line_col(span.start);
        PddlError {
            file: self.file.clone(),
            line,
            col,
            message: message.into(),
        }
    }
}

/// Decodes file bytes as UTF-8 (the file-reading layer). Invalid UTF-8 is reported at the line and
/// column of the first bad byte, never a panic.
pub fn decode_source(bytes: Vec<u8>, file: &str) -> Result<String, PddlError> {
    match String::from_utf8(bytes) {
        Ok(s) => Ok(s),
        Err(e) => {
            let valid = e.utf8_error().valid_up_to();
            let bytes = e.into_bytes();
            let prefix = std::str::from_utf8(&bytes[..valid]).unwrap_or_default();
            let src = SourceMap::new(prefix, file);
            Err(src.error(
                Span {
                    start: valid,
                    end: valid,
                },
                format!("invalid UTF-8 byte 0x{:02x}", bytes[valid]),
            ))
        }
    }
}

/// Reads a file as UTF-8 text; a missing or unreadable file is an error at `file:1:1`.
pub fn read_source(path: &std::path::Path) -> Result<String, PddlError> {
    let file = path.display().to_string();
    match std::fs::read(path) {
        Ok(bytes) => decode_source(bytes, &file),
        Err(e) => Err(PddlError {
            file,
            line: 1,
            col: 1,
            message: format!("cannot read file: {e}"),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_col_counts_characters_from_one() {
        let s = SourceMap::new("ab\nçd\n\nx", "f");
        assert_eq!(s.line_col(0), (1, 1));
        assert_eq!(s.line_col(2), (1, 3));
        assert_eq!(s.line_col(3), (2, 1));
        assert_eq!(s.line_col(5), (2, 2)); // after the 2-byte 'ç'
        assert_eq!(s.line_col(7), (3, 1));
        assert_eq!(s.line_col(8), (4, 1));
        assert_eq!(s.line_col(100), (4, 2));
    }

    #[test]
    fn invalid_utf8_is_located() {
        let e = decode_source(b"(define\n  (x \xff))".to_vec(), "d.pddl").unwrap_err();
        assert_eq!((e.line, e.col), (2, 6));
        assert!(e.message.contains("0xff"), "{e}");
    }
}
