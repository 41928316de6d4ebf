//! Bad programs give one clear message each, at the right line, and runaway grammars stop at the
//! configured limits.

use vsg::{Limits, RunOptions};

fn error_of(src: &str, options: &RunOptions) -> String {
    match vsg::run(src, options) {
        Ok(_) => panic!("expected an error for:\n{src}"),
        Err(e) => e.render("p.vsg", src),
    }
}

fn error(src: &str) -> String {
    error_of(src, &RunOptions::default())
}

#[test]
fn syntax_error_names_line_and_column() {
    let e = error("Axiom::I(\"box\",{1,2,3}){a};\na::split(\"X\",{0.5,,0.5}){b,c};\n");
    assert!(e.starts_with("p.vsg:2:19:"), "{e}");
}

#[test]
fn unknown_shape_type() {
    let e = error("Axiom::I(\"pyramid\",{1,2,3}){a};\na::{j3d.terminal};");
    assert!(
        e.starts_with("p.vsg:1:10: unknown shape type \"pyramid\""),
        "{e}"
    );
}

#[test]
fn wrong_parameter_count() {
    let e = error("Axiom::I(\"cylinder\",{1,2,3}){a};\na::{j3d.terminal};");
    assert!(
        e.contains("p.vsg:1:8: cylinder takes 2 parameters (radius, height), found 3"),
        "{e}"
    );
}

#[test]
fn symbol_without_rule() {
    let e = error("Axiom::I(\"box\",{1,2,3}){building};");
    assert!(
        e.contains("p.vsg:1:25: symbol 'building' has no rule"),
        "{e}"
    );
}

#[test]
fn missing_axiom() {
    assert!(error("a::{j3d.terminal};").contains("no rule for the start symbol Axiom"));
}

#[test]
fn negative_size() {
    let e = error("Axiom::I(\"box\",{1,-2,3}){a};\na::{j3d.terminal};");
    assert!(
        e.contains("p.vsg:1:8: box parameter height = -2 is invalid"),
        "{e}"
    );
}

#[test]
fn non_finite_size() {
    let e = error("float h = 0;\nAxiom::I(\"box\",{1,1/h,3}){a};\na::{j3d.terminal};");
    assert!(e.contains("p.vsg:2:19: division by zero"), "{e}");
    let e = error("Axiom::I(\"sphere\",{pow(10, 400)}){a};\na::{j3d.terminal};");
    assert!(e.contains("not a finite number"), "{e}");
}

#[test]
fn lengths_that_do_not_fit_name_the_rule_line() {
    let e = error(
        "Axiom::I(\"box\",{6,1,1}){a};\na::split(\"X\",{1,3}){b,c};\nb::{j3d.terminal};\nc::{j3d.terminal};",
    );
    assert!(
        e.starts_with("p.vsg:2:4: split lengths along X add up to 4"),
        "{e}"
    );
}

#[test]
fn split_the_shape_does_not_allow() {
    let e = error(
        "Axiom::I(\"box\",{6,1,1}){a};\na::split(\"R\",{1,2}){b,c};\nb::{j3d.terminal};\nc::{j3d.terminal};",
    );
    assert!(e.contains("p.vsg:2:4: box cannot be split along R"), "{e}");
}

#[test]
fn successor_count_must_match() {
    let e = error(
        "Axiom::I(\"box\",{6,1,1}){a};\na::split(\"X\",{1,2,3}){b,c};\nb::{j3d.terminal};\nc::{j3d.terminal};",
    );
    assert!(e.contains("p.vsg:2:"), "{e}");
    assert!(e.contains("3 split lengths but 2 successors"), "{e}");
}

#[test]
fn runaway_recursion_stops_at_the_depth_limit() {
    let src = "Axiom::I(\"box\",{1,1,1}){A};\nA::repeat(\"X\",{1}){A};";
    let options = RunOptions {
        limits: Limits {
            max_depth: 50,
            max_shapes: 1_000_000,
            ..Default::default()
        },
        ..Default::default()
    };
    let e = error_of(src, &options);
    assert!(
        e.contains("p.vsg:2:1: production went deeper than 50 levels at 'A'"),
        "{e}"
    );
}

#[test]
fn runaway_growth_stops_at_the_shape_limit() {
    // A finite but huge tree: ten children per level down to depth 6 is a million shapes.
    let src = "Axiom::I(\"box\",{1,1,1}){A};\n\
               A : depth < 6 : I(\"box\",{1,1,1})I(\"box\",{1,1,1})I(\"box\",{1,1,1})I(\"box\",{1,1,1})I(\"box\",{1,1,1})\
               I(\"box\",{1,1,1})I(\"box\",{1,1,1})I(\"box\",{1,1,1})I(\"box\",{1,1,1})I(\"box\",{1,1,1}){A,A,A,A,A,A,A,A,A,A};\n\
               A : depth >= 6 : {j3d.terminal};";
    let options = RunOptions {
        limits: Limits {
            max_depth: 1000,
            max_shapes: 100_000,
            ..Default::default()
        },
        ..Default::default()
    };
    let e = error_of(src, &options);
    assert!(
        e.contains("p.vsg:2:1: production exceeded 100000 shapes"),
        "{e}"
    );
}

#[test]
fn runaway_repeat_is_refused_before_it_allocates() {
    let src = "Axiom::I(\"box\",{1,1,1}){A};\nA::repeat(\"X\",{1e-9}){B};\nB::{j3d.terminal};";
    let e = error(src);
    assert!(
        e.contains("p.vsg:2:4: repeat would create 1000000002 shapes, more than the limit"),
        "{e}"
    );
}

#[test]
fn the_issue_example_of_a_runaway_grammar_is_an_error() {
    let e = error("Axiom::I(\"box\",{1,1,1}){A};\nA::split(\"X\",{0.5,0.5}){A,A};");
    assert!(e.contains("p.vsg:2:"), "{e}");
}

#[test]
fn unknown_override_lists_the_declared_floats() {
    let src = "float h = 2;\nAxiom::I(\"box\",{1,h,1}){a};\na::{j3d.terminal};";
    let options = RunOptions {
        overrides: vec![("height".into(), 3.0)],
        ..Default::default()
    };
    let e = error_of(src, &options);
    assert!(
        e.contains("declares no float 'height' (it declares: h)"),
        "{e}"
    );
}

#[test]
fn unknown_appearance_attribute() {
    let e =
        error("Axiom::I(\"box\",{1,1,1}){a};\na::appearance(\"colour\",{1,0,0}){j3d.terminal};");
    assert!(
        e.contains("p.vsg:2:15: unknown appearance attribute \"colour\""),
        "{e}"
    );
}

#[test]
fn pathological_nesting_is_an_error_not_a_stack_overflow() {
    let n = 100_000;
    let deep = format!(
        "Axiom::I(\"box\",{{{}1{},1,1}}){{a}};\na::{{j3d.terminal}};",
        "(".repeat(n),
        ")".repeat(n)
    );
    assert!(error(&deep).contains("brackets nest more than 32 deep"));
    let chain = format!(
        "Axiom::I(\"box\",{{1{},1,1}}){{a}};\na::{{j3d.terminal}};",
        "+1".repeat(n)
    );
    assert!(error(&chain).contains("more than 256 operators"));
    let unary = format!(
        "Axiom::I(\"box\",{{{}1,1,1}}){{a}};\na::{{j3d.terminal}};",
        "-".repeat(n)
    );
    assert!(error(&unary).contains("more than 256 operators"));
}

#[test]
fn the_deepest_allowed_expressions_still_run() {
    let nested = format!(
        "Axiom::I(\"box\",{{{}1{},1,1}}){{a}};\na::{{j3d.terminal}};",
        "(".repeat(30),
        ")".repeat(30)
    );
    assert!(vsg::run(&nested, &RunOptions::default()).is_ok());
    let unary = format!(
        "Axiom::I(\"box\",{{{}1,1,1}}){{a}};\na::{{j3d.terminal}};",
        "--".repeat(128)
    );
    assert!(vsg::run(&unary, &RunOptions::default()).is_ok());
    let chain = format!(
        "Axiom::I(\"box\",{{1{},1,1}}){{a}};\na::{{j3d.terminal}};",
        "+0".repeat(256)
    );
    assert!(vsg::run(&chain, &RunOptions::default()).is_ok());
}
