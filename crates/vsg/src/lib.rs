//! The Volumetric Shape Grammar of Sui (2011), chapter 7: a rule language that turns a few
//! parameters into a semantically labelled, volumetric 3D model.
//!
//! # Brief overview
//! - [`parse::parse`] reads a program into an [`ast::Program`], reporting syntax errors as
//!   [`diag::Diagnostic`]s with `line:column`.
//! - [`run`] checks and produces it: from `Axiom`, rules replace each non-terminal shape by its
//!   successors until only terminals remain. The result is a [`tree::Model`], the semantic tree
//!   whose nodes keep symbol, rule line, [`shape::Primitive`], transforms and appearance.
//! - [`shape`] holds the 18 primitive solids of Table 7.1 with exact volumes, meshes and splits.
//! - [`stats::Stats`] counts terminals and sums their exact volumes; [`export`] writes binary
//!   glTF and OBJ.
//!
//! ```
//! let src = r#"
//!     Axiom :: I("box", {4, 3, 2}){wall};
//!     wall :: repeat("X", {1}){stone};
//!     stone :: {j3d.terminal};
//! "#;
//! let model = vsg::run(src, &vsg::RunOptions::default()).unwrap();
//! let stats = vsg::stats::Stats::of(&model, &vsg::shape::Tessellation::default());
//! assert_eq!(stats.terminals, 4);
//! assert!((stats.volume.total - 24.0).abs() < 1e-9);
//! ```

pub mod ast;
pub mod compile;
pub mod csg;
pub mod diag;
pub mod export;
pub mod expr;
pub mod import;
pub mod mesh;
pub mod parse;
pub mod partition;
pub mod produce;
pub mod render;
pub mod shape;
pub mod stats;
pub mod tree;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

pub use diag::Diagnostic;
pub use produce::Limits;
pub use tree::Model;

/// The seed used when none is given, so runs are reproducible by default.
pub const DEFAULT_SEED: u64 = 1;

/// How to run a program.
#[derive(Clone, Debug, PartialEq)]
pub struct RunOptions {
    /// Seeds every random choice (rule probabilities, `rand()`).
    pub seed: u64,
    /// `--set NAME=VALUE`: replaces the value of a declared float.
    pub overrides: Vec<(String, f64)>,
    pub limits: Limits,
}

impl Default for RunOptions {
    fn default() -> Self {
        RunOptions {
            seed: DEFAULT_SEED,
            overrides: Vec::new(),
            limits: Limits::default(),
        }
    }
}

/// Why a program could not be run.
#[derive(Debug)]
pub enum Error {
    /// Syntax or static errors, in source order; spans are numbered across the program and its
    /// imports as `sources` says.
    Program(Vec<Diagnostic>, import::Sources),
    /// A bad `--set`.
    Override(String),
}

impl Error {
    /// The messages, each as `file:line:col: message` with an excerpt (at most
    /// [`diag::MAX_RENDERED`], then a count of the rest). `file` and `src` name the main
    /// program; messages about imported programs name those.
    pub fn render(&self, file: &str, src: &str) -> String {
        match self {
            Error::Program(ds, sources) => sources.render_all(file, src, ds),
            Error::Override(m) => format!("{file}: {m}\n"),
        }
    }
}

/// Parses, checks and produces a program that imports nothing.
pub fn run(src: &str, options: &RunOptions) -> Result<Model, Error> {
    run_with("program", src, options, &mut import::NoImports)
}

/// Parses a program named `name` (for messages and relative imports), splices in its imports
/// through `resolver`, checks and produces it.
pub fn run_with(
    name: &str,
    src: &str,
    options: &RunOptions,
    resolver: &mut dyn import::Resolver,
) -> Result<Model, Error> {
    let (program, sources) =
        import::load(name, src, resolver).map_err(|(ds, s)| Error::Program(ds, s))?;
    let mut rng = ChaCha8Rng::seed_from_u64(options.seed);
    let line_of = |span: ast::Span| sources.line(span);
    let compiled = compile::compile(&program, &line_of, &options.overrides, &mut rng).map_err(
        |e| match e {
            compile::CompileError::Program(ds) => Error::Program(ds, sources.clone()),
            compile::CompileError::Override(m) => Error::Override(m),
        },
    )?;
    produce::produce(&compiled, options.limits, rng)
        .map_err(|d| Error::Program(vec![d], sources.clone()))
}
