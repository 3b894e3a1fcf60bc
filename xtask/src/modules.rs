//! A crate's module tree read from its files: which file each module is, its children
//! (`mod x;`), the items it defines and the names it imports (which may be re-exports).

use crate::lexer::{remove_test_items, strip_comments_and_literals, words};
use crate::paths::{use_statements, UsePath};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// One module backed by its own file.
#[derive(Debug)]
pub struct Module {
    /// The file.
    pub file: PathBuf,
    /// Its parent module (`None` for the crate root).
    pub parent: Option<usize>,
    /// Child modules declared with `mod name;`, by name.
    pub children: BTreeMap<String, usize>,
    /// The code without comments, literals and `#[cfg(test)]` items.
    pub code: String,
    /// Names of the items it defines (`fn`, `struct`, `enum`, `trait`, `type`, `const`, ...).
    pub items: Vec<String>,
    /// Its `use` statements, expanded: the name they bind and the path they name.
    pub imports: Vec<UsePath>,
}

/// A crate: module 0 is its root (`lib.rs` or `main.rs`).
#[derive(Debug)]
pub struct CrateTree {
    /// All modules backed by files.
    pub modules: Vec<Module>,
}

impl CrateTree {
    /// Reads the crate whose root file is `root` and every file its `mod` lines reach.
    pub fn load(root: &Path) -> std::io::Result<CrateTree> {
        let mut tree = CrateTree {
            modules: Vec::new(),
        };
        tree.add(root, None)?;
        Ok(tree)
    }

    fn add(&mut self, file: &Path, parent: Option<usize>) -> std::io::Result<usize> {
        let text = std::fs::read_to_string(file)?;
        let code = remove_test_items(&strip_comments_and_literals(&text));
        let idx = self.modules.len();
        self.modules.push(Module {
            file: file.to_path_buf(),
            parent,
            children: BTreeMap::new(),
            items: defined_items(&code),
            imports: use_statements(&code),
            code: code.clone(),
        });
        let dir = child_dir(file);
        for name in declared_modules(&code) {
            let flat = dir.join(format!("{name}.rs"));
            let nested = dir.join(&name).join("mod.rs");
            let child_file = if flat.is_file() { flat } else { nested };
            if child_file.is_file() {
                let c = self.add(&child_file, Some(idx))?;
                self.modules[idx].children.insert(name, c);
            }
        }
        Ok(idx)
    }

    /// True if `a` is `b` or one of `b`'s ancestors.
    pub fn is_ancestor_or_self(&self, a: usize, b: usize) -> bool {
        let mut m = Some(b);
        while let Some(k) = m {
            if k == a {
                return true;
            }
            m = self.modules[k].parent;
        }
        false
    }
}

/// The folder in which a file's child modules live: its own for `lib.rs`, `main.rs` and
/// `mod.rs`, else a folder named after the file.
fn child_dir(file: &Path) -> PathBuf {
    let dir = file.parent().map(Path::to_path_buf).unwrap_or_default();
    match file.file_name().and_then(|n| n.to_str()) {
        Some("lib.rs" | "main.rs" | "mod.rs") => dir,
        _ => dir.join(file.file_stem().unwrap_or_default()),
    }
}

/// Names of `mod name;` declarations (not inline `mod name { ... }`).
fn declared_modules(code: &str) -> Vec<String> {
    let w = words(code);
    (0..w.len().saturating_sub(2))
        .filter(|&i| w[i] == "mod" && w[i + 2] == ";")
        .map(|i| w[i + 1].to_string())
        .collect()
}

/// Names of the items a file defines.
fn defined_items(code: &str) -> Vec<String> {
    const KINDS: [&str; 9] = [
        "fn",
        "struct",
        "enum",
        "trait",
        "type",
        "const",
        "static",
        "union",
        "macro_rules",
    ];
    let w = words(code);
    (0..w.len().saturating_sub(1))
        .filter(|&i| KINDS.contains(&w[i]))
        .map(|i| {
            if w[i] == "macro_rules" {
                w.get(i + 2).copied().unwrap_or_default().to_string()
            } else {
                w[i + 1].to_string()
            }
        })
        .collect()
}
