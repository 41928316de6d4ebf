//! The token parser: declarations, rules (form 7.1), rule functions and expressions.

use chumsky::input::ValueInput;
use chumsky::prelude::*;

use super::lexer::{Token, span};
use super::ops::{self, Arg, Call};
use crate::ast::*;
use crate::diag::Diagnostic;

pub type TokErr<'t, 's> = extra::Err<Rich<'t, Token<'s>, SimpleSpan, Diagnostic>>;

fn p<'t, 's: 't, I>(s: &'static str) -> impl Parser<'t, I, Token<'s>, TokErr<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    just(Token::Punct(s))
}

fn ident<'t, 's: 't, I>() -> impl Parser<'t, I, Ident, TokErr<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    select! { Token::Ident(s) => s }
        .map_with(|s, e| Ident {
            name: s.to_string(),
            span: span(e.span()),
        })
        .labelled("symbol name")
}

/// A name, possibly qualified by import aliases: `wall`, `tower.roof`, `castle.tower.roof`.
fn qualified<'t, 's: 't, I>() -> impl Parser<'t, I, Ident, TokErr<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    ident()
        .then(p(".").ignore_then(ident()).repeated().collect::<Vec<_>>())
        .map(|(first, rest)| {
            rest.into_iter().fold(first, |acc, next| Ident {
                name: format!("{}.{}", acc.name, next.name),
                span: acc.span.to(next.span),
            })
        })
        .labelled("symbol name")
}

fn string<'t, 's: 't, I>() -> impl Parser<'t, I, StrLit, TokErr<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    select! { Token::Str(s) => s }
        .map_with(|s, e| StrLit {
            value: s.to_string(),
            span: span(e.span()),
        })
        .labelled("string")
}

fn binary(op: BinaryOp, lhs: Expr, rhs: Expr) -> Expr {
    let span = lhs.span().to(rhs.span());
    Expr::Binary {
        op,
        lhs: Box::new(lhs),
        rhs: Box::new(rhs),
        span,
    }
}

/// One precedence level: `next (op next)*`, left associative.
fn level<'t, 's: 't, I, P>(
    next: P,
    table: &'static [(&'static str, BinaryOp)],
) -> impl Parser<'t, I, Expr, TokErr<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
    P: Parser<'t, I, Expr, TokErr<'t, 's>> + Clone,
{
    let op =
        choice(table.iter().map(|&(s, op)| p(s).to(op)).collect::<Vec<_>>()).labelled("operator");
    next.clone()
        .foldl(op.then(next).repeated(), |lhs, (op, rhs)| {
            binary(op, lhs, rhs)
        })
}

/// What may follow a name in an expression.
enum Suffix {
    Index(Expr),
    Call(Vec<Expr>),
}

/// Expressions with the usual precedence: unary, `* / %`, `+ -`, comparisons, `&&`, `||`.
pub fn expr<'t, 's: 't, I>() -> impl Parser<'t, I, Expr, TokErr<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    recursive(|expr| {
        let number = select! { Token::Num(s) => s }.try_map(|s, sp| {
            s.parse::<f64>()
                .map(|n| Expr::Number(n, span(sp)))
                .map_err(|_| {
                    Rich::custom(
                        sp,
                        Diagnostic::new(format!("bad number '{s}'"), span(sp), "here"),
                    )
                })
        });
        let boolean = select! { Token::True => true, Token::False => false }
            .map_with(|b, e| Expr::Bool(b, span(e.span())));
        let args = expr
            .clone()
            .separated_by(p(","))
            .collect::<Vec<_>>()
            .delimited_by(p("("), p(")"));
        let index = expr.clone().delimited_by(p("["), p("]"));
        let named = qualified()
            .then(index.map(Suffix::Index).or(args.map(Suffix::Call)).or_not())
            .map_with(|(name, suffix), e| {
                let span = span(e.span());
                match suffix {
                    None => Expr::Var(name),
                    Some(Suffix::Index(index)) => Expr::Index {
                        array: name,
                        index: Box::new(index),
                        span,
                    },
                    Some(Suffix::Call(args)) => Expr::Call {
                        function: name,
                        args,
                        span,
                    },
                }
            });
        let atom = choice((number, boolean, named, expr.delimited_by(p("("), p(")"))))
            .labelled("expression");

        let prefix = p("-")
            .to(UnaryOp::Neg)
            .or(p("!").to(UnaryOp::Not))
            .map_with(|op, e| (op, span(e.span())));
        let unary = prefix.repeated().foldr(atom, |(op, at), operand: Expr| {
            let span = at.to(operand.span());
            Expr::Unary {
                op,
                operand: Box::new(operand),
                span,
            }
        });

        use BinaryOp::*;
        let product = level(unary, &[("*", Mul), ("/", Div), ("%", Rem)]);
        let sum = level(product, &[("+", Add), ("-", Sub)]);
        let compare = level(
            sum,
            &[
                ("<=", Le),
                (">=", Ge),
                ("<", Lt),
                (">", Gt),
                ("==", Eq),
                ("!=", Ne),
            ],
        );
        let and = level(compare, &[("&&", And)]);
        level(and, &[("||", Or)]).labelled("expression").boxed()
    })
}

/// `name(arg, ...)` before a successor list; `None` when the call was reported as wrong.
fn op<'t, 's: 't, I>() -> impl Parser<'t, I, Option<Op>, TokErr<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    let item = p("~")
        .map_with(|_, e| span(e.span()))
        .or_not()
        .then(expr())
        .labelled("expression");
    let list = item
        .separated_by(p(","))
        .collect::<Vec<_>>()
        .delimited_by(p("{"), p("}"))
        .map_with(|items, e| Arg::List(items, span(e.span())));
    let strings = string()
        .separated_by(p(","))
        .at_least(1)
        .collect::<Vec<_>>()
        .delimited_by(p("{"), p("}"))
        .map_with(|items, e| Arg::Strs(items, span(e.span())));
    let arg =
        choice((string().map(Arg::Str), strings, list, expr().map(Arg::Expr))).labelled("argument");
    ident()
        .labelled("function name")
        .then(
            arg.separated_by(p(","))
                .collect::<Vec<_>>()
                .delimited_by(p("("), p(")")),
        )
        .map_with(|(name, args), e| Call {
            name,
            args,
            span: span(e.span()),
        })
        .validate(|call, _, emitter| {
            let at = call.span;
            match ops::build(call) {
                Ok(kind) => Some(Op { kind, span: at }),
                Err(d) => {
                    emitter.emit(Rich::custom(SimpleSpan::from(d.span.start..d.span.end), d));
                    None
                }
            }
        })
}

/// One successor: a symbol, `j3d.terminal` or `terminal`.
fn successor<'t, 's: 't, I>() -> impl Parser<'t, I, Successor, TokErr<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    let j3d_terminal = just(Token::Ident("j3d"))
        .then(p("."))
        .then(just(Token::Ident("terminal")))
        .map_with(|_, e| Successor::Terminal(span(e.span())));
    let symbol = qualified().validate(|id, _, emitter| {
        if let Some(rest) = id.name.strip_prefix("j3d.") {
            // `j3d.` names nothing but the terminal.
            let at = Span::new(id.span.start + 4, id.span.end);
            emitter.emit(Rich::custom(
                SimpleSpan::from(at.start..at.end),
                Diagnostic::new(format!("expected 'terminal', found '{rest}'"), at, "here"),
            ));
        }
        match id.name.as_str() {
            "terminal" => Successor::Terminal(id.span),
            _ => Successor::Symbol(id),
        }
    });
    j3d_terminal.or(symbol).labelled("symbol name")
}

/// `pred :: body ;`, `pred : cond : body ;`, each optionally with `: prob` before the `;`.
fn rule<'t, 's: 't, I>() -> impl Parser<'t, I, Rule, TokErr<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    let condition = choice((
        p("::").to(None),
        p(":").ignore_then(expr()).then_ignore(p(":")).map(Some),
    ));
    let successors = successor()
        .separated_by(p(","))
        .at_least(1)
        .collect::<Vec<_>>()
        .delimited_by(p("{"), p("}"));
    qualified()
        .then(condition)
        .then(op().repeated().collect::<Vec<_>>())
        .then(successors)
        .then(p(":").ignore_then(expr()).or_not())
        .then_ignore(p(";"))
        .map_with(
            |((((predecessor, condition), ops), successors), probability), e| Rule {
                predecessor,
                condition,
                ops: ops.into_iter().flatten().collect(),
                successors,
                probability,
                span: span(e.span()),
            },
        )
}

/// `float name = expr;` or `float [] name = {expr, ...};`
fn decl<'t, 's: 't, I>() -> impl Parser<'t, I, Decl, TokErr<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    let list = expr()
        .separated_by(p(","))
        .collect::<Vec<_>>()
        .delimited_by(p("{"), p("}"));
    let array = p("[")
        .then(p("]"))
        .ignore_then(ident())
        .then_ignore(p("="))
        .then(list.map(DeclValue::Array));
    let scalar = ident()
        .then_ignore(p("="))
        .then(expr().map(DeclValue::Scalar));
    just(Token::Float)
        .ignore_then(array.or(scalar))
        .then_ignore(p(";"))
        .map_with(|(name, value), e| Decl {
            name,
            value,
            span: span(e.span()),
        })
}

/// `import "file.vsg" as name;`, optionally with `(var = expr, ...)` before the `;`.
fn import<'t, 's: 't, I>() -> impl Parser<'t, I, Import, TokErr<'t, 's>> + Clone
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    let args = ident()
        .then_ignore(p("="))
        .then(expr())
        .separated_by(p(","))
        .collect::<Vec<_>>()
        .delimited_by(p("("), p(")"));
    just(Token::Ident("import"))
        .ignore_then(string())
        .then_ignore(just(Token::Ident("as")))
        .then(ident())
        .then(args.or_not())
        .then_ignore(p(";"))
        .map_with(|((path, alias), args), e| Import {
            path,
            alias,
            args: args.unwrap_or_default(),
            span: span(e.span()),
        })
}

/// The whole program; a broken item is reported and skipped up to its `;`.
pub fn program<'t, 's: 't, I>() -> impl Parser<'t, I, Program, TokErr<'t, 's>>
where
    I: ValueInput<'t, Token = Token<'s>, Span = SimpleSpan>,
{
    let skip = any().and_is(p(";").not()).repeated();
    let recovery = choice((
        skip.clone().then(p(";")).ignored(),
        skip.at_least(1).then(end()).ignored(),
    ));
    let item = choice((
        decl().map(Item::Decl).labelled("declaration"),
        import().map(Item::Import).labelled("import"),
        rule().map(Item::Rule).labelled("rule"),
    ));
    item.map(Some)
        .recover_with(via_parser(recovery.to(None)))
        .repeated()
        .collect::<Vec<_>>()
        .then_ignore(end())
        .map(|items| Program {
            items: items.into_iter().flatten().collect(),
        })
}
