//! `import "file.vsg" as name;` — one program using another (an extension of §7.1, so that
//! generated programs can call the library of §7.2.2). The imported program's symbols and
//! declared floats join the importer under `name.` (`name.Axiom`, `name.radius`); the import may
//! give its floats values, `import "round_tower.vsg" as tower (radius = 2 * w);`, and
//! `--set tower.radius=5` reaches them too. Files are found by the caller's [`Resolver`]: this
//! crate never touches paths.
//!
//! The imported items take the place of the import statement, so an import's arguments may use
//! the importer's floats declared above it. Spans of imported items are shifted past the
//! importer's text; [`Sources`] maps them back to their own file for messages.

use std::collections::HashSet;

use crate::ast::{
    AppearanceValue, DeclValue, Expr, Ident, Import, Item, OpKind, Program, Span, Successor,
};
use crate::diag::{Diagnostic, LineIndex, MAX_RENDERED, Text};

/// Deepest import nesting (`a` imports `b` imports `c` …); splicing recurses once per level.
pub const MAX_IMPORT_DEPTH: usize = 32;
/// Most imports one program may load, counting each time a file is imported (the demo castle
/// loads a few hundred).
pub const MAX_IMPORTS: usize = 2_000;
/// Most text all loaded files may add up to, in bytes. With [`MAX_IMPORTS`] this stops imports
/// that fan out (`a` imports `b` twice, `b` imports `c` twice, …) before they grow
/// exponentially.
pub const MAX_IMPORTED_BYTES: usize = 64 << 20;

/// Finds imported programs for the caller (the binary reads files; tests keep them in memory).
pub trait Resolver {
    /// Loads `path` as written in an import inside the program named `from`. Returns the name
    /// by which the loaded program is known (used in messages and to detect cycles) and its
    /// text, or why it cannot be loaded.
    fn load(&mut self, from: &str, path: &str) -> Result<(String, String), String>;
}

/// A resolver for programs that must not import.
pub struct NoImports;

impl Resolver for NoImports {
    fn load(&mut self, _: &str, _: &str) -> Result<(String, String), String> {
        Err("imports are not available here".into())
    }
}

/// One program text and where its spans start in the combined numbering.
#[derive(Clone, Debug, PartialEq)]
pub struct SourceFile {
    pub name: String,
    pub text: String,
    pub base: usize,
    /// Line starts of `text`, so each rule's line is a binary search.
    lines: LineIndex,
}

/// Every file of a program with its imports, the main program first.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Sources {
    pub files: Vec<SourceFile>,
}

impl Sources {
    fn add(&mut self, name: String, text: String) -> usize {
        let base = self.files.last().map_or(0, |f| f.base + f.text.len() + 1);
        let lines = LineIndex::new(&text);
        self.files.push(SourceFile {
            name,
            text,
            base,
            lines,
        });
        base
    }

    /// Total length of the texts.
    fn bytes(&self) -> usize {
        self.files.last().map_or(0, |f| f.base + f.text.len())
    }

    /// Index in `files` of the file holding combined offset `at` (bases increase).
    fn index_of(&self, at: usize) -> Option<usize> {
        self.files.partition_point(|f| f.base <= at).checked_sub(1)
    }

    /// The file holding combined offset `at`.
    pub fn file_of(&self, at: usize) -> Option<&SourceFile> {
        self.index_of(at).map(|i| &self.files[i])
    }

    /// 1-based line of a span in its own file.
    pub fn line(&self, span: Span) -> u32 {
        match self.file_of(span.start) {
            Some(f) => f.lines.line(span.start - f.base) as u32,
            None => 0,
        }
    }

    /// Renders diagnostics in source order, each in the file it points into; those in the main
    /// program under the caller's `file` and `src`. Shows at most [`MAX_RENDERED`], then counts
    /// the rest; each file's text is indexed once, however many diagnostics point into it.
    pub fn render_all(&self, file: &str, src: &str, diagnostics: &[Diagnostic]) -> String {
        let main = Text::new(file, src);
        let mut texts: Vec<Option<Text>> = self.files.iter().map(|_| None).collect();
        let mut out = Vec::new();
        for d in diagnostics.iter().take(MAX_RENDERED) {
            out.push(match self.index_of(d.span.start) {
                Some(i) if i > 0 => {
                    let f = &self.files[i];
                    let text = texts[i].get_or_insert_with(|| Text::new(&f.name, &f.text));
                    text.render(&local(d, f.base))
                }
                _ => main.render(d),
            });
        }
        if diagnostics.len() > MAX_RENDERED {
            out.push(format!(
                "{file}: and {} more errors\n",
                diagnostics.len() - MAX_RENDERED
            ));
        }
        out.join("\n")
    }

    /// `file:line:col: message` with an excerpt, in the file the diagnostic points into.
    pub fn render(&self, d: &Diagnostic) -> String {
        match self.file_of(d.span.start) {
            Some(f) => local(d, f.base).render(&f.name, &f.text),
            None => d.render("?", ""),
        }
    }
}

/// `d` with its span in the numbering of the file starting at `base`.
fn local(d: &Diagnostic, base: usize) -> Diagnostic {
    let mut local = d.clone();
    local.span = Span::new(d.span.start - base, d.span.end.saturating_sub(base));
    local
}

/// Parses `text` (named `name`) and splices in its imports, recursively.
pub fn load(
    name: &str,
    text: &str,
    resolver: &mut dyn Resolver,
) -> Result<(Program, Sources), (Vec<Diagnostic>, Sources)> {
    let mut sources = Sources::default();
    sources.add(name.to_string(), text.to_string());
    let program = match crate::parse::parse(text) {
        Ok(p) => p,
        Err(ds) => return Err((ds, sources)),
    };
    let mut items = Vec::new();
    let mut stack = vec![name.to_string()];
    match splice(program, "", &mut stack, resolver, &mut sources, &mut items) {
        Ok(()) => Ok((Program { items }, sources)),
        Err(ds) => Err((ds, sources)),
    }
}

/// Appends `program`'s items to `out`, replacing each import by the imported items.
fn splice(
    program: Program,
    prefix: &str,
    stack: &mut Vec<String>,
    resolver: &mut dyn Resolver,
    sources: &mut Sources,
    out: &mut Vec<Item>,
) -> Result<(), Vec<Diagnostic>> {
    for item in program.items {
        let Item::Import(import) = item else {
            out.push(item);
            continue;
        };
        let limit = |why: String| {
            vec![Diagnostic::new(
                format!("cannot import \"{}\": {why}", import.path.value),
                import.path.span,
                "imported here",
            )]
        };
        if stack.len() > MAX_IMPORT_DEPTH {
            return Err(limit(format!(
                "imports nest more than {MAX_IMPORT_DEPTH} deep ({} -> ...)",
                stack[..3].join(" -> ")
            )));
        }
        if sources.files.len() > MAX_IMPORTS {
            return Err(limit(format!(
                "the program loads more than {MAX_IMPORTS} imports (is a file imported many times over?)"
            )));
        }
        let from = stack.last().cloned().unwrap_or_default();
        let (name, text) = resolver.load(&from, &import.path.value).map_err(|why| {
            vec![Diagnostic::new(
                format!("cannot import \"{}\": {why}", import.path.value),
                import.path.span,
                "imported here",
            )]
        })?;
        if let Some(at) = stack.iter().position(|s| *s == name) {
            let cycle = stack[at..].join(" -> ");
            return Err(vec![Diagnostic::new(
                format!("import cycle: {cycle} -> {name}"),
                import.path.span,
                "imported again here",
            )]);
        }
        if sources.bytes() + text.len() > MAX_IMPORTED_BYTES {
            return Err(limit(format!(
                "the program and its imports exceed {} MiB of text (is a file imported many times over?)",
                MAX_IMPORTED_BYTES >> 20
            )));
        }
        let base = sources.add(name.clone(), text.clone());
        let mut sub = crate::parse::parse(&text).map_err(|ds| {
            ds.into_iter()
                .map(|mut d| {
                    d.span = Span::new(d.span.start + base, d.span.end + base);
                    d
                })
                .collect::<Vec<_>>()
        })?;
        let alias = format!("{prefix}{}.", import.alias.name);
        namespace(&mut sub, base, &alias);
        give_arguments(&mut sub, &import, &alias)?;
        stack.push(name);
        splice(sub, &alias, stack, resolver, sources, out)?;
        stack.pop();
    }
    Ok(())
}

/// Replaces the declared values of the imported floats named in the import's arguments.
fn give_arguments(sub: &mut Program, import: &Import, alias: &str) -> Result<(), Vec<Diagnostic>> {
    let mut errors = Vec::new();
    for (name, value) in &import.args {
        let full = format!("{alias}{}", name.name);
        let decl = sub.items.iter_mut().find_map(|i| match i {
            Item::Decl(d) if d.name.name == full => Some(d),
            _ => None,
        });
        match decl {
            Some(d) if matches!(d.value, DeclValue::Scalar(_)) => {
                d.value = DeclValue::Scalar(value.clone());
            }
            _ => {
                let floats: Vec<String> = sub
                    .items
                    .iter()
                    .filter_map(|i| match i {
                        Item::Decl(d) if matches!(d.value, DeclValue::Scalar(_)) => {
                            Some(d.name.name[alias.len()..].to_string())
                        }
                        _ => None,
                    })
                    .collect();
                errors.push(Diagnostic::new(
                    format!(
                        "\"{}\" declares no float '{}' (it declares: {})",
                        import.path.value,
                        name.name,
                        if floats.is_empty() {
                            "none".into()
                        } else {
                            floats.join(", ")
                        }
                    ),
                    name.span,
                    "no such float",
                ));
            }
        }
    }
    if errors.is_empty() {
        Ok(())
    } else {
        Err(errors)
    }
}

/// Shifts every span by `base` and puts symbols and the program's own floats under `alias`.
fn namespace(program: &mut Program, base: usize, alias: &str) {
    let mut own: HashSet<String> = HashSet::new();
    let mut aliases: HashSet<String> = HashSet::new();
    for item in &program.items {
        match item {
            Item::Decl(d) => {
                own.insert(d.name.name.clone());
            }
            Item::Import(i) => {
                aliases.insert(i.alias.name.clone());
            }
            Item::Rule(_) => {}
        }
    }
    let r = Rename {
        base,
        alias,
        own,
        aliases,
    };
    for item in &mut program.items {
        match item {
            Item::Decl(d) => {
                r.span(&mut d.span);
                r.name(&mut d.name);
                match &mut d.value {
                    DeclValue::Scalar(e) => r.expr(e),
                    DeclValue::Array(es) => es.iter_mut().for_each(|e| r.expr(e)),
                }
            }
            Item::Import(i) => {
                r.span(&mut i.span);
                r.span(&mut i.path.span);
                r.span(&mut i.alias.span);
                for (name, e) in &mut i.args {
                    r.span(&mut name.span);
                    r.expr(e);
                }
            }
            Item::Rule(rule) => {
                r.span(&mut rule.span);
                r.name(&mut rule.predecessor);
                if let Some(c) = &mut rule.condition {
                    r.expr(c);
                }
                if let Some(p) = &mut rule.probability {
                    r.expr(p);
                }
                for s in &mut rule.successors {
                    match s {
                        Successor::Symbol(id) => r.name(id),
                        Successor::Terminal(span) => r.span(span),
                    }
                }
                for op in &mut rule.ops {
                    r.span(&mut op.span);
                    r.op(&mut op.kind);
                }
            }
        }
    }
}

struct Rename<'a> {
    base: usize,
    alias: &'a str,
    /// Floats the program declares.
    own: HashSet<String>,
    /// Aliases of the program's own imports: `inner.x` becomes `alias.inner.x`.
    aliases: HashSet<String>,
}

impl Rename<'_> {
    fn span(&self, s: &mut Span) {
        *s = Span::new(s.start + self.base, s.end + self.base);
    }

    /// A symbol or declaration name: always under the alias.
    fn name(&self, id: &mut Ident) {
        self.span(&mut id.span);
        id.name = format!("{}{}", self.alias, id.name);
    }

    /// A variable: under the alias if the program declares it (or imported it); shape
    /// attributes and constants such as `PI` keep their names.
    fn var(&self, id: &mut Ident) {
        self.span(&mut id.span);
        let head = id.name.split('.').next().unwrap_or_default();
        if self.own.contains(&id.name) || (id.name.contains('.') && self.aliases.contains(head)) {
            id.name = format!("{}{}", self.alias, id.name);
        }
    }

    fn expr(&self, e: &mut Expr) {
        match e {
            Expr::Number(_, s) | Expr::Bool(_, s) => self.span(s),
            Expr::Var(id) => self.var(id),
            Expr::Index { array, index, span } => {
                self.span(span);
                self.var(array);
                self.expr(index);
            }
            Expr::Unary { operand, span, .. } => {
                self.span(span);
                self.expr(operand);
            }
            Expr::Binary { lhs, rhs, span, .. } => {
                self.span(span);
                self.expr(lhs);
                self.expr(rhs);
            }
            Expr::Call {
                function,
                args,
                span,
            } => {
                self.span(span);
                self.span(&mut function.span);
                args.iter_mut().for_each(|a| self.expr(a));
            }
        }
    }

    fn op(&self, kind: &mut OpKind) {
        match kind {
            OpKind::Translate(es) | OpKind::Rotate(es) => es.iter_mut().for_each(|e| self.expr(e)),
            OpKind::Instantiate { shape_type, params } => {
                self.span(&mut shape_type.span);
                params.iter_mut().for_each(|e| self.expr(e));
            }
            OpKind::Split { axis, lengths } => {
                self.span(&mut axis.span);
                lengths.iter_mut().for_each(|l| self.expr(&mut l.expr));
            }
            OpKind::Repeat {
                axis,
                lengths,
                offset,
            } => {
                self.span(&mut axis.span);
                lengths.iter_mut().for_each(|l| self.expr(&mut l.expr));
                if let Some(o) = offset {
                    self.expr(o);
                }
            }
            OpKind::Appearance(pairs) => {
                for (name, value) in pairs {
                    self.span(&mut name.span);
                    match value {
                        AppearanceValue::Scalar(e) => self.expr(e),
                        AppearanceValue::List(es) => es.iter_mut().for_each(|e| self.expr(e)),
                        AppearanceValue::Text(s) => self.span(&mut s.span),
                        AppearanceValue::Texts(v) => {
                            v.iter_mut().for_each(|s| self.span(&mut s.span))
                        }
                    }
                }
            }
            OpKind::Void | OpKind::Combine(_) => {}
        }
    }
}
