//! Fuzzing on stable Rust (issue 19), with proptest: (a) any text, parsed and run, never panics
//! and every error points inside the text; (b) generated valid-ish programs (splits, repeats,
//! transforms, Booleans, appearance; numbers huge, tiny, negative, and expressions such as
//! `0/0` or `1e308*10`) run under small limits either fail with a diagnostic or give a model
//! whose every vertex is a finite 32-bit float and which both exporters write; (c) mutations
//! of the shipped programs (`examples/*.vsg`, `library/*.vsg`) never panic.
//!
//! The default case counts keep this file well under a minute in a debug build (CI). A longer
//! run, for developers:
//! `PROPTEST_CASES=20000 cargo test -p vsg --release --test fuzz`
//! Panics found get their own named regression test (in this file, after the properties).

use std::collections::HashMap;
use std::path::Path;

use proptest::prelude::*;
use proptest::sample::select;
use proptest::test_runner::Config;
use vsg::export::{ExportOptions, to_glb, to_obj};
use vsg::import::Resolver;
use vsg::shape::{ShapeType, Tessellation};
use vsg::{Error, Limits, Model, RunOptions};

/// `cases` unless `PROPTEST_CASES` asks for another count.
fn config(cases: u32) -> Config {
    let mut c = Config {
        failure_persistence: None,
        ..Config::default()
    };
    if std::env::var_os("PROPTEST_CASES").is_none() {
        c.cases = cases;
    }
    c
}

/// Small limits, so a fuzzed program is cheap whatever it asks for.
fn options(seed: u64) -> RunOptions {
    RunOptions {
        seed,
        limits: Limits {
            max_depth: 12,
            max_shapes: 2_000,
            tessellation: Tessellation { segments: 8 },
        },
        ..Default::default()
    }
}

fn export_options() -> ExportOptions {
    ExportOptions {
        tessellation: Tessellation { segments: 8 },
        ..Default::default()
    }
}

/// Checks a run: an error has spans inside the texts and renders; a model has finite f32
/// vertices and exports. `len` is the length of all texts together.
fn check(name: &str, src: &str, result: Result<Model, Error>) {
    match result {
        Err(e) => {
            if let Error::Program(ds, sources) = &e {
                let len = sources
                    .files
                    .last()
                    .map_or(src.len(), |f| f.base + f.text.len());
                assert!(!ds.is_empty(), "an error without diagnostics");
                for d in ds {
                    assert!(
                        d.span.start <= d.span.end && d.span.end <= len,
                        "span {:?} outside the {len} bytes of text: {}",
                        d.span,
                        d.message
                    );
                }
            }
            let text = e.render(name, src);
            assert!(!text.is_empty());
        }
        Ok(model) => check_model(&model),
    }
}

fn check_model(model: &Model) {
    let tessellation = Tessellation { segments: 8 };
    for (i, node) in model.nodes.iter().enumerate() {
        let Some(solid) = model.solid(i as u32) else {
            continue;
        };
        for p in &solid.mesh(&tessellation).positions {
            let w = node.world * nalgebra::Point3::from(*p);
            assert!(
                w.iter().all(|&c| (c as f32).is_finite()),
                "vertex {w:?} of node {i} is not a finite f32"
            );
        }
    }
    let glb = to_glb(model, &export_options());
    assert!(glb.is_ok(), "glb export failed: {:?}", glb.err());
    let obj = to_obj(model, &export_options(), "m.mtl");
    assert!(obj.is_ok(), "obj export failed: {:?}", obj.err());
    let (obj, _) = obj.unwrap();
    assert!(!obj.contains("inf") && !obj.contains("NaN"));
}

// ---- (a) arbitrary text ----

/// Text drawn mostly from the characters VSG uses, so the parser gets past the first token.
fn vsg_like_text() -> impl Strategy<Value = String> {
    prop_oneof![
        "[ a-zA-Z0-9_(){}\\[\\],;:.~=+\\-*/%<>!&|\"\n]{0,160}",
        any::<String>(),
        proptest::collection::vec(any::<u8>(), 0..160)
            .prop_map(|b| String::from_utf8_lossy(&b).into_owned()),
    ]
}

proptest! {
    #![proptest_config(config(500))]

    #[test]
    fn any_text_parses_or_fails_inside_itself(src in vsg_like_text()) {
        match vsg::parse::parse(&src) {
            Ok(_) => {}
            Err(ds) => {
                prop_assert!(!ds.is_empty());
                for d in &ds {
                    prop_assert!(d.span.start <= d.span.end && d.span.end <= src.len(),
                        "{:?} in {} bytes: {}", d.span, src.len(), d.message);
                    d.render("f.vsg", &src);
                }
            }
        }
        check("f.vsg", &src, vsg::run(&src, &options(1)));
    }
}

// ---- (b) generated programs ----

/// A literal: mostly ordinary, sometimes extreme (huge, tiny, zero, any finite value).
fn number() -> impl Strategy<Value = String> {
    prop_oneof![
        12 => (1u32..12).prop_map(|n| n.to_string()),
        6 => select(vec!["0.5", "0.25", "2.5", "0.1", "1.5"]).prop_map(String::from),
        1 => extreme(),
    ]
}

fn extreme() -> BoxedStrategy<String> {
    prop_oneof![
        select(vec![
            "1e308", "1e-308", "1e39", "1e7", "1e-9", "0", "1e6", "3e-5", "9e6"
        ])
        .prop_map(String::from),
        any::<f64>()
            .prop_filter("finite", |v| v.is_finite())
            .prop_map(|v| format!("{:e}", v.abs())),
    ]
    .boxed()
}

/// An expression: mostly tame arithmetic on literals, declared floats and shape attributes;
/// one in about 25 wild (`0/0`, `1e308*10`, out-of-range indices, `pow` of anything).
fn expr() -> impl Strategy<Value = String> {
    let leaf = prop_oneof![
        3 => number(),
        1 => select(vec!["sx", "sy", "sz", "px", "index", "depth", "v0", "v1", "PI", "a[0]"])
            .prop_map(String::from),
    ];
    let tame = leaf.prop_recursive(2, 6, 2, |inner| {
        prop_oneof![
            (inner.clone(), select(vec!["+", "*", "/"]), number())
                .prop_map(|(a, o, b)| format!("({a} {o} {b})")),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("({a} - {b})")),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("rand({a}, {b})")),
            (select(vec!["abs", "floor", "sin", "max"]), inner)
                .prop_map(|(f, a)| format!("{f}({a})")),
        ]
    });
    let wild = prop_oneof![
        extreme(),
        select(vec![
            "0/0",
            "1e308*10",
            "(1 % 0)",
            "sqrt(-1)",
            "ln(0)",
            "a[7]",
            "-1e308 - 1e308"
        ])
        .prop_map(String::from),
        (
            tame.clone(),
            select(vec!["%", "<", ">=", "&&", "||", "*1e308+"]),
            tame.clone()
        )
            .prop_map(|(a, o, b)| format!("({a} {o} {b})")),
        (
            select(vec!["pow", "rand", "atan2"]),
            tame.clone(),
            tame.clone()
        )
            .prop_map(|(f, a, b)| format!("{f}({a}, {b})")),
        tame.clone().prop_map(|a| format!("-{a}")),
        (
            select(vec!["sqrt", "exp", "ln", "tan", "asin"]),
            tame.clone()
        )
            .prop_map(|(f, a)| format!("{f}({a})")),
    ];
    prop_oneof![25 => tame, 1 => wild]
}

fn list(n: std::ops::Range<usize>) -> impl Strategy<Value = Vec<String>> {
    proptest::collection::vec(expr(), n)
}

const SYMBOLS: [&str; 4] = ["s0", "s1", "s2", "s3"];

fn successors(n: usize) -> impl Strategy<Value = String> {
    proptest::collection::vec(select(vec!["s0", "s1", "s2", "s3", "j3d.terminal"]), n)
        .prop_map(|v| v.join(", "))
}

fn transform() -> impl Strategy<Value = String> {
    (select(vec!["T", "R"]), list(3..4)).prop_map(|(f, e)| format!("{f}({})", e.join(", ")))
}

fn instantiate() -> impl Strategy<Value = String> {
    let simple = select(vec![ShapeType::Box, ShapeType::Cylinder, ShapeType::Sphere]);
    let any_type = select(ShapeType::ALL.to_vec());
    (prop_oneof![3 => simple, 1 => any_type], any::<bool>()).prop_flat_map(|(t, tame)| {
        let (lo, hi) = (t.required_params(), t.param_names().len());
        // Ordinary sizes mostly, so most shapes are valid and production goes on.
        let param = if tame {
            number().boxed()
        } else {
            expr().boxed()
        };
        (
            proptest::option::of(transform()),
            proptest::collection::vec(param, lo..hi + 1),
        )
            .prop_map(move |(tr, params)| {
                format!(
                    "{}I(\"{}\", {{{}}})",
                    tr.unwrap_or_default(),
                    t.name(),
                    params.join(", ")
                )
            })
    })
}

/// A rule body (functions and successors) of one of the three geometries.
fn body() -> impl Strategy<Value = String> {
    // Relative lengths mostly: absolute ones rarely add up to the extent.
    let length = (proptest::bool::weighted(0.8), expr())
        .prop_map(|(rel, e)| if rel { format!("~{e}") } else { e });
    let lengths = proptest::collection::vec(length, 1..4);
    let axis = select(vec!["X", "Y", "Z", "R", "Theta", "Phi"]);
    let keep = (
        proptest::collection::vec(transform(), 0..3),
        any::<bool>(),
        1usize..3,
    )
        .prop_flat_map(|(ts, void, n)| {
            successors(n).prop_map(move |s| {
                format!(
                    "{}{}{{{s}}}",
                    ts.join(" "),
                    if void { " void()" } else { "" }
                )
            })
        });
    let shapes =
        (proptest::collection::vec(instantiate(), 1..3), 0u8..6).prop_flat_map(|(is, boolean)| {
            let n = is.len();
            let combine = match boolean {
                0 if n > 1 => Some("union()"),
                1 if n > 1 => Some("difference()"),
                _ => None,
            };
            // A unique shape is terminal (§7.1.2): its successor is j3d.terminal.
            let s = match combine {
                Some(_) => Just("j3d.terminal".to_string()).boxed(),
                None => successors(n).boxed(),
            };
            s.prop_map(move |s| format!("{} {}{{{s}}}", is.join(" "), combine.unwrap_or("")))
        });
    let divide = (
        select(vec!["split", "repeat"]),
        axis,
        lengths,
        proptest::option::of(expr()),
    )
        .prop_flat_map(|(f, a, ls, offset)| {
            let n = ls.len();
            let offset = match (f, offset) {
                ("repeat", Some(o)) => format!(", {o}"),
                _ => String::new(),
            };
            successors(n)
                .prop_map(move |s| format!("{f}(\"{a}\", {{{}}}{offset}){{{s}}}", ls.join(", ")))
        });
    let component = prop_oneof![
        6 => select(vec!["0.2", "0.5", "1", "0"]).prop_map(String::from),
        1 => expr(),
    ];
    let colour = proptest::collection::vec(component, 3)
        .prop_map(|c| format!("appearance(\"color\", {{{}}}) ", c.join(", ")));
    (
        proptest::option::of(colour),
        prop_oneof![2 => keep, 3 => shapes, 3 => divide],
    )
        .prop_map(|(c, b)| format!("{}{b}", c.unwrap_or_default()))
}

/// The start rule instantiates, so the others have a shape to work on.
fn axiom() -> impl Strategy<Value = String> {
    (instantiate(), successors(1)).prop_map(|(i, s)| format!("Axiom :: {i}{{{s}}};"))
}

fn rule(symbol: &'static str) -> impl Strategy<Value = String> {
    let condition = prop_oneof![
        3 => (select(vec!["sx", "sy", "depth", "index", "v0"]), select(vec!["<", ">", ">="]), number())
            .prop_map(|(a, c, n)| format!("{a} {c} {n}")),
        1 => expr(),
    ];
    let probability = prop_oneof![
        3 => select(vec!["0.5", "0.3", "1", "0", "0.99"]).prop_map(String::from),
        1 => expr(),
    ];
    (
        proptest::option::weighted(0.3, condition),
        body(),
        proptest::option::weighted(0.3, probability),
    )
        .prop_map(move |(condition, body, probability)| {
            let head = match condition {
                Some(c) => format!("{symbol} : {c} :"),
                None => format!("{symbol} ::"),
            };
            let tail = probability.map(|p| format!(" : {p}")).unwrap_or_default();
            format!("{head} {body}{tail};")
        })
}

fn program() -> impl Strategy<Value = String> {
    let rules = SYMBOLS.map(|s| proptest::collection::vec(rule(s), 1..3));
    // Declarations are evaluated before any shape exists: numbers only.
    let numbers = |n| proptest::collection::vec(number(), n);
    (numbers(2..3), numbers(1..4), axiom(), rules).prop_map(|(vars, array, axiom, rules)| {
        let mut src = format!(
            "float v0 = {};\nfloat v1 = {};\nfloat [] a = {{{}}};\n",
            vars[0],
            vars[1],
            array.join(", ")
        );
        src += &axiom;
        src.push('\n');
        for r in rules.iter().flatten() {
            src += r;
            src.push('\n');
        }
        src
    })
}

proptest! {
    #![proptest_config(config(400))]

    #[test]
    fn generated_programs_fail_cleanly_or_export_finite_models(src in program(), seed in 0u64..4) {
        check("g.vsg", &src, vsg::run(&src, &options(seed)));
    }
}

// ---- (c) mutations of the shipped programs ----

fn root() -> &'static Path {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

/// Every shipped program by file name: `examples/*.vsg` and `library/*.vsg`.
fn shipped() -> Vec<(String, String)> {
    let mut out = Vec::new();
    for dir in ["examples", "library"] {
        let mut files: Vec<_> = std::fs::read_dir(root().join(dir))
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|e| e == "vsg"))
            .collect();
        files.sort();
        for f in files {
            let name = f.file_name().unwrap().to_string_lossy().into_owned();
            out.push((name, std::fs::read_to_string(&f).unwrap()));
        }
    }
    out
}

/// The library, for imports of the mutated programs.
struct Library(HashMap<String, String>);

impl Resolver for Library {
    fn load(&mut self, _from: &str, path: &str) -> Result<(String, String), String> {
        let name = path.rsplit('/').next().unwrap_or(path);
        self.0
            .get(name)
            .map(|t| (name.to_string(), t.clone()))
            .ok_or_else(|| format!("no file {path}"))
    }
}

#[derive(Clone, Debug)]
enum Mutation {
    DeleteByte(usize),
    DeleteToken(usize),
    DuplicateToken(usize),
    /// Token `.0` replaced by token `.1`.
    ReplaceToken(usize, usize),
    InsertText(usize, String),
}

/// Byte ranges of the file's tokens: runs of word characters, or single other characters.
fn tokens(src: &str) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut chars = src.char_indices().peekable();
    while let Some((at, c)) = chars.next() {
        if c.is_whitespace() {
            continue;
        }
        let mut end = at + c.len_utf8();
        if c.is_alphanumeric() || c == '_' || c == '.' {
            while let Some(&(next, d)) = chars.peek() {
                if !(d.is_alphanumeric() || d == '_' || d == '.') {
                    break;
                }
                end = next + d.len_utf8();
                chars.next();
            }
        }
        out.push((at, end));
    }
    out
}

/// The char boundary at or before byte `at` (`str::floor_char_boundary` needs Rust 1.91).
fn floor(src: &str, mut at: usize) -> usize {
    while !src.is_char_boundary(at) {
        at -= 1;
    }
    at
}

fn apply(src: &str, m: &Mutation) -> String {
    let toks = tokens(src);
    let tok = |i: usize| toks[i % toks.len()];
    let mut out = src.to_string();
    match m {
        Mutation::DeleteByte(i) => {
            let at = floor(src, i % src.len());
            out.remove(at);
        }
        Mutation::DeleteToken(i) => {
            let (a, b) = tok(*i);
            out.replace_range(a..b, "");
        }
        Mutation::DuplicateToken(i) => {
            let (a, b) = tok(*i);
            out.insert_str(b, &format!(" {}", &src[a..b]));
        }
        Mutation::ReplaceToken(i, j) => {
            let (a, b) = tok(*i);
            let (c, d) = tok(*j);
            out.replace_range(a..b, &src[c..d]);
        }
        Mutation::InsertText(i, t) => {
            let at = floor(src, i % src.len());
            out.insert_str(at, t);
        }
    }
    out
}

fn mutation() -> impl Strategy<Value = Mutation> {
    let at = any::<usize>();
    prop_oneof![
        at.prop_map(Mutation::DeleteByte),
        at.prop_map(Mutation::DeleteToken),
        at.prop_map(Mutation::DuplicateToken),
        (at, any::<usize>()).prop_map(|(i, j)| Mutation::ReplaceToken(i, j)),
        (
            at,
            select(vec![
                "1e308",
                "0/0",
                "-",
                "{",
                "}",
                "(",
                ";",
                "~",
                "*1e39",
                "\u{FEFF}",
                "é",
                "\"",
                "1e-308",
                "import \"keep.vsg\" as k;",
                "//",
                "\n"
            ])
        )
            .prop_map(|(i, t)| Mutation::InsertText(i, t.to_string())),
    ]
}

proptest! {
    #![proptest_config(config(300))]

    #[test]
    fn mutated_shipped_programs_never_panic(
        file in any::<usize>(),
        mutations in proptest::collection::vec(mutation(), 1..4),
    ) {
        let programs = shipped();
        let library = Library(programs.iter().cloned().collect());
        let (name, text) = &programs[file % programs.len()];
        let mut src = text.clone();
        for m in &mutations {
            if !src.is_empty() {
                src = apply(&src, m);
            }
        }
        let mut resolver = library;
        check(name, &src, vsg::run_with(name, &src, &options(1), &mut resolver));
    }
}

#[test]
fn the_shipped_programs_are_found_and_unmutated_run() {
    let programs = shipped();
    assert!(programs.len() >= 10, "{}", programs.len());
    let library = Library(programs.iter().cloned().collect());
    for (name, src) in &programs {
        let mut resolver = Library(library.0.clone());
        let options = RunOptions {
            limits: Limits {
                tessellation: Tessellation { segments: 8 },
                ..Limits::default()
            },
            ..Default::default()
        };
        let result = vsg::run_with(name, src, &options, &mut resolver);
        assert!(
            result.is_ok(),
            "{name}: {}",
            result.err().unwrap().render(name, src)
        );
    }
}

// ---- regressions found by the properties ----

/// The generator is not vacuous: a fair share of its programs produce models with terminals,
/// so property (b) checks exports, not only errors.
#[test]
fn generated_programs_often_produce_models() {
    use proptest::strategy::ValueTree;
    let mut runner = proptest::test_runner::TestRunner::deterministic();
    let (mut models, mut errors) = (0, HashMap::<String, usize>::new());
    for _ in 0..200 {
        let src = program().new_tree(&mut runner).unwrap().current();
        match vsg::run(&src, &options(1)) {
            Ok(m) if m.terminals().count() > 0 => models += 1,
            Ok(_) => {}
            Err(e) => {
                let text = e.render("g.vsg", &src);
                let first = text
                    .lines()
                    .next()
                    .unwrap_or("")
                    .splitn(4, ':')
                    .nth(3)
                    .unwrap_or("")
                    .chars()
                    .take(40)
                    .collect();
                *errors.entry(first).or_default() += 1;
            }
        }
    }
    let mut top: Vec<_> = errors.into_iter().collect();
    top.sort_by_key(|e| std::cmp::Reverse(e.1));
    eprintln!(
        "{models} models of 200; errors: {:?}",
        &top[..top.len().min(12)]
    );
    assert!(models >= 20, "{models} models of 200");
}
