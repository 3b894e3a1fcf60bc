//! The file graph of a crate and its cycles (strongly connected components, Tarjan).

use crate::modules::CrateTree;
use crate::paths::inline_paths;
use crate::resolve::resolve;
use std::collections::BTreeMap;

/// An edge: file `from` refers to something defined in file `to`, first through `via`.
#[derive(Debug, Clone)]
pub struct Edge {
    /// The referring module.
    pub from: usize,
    /// The module referred to.
    pub to: usize,
    /// The first path that made the edge, e.g. `crate::walls::Wall`.
    pub via: String,
}

/// The edges between files, without those from a module to its own ancestors: a child may
/// use what its parent holds (types shared by siblings live in the parent).
pub fn edges(tree: &CrateTree) -> Vec<Edge> {
    let mut out: BTreeMap<(usize, usize), String> = BTreeMap::new();
    for (from, m) in tree.modules.iter().enumerate() {
        let mut heads: Vec<String> = m.children.keys().cloned().collect();
        heads.extend(m.imports.iter().map(|u| u.name.clone()));
        let paths = m
            .imports
            .iter()
            .map(|u| u.segments.clone())
            .chain(inline_paths(&m.code, &heads));
        for segs in paths {
            let Some(to) = resolve(tree, from, &segs) else {
                continue;
            };
            if to != from && !tree.is_ancestor_or_self(to, from) {
                out.entry((from, to)).or_insert_with(|| segs.join("::"));
            }
        }
    }
    out.into_iter()
        .map(|((from, to), via)| Edge { from, to, via })
        .collect()
}

/// The strongly connected components of more than one module: each is an import cycle.
pub fn cycles(n: usize, edges: &[Edge]) -> Vec<Vec<usize>> {
    let mut adj = vec![Vec::new(); n];
    for e in edges {
        adj[e.from].push(e.to);
    }
    let mut t = Tarjan {
        adj,
        index: vec![usize::MAX; n],
        low: vec![0; n],
        on_stack: vec![false; n],
        stack: Vec::new(),
        next: 0,
        out: Vec::new(),
    };
    for v in 0..n {
        if t.index[v] == usize::MAX {
            t.visit(v);
        }
    }
    t.out.retain(|c| c.len() > 1);
    t.out
}

struct Tarjan {
    adj: Vec<Vec<usize>>,
    index: Vec<usize>,
    low: Vec<usize>,
    on_stack: Vec<bool>,
    stack: Vec<usize>,
    next: usize,
    out: Vec<Vec<usize>>,
}

impl Tarjan {
    fn visit(&mut self, v: usize) {
        self.index[v] = self.next;
        self.low[v] = self.next;
        self.next += 1;
        self.stack.push(v);
        self.on_stack[v] = true;
        for k in 0..self.adj[v].len() {
            let w = self.adj[v][k];
            if self.index[w] == usize::MAX {
                self.visit(w);
                self.low[v] = self.low[v].min(self.low[w]);
            } else if self.on_stack[w] {
                self.low[v] = self.low[v].min(self.index[w]);
            }
        }
        if self.low[v] == self.index[v] {
            let mut comp = Vec::new();
            while let Some(w) = self.stack.pop() {
                self.on_stack[w] = false;
                comp.push(w);
                if w == v {
                    break;
                }
            }
            comp.sort_unstable();
            self.out.push(comp);
        }
    }
}
