//! Rule functions (§7.1.1): the grammar parses every `name(arg, ...)` before a successor list
//! generically into a [`Call`]; this table then checks the name, the arity and the kind of each
//! argument and builds the [`OpKind`]. A new operation is one line in [`OPS`].

use crate::ast::{AppearanceValue, AxisArg, Expr, Ident, Length, OpKind, Span, StrLit};
use crate::csg::BoolOp;
use crate::diag::Diagnostic;

/// One argument as written, before we know what the function wants.
#[derive(Clone, Debug)]
pub enum Arg {
    Str(StrLit),
    /// `{e, ~e, ...}`: items with the span of their `~`, if any.
    List(Vec<(Option<Span>, Expr)>, Span),
    /// `{"a.png", "b.png"}`
    Strs(Vec<StrLit>, Span),
    Expr(Expr),
}

impl Arg {
    fn span(&self) -> Span {
        match self {
            Arg::Str(s) => s.span,
            Arg::List(_, span) | Arg::Strs(_, span) => *span,
            Arg::Expr(e) => e.span(),
        }
    }

    fn kind(&self) -> &'static str {
        match self {
            Arg::Str(_) => "a string",
            Arg::List(..) => "a list",
            Arg::Strs(..) => "a list of strings",
            Arg::Expr(_) => "an expression",
        }
    }
}

/// `name(args)` as parsed.
#[derive(Clone, Debug)]
pub struct Call {
    pub name: Ident,
    pub args: Vec<Arg>,
    pub span: Span,
}

type Build = fn(Call) -> Result<OpKind, Diagnostic>;

/// The rule functions by name.
const OPS: &[(&str, Build)] = &[
    ("T", |c| Ok(OpKind::Translate(c.arity(3)?.exprs3()?))),
    ("R", |c| Ok(OpKind::Rotate(c.arity(3)?.exprs3()?))),
    ("I", instantiate),
    ("split", split),
    ("repeat", repeat),
    ("appearance", appearance),
    ("void", |c| c.arity(0).map(|_| OpKind::Void)),
    ("union", |c| {
        c.arity(0).map(|_| OpKind::Combine(BoolOp::Union))
    }),
    ("intersection", |c| {
        c.arity(0).map(|_| OpKind::Combine(BoolOp::Intersection))
    }),
    ("difference", |c| {
        c.arity(0).map(|_| OpKind::Combine(BoolOp::Difference))
    }),
];

/// Checks a parsed call against [`OPS`] and builds its operation.
pub fn build(call: Call) -> Result<OpKind, Diagnostic> {
    match OPS.iter().find(|(name, _)| *name == call.name.name) {
        Some((_, build)) => build(call),
        None => {
            let known: Vec<&str> = OPS.iter().map(|(name, _)| *name).collect();
            Err(Diagnostic::new(
                format!(
                    "unknown function '{}'; expected one of {}",
                    call.name.name,
                    known.join(", ")
                ),
                call.name.span,
                "unknown function",
            ))
        }
    }
}

fn instantiate(c: Call) -> Result<OpKind, Diagnostic> {
    let mut args = c.arity(2)?.args.into_iter();
    let shape_type = string(args.next().unwrap(), "I", 1, "the shape type")?;
    let params = plain_list(args.next().unwrap(), "I", 2, "the shape parameters")?;
    Ok(OpKind::Instantiate { shape_type, params })
}

fn split(c: Call) -> Result<OpKind, Diagnostic> {
    let mut args = c.arity(2)?.args.into_iter();
    let axis = axis(args.next().unwrap(), "split")?;
    let lengths = lengths(args.next().unwrap(), "split")?;
    Ok(OpKind::Split { axis, lengths })
}

fn repeat(c: Call) -> Result<OpKind, Diagnostic> {
    if !(2..=3).contains(&c.args.len()) {
        return Err(c.arity_error("2 or 3 arguments"));
    }
    let mut args = c.args.into_iter();
    let axis = axis(args.next().unwrap(), "repeat")?;
    let lengths = lengths(args.next().unwrap(), "repeat")?;
    let offset = args
        .next()
        .map(|a| expr(a, "repeat", 3, "the offset"))
        .transpose()?;
    Ok(OpKind::Repeat {
        axis,
        lengths,
        offset,
    })
}

fn appearance(c: Call) -> Result<OpKind, Diagnostic> {
    if c.args.is_empty() || !c.args.len().is_multiple_of(2) {
        return Err(c.arity_error("pairs of \"attribute\", value arguments"));
    }
    let mut pairs = Vec::new();
    let mut args = c.args.into_iter().enumerate();
    while let (Some((i, attr)), Some((_, value))) = (args.next(), args.next()) {
        let attr = string(attr, "appearance", i + 1, "an attribute name")?;
        let value = match value {
            Arg::Str(s) => AppearanceValue::Text(s),
            Arg::Strs(v, _) => AppearanceValue::Texts(v),
            Arg::Expr(e) => AppearanceValue::Scalar(e),
            list => AppearanceValue::List(plain_list(list, "appearance", i + 2, "a value list")?),
        };
        pairs.push((attr, value));
    }
    Ok(OpKind::Appearance(pairs))
}

impl Call {
    fn arity(self, n: usize) -> Result<Call, Diagnostic> {
        if self.args.len() == n {
            Ok(self)
        } else {
            let what = if n == 1 {
                "1 argument".into()
            } else {
                format!("{n} arguments")
            };
            Err(self.arity_error(&what))
        }
    }

    fn arity_error(&self, what: &str) -> Diagnostic {
        Diagnostic::new(
            format!("{} takes {what}, found {}", self.name.name, self.args.len()),
            self.span,
            "wrong number of arguments",
        )
    }

    /// The three expressions of `T`/`R` (arity already checked).
    fn exprs3(self) -> Result<[Expr; 3], Diagnostic> {
        let name = self.name.name;
        let mut args = self
            .args
            .into_iter()
            .enumerate()
            .map(|(i, a)| expr(a, &name, i + 1, "a coordinate"));
        Ok([
            args.next().unwrap()?,
            args.next().unwrap()?,
            args.next().unwrap()?,
        ])
    }
}

fn wrong(arg: &Arg, func: &str, pos: usize, want: &str, example: &str) -> Diagnostic {
    Diagnostic::new(
        format!(
            "argument {pos} of {func} must be {example}, found {}",
            arg.kind()
        ),
        arg.span(),
        format!("expected {want} here"),
    )
}

fn expr(arg: Arg, func: &str, pos: usize, want: &str) -> Result<Expr, Diagnostic> {
    match arg {
        Arg::Expr(e) => Ok(e),
        other => Err(wrong(&other, func, pos, want, "an expression")),
    }
}

fn string(arg: Arg, func: &str, pos: usize, want: &str) -> Result<StrLit, Diagnostic> {
    match arg {
        Arg::Str(s) => Ok(s),
        other => Err(wrong(&other, func, pos, want, "a string such as \"box\"")),
    }
}

fn axis(arg: Arg, func: &str) -> Result<AxisArg, Diagnostic> {
    match arg {
        Arg::Str(s) => Ok(AxisArg {
            name: s.value,
            span: s.span,
        }),
        Arg::Expr(Expr::Var(id)) => Ok(AxisArg {
            name: id.name,
            span: id.span,
        }),
        other => Err(wrong(
            &other,
            func,
            1,
            "the direction",
            "a direction such as \"X\" or X",
        )),
    }
}

fn lengths(arg: Arg, func: &str) -> Result<Vec<Length>, Diagnostic> {
    match arg {
        Arg::List(items, _) => Ok(items
            .into_iter()
            .map(|(tilde, expr)| Length {
                relative: tilde.is_some(),
                expr,
            })
            .collect()),
        other => Err(wrong(
            &other,
            func,
            2,
            "the lengths",
            "a list such as {1, ~2}",
        )),
    }
}

/// A brace list without `~` items.
fn plain_list(arg: Arg, func: &str, pos: usize, want: &str) -> Result<Vec<Expr>, Diagnostic> {
    match arg {
        Arg::List(items, _) => items
            .into_iter()
            .map(|(tilde, expr)| match tilde {
                None => Ok(expr),
                Some(at) => Err(Diagnostic::new(
                    format!(
                        "relative lengths ('~') are only allowed in split and repeat, not in {func}"
                    ),
                    at,
                    "remove this '~'",
                )),
            })
            .collect(),
        other => Err(wrong(&other, func, pos, want, "a list such as {1, 2}")),
    }
}
