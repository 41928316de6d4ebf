//! The VSG parser: program text to the [`Program`](crate::ast::Program) syntax tree, with
//! declarations and rules of form 7.1 (`predecessor : condition : successor : probability`,
//! §7.1) and the rule functions of §7.1.1. Errors come back as [`Diagnostic`]s with spans.
//!
//! ```
//! let program = vsg::parse::parse("Axiom::I(\"box\",{5,10,3}){building};").unwrap();
//! assert_eq!(program.items.len(), 1);
//!
//! let errors = vsg::parse::parse("a::{b;").unwrap_err();
//! assert_eq!(errors[0].message, "expected ',' or '}', found ';'");
//! ```

mod grammar;
mod lexer;
mod ops;
#[cfg(test)]
mod tests;

use chumsky::error::{RichPattern, RichReason};
use chumsky::prelude::*;

use crate::ast::Program;
use crate::diag::Diagnostic;
use lexer::{Token, span};

/// Parses a whole program. On failure, returns every error found (at least one), in source order.
pub fn parse(src: &str) -> Result<Program, Vec<Diagnostic>> {
    let (tokens, lex_errors) = lexer::lexer().parse(src).into_output_errors();
    if !lex_errors.is_empty() {
        return Err(sorted(
            lex_errors
                .into_iter()
                .map(|e| diagnostic(e, char_name))
                .collect(),
        ));
    }
    let tokens = tokens.unwrap_or_default();
    let eoi = SimpleSpan::from(src.len()..src.len());
    let (program, errors) = grammar::program()
        .parse(tokens.as_slice().split_token_span(eoi))
        .into_output_errors();
    match program {
        Some(program) if errors.is_empty() => Ok(program),
        _ if errors.is_empty() => Err(vec![Diagnostic::new(
            "could not parse the program",
            span(eoi),
            "here",
        )]),
        _ => Err(sorted(
            errors
                .into_iter()
                .map(|e| diagnostic(e, token_name))
                .collect(),
        )),
    }
}

fn sorted(mut diags: Vec<Diagnostic>) -> Vec<Diagnostic> {
    diags.sort_by_key(|d| (d.span.start, d.span.end));
    diags.dedup();
    diags
}

fn token_name(t: &Token) -> String {
    format!("'{t}'")
}

fn char_name(c: &char) -> String {
    format!("{c:?}")
}

/// Turns a chumsky error into a diagnostic: custom ones carry theirs, the others read
/// "expected A, B or C, found D".
fn diagnostic<T>(e: Rich<T, SimpleSpan, Diagnostic>, name: fn(&T) -> String) -> Diagnostic {
    let at = span(*e.span());
    match e.into_reason() {
        RichReason::Custom(d) => d,
        RichReason::ExpectedFound { expected, found } => {
            let mut names: Vec<String> = expected
                .iter()
                .map(|p| match p {
                    RichPattern::Token(t) => name(t),
                    RichPattern::Label(l) => l.to_string(),
                    RichPattern::Identifier(i) => format!("'{i}'"),
                    RichPattern::EndOfInput => "end of input".into(),
                    _ => "something else".into(),
                })
                .collect();
            // Tokens first, then labels, end of input last; each once.
            names.sort_by_key(|n| (n == "end of input", !n.starts_with('\''), n.clone()));
            names.dedup();
            let found = found.map_or("end of input".to_string(), |t| name(&t));
            let message = match names.as_slice() {
                [] => format!("unexpected {found}"),
                [one] => format!("expected {one}, found {found}"),
                [init @ .., last] => {
                    format!("expected {} or {last}, found {found}", init.join(", "))
                }
            };
            Diagnostic::new(message, at, format!("unexpected {found}"))
        }
    }
}
