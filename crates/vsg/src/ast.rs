//! The syntax tree of a VSG program (§7.1, rule form 7.1): declarations and rules, every node
//! carrying the byte span it came from so errors can point at `line:column`.

/// Byte offsets `start..end` into the program text.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Span {
    pub start: usize,
    pub end: usize,
}

impl Span {
    pub fn new(start: usize, end: usize) -> Span {
        Span { start, end }
    }

    /// The smallest span covering both.
    pub fn to(self, other: Span) -> Span {
        Span::new(self.start.min(other.start), self.end.max(other.end))
    }
}

/// A name with the place it was written.
#[derive(Clone, Debug, PartialEq)]
pub struct Ident {
    pub name: String,
    pub span: Span,
}

/// A whole program: declarations and rules in source order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Program {
    pub items: Vec<Item>,
}

#[derive(Clone, Debug, PartialEq)]
pub enum Item {
    Decl(Decl),
    Rule(Rule),
    Import(Import),
}

/// `import "file.vsg" as name;` or `import "file.vsg" as name (var = expr, ...);`: the other
/// program's rules, symbols and floats join this one under `name.` (see [`crate::import`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Import {
    pub path: StrLit,
    pub alias: Ident,
    /// Values for the imported program's declared floats, in the importer's scope.
    pub args: Vec<(Ident, Expr)>,
    pub span: Span,
}

/// `float name = expr;` or `float [] name = {expr, ...};`
#[derive(Clone, Debug, PartialEq)]
pub struct Decl {
    pub name: Ident,
    pub value: DeclValue,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum DeclValue {
    Scalar(Expr),
    Array(Vec<Expr>),
}

/// `predecessor : condition : ops {successors} : probability ;`
#[derive(Clone, Debug, PartialEq)]
pub struct Rule {
    pub predecessor: Ident,
    pub condition: Option<Expr>,
    pub ops: Vec<Op>,
    pub successors: Vec<Successor>,
    pub probability: Option<Expr>,
    pub span: Span,
}

/// One entry of a rule's `{...}` successor list.
#[derive(Clone, Debug, PartialEq)]
pub enum Successor {
    Symbol(Ident),
    /// `j3d.terminal` (or `terminal`).
    Terminal(Span),
}

/// A rule function call written before the successor list (§7.1.1).
#[derive(Clone, Debug, PartialEq)]
pub struct Op {
    pub kind: OpKind,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum OpKind {
    /// `T(x, y, z)`
    Translate([Expr; 3]),
    /// `R(rx, ry, rz)`, radians
    Rotate([Expr; 3]),
    /// `I("type", {params})`
    Instantiate {
        shape_type: StrLit,
        params: Vec<Expr>,
    },
    /// `split(dir, {lengths})`
    Split { axis: AxisArg, lengths: Vec<Length> },
    /// `repeat(dir, {lengths}, offset)`; offset defaults to 0
    Repeat {
        axis: AxisArg,
        lengths: Vec<Length>,
        offset: Option<Expr>,
    },
    /// `appearance("attr", value, "attr", value, ...)`
    Appearance(Vec<(StrLit, AppearanceValue)>),
    /// `void()`
    Void,
    /// `union()`, `intersection()`, `difference()`: the shapes instantiated so far in the rule
    /// become one unique shape (§7.1.2).
    Combine(crate::csg::BoolOp),
}

/// A string literal without its quotes.
#[derive(Clone, Debug, PartialEq)]
pub struct StrLit {
    pub value: String,
    pub span: Span,
}

/// A split direction, written `"X"` or `X`.
#[derive(Clone, Debug, PartialEq)]
pub struct AxisArg {
    pub name: String,
    pub span: Span,
}

/// A split or repeat length; `~expr` is relative: it takes a share, proportional to `expr`, of
/// what the absolute lengths leave (as CityEngine's floating sizes do).
#[derive(Clone, Debug, PartialEq)]
pub struct Length {
    pub relative: bool,
    pub expr: Expr,
}

#[derive(Clone, Debug, PartialEq)]
pub enum AppearanceValue {
    /// `0.5` or any expression
    Scalar(Expr),
    /// `{0.3, 0.3, 0.7}`
    List(Vec<Expr>),
    /// `"bricks.png"`
    Text(StrLit),
    /// `{"a.png", "b.png"}`: one is picked per shape (figure 7.6)
    Texts(Vec<StrLit>),
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnaryOp {
    Neg,
    Not,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinaryOp {
    Add,
    Sub,
    Mul,
    Div,
    Rem,
    Lt,
    Le,
    Gt,
    Ge,
    Eq,
    Ne,
    And,
    Or,
}

/// Expressions: numbers, variables, `a[i]`, unary `-`/`!`, binary arithmetic, comparison and
/// logic, and calls of maths functions. Booleans are numbers (0 false, anything else true).
#[derive(Clone, Debug, PartialEq)]
pub enum Expr {
    Number(f64, Span),
    Bool(bool, Span),
    Var(Ident),
    Index {
        array: Ident,
        index: Box<Expr>,
        span: Span,
    },
    Unary {
        op: UnaryOp,
        operand: Box<Expr>,
        span: Span,
    },
    Binary {
        op: BinaryOp,
        lhs: Box<Expr>,
        rhs: Box<Expr>,
        span: Span,
    },
    Call {
        function: Ident,
        args: Vec<Expr>,
        span: Span,
    },
}

impl Expr {
    pub fn span(&self) -> Span {
        match self {
            Expr::Number(_, s) | Expr::Bool(_, s) => *s,
            Expr::Var(id) => id.span,
            Expr::Index { span, .. }
            | Expr::Unary { span, .. }
            | Expr::Binary { span, .. }
            | Expr::Call { span, .. } => *span,
        }
    }
}
