//! The lexer: program text to tokens with byte spans. Whitespace (newlines included) and
//! `// ...` comments between tokens are skipped; bad characters and unterminated strings are
//! reported and lexing carries on. A leading byte-order mark (which Windows editors write) is
//! nothing: this is the one place every program text, main or imported, goes through.

use std::fmt;

use chumsky::prelude::*;

use crate::ast::Span;
use crate::diag::Diagnostic;

/// A token; slices borrow the program text.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Token<'s> {
    /// A number as written: `12`, `0.5`, `.5`, `1e-3`, `2.`.
    Num(&'s str),
    /// A string literal's contents, without quotes.
    Str(&'s str),
    Ident(&'s str),
    Float,
    True,
    False,
    /// Punctuation and operators.
    Punct(&'static str),
    /// A character no token starts with (already reported; dropped before parsing).
    Error,
}

impl fmt::Display for Token<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Token::Num(s) | Token::Ident(s) | Token::Punct(s) => f.write_str(s),
            Token::Str(s) => write!(f, "\"{s}\""),
            Token::Float => f.write_str("float"),
            Token::True => f.write_str("true"),
            Token::False => f.write_str("false"),
            Token::Error => f.write_str("<error>"),
        }
    }
}

/// Multi-character operators come first so the longest match wins.
const PUNCT: [&str; 27] = [
    "::", "<=", ">=", "==", "!=", "&&", "||", "(", ")", "{", "}", "[", "]", ",", ";", ":", ".",
    "~", "=", "+", "-", "*", "/", "%", "<", ">", "!",
];

pub type Spanned<'s> = (Token<'s>, SimpleSpan);
type LexErr<'s> = extra::Err<Rich<'s, char, SimpleSpan, Diagnostic>>;

pub fn span(s: SimpleSpan) -> Span {
    Span::new(s.start, s.end)
}

/// Tokens of the whole text; never fails (errors are emitted and lexing continues).
pub fn lexer<'s>() -> impl Parser<'s, &'s str, Vec<Spanned<'s>>, LexErr<'s>> {
    let digits = text::digits(10);
    let exponent = one_of("eE").then(one_of("+-").or_not()).then(digits);
    let num = choice((
        digits
            .then(just('.').then(digits.or_not()).or_not())
            .ignored(),
        just('.').then(digits).ignored(),
    ))
    .then(exponent.or_not())
    .to_slice()
    .map(Token::Num);

    let string = just('"')
        .ignore_then(none_of("\"\r\n").repeated().to_slice())
        .then(just('"').or_not())
        .validate(|(body, close), e, emitter| {
            if close.is_none() {
                emitter.emit(Rich::custom(
                    e.span(),
                    Diagnostic::new(
                        "unterminated string literal",
                        span(e.span()),
                        "this string has no closing '\"' on its line",
                    ),
                ));
            }
            Token::Str(body)
        });

    let word = text::ascii::ident().map(|w: &str| match w {
        "float" => Token::Float,
        "true" => Token::True,
        "false" => Token::False,
        _ => Token::Ident(w),
    });

    let punct = choice(PUNCT.map(|p| just(p).to(Token::Punct(p))));

    let stray = any().validate(|c: char, e, emitter| {
        emitter.emit(Rich::custom(
            e.span(),
            Diagnostic::new(
                format!("unexpected character '{c}'"),
                span(e.span()),
                "no token starts with this character",
            ),
        ));
        Token::Error
    });

    let comment = just("//").then(none_of('\n').repeated()).ignored();
    let blank = any().filter(|c: &char| c.is_whitespace()).ignored();
    let skip = comment.or(blank).repeated();

    let bom = just('\u{FEFF}').or_not();

    bom.ignore_then(
        choice((num, string, word, punct, stray))
            .map_with(|t, e| (t, e.span()))
            .padded_by(skip)
            .repeated()
            .collect::<Vec<_>>(),
    )
    .then_ignore(skip)
    .then_ignore(end())
    .map(|tokens| {
        tokens
            .into_iter()
            .filter(|(t, _)| *t != Token::Error)
            .collect()
    })
}
