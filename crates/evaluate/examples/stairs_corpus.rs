//! The staircases of a style corpus made by `bench/styles.sh`, mapped again: for each building
//! folder, the registered map (`reg/map.pcd`) is mapped with the default configuration and its
//! staircases scored against `building.toml`; the staircases the scans saw are those the
//! folder's `eval.json` expected (matched or missed). Prints one line per building and the
//! totals (exact step counts / staircases seen, false staircases).
//!
//! `cargo run --release -p evaluate --example stairs_corpus -- bench/work/styles-x/office-*`

use evaluate::evaluate;
use scanner::Building;
use semantic::{build_semantic_map, SemanticConfig};
use std::path::Path;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let (mut exact, mut seen, mut false_stairs) = (0, 0, 0);
    for dir in std::env::args().skip(1) {
        let d = Path::new(&dir);
        let Ok(old) = std::fs::read_to_string(d.join("eval.json")) else {
            println!("{dir}: no eval.json");
            continue;
        };
        let Ok(old) = serde_json::from_str::<serde_json::Value>(&old) else {
            println!("{dir}: eval.json unreadable (its evaluation failed)");
            continue;
        };
        let mut expected: Vec<String> = Vec::new();
        for m in old["stairs_matches"].as_array().into_iter().flatten() {
            expected.extend(m["truth"].as_str().map(String::from));
        }
        for m in old["missed"].as_array().into_iter().flatten() {
            expected.extend(
                m.as_str()
                    .filter(|n| n.starts_with("stairs"))
                    .map(String::from),
            );
        }
        let out = cloud::read_cloud(&d.join("reg/map.pcd"))
            .map_err(|e| e.to_string())
            .and_then(|c| {
                build_semantic_map(&c, &SemanticConfig::default()).map_err(|e| e.to_string())
            });
        let (out, building) = match (out, Building::load(&d.join("building.toml"))) {
            (Ok(o), Ok(b)) => (o, b),
            (o, b) => {
                println!("{dir}: {:?} {:?}", o.err(), b.err());
                continue;
            }
        };
        let ev = evaluate(&out.map, &building, None);
        let mut line = format!("{dir}: seen {expected:?}");
        for m in &ev.stairs_matches {
            let was_seen = expected.contains(&m.truth);
            exact += usize::from(was_seen && m.steps == m.steps_truth);
            line += &format!(
                " | {} {}/{} steps{} width {:+.2} dir {:.1} start {:.2}",
                m.truth,
                m.steps,
                m.steps_truth,
                if was_seen { "" } else { " (unseen)" },
                m.width_error_m,
                m.direction_error_deg,
                m.start_error_m
            );
        }
        let spurious = ev.stairs.detected - ev.stairs.matched;
        seen += expected.len();
        false_stairs += spurious;
        println!("{line} | false {spurious}");
    }
    println!("exact {exact}/{seen}, false stairs {false_stairs}");
    Ok(())
}
