//! The module graph of each crate, and the check that it has no cycle (`cargo xtask layers`, and a test).
//!
//! Cargo keeps crates acyclic; inside a crate nothing does. This reads every source file with `syn`, follows `mod`
//! declarations from the crate root, and draws an edge from a file to each file one of its paths names
//! (`crate::..`, `super::..`, `self::..` or a child module). A path that names an item a module re-exports is followed
//! to the file that defines it, so a facade's `pub use` is not itself a dependency. Test code (`#[cfg(test)]`) is left
//! out: a test may read any module. A cycle is a strongly connected component of more than one file, or of more than
//! one sibling module taken whole (a folder module with everything under it), so a crate's modules form layers at
//! every level of its tree.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use syn::visit::Visit;

/// Crates of the workspace, by their source folder.
pub const CRATES: &[&str] =
    &["fractal-dsl/src", "fractal-macros/src", "fractal-render/src", "fractal-runtime/src", "scenes/src", "src"];

/// One source file: its module path, what it defines, what it re-exports and which paths it names.
#[derive(Default, Debug)]
struct File {
    path: PathBuf,
    children: BTreeSet<String>,
    items: BTreeSet<String>,
    /// A re-exported name and the path it stands for (relative to this module).
    reexports: BTreeMap<String, Vec<String>>,
    /// `pub use x::*` targets.
    globs: Vec<Vec<String>>,
    /// Paths named outside re-exports, each as written (`crate`, `super` and `self` kept).
    uses: Vec<Vec<String>>,
}

/// A crate's files by module path (`[]` is the root).
pub struct Graph {
    root: PathBuf,
    files: BTreeMap<Vec<String>, File>,
}

fn is_test(attrs: &[syn::Attribute]) -> bool {
    attrs
        .iter()
        .any(|a| a.path().is_ident("cfg") && a.meta.require_list().is_ok_and(|l| l.tokens.to_string().contains("test")))
}

fn use_paths(tree: &syn::UseTree, prefix: &mut Vec<String>, out: &mut Vec<(Vec<String>, Option<String>)>) {
    match tree {
        syn::UseTree::Path(p) => {
            prefix.push(p.ident.to_string());
            use_paths(&p.tree, prefix, out);
            prefix.pop();
        }
        syn::UseTree::Name(n) => {
            let name = n.ident.to_string();
            let mut full = prefix.clone();
            if name != "self" {
                full.push(name.clone());
            }
            let alias = if name == "self" { prefix.last().cloned() } else { Some(name) };
            out.push((full, alias));
        }
        syn::UseTree::Rename(r) => {
            let mut full = prefix.clone();
            full.push(r.ident.to_string());
            out.push((full, Some(r.rename.to_string())));
        }
        syn::UseTree::Glob(_) => out.push((prefix.clone(), None)),
        syn::UseTree::Group(g) => g.items.iter().for_each(|t| use_paths(t, prefix, out)),
    }
}

/// Collects the paths a file names, skipping test code.
struct Collector<'a> {
    file: &'a mut File,
}

impl<'ast> Visit<'ast> for Collector<'_> {
    fn visit_item(&mut self, item: &'ast syn::Item) {
        let attrs = match item {
            syn::Item::Fn(i) => &i.attrs,
            syn::Item::Mod(i) => &i.attrs,
            syn::Item::Use(i) => &i.attrs,
            syn::Item::Impl(i) => &i.attrs,
            syn::Item::Const(i) => &i.attrs,
            syn::Item::Static(i) => &i.attrs,
            syn::Item::Struct(i) => &i.attrs,
            syn::Item::Enum(i) => &i.attrs,
            syn::Item::Trait(i) => &i.attrs,
            syn::Item::Macro(i) => &i.attrs,
            _ => return syn::visit::visit_item(self, item),
        };
        if is_test(attrs) {
            return;
        }
        if let syn::Item::Use(u) = item {
            let mut found = Vec::new();
            use_paths(&u.tree, &mut Vec::new(), &mut found);
            let public = !matches!(u.vis, syn::Visibility::Inherited);
            for (path, alias) in found {
                match (public, alias) {
                    (true, Some(alias)) => {
                        self.file.reexports.insert(alias, path);
                    }
                    (true, None) => self.file.globs.push(path),
                    (false, _) => self.file.uses.push(path),
                }
            }
            return;
        }
        syn::visit::visit_item(self, item);
    }

    fn visit_impl_item_fn(&mut self, f: &'ast syn::ImplItemFn) {
        if !is_test(&f.attrs) {
            syn::visit::visit_impl_item_fn(self, f);
        }
    }

    fn visit_path(&mut self, p: &'ast syn::Path) {
        if p.leading_colon.is_none() && p.segments.len() > 1 {
            self.file.uses.push(p.segments.iter().map(|s| s.ident.to_string()).collect());
        }
        syn::visit::visit_path(self, p);
    }

    fn visit_macro(&mut self, m: &'ast syn::Macro) {
        token_paths(m.tokens.clone(), &mut self.file.uses);
        syn::visit::visit_macro(self, m);
    }

    fn visit_attribute(&mut self, a: &'ast syn::Attribute) {
        // `#[error("{}", crate::x::Y)]` names a path inside an attribute's tokens.
        if !a.path().is_ident("doc") {
            if let syn::Meta::List(list) = &a.meta {
                token_paths(list.tokens.clone(), &mut self.file.uses);
            }
        }
    }
}

/// Paths starting with `crate`, `super` or `self` in a token stream (a macro's body, an attribute's arguments).
fn token_paths(tokens: proc_macro2::TokenStream, out: &mut Vec<Vec<String>>) {
    use proc_macro2::TokenTree;
    let trees: Vec<TokenTree> = tokens.into_iter().collect();
    let mut i = 0;
    while i < trees.len() {
        match &trees[i] {
            TokenTree::Group(g) => token_paths(g.stream(), out),
            TokenTree::Ident(id) if ["crate", "super", "self"].contains(&id.to_string().as_str()) => {
                let mut path = vec![id.to_string()];
                let mut j = i + 1;
                while let (Some(TokenTree::Punct(a)), Some(TokenTree::Punct(b)), Some(TokenTree::Ident(next))) =
                    (trees.get(j), trees.get(j + 1), trees.get(j + 2))
                {
                    if a.as_char() != ':' || b.as_char() != ':' {
                        break;
                    }
                    path.push(next.to_string());
                    j += 3;
                }
                if path.len() > 1 {
                    out.push(path);
                }
                i = j;
                continue;
            }
            _ => {}
        }
        i += 1;
    }
}

fn defined(items: &[syn::Item], file: &mut File) {
    for item in items {
        let name = match item {
            syn::Item::Fn(i) if !is_test(&i.attrs) => i.sig.ident.to_string(),
            syn::Item::Const(i) => i.ident.to_string(),
            syn::Item::Static(i) => i.ident.to_string(),
            syn::Item::Struct(i) => i.ident.to_string(),
            syn::Item::Enum(i) => i.ident.to_string(),
            syn::Item::Trait(i) => i.ident.to_string(),
            syn::Item::Type(i) => i.ident.to_string(),
            syn::Item::Union(i) => i.ident.to_string(),
            syn::Item::Macro(i) => i.ident.as_ref().map(|i| i.to_string()).unwrap_or_default(),
            syn::Item::Mod(i) if i.content.is_some() && !is_test(&i.attrs) => i.ident.to_string(),
            _ => continue,
        };
        file.items.insert(name);
    }
}

impl Graph {
    /// Reads the crate whose root file is `src/lib.rs` or `src/main.rs` under `dir`.
    pub fn read(dir: &Path) -> Result<Graph, String> {
        let root = ["lib.rs", "main.rs"].iter().map(|f| dir.join(f)).find(|p| p.exists());
        let root = root.ok_or_else(|| format!("{}: no lib.rs or main.rs", dir.display()))?;
        let workspace = dir.ancestors().find(|a| a.join("Cargo.lock").exists()).unwrap_or(dir);
        let mut graph = Graph { root: workspace.to_path_buf(), files: BTreeMap::new() };
        graph.add(Vec::new(), root, dir.to_path_buf())?;
        Ok(graph)
    }

    fn add(&mut self, module: Vec<String>, path: PathBuf, folder: PathBuf) -> Result<(), String> {
        let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let ast = syn::parse_file(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        let mut file = File { path: path.clone(), ..File::default() };
        defined(&ast.items, &mut file);
        Collector { file: &mut file }.visit_file(&ast);
        let mut children = Vec::new();
        for item in &ast.items {
            if let syn::Item::Mod(m) = item {
                if m.content.is_none() && !is_test(&m.attrs) {
                    let name = m.ident.to_string();
                    let flat = folder.join(format!("{name}.rs"));
                    let nested = folder.join(&name).join("mod.rs");
                    let child = if flat.exists() { flat } else { nested };
                    let child_folder = folder.join(&name);
                    file.children.insert(name.clone());
                    let mut sub = module.clone();
                    sub.push(name);
                    children.push((sub, child, child_folder));
                }
            }
        }
        self.files.insert(module, file);
        for (sub, child, child_folder) in children {
            self.add(sub, child, child_folder)?;
        }
        Ok(())
    }

    /// The file a path written in `from` leads to, following re-exports; `None` outside the crate.
    fn resolve(&self, from: &[String], path: &[String], depth: usize) -> Option<Vec<String>> {
        let mut at: Vec<String> = from.to_vec();
        let mut rest = path;
        match rest.first().map(String::as_str) {
            Some("crate") => {
                at.clear();
                rest = &rest[1..];
            }
            Some("self") => rest = &rest[1..],
            Some("super") => {
                while rest.first().map(String::as_str) == Some("super") {
                    at.pop();
                    rest = &rest[1..];
                }
            }
            Some(first) if self.files[from].children.contains(first) => {}
            _ => return None,
        }
        self.walk(at, rest, depth)
    }

    fn walk(&self, mut at: Vec<String>, rest: &[String], depth: usize) -> Option<Vec<String>> {
        if depth > 16 {
            return Some(at);
        }
        for (i, segment) in rest.iter().enumerate() {
            let file = &self.files[&at];
            if file.children.contains(segment) {
                at.push(segment.clone());
                continue;
            }
            if file.items.contains(segment) {
                return Some(at);
            }
            if let Some(target) = file.reexports.get(segment) {
                let mut path = target.clone();
                path.extend_from_slice(&rest[i + 1..]);
                return self.resolve(&at, &path, depth + 1).or(Some(at));
            }
            for glob in &file.globs {
                let mut path = glob.clone();
                path.extend_from_slice(&rest[i..]);
                if let Some(found) = self.resolve(&at, &path, depth + 1) {
                    if found != at {
                        return Some(found);
                    }
                }
            }
            return Some(at);
        }
        Some(at)
    }

    /// Each file's dependencies (other files of the crate), by module path.
    pub fn edges(&self) -> BTreeMap<Vec<String>, BTreeSet<Vec<String>>> {
        let mut edges = BTreeMap::new();
        for (module, file) in &self.files {
            let targets: BTreeSet<Vec<String>> =
                file.uses.iter().filter_map(|p| self.resolve(module, p, 0)).filter(|t| t != module).collect();
            edges.insert(module.clone(), targets);
        }
        edges
    }

    /// Cycles between sibling modules, each taken whole (a folder module with everything under it): for every module,
    /// the strongly connected components of more than one child, with one loop spelled out.
    pub fn sibling_cycles(&self) -> Vec<String> {
        let edges = self.edges();
        let mut out = Vec::new();
        for (parent, file) in &self.files {
            let children: Vec<&String> = file.children.iter().collect();
            if children.len() < 2 {
                continue;
            }
            // The child of `parent` a file lies under, if it lies under one.
            let child_of = |m: &Vec<String>| -> Option<usize> {
                (m.len() > parent.len() && m[..parent.len()] == parent[..])
                    .then(|| children.iter().position(|c| **c == m[parent.len()]))
                    .flatten()
            };
            let mut adj = vec![BTreeSet::new(); children.len()];
            for (from, targets) in &edges {
                let Some(a) = child_of(from) else { continue };
                for t in targets {
                    if let Some(b) = child_of(t) {
                        if a != b {
                            adj[a].insert(b);
                        }
                    }
                }
            }
            let adj: Vec<Vec<usize>> = adj.into_iter().map(|s| s.into_iter().collect()).collect();
            for c in tarjan(&adj).into_iter().filter(|c| c.len() > 1) {
                let members: BTreeSet<usize> = c.iter().copied().collect();
                let names: Vec<String> = a_loop(&adj, &members, c[0])
                    .iter()
                    .map(|&i| {
                        let mut m = parent.clone();
                        m.push(children[i].clone());
                        m.join("::")
                    })
                    .collect();
                let krate = self.root_name();
                out.push(format!("{krate}: modules {}", names.join(" → ")));
            }
        }
        out
    }

    fn root_name(&self) -> String {
        let path = &self.files[&Vec::new()].path;
        path.strip_prefix(&self.root).unwrap_or(path).display().to_string()
    }

    /// The cycles: strongly connected components of more than one file (Tarjan), each with one loop spelled out.
    pub fn cycles(&self) -> Vec<String> {
        let edges = self.edges();
        let nodes: Vec<&Vec<String>> = edges.keys().collect();
        let index_of: BTreeMap<&Vec<String>, usize> = nodes.iter().enumerate().map(|(i, n)| (*n, i)).collect();
        let adj: Vec<Vec<usize>> = nodes.iter().map(|n| edges[*n].iter().map(|t| index_of[t]).collect()).collect();
        let components = tarjan(&adj);
        let name = |i: usize| {
            let path = &self.files[nodes[i]].path;
            path.strip_prefix(&self.root).unwrap_or(path).display().to_string()
        };
        components
            .into_iter()
            .filter(|c| c.len() > 1)
            .map(|c| {
                let members: BTreeSet<usize> = c.iter().copied().collect();
                let lp = a_loop(&adj, &members, c[0]);
                let others = c.len() + 1 - lp.len();
                let tail =
                    if others > 0 { format!(" (and {others} more files in the same knot)") } else { String::new() };
                lp.iter().map(|&i| name(i)).collect::<Vec<_>>().join(" → ") + &tail
            })
            .collect()
    }
}

/// One loop through `start` inside a strongly connected component (breadth-first back to `start`).
fn a_loop(adj: &[Vec<usize>], members: &BTreeSet<usize>, start: usize) -> Vec<usize> {
    let mut parent = BTreeMap::new();
    let mut queue = std::collections::VecDeque::from([start]);
    while let Some(n) = queue.pop_front() {
        for &m in &adj[n] {
            if !members.contains(&m) {
                continue;
            }
            if m == start {
                let mut path = vec![start];
                let mut at = n;
                while at != start {
                    path.push(at);
                    at = parent[&at];
                }
                path.push(start);
                let last = path.len() - 1;
                path[1..last].reverse();
                return path;
            }
            if let std::collections::btree_map::Entry::Vacant(e) = parent.entry(m) {
                e.insert(n);
                queue.push_back(m);
            }
        }
    }
    vec![start]
}

fn tarjan(adj: &[Vec<usize>]) -> Vec<Vec<usize>> {
    struct State<'a> {
        adj: &'a [Vec<usize>],
        index: Vec<Option<usize>>,
        low: Vec<usize>,
        on_stack: Vec<bool>,
        stack: Vec<usize>,
        next: usize,
        out: Vec<Vec<usize>>,
    }
    fn visit(s: &mut State, v: usize) {
        s.index[v] = Some(s.next);
        s.low[v] = s.next;
        s.next += 1;
        s.stack.push(v);
        s.on_stack[v] = true;
        for &w in &s.adj[v] {
            match s.index[w] {
                None => {
                    visit(s, w);
                    s.low[v] = s.low[v].min(s.low[w]);
                }
                Some(i) if s.on_stack[w] => s.low[v] = s.low[v].min(i),
                _ => {}
            }
        }
        if Some(s.low[v]) == s.index[v] {
            let mut component = Vec::new();
            while let Some(w) = s.stack.pop() {
                s.on_stack[w] = false;
                component.push(w);
                if w == v {
                    break;
                }
            }
            s.out.push(component);
        }
    }
    let n = adj.len();
    let mut s = State {
        adj,
        index: vec![None; n],
        low: vec![0; n],
        on_stack: vec![false; n],
        stack: Vec::new(),
        next: 0,
        out: Vec::new(),
    };
    for v in 0..n {
        if s.index[v].is_none() {
            visit(&mut s, v);
        }
    }
    s.out
}

/// The cycles of every crate of the workspace under `root`, one line each.
pub fn workspace_cycles(root: &Path) -> Result<Vec<String>, String> {
    let mut all = Vec::new();
    for dir in CRATES {
        let dir = root.join(dir);
        if dir.exists() {
            let graph = Graph::read(&dir)?;
            all.extend(graph.cycles());
            all.extend(graph.sibling_cycles());
        }
    }
    Ok(all)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn root() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap().to_path_buf()
    }

    #[test]
    fn no_crate_has_a_module_cycle() {
        let cycles = workspace_cycles(&root()).unwrap();
        assert!(cycles.is_empty(), "module cycles:\n{}", cycles.join("\n"));
    }

    #[test]
    fn a_cycle_is_found() {
        let dir = std::env::temp_dir().join(format!("layers-test-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("b")).unwrap();
        std::fs::write(dir.join("lib.rs"), "mod a; mod b; pub use b::Deep;").unwrap();
        std::fs::write(dir.join("a.rs"), "pub const A: u8 = crate::Deep::X;").unwrap();
        std::fs::write(dir.join("b/mod.rs"), "mod deep; pub use deep::*;").unwrap();
        std::fs::write(dir.join("b/deep.rs"), "pub struct Deep; impl Deep { const X: u8 = super::super::a::A; }")
            .unwrap();
        let cycles = Graph::read(&dir).unwrap().cycles();
        std::fs::remove_dir_all(&dir).unwrap();
        assert_eq!(cycles.len(), 1, "{cycles:?}");
        assert!(cycles[0].contains("a.rs") && cycles[0].contains("deep.rs"), "{cycles:?}");
    }
}
