//! Resolving a path to the file that defines what it names, following imports and
//! re-exports (`pub use walls::Wall` in `lib.rs` sends `crate::Wall` to `walls.rs`).

use crate::modules::CrateTree;

/// How deep re-exports are followed (guards against `use` loops).
const MAX_HOPS: usize = 16;

/// The module (file) that defines what `segments` names, as seen from module `from`;
/// `None` for paths outside the crate (other crates, `std`).
pub fn resolve(tree: &CrateTree, from: usize, segments: &[String]) -> Option<usize> {
    resolve_hops(tree, from, segments, 0)
}

fn resolve_hops(tree: &CrateTree, from: usize, segments: &[String], hops: usize) -> Option<usize> {
    if hops > MAX_HOPS {
        return None;
    }
    let (first, rest) = segments.split_first()?;
    let mut at = match first.as_str() {
        "crate" => 0,
        "self" => from,
        "super" => tree.modules[from].parent?,
        name => {
            if let Some(&c) = tree.modules[from].children.get(name) {
                c
            } else {
                // A name the module imported (`use crate::walls; walls::fit(...)`).
                let import = tree.modules[from].imports.iter().find(|u| {
                    u.name == name && u.segments.first().map(String::as_str) != Some(name)
                })?;
                let mut path = import.segments.clone();
                path.extend(rest.iter().cloned());
                return resolve_hops(tree, from, &path, hops + 1);
            }
        }
    };
    for (k, seg) in rest.iter().enumerate() {
        if seg == "super" {
            at = tree.modules[at].parent?;
            continue;
        }
        if let Some(&c) = tree.modules[at].children.get(seg) {
            at = c;
            continue;
        }
        return Some(item_home(tree, at, seg, &rest[k + 1..], hops));
    }
    Some(at)
}

/// Where item `name` of module `at` is defined: `at` itself, or wherever an import of that
/// name (or a glob import that provides it) leads.
fn item_home(tree: &CrateTree, at: usize, name: &str, rest: &[String], hops: usize) -> usize {
    let m = &tree.modules[at];
    if m.items.iter().any(|i| i == name) {
        return at;
    }
    let follow = |segs: &[String]| {
        let mut path = segs.to_vec();
        path.extend(rest.iter().cloned());
        resolve_hops(tree, at, &path, hops + 1)
    };
    if let Some(u) = m.imports.iter().find(|u| u.name == name) {
        return follow(&u.segments).unwrap_or(at);
    }
    for glob in m.imports.iter().filter(|u| u.name == "*") {
        if let Some(g) = resolve_hops(tree, at, &glob.segments, hops + 1) {
            let gm = &tree.modules[g];
            if gm.items.iter().any(|i| i == name) || gm.imports.iter().any(|u| u.name == name) {
                let mut segs = glob.segments.clone();
                segs.push(name.to_string());
                return follow(&segs).unwrap_or(at);
            }
        }
    }
    at
}
