//! Diagnostics for VSG programs: a message tied to a span, rendered as `file:line:column:
//! message` followed by the offending excerpt (via ariadne), so users find the fault at once.

use crate::ast::Span;

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
        use ariadne::{Config, Label, Report, ReportKind, Source};
        let (line, col) = self.line_col(src);
        let start = char_index(src, self.span.start);
        let end = char_index(src, self.span.end.max(self.span.start + 1)).max(start + 1);
        let mut out = Vec::new();
        let report = Report::build(ReportKind::Error, (file, start..end))
            .with_config(Config::default().with_color(false))
            .with_message(&self.message)
            .with_label(Label::new((file, start..end)).with_message(&self.label))
            .finish();
        let header = format!("{file}:{line}:{col}: {}\n", self.message);
        if report.write((file, Source::from(src)), &mut out).is_err() {
            return header;
        }
        header + &String::from_utf8_lossy(&out)
    }
}

impl std::fmt::Display for Diagnostic {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.message)
    }
}

/// 1-based line and character column of byte offset `at`.
pub fn line_col(src: &str, at: usize) -> (usize, usize) {
    let at = at.min(src.len());
    let before = &src[..floor_boundary(src, at)];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

fn floor_boundary(src: &str, mut at: usize) -> usize {
    while !src.is_char_boundary(at) {
        at -= 1;
    }
    at
}

fn char_index(src: &str, byte: usize) -> usize {
    src[..floor_boundary(src, byte.min(src.len()))]
        .chars()
        .count()
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
