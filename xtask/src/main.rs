//! `cargo run -p xtask -- import-cycles [WORKSPACE]`: lists every file-level import cycle
//! inside the workspace's crates; exit 0 if there is none, 1 if there are, 2 on bad usage.

use std::path::PathBuf;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (Some("import-cycles"), rest) = (args.first().map(String::as_str), args.get(1..)) else {
        eprintln!("usage: cargo run -p xtask -- import-cycles [WORKSPACE_DIR]");
        return ExitCode::from(2);
    };
    let workspace = rest
        .and_then(|r| r.first())
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(".."));
    let report = match xtask::workspace_cycles(&workspace) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("error: {}: {e}", workspace.display());
            return ExitCode::from(2);
        }
    };
    for c in &report.cycles {
        println!("import cycle between {} files:", c.files.len());
        for r in &c.references {
            println!("  {r}");
        }
    }
    println!(
        "{} import cycle(s) in {} crate roots ({} files)",
        report.cycles.len(),
        report.crates.len(),
        report.files
    );
    if report.cycles.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    }
}
