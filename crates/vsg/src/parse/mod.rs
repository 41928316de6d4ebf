//! The VSG parser: program text to the [`Program`](crate::ast::Program) syntax tree, with
//! declarations and rules of form 7.1 (`predecessor : condition : successor : probability`,
//! §7.1) and the rule functions of §7.1.1. Errors come back as [`Diagnostic`]s with spans.
//!
//! ```
//! let program = vsg::parse::parse("Axiom::I(\"box\",{5,10,3}){building};").unwrap();
//! assert_eq!(program.items.len(), 1);
//!
//! let errors = vsg::parse::parse("a::{b;").unwrap_err();
//! assert_eq!(errors[0].message, "expected ',', '.' or '}', found ';'");
//! ```

mod grammar;
mod lexer;
mod ops;
#[cfg(test)]
mod tests;

use chumsky::error::{RichPattern, RichReason};
use chumsky::prelude::*;

use crate::ast::{Program, Span};
use crate::diag::Diagnostic;
use lexer::{Token, span};

/// Stack of the parsing thread: chumsky's recursive descent takes about 130 KiB per bracket
/// level in debug builds, so [`MAX_NESTING`] levels need more than a test thread's 2 MiB.
const PARSER_STACK: usize = 64 << 20;

/// Parses a whole program. On failure, returns every error found (at least one), in source order.
pub fn parse(src: &str) -> Result<Program, Vec<Diagnostic>> {
    std::thread::scope(|scope| {
        let parser = std::thread::Builder::new()
            .name("vsg-parse".into())
            .stack_size(PARSER_STACK)
            .spawn_scoped(scope, || parse_here(src));
        match parser {
            Ok(handle) => handle
                .join()
                .unwrap_or_else(|p| std::panic::resume_unwind(p)),
            Err(e) => Err(vec![Diagnostic::new(
                format!("cannot start the parser thread: {e}"),
                Span::new(0, 0),
                "",
            )]),
        }
    })
}

fn parse_here(src: &str) -> Result<Program, Vec<Diagnostic>> {
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
    check_nesting(&tokens)?;
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

/// Deepest bracket nesting a program may use.
pub const MAX_NESTING: usize = 32;
/// Most operators one expression may chain (counted through its enclosing brackets).
pub const MAX_OPERATORS: usize = 256;

/// Bounds how deep expressions can nest before they are parsed, since parsing and evaluating
/// them recurse: a pathological program gets an error, never a stack overflow.
fn check_nesting(tokens: &[lexer::Spanned]) -> Result<(), Vec<Diagnostic>> {
    // Operators since the last separator, per open bracket level.
    let mut runs: Vec<usize> = vec![0];
    for (token, at) in tokens {
        let Token::Punct(p) = token else { continue };
        match *p {
            "(" | "[" | "{" => {
                if runs.len() > MAX_NESTING {
                    return Err(vec![Diagnostic::new(
                        format!("brackets nest more than {MAX_NESTING} deep"),
                        span(*at),
                        "too deep",
                    )]);
                }
                runs.push(0);
            }
            ")" | "]" | "}" if runs.len() > 1 => {
                runs.pop();
            }
            "," | ";" | ":" | "::" => *runs.last_mut().expect("never empty") = 0,
            "+" | "-" | "*" | "/" | "%" | "!" | "<" | "<=" | ">" | ">=" | "==" | "!=" | "&&"
            | "||" | "~" => {
                *runs.last_mut().expect("never empty") += 1;
                if runs.iter().sum::<usize>() > MAX_OPERATORS {
                    return Err(vec![Diagnostic::new(
                        format!(
                            "expression chains more than {MAX_OPERATORS} operators; split it up with declarations"
                        ),
                        span(*at),
                        "too long",
                    )]);
                }
            }
            _ => {}
        }
    }
    Ok(())
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
