//! The module graph of a crate, read from its sources: which module file
//! uses which, and the circles they form (docs/ARCHITECTURE.md, "No
//! circles").
//!
//! A file uses another when one of its `use` items, or a path in its code
//! (`crate::x::f()`, `super::T`, `child::g()`), names an item of the other.
//! Declaring a module (`mod x;`) is not a use; a path through a re-export
//! (`crate::Env` with `pub use env::Env` at the root) counts as a use of
//! the module that defines the item, not of the one that re-exports it.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use syn::punctuated::Punctuated;
use syn::visit::Visit;

/// One crate's module files and the uses between them.
#[derive(Debug, Default)]
pub struct ModuleGraph {
    /// Every module file, the crate root first.
    pub files: Vec<PathBuf>,
    /// For each `(from, to)` pair of file indices, the names `from` takes from `to`.
    pub uses: BTreeMap<(usize, usize), BTreeSet<String>>,
    /// Paths into other crates (`std::fs::write`) outside test code, with
    /// the file naming them.
    pub external: Vec<(usize, String)>,
}

/// A module (a file, or an inline `mod x { .. }` inside one) and what it names.
#[derive(Debug, Default)]
struct Module {
    file: usize,
    children: BTreeSet<String>,
    /// Names of the items it defines.
    defines: BTreeSet<String>,
    /// Names bound by its `use` items, to the absolute paths they stand for.
    bindings: BTreeMap<String, Vec<String>>,
    /// The modules it glob-imports (`use x::*`), as absolute paths.
    globs: Vec<Vec<String>>,
    /// Absolute paths of its `use` items (globs included) and of the paths in its code.
    named: Vec<Vec<String>>,
    /// Paths into other crates, joined with `::`, names bound by `use`
    /// written out (`File::create` as `std::fs::File::create`).
    external: Vec<String>,
    /// Whether it is test code (`#[cfg(test)]`, or inside such a module).
    test: bool,
}

impl ModuleGraph {
    /// Reads the crate whose root file is `root` (a `lib.rs`, `main.rs` or
    /// any target's file) and every module file it declares.
    pub fn read(root: &Path) -> Result<Self, String> {
        let mut reader = Reader::default();
        reader.file(root, Vec::new(), false)?;
        let mut graph = ModuleGraph {
            files: reader.files,
            ..ModuleGraph::default()
        };
        for module in reader.modules.values() {
            if !module.test {
                let external = module.external.iter().map(|p| (module.file, p.clone()));
                graph.external.extend(external);
            }
            let globbed = module
                .globs
                .iter()
                .flat_map(|g| glob_names(&reader.modules, g));
            let named: Vec<Vec<String>> = module.named.iter().cloned().chain(globbed).collect();
            for path in &named {
                if let Some((to, name)) = resolve(&reader.modules, path, 0)
                    && to != module.file
                {
                    graph
                        .uses
                        .entry((module.file, to))
                        .or_default()
                        .insert(name);
                }
            }
        }
        Ok(graph)
    }

    /// Every path into another crate outside test code, with the file that
    /// names it.
    pub fn external_paths(&self) -> impl Iterator<Item = (&Path, &str)> {
        (self.external.iter()).map(|(file, path)| (self.files[*file].as_path(), path.as_str()))
    }

    /// The circles: every set of two or more files each of which reaches
    /// the others through uses (the strongly connected components), each
    /// described with the uses inside it.
    pub fn circles(&self) -> Vec<String> {
        let next: Vec<Vec<usize>> = (0..self.files.len())
            .map(|from| {
                (self.uses.keys())
                    .filter(|(f, _)| *f == from)
                    .map(|(_, to)| *to)
                    .collect()
            })
            .collect();
        let name = |i: usize| self.files[i].display().to_string();
        strongly_connected(&next)
            .into_iter()
            .filter(|component| component.len() > 1)
            .map(|component| {
                let ties: Vec<String> = (self.uses.iter())
                    .filter(|((f, t), _)| component.contains(f) && component.contains(t))
                    .map(|((f, t), names)| {
                        let names: Vec<&str> = names.iter().map(String::as_str).collect();
                        format!("{} -> {}: {}", name(*f), name(*t), names.join(", "))
                    })
                    .collect();
                ties.join("; ")
            })
            .collect()
    }
}

/// Where an absolute path leads: the file of the module that defines the
/// item it names (through re-exports and glob imports), and the item's name.
fn resolve(
    modules: &BTreeMap<Vec<String>, Module>,
    path: &[String],
    depth: usize,
) -> Option<(usize, String)> {
    let split = (0..=path.len())
        .rev()
        .find(|&n| modules.contains_key(&path[..n]))?;
    let (module, rest) = (&modules[&path[..split]], &path[split..]);
    let Some(first) = rest.first() else {
        let name = path.last().cloned().unwrap_or_else(|| "crate".into());
        return Some((module.file, name));
    };
    if depth < 16 && !module.defines.contains(first) {
        let through = |target: &[String]| {
            let mut path = target.to_vec();
            path.extend_from_slice(rest);
            path
        };
        if let Some(target) = module.bindings.get(first) {
            let mut path = target.clone();
            path.extend_from_slice(&rest[1..]);
            if let Some(found) = resolve(modules, &path, depth + 1) {
                return Some(found);
            }
        }
        for glob in &module.globs {
            let defines = modules.get(glob).is_some_and(|m| {
                m.defines.contains(first) || m.bindings.contains_key(first) || !m.globs.is_empty()
            });
            if defines
                && let Some(found) = resolve(modules, &through(glob), depth + 1)
                && found.0 != module.file
            {
                return Some(found);
            }
        }
    }
    Some((module.file, first.clone()))
}

/// What a glob import of the module at `glob` names: each item it defines
/// (its child modules aside) and each name its `use` items bind.
fn glob_names(modules: &BTreeMap<Vec<String>, Module>, glob: &[String]) -> Vec<Vec<String>> {
    let Some(module) = modules.get(glob) else {
        return vec![glob.to_vec()];
    };
    let defined = module
        .defines
        .iter()
        .filter(|n| !module.children.contains(*n));
    (defined.chain(module.bindings.keys()))
        .map(|name| {
            let mut path = glob.to_vec();
            path.push(name.clone());
            path
        })
        .collect()
}

/// Tarjan's strongly connected components of the graph `next`.
fn strongly_connected(next: &[Vec<usize>]) -> Vec<Vec<usize>> {
    struct Tarjan<'a> {
        next: &'a [Vec<usize>],
        index: Vec<Option<usize>>,
        low: Vec<usize>,
        stack: Vec<usize>,
        on_stack: Vec<bool>,
        count: usize,
        components: Vec<Vec<usize>>,
    }
    impl Tarjan<'_> {
        fn visit(&mut self, v: usize) {
            self.index[v] = Some(self.count);
            self.low[v] = self.count;
            self.count += 1;
            self.stack.push(v);
            self.on_stack[v] = true;
            for &w in &self.next[v] {
                match self.index[w] {
                    None => {
                        self.visit(w);
                        self.low[v] = self.low[v].min(self.low[w]);
                    }
                    Some(i) if self.on_stack[w] => self.low[v] = self.low[v].min(i),
                    Some(_) => {}
                }
            }
            if Some(self.low[v]) == self.index[v] {
                let mut component = Vec::new();
                while let Some(w) = self.stack.pop() {
                    self.on_stack[w] = false;
                    component.push(w);
                    if w == v {
                        break;
                    }
                }
                component.sort_unstable();
                self.components.push(component);
            }
        }
    }
    let n = next.len();
    let mut t = Tarjan {
        next,
        index: vec![None; n],
        low: vec![0; n],
        stack: Vec::new(),
        on_stack: vec![false; n],
        count: 0,
        components: Vec::new(),
    };
    for v in 0..n {
        if t.index[v].is_none() {
            t.visit(v);
        }
    }
    t.components
}

/// Walks a crate's module tree from its root file.
#[derive(Default)]
struct Reader {
    files: Vec<PathBuf>,
    modules: BTreeMap<Vec<String>, Module>,
}

impl Reader {
    /// Reads the module file `path`, whose module path is `module` (test
    /// code if `test`).
    fn file(&mut self, path: &Path, module: Vec<String>, test: bool) -> Result<(), String> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        let parsed =
            syn::parse_file(&text).map_err(|e| format!("cannot parse {}: {e}", path.display()))?;
        let file = self.files.len();
        self.files.push(path.to_owned());
        // A crate root and a `mod.rs` keep their modules beside them.
        let beside = module.is_empty() || path.file_name().is_some_and(|n| n == "mod.rs");
        let own_dir = match path.parent() {
            Some(dir) if beside => dir.to_owned(),
            Some(dir) => dir.join(path.file_stem().unwrap_or_default()),
            None => PathBuf::new(),
        };
        self.items(&parsed.items, file, &own_dir, module, test)
    }

    /// Reads the items of module `module` (test code if `test`), which
    /// lives in file `file` and whose child module files are in `dir`.
    fn items(
        &mut self,
        items: &[syn::Item],
        file: usize,
        dir: &Path,
        module: Vec<String>,
        test: bool,
    ) -> Result<(), String> {
        let mut collector = NameCollector::default();
        let mut defines = BTreeSet::new();
        for item in items {
            match item {
                syn::Item::Mod(m) => {
                    collector.children.insert(m.ident.to_string());
                }
                other => collector.visit_item(other),
            }
            defines.extend(defined_name(item));
        }
        let children = collector.children.clone();
        let mut own = Module {
            file,
            children,
            defines,
            test,
            ..Module::default()
        };
        let mut outside = BTreeMap::new();
        for (tree, is_glob) in &collector.use_trees {
            let Some(absolute) = absolute(&module, &own.children, &tree.0) else {
                own.external.push(tree.0.join("::"));
                if !is_glob {
                    outside.insert(tree.1.clone(), tree.0.clone());
                }
                continue;
            };
            if *is_glob {
                own.globs.push(absolute);
            } else {
                own.bindings.insert(tree.1.clone(), absolute.clone());
                own.named.push(absolute);
            }
        }
        for path in &collector.paths {
            let starts_local = matches!(path[0].as_str(), "crate" | "super" | "self")
                || own.children.contains(&path[0]);
            if path.len() > 1 && starts_local {
                if let Some(absolute) = absolute(&module, &own.children, path) {
                    own.named.push(absolute);
                }
            } else if path.len() > 1 {
                let mut full = outside
                    .get(&path[0])
                    .cloned()
                    .unwrap_or_else(|| vec![path[0].clone()]);
                full.extend_from_slice(&path[1..]);
                own.external.push(full.join("::"));
            }
        }
        self.modules.insert(module.clone(), own);
        for item in items {
            let syn::Item::Mod(m) = item else { continue };
            let mut child = module.clone();
            child.push(m.ident.to_string());
            let test = test || m.attrs.iter().any(is_cfg_test);
            match &m.content {
                Some((_, inner)) => {
                    self.items(inner, file, &dir.join(m.ident.to_string()), child, test)?
                }
                None => {
                    let name = m.ident.to_string();
                    let flat = dir.join(format!("{name}.rs"));
                    let nested = dir.join(&name).join("mod.rs");
                    let found = [flat, nested].into_iter().find(|p| p.is_file());
                    let path = found.ok_or_else(|| {
                        format!(
                            "module {name} declared in {} has no file",
                            self.files[file].display()
                        )
                    })?;
                    self.file(&path, child, test)?;
                }
            }
        }
        Ok(())
    }
}

/// Whether `attr` is `#[cfg(test)]`.
fn is_cfg_test(attr: &syn::Attribute) -> bool {
    attr.path().is_ident("cfg")
        && attr
            .parse_args::<syn::Ident>()
            .is_ok_and(|ident| ident == "test")
}

/// The name an item defines, if any.
fn defined_name(item: &syn::Item) -> Option<String> {
    let ident = match item {
        syn::Item::Const(i) => &i.ident,
        syn::Item::Enum(i) => &i.ident,
        syn::Item::Fn(i) => &i.sig.ident,
        syn::Item::Mod(i) => &i.ident,
        syn::Item::Static(i) => &i.ident,
        syn::Item::Struct(i) => &i.ident,
        syn::Item::Trait(i) => &i.ident,
        syn::Item::Type(i) => &i.ident,
        syn::Item::Union(i) => &i.ident,
        syn::Item::Macro(i) => i.ident.as_ref()?,
        _ => return None,
    };
    Some(ident.to_string())
}

/// `path` as seen from module `module` (with child modules `children`),
/// made absolute; `None` for a path into another crate.
fn absolute(
    module: &[String],
    children: &BTreeSet<String>,
    path: &[String],
) -> Option<Vec<String>> {
    let mut out: Vec<String> = module.to_vec();
    let mut rest = path;
    match rest.first()?.as_str() {
        "crate" => {
            out.clear();
            rest = &rest[1..];
        }
        "self" => rest = &rest[1..],
        "super" => {
            while rest.first().is_some_and(|s| s == "super") {
                out.pop()?;
                rest = &rest[1..];
            }
        }
        first if children.contains(first) => {}
        _ => return None,
    }
    out.extend(rest.iter().cloned());
    Some(out)
}

/// What one module's items name: its `use` trees and the paths in its code
/// (nested inline modules are read on their own).
#[derive(Default)]
struct NameCollector {
    children: BTreeSet<String>,
    /// Each flattened `use`: (segments, bound name), and whether it is a glob.
    use_trees: Vec<((Vec<String>, String), bool)>,
    paths: Vec<Vec<String>>,
}

impl NameCollector {
    fn flatten(&mut self, tree: &syn::UseTree, prefix: &mut Vec<String>) {
        match tree {
            syn::UseTree::Path(p) => {
                prefix.push(p.ident.to_string());
                self.flatten(&p.tree, prefix);
                prefix.pop();
            }
            syn::UseTree::Name(n) if n.ident == "self" => {
                let bound = prefix.last().cloned().unwrap_or_default();
                self.use_trees.push(((prefix.clone(), bound), false));
            }
            syn::UseTree::Name(n) => {
                let mut full = prefix.clone();
                full.push(n.ident.to_string());
                self.use_trees.push(((full, n.ident.to_string()), false));
            }
            syn::UseTree::Rename(r) => {
                let mut full = prefix.clone();
                if r.ident != "self" {
                    full.push(r.ident.to_string());
                }
                self.use_trees.push(((full, r.rename.to_string()), false));
            }
            syn::UseTree::Glob(_) => {
                self.use_trees.push(((prefix.clone(), String::new()), true));
            }
            syn::UseTree::Group(g) => {
                for tree in &g.items {
                    self.flatten(tree, prefix);
                }
            }
        }
    }
}

impl<'ast> Visit<'ast> for NameCollector {
    fn visit_item_mod(&mut self, m: &'ast syn::ItemMod) {
        // A module inside a function or block: read as part of this one.
        if let Some((_, items)) = &m.content {
            for item in items {
                self.visit_item(item);
            }
        }
    }

    fn visit_item_use(&mut self, u: &'ast syn::ItemUse) {
        self.flatten(&u.tree, &mut Vec::new());
    }

    fn visit_path(&mut self, path: &'ast syn::Path) {
        if path.leading_colon.is_none() {
            let segments: Vec<String> = path.segments.iter().map(|s| s.ident.to_string()).collect();
            self.paths.push(segments);
        }
        syn::visit::visit_path(self, path);
    }

    fn visit_macro(&mut self, mac: &'ast syn::Macro) {
        // Most macros take expressions (format!, assert!, vec!): read them as such.
        let parser = Punctuated::<syn::Expr, syn::Token![,]>::parse_terminated;
        if let Ok(exprs) = mac.parse_body_with(parser) {
            for expr in &exprs {
                self.visit_expr(expr);
            }
        }
        syn::visit::visit_macro(self, mac);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn graph(files: &[(&str, &str)]) -> ModuleGraph {
        let dir = tempfile::tempdir().unwrap();
        for (name, text) in files {
            let path = dir.path().join(name);
            std::fs::create_dir_all(path.parent().unwrap()).unwrap();
            std::fs::write(path, text).unwrap();
        }
        ModuleGraph::read(&dir.path().join("lib.rs")).unwrap()
    }

    #[test]
    fn two_files_that_use_each_other_are_a_circle() {
        let g = graph(&[
            ("lib.rs", "mod a;\nmod b;\n"),
            ("a.rs", "use crate::b::B;\npub struct A(B);\n"),
            ("b.rs", "pub struct B;\npub fn f(_: crate::a::A) {}\n"),
        ]);
        let circles = g.circles();
        assert_eq!(circles.len(), 1, "{circles:?}");
        assert!(
            circles[0].contains("a.rs -> ") && circles[0].contains(": B"),
            "{circles:?}"
        );
        assert!(
            circles[0].contains("b.rs -> ") && circles[0].contains(": A"),
            "{circles:?}"
        );
    }

    #[test]
    fn a_child_that_reaches_back_into_its_user_is_a_circle() {
        let g = graph(&[
            ("lib.rs", "mod m;\n"),
            ("m.rs", "mod c;\npub struct S;\nfn f() { c::g(S) }\n"),
            ("m/c.rs", "pub fn g(_: super::S) {}\n"),
        ]);
        assert_eq!(g.circles().len(), 1, "{:?}", g.circles());
    }

    #[test]
    fn re_exports_and_declarations_are_not_circles() {
        let g = graph(&[
            (
                "lib.rs",
                "mod a;\nmod b;\npub use a::A;\nmod inner { use super::*; }\n",
            ),
            (
                "a.rs",
                "pub struct A;\n#[cfg(test)]\nmod tests { use super::*; }\n",
            ),
            (
                "b.rs",
                "pub fn f() -> crate::A { let _ = format!(\"{:?}\", crate::a::A); crate::A }\n",
            ),
        ]);
        assert!(g.circles().is_empty(), "{:?}", g.circles());
        let b_to_a = g.uses.get(&(2, 1)).expect("b uses a");
        assert!(b_to_a.contains("A"));
    }

    #[test]
    fn paths_into_other_crates_are_written_out_outside_tests() {
        let g = graph(&[(
            "lib.rs",
            "use std::fs::File;\nfn f() { File::create(\"x\"); std::fs::write(\"y\", b\"\"); }\n\
             #[cfg(test)]\nmod tests { fn g() { std::fs::remove_file(\"z\"); } }\n",
        )]);
        let paths: Vec<&str> = g.external_paths().map(|(_, p)| p).collect();
        assert!(paths.contains(&"std::fs::File::create"), "{paths:?}");
        assert!(paths.contains(&"std::fs::write"), "{paths:?}");
        assert!(
            !paths.iter().any(|p| p.contains("remove_file")),
            "{paths:?}"
        );
    }
}
