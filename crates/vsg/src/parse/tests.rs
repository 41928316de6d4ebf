use super::parse;
use crate::ast::*;

const RULES_7_1: &str = include_str!("../../../../examples/rules_7_1.vsg");
const RULES_7_3: &str = include_str!("../../../../examples/rules_7_3.vsg");

fn ok(src: &str) -> Program {
    match parse(src) {
        Ok(p) => p,
        Err(es) => panic!("{src:?} failed: {}", es[0].render("t.vsg", src)),
    }
}

fn rules(p: &Program) -> Vec<&Rule> {
    p.items
        .iter()
        .filter_map(|i| if let Item::Rule(r) = i { Some(r) } else { None })
        .collect()
}

fn decls(p: &Program) -> Vec<&Decl> {
    p.items
        .iter()
        .filter_map(|i| if let Item::Decl(d) = i { Some(d) } else { None })
        .collect()
}

fn rule<'p>(p: &'p Program, name: &str) -> &'p Rule {
    rules(p)
        .into_iter()
        .find(|r| r.predecessor.name == name)
        .unwrap()
}

fn only_rule(src: &str) -> Rule {
    let p = ok(src);
    assert_eq!(p.items.len(), 1, "{src}");
    rules(&p)[0].clone()
}

/// The first error as `(line, column, message)`.
fn err(src: &str) -> (usize, usize, String) {
    let es = parse(src).expect_err(src);
    let (line, col) = es[0].line_col(src);
    (line, col, es[0].message.clone())
}

/// The expression of `float x = <src>;`.
fn ex(src: &str) -> Expr {
    let p = ok(&format!("float x = {src};"));
    match &decls(&p)[0].value {
        DeclValue::Scalar(e) => e.clone(),
        v => panic!("{v:?}"),
    }
}

/// A compact prefix form of an expression, for precedence checks.
fn show(e: &Expr) -> String {
    match e {
        Expr::Number(n, _) => format!("{n}"),
        Expr::Bool(b, _) => format!("{b}"),
        Expr::Var(id) => id.name.clone(),
        Expr::Index { array, index, .. } => format!("{}[{}]", array.name, show(index)),
        Expr::Unary { op, operand, .. } => format!("({op:?} {})", show(operand)),
        Expr::Binary { op, lhs, rhs, .. } => format!("({op:?} {} {})", show(lhs), show(rhs)),
        Expr::Call { function, args, .. } => {
            let args: Vec<String> = args.iter().map(show).collect();
            format!("{}({})", function.name, args.join(","))
        }
    }
}

fn symbols(r: &Rule) -> Vec<String> {
    r.successors
        .iter()
        .map(|s| match s {
            Successor::Symbol(id) => id.name.clone(),
            Successor::Terminal(_) => "<terminal>".into(),
        })
        .collect()
}

#[test]
fn rules_7_1_parse_to_14_rules_and_no_declarations() {
    let p = ok(RULES_7_1);
    assert_eq!(rules(&p).len(), 14);
    assert!(decls(&p).is_empty());
    let b = rule(&p, "building");
    assert_eq!(symbols(b), ["wallN", "midBuilding", "walls"]);
    assert!(b.condition.is_none() && b.probability.is_none());
}

#[test]
fn rules_7_3_parse_to_12_declarations_and_20_rules() {
    // The listing has 12 `float []` lines and 20 `::` rules (Axiom, 3 for tower1, 13 for the
    // keep, 3 for tower2).
    let p = ok(RULES_7_3);
    assert_eq!(decls(&p).len(), 12);
    assert_eq!(rules(&p).len(), 20);
    let k1p = decls(&p)
        .into_iter()
        .find(|d| d.name.name == "k1P")
        .unwrap();
    let DeclValue::Array(values) = &k1p.value else {
        panic!("{k1p:?}")
    };
    assert_eq!(
        values.iter().map(show).collect::<Vec<_>>(),
        ["420", "87.5", "335"]
    );
}

#[test]
fn mid_wall_s_in_7_1_is_a_repeat_along_x_with_offset() {
    let p = ok(RULES_7_1);
    let r = rule(&p, "midWallS");
    let [
        Op {
            kind:
                OpKind::Repeat {
                    axis,
                    lengths,
                    offset,
                },
            ..
        },
    ] = r.ops.as_slice()
    else {
        panic!("{r:?}")
    };
    assert_eq!(axis.name, "X");
    assert_eq!(lengths.len(), 2);
    assert!(lengths.iter().all(|l| !l.relative));
    assert!(matches!(offset, Some(Expr::Number(n, _)) if *n == 0.5));
    assert_eq!(symbols(r), ["window", "brickWall"]);
}

#[test]
fn axiom_in_7_3_has_nine_ops_and_three_successors() {
    let p = ok(RULES_7_3);
    let r = rule(&p, "Axiom");
    let kinds: String = r
        .ops
        .iter()
        .map(|o| match &o.kind {
            OpKind::Translate(_) => 'T',
            OpKind::Rotate(_) => 'R',
            OpKind::Instantiate { .. } => 'I',
            _ => '?',
        })
        .collect();
    assert_eq!(kinds, "TRITRITRI");
    assert_eq!(symbols(r), ["tower1", "keep1", "tower2"]);
    // `k1P\n    [0]`: indexing across a line break.
    let OpKind::Translate(t) = &r.ops[3].kind else {
        panic!()
    };
    assert_eq!(
        t.iter().map(show).collect::<Vec<_>>(),
        ["k1P[0]", "k1P[1]", "k1P[2]"]
    );
    let OpKind::Instantiate { shape_type, params } = &r.ops[5].kind else {
        panic!()
    };
    assert_eq!(shape_type.value, "box");
    assert_eq!(params.len(), 3);
    let OpKind::Split { lengths, .. } = &rule(&p, "keep1FloorMid").ops[0].kind else {
        panic!()
    };
    assert_eq!(
        show(&lengths[2].expr),
        "(Sub (Sub k1FlPar[1] k1WinVer[2]) k1WinVer[3])"
    );
}

#[test]
fn window_in_7_1_sets_colour_list_and_transparency() {
    let p = ok(RULES_7_1);
    let r = rule(&p, "window");
    assert_eq!(r.ops.len(), 1);
    let OpKind::Appearance(pairs) = &r.ops[0].kind else {
        panic!("{r:?}")
    };
    assert_eq!(pairs.len(), 2);
    assert_eq!(pairs[0].0.value, "color");
    assert!(matches!(&pairs[0].1, AppearanceValue::List(l) if l.len() == 3));
    assert_eq!(pairs[1].0.value, "transparency");
    assert!(matches!(&pairs[1].1, AppearanceValue::Scalar(Expr::Number(n, _)) if *n == 0.5));
    assert!(matches!(r.successors.as_slice(), [Successor::Terminal(_)]));
}

#[test]
fn other_ops_and_successors() {
    let r = only_rule(
        "a::void()split(Y,{1,~2,~1})I(\"box\",{})appearance(\"texture\",\"b.png\"){terminal, j3d.terminal, s_1};",
    );
    assert!(matches!(r.ops[0].kind, OpKind::Void));
    let OpKind::Split { axis, lengths } = &r.ops[1].kind else {
        panic!()
    };
    assert_eq!(axis.name, "Y");
    assert_eq!(
        lengths.iter().map(|l| l.relative).collect::<Vec<_>>(),
        [false, true, true]
    );
    assert!(matches!(&r.ops[2].kind, OpKind::Instantiate { params, .. } if params.is_empty()));
    let OpKind::Appearance(pairs) = &r.ops[3].kind else {
        panic!()
    };
    assert!(matches!(&pairs[0].1, AppearanceValue::Text(s) if s.value == "b.png"));
    assert_eq!(symbols(&r), ["<terminal>", "<terminal>", "s_1"]);
    let r = only_rule("a::repeat(\"Z\",{~1}){b};");
    assert!(
        matches!(&r.ops[0].kind, OpKind::Repeat { offset: None, lengths, .. } if lengths[0].relative)
    );
}

#[test]
fn spans_cover_rules_declarations_and_nodes() {
    let src = "float y = 2;\n  wallN :: T(1, 2, 3) {j3d.terminal} ; ";
    let p = ok(src);
    let d = decls(&p)[0];
    assert_eq!(&src[d.span.start..d.span.end], "float y = 2;");
    let r = rules(&p)[0];
    let text = |s: Span| &src[s.start..s.end];
    assert_eq!(text(r.span), "wallN :: T(1, 2, 3) {j3d.terminal} ;");
    assert_eq!(text(r.predecessor.span), "wallN");
    assert_eq!(&src[r.ops[0].span.start..r.ops[0].span.end], "T(1, 2, 3)");
    let Successor::Terminal(t) = r.successors[0] else {
        panic!()
    };
    assert_eq!(&src[t.start..t.end], "j3d.terminal");
    let p = ok("float[] w = {};");
    assert!(matches!(&decls(&p)[0].value, DeclValue::Array(v) if v.is_empty()));
    let e = ex("a[i] + f(1, 2)");
    assert_eq!(e.span(), Span::new(10, 24));
}

#[test]
fn operator_precedence_and_associativity() {
    let cases = [
        ("1+2*3", "(Add 1 (Mul 2 3))"),
        ("-2*3", "(Mul (Neg 2) 3)"),
        ("a<b&&c", "(And (Lt a b) c)"),
        ("1-2-3", "(Sub (Sub 1 2) 3)"),
        ("8/4%3*2", "(Mul (Rem (Div 8 4) 3) 2)"),
        ("a||b&&c", "(Or a (And b c))"),
        ("a==b!=c", "(Ne (Eq a b) c)"),
        ("1+2<=3-4", "(Le (Add 1 2) (Sub 3 4))"),
        ("!a>=b", "(Ge (Not a) b)"),
        ("--x", "(Neg (Neg x))"),
        ("(1+2)*3", "(Mul (Add 1 2) 3)"),
        (
            "max(a[1+1], sin(0.5)) > 2",
            "(Gt max(a[(Add 1 1)],sin(0.5)) 2)",
        ),
        ("true && !false", "(And true (Not false))"),
    ];
    for (src, want) in cases {
        assert_eq!(show(&ex(src)), want, "{src}");
    }
}

#[test]
fn number_forms() {
    for (src, want) in [
        ("12", 12.0),
        ("0.5", 0.5),
        (".5", 0.5),
        ("1e-3", 0.001),
        ("2.", 2.0),
        ("2.5E2", 250.0),
    ] {
        assert!(matches!(ex(src), Expr::Number(n, _) if n == want), "{src}");
    }
}

#[test]
fn conditions_and_probabilities() {
    let r = only_rule("a : h > 2 && !done : {b};");
    assert_eq!(
        show(r.condition.as_ref().unwrap()),
        "(And (Gt h 2) (Not done))"
    );
    assert!(r.probability.is_none());
    let r = only_rule("a : 1 : T(0,0,0){b} : 0.25 ;");
    assert!(r.condition.is_some());
    assert!(matches!(r.probability, Some(Expr::Number(n, _)) if n == 0.25));
    let r = only_rule("a :: {b, c} : p * 2;");
    assert!(r.condition.is_none());
    assert_eq!(show(r.probability.as_ref().unwrap()), "(Mul p 2)");
}

#[test]
fn comments_and_line_breaks_everywhere() {
    let src = "// head\nfloat // a\n [ // b\n ] // c\n v // d\n = { 1 , // e\n 2 } ; // f\n\
               a // g\n : // h\n v // i\n [0] > 1 : split // j\n ( X , { ~ 1 } ) // k\n\
               { b // l\n , c } : 0.5 // m\n ; // tail";
    let p = ok(src);
    assert_eq!(decls(&p).len(), 1);
    let r = rules(&p)[0];
    assert_eq!(show(r.condition.as_ref().unwrap()), "(Gt v[0] 1)");
    assert_eq!(symbols(r), ["b", "c"]);
    assert!(ok("").items.is_empty());
    assert!(ok("  // only a comment").items.is_empty());
}

#[test]
fn empty_list_braces_and_comma_errors_point_at_the_token() {
    assert_eq!(
        err("Axiom::I(\"box\",{1,2,,3}){a};"),
        (1, 21, "expected expression, found ','".into())
    );
    assert_eq!(
        err("a::{b;"),
        (1, 6, "expected ',', '.' or '}', found ';'".into())
    );
    assert_eq!(
        err("a::{};"),
        (1, 5, "expected symbol name, found '}'".into())
    );
    assert_eq!(
        err("a::split(X,{1 2}){b};"),
        (1, 15, "expected ',', '}' or operator, found '2'".into())
    );
    assert_eq!(
        err("float x = ;"),
        (1, 11, "expected expression, found ';'".into())
    );
    assert_eq!(
        err(")"),
        (
            1,
            1,
            "expected declaration, import or rule, found ')'".into()
        )
    );
    assert_eq!(
        err("a::{j3d.foo};"),
        (1, 9, "expected 'terminal', found 'foo'".into())
    );
}

#[test]
fn missing_semicolon_points_at_the_next_token() {
    assert_eq!(
        err("a::{b}\nc::{d};"),
        (2, 1, "expected ':' or ';', found 'c'".into())
    );
    assert_eq!(
        err("a::{b}\n"),
        (2, 1, "expected ':' or ';', found end of input".into())
    );
    assert_eq!(
        err("float [] v = {1}\n"),
        (2, 1, "expected ';', found end of input".into())
    );
}

#[test]
fn lexical_errors() {
    assert_eq!(
        err("a::I(\"box,{1}){b};"),
        (1, 6, "unterminated string literal".into())
    );
    assert_eq!(
        err("a::{b};\n  c::@{d};"),
        (2, 6, "unexpected character '@'".into())
    );
    assert_eq!(
        err("a : x & y : {b};"),
        (1, 7, "unexpected character '&'".into())
    );
}

#[test]
fn unknown_functions_wrong_arity_and_wrong_arguments() {
    let unknown = "unknown function 'divide'; expected one of T, R, I, split, repeat, appearance, void, union, intersection, difference";
    assert_eq!(err("a::\n  divide(\"X\",{1}){b};"), (2, 3, unknown.into()));
    assert_eq!(
        err("a::T(1,2){c};"),
        (1, 4, "T takes 3 arguments, found 2".into())
    );
    assert_eq!(
        err("a::R(1,2,3,4){c};"),
        (1, 4, "R takes 3 arguments, found 4".into())
    );
    assert_eq!(
        err("a::void(1){c};"),
        (1, 4, "void takes 0 arguments, found 1".into())
    );
    assert_eq!(
        err("a::split(X){c};"),
        (1, 4, "split takes 2 arguments, found 1".into())
    );
    assert_eq!(
        err("a::repeat(X,{1},2,3){c};"),
        (1, 4, "repeat takes 2 or 3 arguments, found 4".into())
    );
    let (l, c, m) = err("a::appearance(\"color\"){c};");
    assert_eq!((l, c), (1, 4));
    assert!(m.starts_with("appearance takes pairs"), "{m}");
    let (l, c, m) = err("a::I(box,{1}){c};");
    assert_eq!(
        (l, c, m.as_str()),
        (
            1,
            6,
            "argument 1 of I must be a string such as \"box\", found an expression"
        )
    );
    let (l, c, m) = err("a::split(X, 3){c};");
    assert_eq!((l, c), (1, 13));
    assert!(m.contains("must be a list"), "{m}");
    let (l, c, m) = err("a::split(1+2, {3}){c};");
    assert_eq!((l, c), (1, 10));
    assert!(m.contains("direction"), "{m}");
    let (_, c, m) = err("a::appearance(\"c\",{1,~2}){c};");
    assert_eq!(c, 22);
    assert!(m.contains("'~'"), "{m}");
}

#[test]
fn several_errors_are_reported_in_order() {
    let src = "a::{b;\nfloat x = 1;\nc::T(1,2){d};\ne::{f,,g};\nh::divide(){i};\nj::{k};";
    let es = parse(src).unwrap_err();
    let at: Vec<_> = es.iter().map(|e| e.line_col(src).0).collect();
    assert_eq!(at, [1, 3, 4, 5], "{es:?}");
    assert!(es[2].message.contains("found ','"));
}

#[test]
fn diagnostics_render_with_file_line_and_column() {
    let src = "a::{b};\nc::T(1,2){d};";
    let es = parse(src).unwrap_err();
    let text = es[0].render("p.vsg", src);
    assert!(
        text.starts_with("p.vsg:2:4: T takes 3 arguments, found 2"),
        "{text}"
    );
    assert!(text.contains("c::T(1,2){d};"), "{text}");
}

/// `Debug` output with every `Span { .. }` blanked out.
fn without_spans(p: &Program) -> String {
    let text = format!("{p:?}");
    let mut out = String::new();
    let mut rest = text.as_str();
    while let Some(i) = rest.find("Span { start: ") {
        out.push_str(&rest[..i]);
        let end = rest[i..].find('}').unwrap();
        rest = &rest[i + end + 1..];
    }
    out + rest
}

#[test]
fn random_blanks_and_comments_between_tokens_do_not_change_the_tree() {
    use chumsky::Parser;
    let tokens = super::lexer::lexer()
        .parse(RULES_7_1)
        .into_output()
        .unwrap();
    let want = without_spans(&ok(RULES_7_1));
    let fillers = [
        " ",
        "\n",
        "\t",
        "  \n\n ",
        " // note {;}\n",
        "// x\n   ",
        "\r\n",
    ];
    let mut seed: u64 = 0x5eed_0701;
    let mut next = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    };
    for _ in 0..40 {
        let mut src = String::new();
        for (_, s) in &tokens {
            src.push_str(&RULES_7_1[s.start..s.end]);
            if next() % 3 == 0 {
                src.push_str(fillers[(next() % fillers.len() as u64) as usize]);
            } else {
                // Tokens keep at least the separation they had.
                src.push(' ');
            }
        }
        assert_eq!(without_spans(&ok(&src)), want, "{src}");
    }
}
