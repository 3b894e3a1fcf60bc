//! A small XML writer for the MJCF and SDF exports: indented elements, escaped attribute
//! values and text, comments that stay comments, and numbers written so that they read back
//! exactly (Rust's shortest round-trip form).

use std::fmt::Write as _;

/// An XML document being written, element by element.
pub(crate) struct Xml {
    out: String,
    open: Vec<String>,
}

/// An attribute: name and (unescaped) value.
pub(crate) type Attr<'a> = (&'a str, String);

impl Xml {
    /// A document with the XML declaration.
    pub(crate) fn new() -> Xml {
        Xml {
            out: String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"),
            open: vec![],
        }
    }

    fn indent(&mut self) {
        for _ in 0..self.open.len() {
            self.out.push_str("  ");
        }
    }

    fn start_tag(&mut self, tag: &str, attrs: &[Attr]) {
        self.indent();
        self.out.push('<');
        self.out.push_str(tag);
        for (name, value) in attrs {
            let _ = write!(self.out, " {name}=\"{}\"", escape(value));
        }
    }

    /// Opens an element; [`Xml::close`] closes it.
    pub(crate) fn open(&mut self, tag: &str, attrs: &[Attr]) {
        self.start_tag(tag, attrs);
        self.out.push_str(">\n");
        self.open.push(tag.to_string());
    }

    /// Closes the innermost open element.
    pub(crate) fn close(&mut self) {
        if let Some(tag) = self.open.pop() {
            self.indent();
            let _ = writeln!(self.out, "</{tag}>");
        }
    }

    /// An empty element (`<tag a="1"/>`).
    pub(crate) fn empty(&mut self, tag: &str, attrs: &[Attr]) {
        self.start_tag(tag, attrs);
        self.out.push_str("/>\n");
    }

    /// An element holding text (`<tag>text</tag>`).
    pub(crate) fn text(&mut self, tag: &str, attrs: &[Attr], text: &str) {
        self.start_tag(tag, attrs);
        let _ = writeln!(self.out, ">{}</{tag}>", escape(text));
    }

    /// A comment (a `--` in the text is broken up, which XML forbids in comments).
    pub(crate) fn comment(&mut self, text: &str) {
        let mut safe = text.replace("--", "- -");
        if safe.ends_with('-') {
            safe.push(' ');
        }
        self.indent();
        let _ = writeln!(self.out, "<!-- {safe} -->");
    }

    /// The document, every open element closed.
    pub(crate) fn finish(mut self) -> String {
        while !self.open.is_empty() {
            self.close();
        }
        self.out
    }
}

/// Escapes the five XML special characters; control characters XML 1.0 cannot carry
/// (all but tab, newline and carriage return) become spaces.
pub(crate) fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            '\t' | '\n' | '\r' => out.push(c),
            c if (c as u32) < 0x20 || c == '\u{fffe}' || c == '\u{ffff}' => out.push(' '),
            c => out.push(c),
        }
    }
    out
}

/// A number in its shortest round-trip form (`0.7`, `-1.5707963267948966`), `-0` as `0`.
pub(crate) fn num(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else {
        format!("{v}")
    }
}

/// Numbers separated by spaces.
pub(crate) fn nums(values: &[f64]) -> String {
    values.iter().map(|v| num(*v)).collect::<Vec<_>>().join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_and_nests() {
        let mut x = Xml::new();
        x.open("a", &[("name", "x<\"&'>".into())]);
        x.comment("no -- here-");
        x.text("b", &[], "1 < 2");
        x.empty("c", &[("v", nums(&[0.5, -0.0, 1e-3]))]);
        let s = x.finish();
        assert!(s.contains("<a name=\"x&lt;&quot;&amp;&apos;&gt;\">"), "{s}");
        assert!(s.contains("<!-- no - - here-  -->"), "{s}");
        assert!(s.contains("  <b>1 &lt; 2</b>"), "{s}");
        assert!(s.contains("<c v=\"0.5 0 0.001\"/>"), "{s}");
        assert!(s.ends_with("</a>\n"), "{s}");
    }
}
