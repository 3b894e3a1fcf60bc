//! Paths a file refers to: expanded `use` trees, and inline paths such as `crate::a::B` or
//! `child::f()` in the code.

use crate::lexer::words;

/// One name a `use` statement binds, and the path it names (`self` resolved).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UsePath {
    /// The name it binds (the last segment, or the `as` alias; `*` for a glob).
    pub name: String,
    /// The path's segments, e.g. `["crate", "walls", "Wall"]`.
    pub segments: Vec<String>,
}

/// Every `use` statement of `code`, expanded into one [`UsePath`] per name it binds.
pub fn use_statements(code: &str) -> Vec<UsePath> {
    let w = words(code);
    let mut out = Vec::new();
    let mut i = 0;
    while i < w.len() {
        if w[i] == "use" {
            let end = (i..w.len()).find(|&j| w[j] == ";").unwrap_or(w.len());
            expand(&w[i + 1..end], &[], &mut out);
            i = end;
        }
        i += 1;
    }
    out
}

/// Expands one use tree (`a::b::{c, d::e as f, self, *}`) with `prefix` already read.
fn expand(tree: &[&str], prefix: &[String], out: &mut Vec<UsePath>) {
    let mut segs: Vec<String> = prefix.to_vec();
    let mut i = 0;
    while i < tree.len() {
        match tree[i] {
            ":" => i += 1,
            "{" => {
                // Split the group at top-level commas.
                let close = matching_brace(tree, i);
                let mut start = i + 1;
                let mut depth = 0;
                for k in i + 1..close {
                    match tree[k] {
                        "{" => depth += 1,
                        "}" => depth -= 1,
                        "," if depth == 0 => {
                            expand(&tree[start..k], &segs, out);
                            start = k + 1;
                        }
                        _ => {}
                    }
                }
                expand(&tree[start..close], &segs, out);
                return;
            }
            "as" => {
                if let (Some(alias), false) = (tree.get(i + 1), segs.is_empty()) {
                    out.push(UsePath {
                        name: alias.to_string(),
                        segments: segs,
                    });
                }
                return;
            }
            "*" => {
                out.push(UsePath {
                    name: "*".into(),
                    segments: segs,
                });
                return;
            }
            "self" if i > 0 || !prefix.is_empty() => {}
            s if s.chars().all(|c| c.is_alphanumeric() || c == '_') => segs.push(s.to_string()),
            _ => {}
        }
        i += 1;
    }
    if let Some(last) = segs.last() {
        out.push(UsePath {
            name: last.clone(),
            segments: segs,
        });
    }
}

fn matching_brace(tree: &[&str], open: usize) -> usize {
    let mut depth = 0;
    for (k, t) in tree.iter().enumerate().skip(open) {
        match *t {
            "{" => depth += 1,
            "}" => {
                depth -= 1;
                if depth == 0 {
                    return k;
                }
            }
            _ => {}
        }
    }
    tree.len()
}

/// Inline paths outside `use` statements that start with `crate`, `super`, `self` or one of
/// `heads` (the module's children and imported names), as segment lists.
pub fn inline_paths(code: &str, heads: &[String]) -> Vec<Vec<String>> {
    let w = words(code);
    let mut out = Vec::new();
    let mut i = 0;
    while i < w.len() {
        if w[i] == "use" {
            i = (i..w.len()).find(|&j| w[j] == ";").unwrap_or(w.len());
            continue;
        }
        let after_colons = i >= 2 && w[i - 1] == ":" && w[i - 2] == ":";
        let head = matches!(w[i], "crate" | "super" | "self") || heads.iter().any(|h| h == w[i]);
        if head && !after_colons && w.get(i + 1) == Some(&":") && w.get(i + 2) == Some(&":") {
            let mut segs = vec![w[i].to_string()];
            let mut j = i + 3;
            while j < w.len() && is_ident(w[j]) {
                segs.push(w[j].to_string());
                if w.get(j + 1) == Some(&":") && w.get(j + 2) == Some(&":") {
                    j += 3;
                } else {
                    break;
                }
            }
            out.push(segs);
            i = j;
        }
        i += 1;
    }
    out
}

fn is_ident(s: &str) -> bool {
    s.chars().all(|c| c.is_alphanumeric() || c == '_')
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(v: &[UsePath]) -> Vec<String> {
        v.iter()
            .map(|u| format!("{}={}", u.name, u.segments.join("::")))
            .collect()
    }

    #[test]
    fn use_trees_expand_with_groups_aliases_self_and_globs() {
        let u = use_statements("pub(crate) use crate::{a::{self, B as C}, d::*}; use super::e::F;");
        assert_eq!(
            names(&u),
            ["a=crate::a", "C=crate::a::B", "*=crate::d", "F=super::e::F"]
        );
    }

    #[test]
    fn inline_paths_start_at_known_heads_only() {
        let p = inline_paths(
            "use crate::x::Y; fn f() { crate::a::g(); fit::h(); std::mem::drop(1); z::crate_like(); }",
            &["fit".to_string()],
        );
        let p: Vec<String> = p.iter().map(|s| s.join("::")).collect();
        assert_eq!(p, ["crate::a::g", "fit::h"]);
    }
}
