//! Source text reduced to what the import checker reads: comments, string and character
//! literals blanked out, and `#[cfg(test)]` items removed (test code may reach anywhere).

/// `src` with comments, string literals and char literals replaced by spaces (line breaks
/// kept), so paths inside them are not read as references.
pub fn strip_comments_and_literals(src: &str) -> String {
    let b: Vec<char> = src.chars().collect();
    let mut out = String::with_capacity(src.len());
    let mut i = 0;
    let blank = |c: char| if c == '\n' { '\n' } else { ' ' };
    while i < b.len() {
        let c = b[i];
        let next = b.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < b.len() && b[i] != '\n' {
                out.push(' ');
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0usize;
            while i < b.len() {
                if b[i] == '/' && b.get(i + 1) == Some(&'*') {
                    depth += 1;
                    out.push_str("  ");
                    i += 2;
                } else if b[i] == '*' && b.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    out.push_str("  ");
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    out.push(blank(b[i]));
                    i += 1;
                }
            }
        } else if c == 'r' && (next == Some('"') || next == Some('#')) && !ident_before(&b, i) {
            // Raw string r"..." or r#"..."#.
            let mut j = i + 1;
            let mut hashes = 0;
            while b.get(j) == Some(&'#') {
                hashes += 1;
                j += 1;
            }
            if b.get(j) != Some(&'"') {
                out.push(c);
                i += 1;
                continue;
            }
            j += 1;
            while j < b.len() {
                if b[j] == '"' && (0..hashes).all(|h| b.get(j + 1 + h) == Some(&'#')) {
                    j += 1 + hashes;
                    break;
                }
                j += 1;
            }
            for &ch in &b[i..j.min(b.len())] {
                out.push(blank(ch));
            }
            i = j;
        } else if c == '"' {
            out.push(' ');
            i += 1;
            while i < b.len() && b[i] != '"' {
                if b[i] == '\\' {
                    out.push(' ');
                    i += 1;
                }
                if i < b.len() {
                    out.push(blank(b[i]));
                    i += 1;
                }
            }
            out.push(' ');
            i += 1;
        } else if c == '\'' {
            // A char literal ('a', '\n', '\u{..}') or a lifetime ('a): only the first is blanked.
            let close = if next == Some('\\') {
                (i + 2..b.len().min(i + 12)).find(|&j| b[j] == '\'')
            } else if b.get(i + 2) == Some(&'\'') {
                Some(i + 2)
            } else {
                None
            };
            match close {
                Some(j) => {
                    for _ in i..=j {
                        out.push(' ');
                    }
                    i = j + 1;
                }
                None => {
                    out.push(c);
                    i += 1;
                }
            }
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

fn ident_before(b: &[char], i: usize) -> bool {
    i > 0 && (b[i - 1].is_alphanumeric() || b[i - 1] == '_')
}

/// `code` (already stripped) without the items that follow a `#[cfg(test)]` attribute: a
/// `mod tests { ... }`, a `mod tests;`, or any other item up to its closing brace or semicolon.
pub fn remove_test_items(code: &str) -> String {
    let mut out = String::with_capacity(code.len());
    let mut rest = code;
    while let Some(at) = rest.find("#[cfg(test)]") {
        out.push_str(&rest[..at]);
        let item = &rest[at..];
        let end = item_end(item);
        for ch in item[..end].chars() {
            out.push(if ch == '\n' { '\n' } else { ' ' });
        }
        rest = &item[end..];
    }
    out.push_str(rest);
    out
}

/// Byte length of the item starting at `s` (its attribute included): up to the `;` or the
/// brace that closes its first `{`, whichever comes first at depth 0.
fn item_end(s: &str) -> usize {
    let mut depth = 0i32;
    let attr_end = s.find(']').map_or(0, |e| e + 1);
    for (k, ch) in s[attr_end..].char_indices() {
        match ch {
            '{' => depth += 1,
            '}' => {
                depth -= 1;
                if depth == 0 {
                    return attr_end + k + 1;
                }
            }
            ';' if depth == 0 => return attr_end + k + 1,
            _ => {}
        }
    }
    s.len()
}

/// Words of `code` (identifiers and single punctuation characters), in order.
pub fn words(code: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let mut start = None;
    for (i, ch) in code.char_indices() {
        let ident = ch.is_alphanumeric() || ch == '_';
        match (ident, start) {
            (true, None) => start = Some(i),
            (false, Some(s)) => {
                out.push(&code[s..i]);
                start = None;
            }
            _ => {}
        }
        if !ident && !ch.is_whitespace() {
            out.push(&code[i..i + ch.len_utf8()]);
        }
    }
    if let Some(s) = start {
        out.push(&code[s..]);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paths_in_comments_strings_and_chars_are_blanked_but_lifetimes_stay() {
        let src = "use crate::a; // crate::b\n/* crate::c */ let s = \"crate::d\"; let c = '\"'; fn f<'a>(x: &'a crate::e::E) {}";
        let out = strip_comments_and_literals(src);
        assert!(out.contains("crate::a"));
        assert!(
            !out.contains("crate::b") && !out.contains("crate::c") && !out.contains("crate::d")
        );
        assert!(out.contains("&'a crate::e::E"));
        assert_eq!(out.lines().count(), src.lines().count());
    }

    #[test]
    fn test_modules_and_test_only_items_are_removed() {
        let code = "use crate::a;\n#[cfg(test)]\nmod tests {\n use crate::b; fn f() { {} }\n}\nuse crate::c;\n#[cfg(test)]\nuse crate::d;\n";
        let out = remove_test_items(code);
        assert!(out.contains("crate::a") && out.contains("crate::c"));
        assert!(!out.contains("crate::b") && !out.contains("crate::d"));
    }
}
