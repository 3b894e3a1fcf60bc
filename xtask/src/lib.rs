//! Repository checks for semsim, run by CI and by anyone (`cargo run -p xtask -- import-cycles`).
//!
//! **No file-level import cycle inside any crate.** A file refers to another when it names an
//! item defined there: through `use crate::...`, `use super::...`, a child module's name, or an
//! inline path such as `crate::walls::Wall`; names re-exported by `lib.rs` (or any module)
//! resolve to the file that defines them, and `#[cfg(test)]` items are not read. A child may
//! refer to its ancestors (types shared by siblings live in the parent), so those edges are
//! left out; any other cycle of references between files is reported.
//!
//! ```
//! let dir = std::env::temp_dir().join(format!("xtask-doc-{}", std::process::id()));
//! std::fs::create_dir_all(&dir).unwrap();
//! std::fs::write(dir.join("lib.rs"), "mod a;\nmod b;\n").unwrap();
//! std::fs::write(dir.join("a.rs"), "use crate::b::B;\npub struct A;\n").unwrap();
//! std::fs::write(dir.join("b.rs"), "pub struct B(crate::a::A);\n").unwrap();
//! let cycles = xtask::crate_cycles(&dir.join("lib.rs")).unwrap();
//! assert_eq!(cycles.len(), 1);
//! assert!(cycles[0].files.iter().any(|f| f.ends_with("a.rs")));
//! std::fs::remove_dir_all(&dir).unwrap();
//! ```
#![warn(missing_docs)]

mod graph;
mod lexer;
mod modules;
mod paths;
mod resolve;

use std::path::{Path, PathBuf};

/// An import cycle: the files in it and the references that close it.
#[derive(Debug, Clone)]
pub struct Cycle {
    /// The files, in path order.
    pub files: Vec<PathBuf>,
    /// `from -> to (via path)` for every reference inside the cycle.
    pub references: Vec<String>,
}

/// The import cycles of the crate whose root file (`lib.rs` or `main.rs`) is `root`, and the
/// the references that close them.
pub fn crate_cycles(root: &Path) -> std::io::Result<Vec<Cycle>> {
    Ok(check_crate(root)?.0)
}

fn check_crate(root: &Path) -> std::io::Result<(Vec<Cycle>, usize)> {
    let tree = modules::CrateTree::load(root)?;
    let edges = graph::edges(&tree);
    let name = |k: usize| tree.modules[k].file.clone();
    let cycles = graph::cycles(tree.modules.len(), &edges)
        .into_iter()
        .map(|comp| Cycle {
            files: {
                let mut f: Vec<PathBuf> = comp.iter().map(|&k| name(k)).collect();
                f.sort();
                f
            },
            references: edges
                .iter()
                .filter(|e| comp.contains(&e.from) && comp.contains(&e.to))
                .map(|e| {
                    format!(
                        "{} -> {} (via {})",
                        name(e.from).display(),
                        name(e.to).display(),
                        e.via
                    )
                })
                .collect(),
        })
        .collect();
    Ok((cycles, tree.modules.len()))
}

/// What [`workspace_cycles`] found.
#[derive(Debug, Default)]
pub struct WorkspaceReport {
    /// Crate roots checked.
    pub crates: Vec<PathBuf>,
    /// Files read.
    pub files: usize,
    /// Cycles found, all crates together.
    pub cycles: Vec<Cycle>,
}

/// Checks every crate under `workspace/crates/*/src` and `workspace/xtask/src` (library and
/// binary roots alike).
pub fn workspace_cycles(workspace: &Path) -> std::io::Result<WorkspaceReport> {
    let mut report = WorkspaceReport::default();
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(workspace.join("crates"))?
        .filter_map(|e| e.ok().map(|e| e.path().join("src")))
        .collect();
    dirs.push(workspace.join("xtask/src"));
    dirs.sort();
    for dir in dirs {
        for root in ["lib.rs", "main.rs"].map(|f| dir.join(f)) {
            if root.is_file() {
                let (cycles, files) = check_crate(&root)?;
                report.files += files;
                report.cycles.extend(cycles);
                report.crates.push(root);
            }
        }
    }
    Ok(report)
}
