//! What every reader shares: reading a file (a folder is named as such), the text of a file
//! (UTF-8 with an optional byte-order mark), quoting a file's text in a message (control and
//! invisible characters escaped, long text shortened) and the notes a reader leaves.

use crate::error::{CloudError, Result};
use std::path::Path;

/// The UTF-8 byte-order mark some Windows tools write at the start of text files.
const BOM: &[u8] = b"\xef\xbb\xbf";

/// The longest piece of a file's text quoted in a message, in characters.
const MAX_SHOWN: usize = 60;

/// Reads a whole file. A folder is "is a folder, not a file"; other failures are the
/// operating system's error, naming the path.
pub(crate) fn read_file(path: &Path) -> Result<Vec<u8>> {
    std::fs::read(path).map_err(|e| CloudError::reading(path, e))
}

/// `bytes` without a leading UTF-8 byte-order mark.
pub(crate) fn strip_bom(bytes: &[u8]) -> &[u8] {
    bytes.strip_prefix(BOM).unwrap_or(bytes)
}

/// The text of a file (byte-order mark removed); invalid UTF-8 is a parse error naming its line.
pub(crate) fn text<'a>(path: &Path, bytes: &'a [u8]) -> Result<&'a str> {
    let bytes = strip_bom(bytes);
    std::str::from_utf8(bytes).map_err(|e| {
        let good = bytes.get(..e.valid_up_to()).unwrap_or_default();
        let line = 1 + good.iter().filter(|&&b| b == b'\n').count();
        CloudError::parse(path, line, "not UTF-8 text")
    })
}

/// A piece of a file's text as it may appear in a message: control characters, NUL and
/// invisible or direction-changing characters escaped as `\u{..}`, and at most 60 characters
/// (then `...`), so that no file can write to the terminal through an error message.
pub(crate) fn shown(s: &str) -> String {
    let mut out = String::with_capacity(s.len().min(4 * MAX_SHOWN));
    for (k, c) in s.chars().enumerate() {
        if k == MAX_SHOWN {
            out.push_str("...");
            break;
        }
        if invisible(c) {
            out.extend(c.escape_unicode());
        } else {
            out.push(c);
        }
    }
    out
}

/// Characters that must not reach a terminal as they are.
fn invisible(c: char) -> bool {
    c.is_control()
        || matches!(c,
            '\u{200B}'..='\u{200F}' // zero-width spaces, marks
            | '\u{2028}'..='\u{202E}' // line/paragraph separators, bidirectional embeddings
            | '\u{2060}'..='\u{206F}' // word joiner, invisible operators, bidirectional isolates
            | '\u{FEFF}' // byte-order mark
            | '\u{FFF9}'..='\u{FFFB}' // interlinear annotations
        )
}

/// Things a reader converted or skipped rather than refusing the file, each naming the file.
pub(crate) struct Notes<'a> {
    path: &'a Path,
    pub(crate) list: Vec<String>,
}

impl<'a> Notes<'a> {
    pub(crate) fn new(path: &'a Path) -> Self {
        Notes {
            path,
            list: Vec::new(),
        }
    }

    /// Adds `path: msg`.
    pub(crate) fn add(&mut self, msg: impl std::fmt::Display) {
        self.list.push(format!("{}: {msg}", self.path.display()));
    }
}

/// Prints each note to standard error as `note: ...`.
pub fn print_notes(notes: &[String]) {
    for n in notes {
        eprintln!("note: {n}");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shown_escapes_what_a_terminal_would_interpret() {
        assert_eq!(shown("abc é"), "abc é");
        assert_eq!(shown("a\u{0}b\u{1b}[31m"), "a\\u{0}b\\u{1b}[31m");
        assert_eq!(shown("\u{feff}#"), "\\u{feff}#");
        assert_eq!(shown("x\u{202e}y"), "x\\u{202e}y");
        let long = "9".repeat(1000);
        assert_eq!(shown(&long).len(), MAX_SHOWN + 3);
    }

    #[test]
    fn text_strips_a_bom_and_names_the_bad_line() {
        assert_eq!(
            text(Path::new("a"), b"\xef\xbb\xbf1 2 3\n").ok(),
            Some("1 2 3\n")
        );
        let e = text(Path::new("a"), b"1\n2\n\xff\n").unwrap_err();
        assert!(matches!(e, CloudError::Parse { line: 3, .. }), "{e}");
    }
}
