//! Diagnostics for VSG programs: a message tied to a span, rendered as `file:line:column:
//! message` followed by the offending excerpt (via ariadne), so users find the fault at once.
//!
//! Positions come from a [`LineIndex`] built once per text: a span's line is a binary search
//! over line starts, never a rescan of the text, so a program with many rules (each remembers
//! its line) or many errors costs O(n log n), not O(n²).

use crate::ast::Span;

/// Most diagnostics [`crate::Error::render`] shows in full; the rest are counted. A program with
/// thousands of errors gets the first ones, each with its excerpt, instead of megabytes.
pub const MAX_RENDERED: usize = 100;

/// One error in a program, with where it is.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    pub message: String,
    pub span: Span,
    /// A short note shown under the excerpt, at the span.
    pub label: String,
}

impl Diagnostic {
    pub fn new(message: impl Into<String>, span: Span, label: impl Into<String>) -> Diagnostic {
        Diagnostic {
            message: message.into(),
            span,
            label: label.into(),
        }
    }

    /// 1-based `(line, column)` of the span start; columns count characters.
    pub fn line_col(&self, src: &str) -> (usize, usize) {
        line_col(src, self.span.start)
    }

    /// `file:line:col: message` and an excerpt of the source, without colour codes.
    pub fn render(&self, file: &str, src: &str) -> String {
        Text::new(file, src).render(self)
    }
}

impl std::fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

/// Byte offsets of the line starts of a text, and the characters before each, built once in
/// O(n).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LineIndex {
    /// `(byte offset, characters before it)` of every line start; the first is `(0, 0)`.
    starts: Vec<(usize, usize)>,
}

impl LineIndex {
    pub fn new(src: &str) -> LineIndex {
        let mut starts = vec![(0, 0)];
        let mut chars = 0;
        for (at, c) in src.char_indices() {
            chars += 1;
            if c == '\n' {
                starts.push((at + 1, chars));
            }
        }
        LineIndex { starts }
    }

    /// 1-based line of byte offset `at`.
    pub fn line(&self, at: usize) -> usize {
        self.starts.partition_point(|&(s, _)| s <= at).max(1)
    }

    /// 1-based line and character column of byte offset `at` in `src` (the text the index was
    /// built from): a binary search, then a count over that line only.
    pub fn line_col(&self, src: &str, at: usize) -> (usize, usize) {
        let line = self.line(at);
        let at = floor_boundary(src, at.min(src.len()));
        // A leading byte-order mark is no character of the first line (the lexer skips it).
        let bom = if line == 1 && src.starts_with('\u{FEFF}') {
            '\u{FEFF}'.len_utf8()
        } else {
            0
        };
        let start = (self.starts[line - 1].0 + bom).min(at);
        (line, src[start..at].chars().count() + 1)
    }

    /// Character index of byte offset `at` (ariadne counts characters).
    fn char_index(&self, src: &str, at: usize) -> usize {
        let at = floor_boundary(src, at.min(src.len()));
        let (start, before) = self.starts[self.line(at) - 1];
        before + src[start.min(at)..at].chars().count()
    }
}

/// A text prepared for rendering several diagnostics: its line index and ariadne's source
/// (each O(n) to build), made once.
pub struct Text<'a> {
    name: &'a str,
    src: &'a str,
    lines: LineIndex,
    source: ariadne::Source<&'a str>,
}

impl<'a> Text<'a> {
    pub fn new(name: &'a str, src: &'a str) -> Text<'a> {
        Text {
            name,
            src,
            lines: LineIndex::new(src),
            source: ariadne::Source::from(src),
        }
    }

    /// `file:line:col: message` and an excerpt of the source, without colour codes.
    pub fn render(&self, d: &Diagnostic) -> String {
        use ariadne::{Config, Label, Report, ReportKind};
        let (file, src) = (self.name, self.src);
        let (line, col) = self.lines.line_col(src, d.span.start);
        let start = self.lines.char_index(src, d.span.start);
        let end = self
            .lines
            .char_index(src, d.span.end.max(d.span.start + 1))
            .max(start + 1);
        let mut out = Vec::new();
        let report = Report::build(ReportKind::Error, (file, start..end))
            .with_config(Config::default().with_color(false))
            .with_message(&d.message)
            .with_label(Label::new((file, start..end)).with_message(&d.label))
            .finish();
        let header = format!("{file}:{line}:{col}: {}\n", d.message);
        if report.write((file, &self.source), &mut out).is_err() {
            return header;
        }
        header + &String::from_utf8_lossy(&out)
    }
}

/// A number for a message: as Rust writes it when that reads well (0, or 1e-4 ≤ |v| < 1e9),
/// otherwise in scientific notation, so `1e308` is not spelled out in 309 digits.
pub fn num(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-4..1e9).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// 1-based line and character column of byte offset `at`, for one lookup (many go through one
/// [`LineIndex`]).
pub fn line_col(src: &str, at: usize) -> (usize, usize) {
    LineIndex::new(src).line_col(src, at)
}

fn floor_boundary(src: &str, mut at: usize) -> usize {
    while !src.is_char_boundary(at) {
        at -= 1;
    }
    at
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_col_counts_from_one() {
        let src = "ab\ncd\nef";
        assert_eq!(line_col(src, 0), (1, 1));
        assert_eq!(line_col(src, 4), (2, 2));
        assert_eq!(line_col(src, 6), (3, 1));
    }

    #[test]
    fn render_names_file_line_and_column_and_shows_excerpt() {
        let src = "Axiom::I(\"box\",{1,2}){a};\nb::{j3d.terminal};";
        let d = Diagnostic::new("box takes 3 parameters", Span::new(26, 27), "here");
        let text = d.render("p.vsg", src);
        assert!(
            text.starts_with("p.vsg:2:1: box takes 3 parameters"),
            "{text}"
        );
        assert!(text.contains("b::{j3d.terminal};"), "{text}");
    }
}
