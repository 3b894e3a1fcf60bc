//! The workspace has no file-level import cycle inside any crate, and the checker finds the
//! cycles it must (sibling cycles, cycles through re-exports) while allowing a child to use
//! its parent.

use std::path::{Path, PathBuf};

fn crate_from(files: &[(&str, &str)]) -> (tempfile_dir::Dir, PathBuf) {
    let dir = tempfile_dir::Dir::new();
    for (name, text) in files {
        let p = dir.0.join(name);
        std::fs::create_dir_all(p.parent().expect("a parent")).expect("mkdir");
        std::fs::write(&p, text).expect("write");
    }
    let root = dir.0.join("lib.rs");
    (dir, root)
}

/// A temporary folder removed on drop (xtask has no dependencies).
mod tempfile_dir {
    pub struct Dir(pub std::path::PathBuf);
    impl Dir {
        pub fn new() -> Dir {
            use std::sync::atomic::{AtomicUsize, Ordering};
            static N: AtomicUsize = AtomicUsize::new(0);
            let p = std::env::temp_dir().join(format!(
                "xtask-test-{}-{}",
                std::process::id(),
                N.fetch_add(1, Ordering::Relaxed)
            ));
            std::fs::create_dir_all(&p).expect("temp dir");
            Dir(p)
        }
    }
    impl Drop for Dir {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}

fn file_names(c: &xtask::Cycle) -> Vec<String> {
    c.files
        .iter()
        .map(|f| {
            let parts: Vec<_> = f.components().rev().take(2).collect();
            parts
                .iter()
                .rev()
                .map(|p| p.as_os_str().to_string_lossy().into_owned())
                .collect::<Vec<_>>()
                .join("/")
        })
        .collect()
}

#[test]
fn the_workspace_has_no_import_cycle_inside_any_crate() {
    let ws = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let report = xtask::workspace_cycles(&ws).expect("the workspace reads");
    assert!(
        report.crates.len() >= 8,
        "crates found: {:?}",
        report.crates
    );
    let listing: Vec<String> = report
        .cycles
        .iter()
        .flat_map(|c| c.references.clone())
        .collect();
    assert!(
        report.cycles.is_empty(),
        "import cycles (run `cargo run -p xtask -- import-cycles`):\n{}",
        listing.join("\n")
    );
}

#[test]
fn siblings_that_use_each_other_are_a_cycle_but_a_child_may_use_its_parent() {
    let (_d, root) = crate_from(&[
        ("lib.rs", "pub mod walls;\npub use walls::Wall;\n"),
        (
            "walls/mod.rs",
            "mod fit;\nmod extent;\npub struct Wall;\npub fn run() { fit::fit(); }\n",
        ),
        (
            "walls/fit.rs",
            "use super::Wall;\nuse super::extent::extent;\npub fn fit() { extent(); }\n",
        ),
        ("walls/extent.rs", "use crate::Wall;\npub fn extent() {}\n"),
    ]);
    assert!(xtask::crate_cycles(&root).expect("reads").is_empty());
    let (_d, root) = crate_from(&[
        ("lib.rs", "pub mod walls;\n"),
        ("walls/mod.rs", "mod fit;\nmod extent;\n"),
        (
            "walls/fit.rs",
            "pub fn fit() { super::extent::extent(); }\n",
        ),
        (
            "walls/extent.rs",
            "pub fn extent() {}\npub fn again() { crate::walls::fit::fit(); }\n",
        ),
    ]);
    let c = xtask::crate_cycles(&root).expect("reads");
    assert_eq!(c.len(), 1);
    assert_eq!(file_names(&c[0]), ["walls/extent.rs", "walls/fit.rs"]);
}

#[test]
fn a_cycle_through_a_re_export_of_the_crate_root_is_found() {
    // error.rs names IcpResult through lib.rs's re-export; icp.rs returns the error type.
    let (_d, root) = crate_from(&[
        ("lib.rs", "mod error;\nmod icp;\npub use error::RegistrationError;\npub use icp::{register, IcpResult};\n"),
        ("error.rs", "use crate::IcpResult;\npub enum RegistrationError { NotConverged(IcpResult) }\n"),
        ("icp.rs", "use crate::error::RegistrationError;\npub struct IcpResult;\npub fn register() -> Result<IcpResult, RegistrationError> { todo!() }\n"),
    ]);
    let c = xtask::crate_cycles(&root).expect("reads");
    assert_eq!(c.len(), 1, "{c:?}");
    assert!(c[0]
        .references
        .iter()
        .any(|r| r.contains("via crate::IcpResult")));
}

#[test]
fn references_in_comments_strings_and_tests_are_not_edges() {
    let (_d, root) = crate_from(&[
        ("lib.rs", "mod a;\nmod b;\n"),
        ("a.rs", "use crate::b::B;\npub struct A;\n"),
        (
            "b.rs",
            "pub struct B;\n// crate::a::A\nconst S: &str = \"crate::a::A\";\n#[cfg(test)]\nmod tests { use crate::a::A; }\n",
        ),
    ]);
    assert!(xtask::crate_cycles(&root).expect("reads").is_empty());
}
