//! Static checks of a parsed program before production (§7.1): declarations evaluated with
//! `--set` overrides, symbols interned, and every rule checked for what can be known without
//! running it: shape types and parameter counts, split directions, successor counts, symbols
//! that have no rule.

use std::collections::HashMap;

use rand_chacha::ChaCha8Rng;

use crate::ast::{DeclValue, Ident, Item, Op, OpKind, Program, Rule, Span, Successor};
use crate::csg::BoolOp;
use crate::diag::Diagnostic;
use crate::expr::{Scope, Value};
use crate::shape::{Axis, ShapeType};

/// The start symbol.
pub const AXIOM: &str = "Axiom";

/// A successor after interning.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Succ {
    Symbol(u32),
    Terminal,
}

/// What a rule does to the shape geometry.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Geometry {
    /// No I, split or repeat: successors get the predecessor's shape.
    Keep,
    /// `n` instantiations, bound to the successors in order.
    Instantiate(usize),
    /// One split or repeat (index into the rule's ops) along a checked axis.
    Divide { op: usize, axis: Axis },
}

/// A checked rule.
pub struct CompiledRule<'p> {
    pub ast: &'p Rule,
    pub line: u32,
    pub successors: Vec<Succ>,
    pub geometry: Geometry,
    /// Instantiated types, in order.
    pub types: Vec<ShapeType>,
    /// `union()`/`intersection()`/`difference()`: the instantiations make one unique shape,
    /// bound to the single successor.
    pub combine: Option<BoolOp>,
}

/// A checked program, ready to produce.
pub struct Compiled<'p> {
    pub vars: HashMap<String, Value>,
    pub symbols: Vec<String>,
    pub rules: Vec<CompiledRule<'p>>,
    /// Rules of each symbol, by symbol id.
    pub rules_by_symbol: Vec<Vec<usize>>,
    pub axiom: u32,
}

/// Errors found before production: all syntax-free problems of the program, or a bad override.
#[derive(Debug)]
pub enum CompileError {
    Program(Vec<Diagnostic>),
    Override(String),
}

pub fn compile<'p>(
    program: &'p Program,
    line_of: &dyn Fn(Span) -> u32,
    overrides: &[(String, f64)],
    rng: &mut ChaCha8Rng,
) -> Result<Compiled<'p>, CompileError> {
    let vars = declarations(program, overrides, rng)?;
    let mut symbols = Symbols::default();
    let axiom = symbols.intern(AXIOM);
    let mut errors = Vec::new();
    let mut rules = Vec::new();
    for item in &program.items {
        if let Item::Rule(rule) = item {
            symbols.intern(&rule.predecessor.name);
            match check_rule(rule, line_of, &mut symbols) {
                Ok(r) => rules.push(r),
                Err(d) => errors.push(d),
            }
        }
    }
    let mut rules_by_symbol = vec![Vec::new(); symbols.names.len()];
    for (i, r) in rules.iter().enumerate() {
        rules_by_symbol[symbols.ids[&r.ast.predecessor.name] as usize].push(i);
    }
    if rules_by_symbol[axiom as usize].is_empty() && errors.is_empty() {
        errors.push(Diagnostic::new(
            format!("the program has no rule for the start symbol {AXIOM}"),
            Span::new(0, 0),
            format!("add a rule such as `{AXIOM} :: I(\"box\", {{1, 1, 1}}){{building}};`"),
        ));
    }
    for r in &rules {
        for (s, ast) in r.successors.iter().zip(&r.ast.successors) {
            if let (Succ::Symbol(id), Successor::Symbol(ident)) = (s, ast)
                && rules_by_symbol
                    .get(*id as usize)
                    .is_none_or(|v| v.is_empty())
            {
                errors.push(Diagnostic::new(
                    format!(
                        "symbol '{}' has no rule; end it with `{} :: {{j3d.terminal}};`",
                        ident.name, ident.name
                    ),
                    ident.span,
                    "no rule for this symbol",
                ));
            }
        }
    }
    for r in rules.iter().filter(|r| r.combine.is_some()) {
        if let (Succ::Symbol(id), Successor::Symbol(ident)) =
            (r.successors[0], &r.ast.successors[0])
            && let Some(own) = rules_by_symbol.get(id as usize).filter(|v| !v.is_empty())
            && !own.iter().all(|&k| ends_in_place(&rules[k]))
        {
            errors.push(Diagnostic::new(
                format!(
                    "a unique shape is terminal (§7.1.2), but '{}' has a rule that replaces or divides it; its rules may only move, colour or void it before {{j3d.terminal}}",
                    ident.name
                ),
                ident.span,
                "this successor must be terminal",
            ));
        }
    }
    rules_by_symbol.resize(symbols.names.len(), Vec::new());
    if !errors.is_empty() {
        errors.sort_by_key(|d| d.span.start);
        return Err(CompileError::Program(errors));
    }
    Ok(Compiled {
        vars,
        symbols: symbols.names,
        rules,
        rules_by_symbol,
        axiom,
    })
}

#[derive(Default)]
struct Symbols {
    names: Vec<String>,
    ids: HashMap<String, u32>,
}

impl Symbols {
    fn intern(&mut self, name: &str) -> u32 {
        if let Some(&id) = self.ids.get(name) {
            return id;
        }
        let id = self.names.len() as u32;
        self.names.push(name.to_string());
        self.ids.insert(name.to_string(), id);
        id
    }
}

fn declarations(
    program: &Program,
    overrides: &[(String, f64)],
    rng: &mut ChaCha8Rng,
) -> Result<HashMap<String, Value>, CompileError> {
    let mut vars: HashMap<String, Value> = HashMap::new();
    let mut errors = Vec::new();
    for item in &program.items {
        let Item::Decl(decl) = item else { continue };
        if vars.contains_key(&decl.name.name) {
            errors.push(Diagnostic::new(
                format!("'{}' is declared twice", decl.name.name),
                decl.name.span,
                "second declaration",
            ));
            continue;
        }
        if let Some((_, v)) = overrides.iter().find(|(n, _)| *n == decl.name.name) {
            if let DeclValue::Array(_) = decl.value {
                return Err(CompileError::Override(format!(
                    "--set {}: '{}' is an array; only float variables can be set",
                    decl.name.name, decl.name.name
                )));
            }
            if !v.is_finite() {
                return Err(CompileError::Override(format!(
                    "--set {}={v}: not a finite number",
                    decl.name.name
                )));
            }
            vars.insert(decl.name.name.clone(), Value::Scalar(*v));
            continue;
        }
        let mut scope = Scope {
            vars: &vars,
            shape: None,
            rng,
        };
        let value = match &decl.value {
            DeclValue::Scalar(e) => scope.eval(e).map(Value::Scalar),
            DeclValue::Array(es) => es
                .iter()
                .map(|e| scope.eval(e))
                .collect::<Result<_, _>>()
                .map(Value::Array),
        };
        match value {
            Ok(v) => {
                vars.insert(decl.name.name.clone(), v);
            }
            Err(d) => errors.push(d),
        }
    }
    for (name, _) in overrides {
        if !vars.contains_key(name) && errors.is_empty() {
            let declared: Vec<&str> = program
                .items
                .iter()
                .filter_map(|i| match i {
                    Item::Decl(d) if matches!(d.value, DeclValue::Scalar(_)) => {
                        Some(d.name.name.as_str())
                    }
                    _ => None,
                })
                .collect();
            return Err(CompileError::Override(format!(
                "--set {name}: the program declares no float '{name}' (it declares: {})",
                if declared.is_empty() {
                    "none".to_string()
                } else {
                    declared.join(", ")
                }
            )));
        }
    }
    if errors.is_empty() {
        Ok(vars)
    } else {
        Err(CompileError::Program(errors))
    }
}

fn check_rule<'p>(
    rule: &'p Rule,
    line_of: &dyn Fn(Span) -> u32,
    symbols: &mut Symbols,
) -> Result<CompiledRule<'p>, Diagnostic> {
    let successors: Vec<Succ> = rule
        .successors
        .iter()
        .map(|s| match s {
            Successor::Symbol(id) => Succ::Symbol(symbols.intern(&id.name)),
            Successor::Terminal(_) => Succ::Terminal,
        })
        .collect();
    let mut types = Vec::new();
    let mut divide: Option<(usize, Axis, usize, &Op)> = None;
    let mut combine: Option<(BoolOp, &Op)> = None;
    for (i, op) in rule.ops.iter().enumerate() {
        if let Some((c, _)) = combine
            && matches!(
                op.kind,
                OpKind::Instantiate { .. }
                    | OpKind::Split { .. }
                    | OpKind::Repeat { .. }
                    | OpKind::Translate(_)
                    | OpKind::Rotate(_)
                    | OpKind::Combine(_)
            )
        {
            return Err(Diagnostic::new(
                format!(
                    "{}() ends the geometry of its rule: only appearance() and void() may follow it",
                    c.name()
                ),
                op.span,
                "after the Boolean",
            ));
        }
        match &op.kind {
            OpKind::Combine(c) => {
                if types.is_empty() {
                    return Err(Diagnostic::new(
                        format!(
                            "{}() combines the shapes instantiated before it in the rule, and there are none; add I() calls before it",
                            c.name()
                        ),
                        op.span,
                        "nothing to combine",
                    ));
                }
                combine = Some((*c, op));
            }
            OpKind::Instantiate { shape_type, params } => {
                let kind = ShapeType::parse(&shape_type.value).ok_or_else(|| {
                    let names: Vec<&str> = ShapeType::ALL.iter().map(|t| t.name()).collect();
                    Diagnostic::new(
                        format!(
                            "unknown shape type \"{}\"; the types are {}",
                            shape_type.value,
                            names.join(", ")
                        ),
                        shape_type.span,
                        "unknown shape type",
                    )
                })?;
                let (lo, hi) = (kind.required_params(), kind.param_names().len());
                if params.len() < lo || params.len() > hi {
                    let expected = if lo == hi {
                        lo.to_string()
                    } else {
                        format!("{lo} to {hi}")
                    };
                    return Err(Diagnostic::new(
                        format!(
                            "{kind} takes {expected} parameters ({}), found {}",
                            kind.param_names().join(", "),
                            params.len()
                        ),
                        op.span,
                        "wrong number of parameters",
                    ));
                }
                types.push(kind);
            }
            OpKind::Split { axis, lengths } | OpKind::Repeat { axis, lengths, .. } => {
                if let Some((_, _, _, first)) = divide {
                    return Err(Diagnostic::new(
                        "a rule can split or repeat only once",
                        op.span.to(first.span),
                        "second split in this rule",
                    ));
                }
                let a = Axis::parse(&axis.name).ok_or_else(|| {
                    Diagnostic::new(
                        format!(
                            "unknown split direction \"{}\"; directions are X, Y, Z, R, Theta, Phi",
                            axis.name
                        ),
                        axis.span,
                        "unknown direction",
                    )
                })?;
                divide = Some((i, a, lengths.len(), op));
            }
            _ => {}
        }
    }
    let geometry = match (types.len(), divide) {
        (0, None) => Geometry::Keep,
        (n, None) => Geometry::Instantiate(n),
        (0, Some((op, axis, _, _))) => Geometry::Divide { op, axis },
        (_, Some((_, _, _, d))) => {
            return Err(Diagnostic::new(
                "a rule can instantiate shapes or split its shape, not both",
                d.span,
                "split in a rule with I()",
            ));
        }
    };
    let wanted = match (geometry, divide) {
        (Geometry::Instantiate(_), _) if combine.is_some() => Some((1, "unique shape")),
        (Geometry::Instantiate(n), _) => Some((n, "instantiations")),
        (Geometry::Divide { .. }, Some((_, _, n, op))) => Some((
            n,
            if matches!(op.kind, OpKind::Split { .. }) {
                "split lengths"
            } else {
                "repeat lengths"
            },
        )),
        _ => None,
    };
    if let Some((n, what)) = wanted
        && n != successors.len()
    {
        return Err(Diagnostic::new(
            format!(
                "the rule has {n} {what} but {} successors; they are bound in order, one each",
                successors.len()
            ),
            successor_span(rule),
            format!("{} successors", successors.len()),
        ));
    }
    Ok(CompiledRule {
        ast: rule,
        line: line_of(rule.span),
        successors,
        geometry,
        types,
        combine: combine.map(|c| c.0),
    })
}

/// A rule that keeps its shape and ends it: no I, split or repeat, one `j3d.terminal`.
fn ends_in_place(rule: &CompiledRule) -> bool {
    rule.geometry == Geometry::Keep && rule.successors == [Succ::Terminal]
}

fn successor_span(rule: &Rule) -> Span {
    let spans = rule.successors.iter().map(|s| match s {
        Successor::Symbol(Ident { span, .. }) | Successor::Terminal(span) => *span,
    });
    spans.reduce(Span::to).unwrap_or(rule.span)
}
