//! Issue 19: program texts as they come: a leading byte-order mark is nothing, positions stay
//! right with multi-byte characters, and a program with very many rules or errors is checked
//! and reported in O(n log n) (each rule's line comes from a line index, not a rescan).

use vsg::RunOptions;

#[test]
fn a_bom_is_ignored() {
    let src = "\u{FEFF}Axiom :: I(\"box\",{1,2,3}){j3d.terminal};\n";
    let model = vsg::run(src, &RunOptions::default()).unwrap();
    assert_eq!(model.terminals().count(), 1);
    assert!(vsg::parse::parse("\u{FEFF}").unwrap().items.is_empty());
}

#[test]
fn an_error_after_a_bom_is_at_the_same_column_as_without_it() {
    let bad = "Axiom :: I(\"pyramid\",{1,2,3}){a};\na :: {j3d.terminal};\n";
    let plain = vsg::run(bad, &RunOptions::default())
        .unwrap_err()
        .render("p.vsg", bad);
    let with_bom = format!("\u{FEFF}{bad}");
    let e = vsg::run(&with_bom, &RunOptions::default())
        .unwrap_err()
        .render("p.vsg", &with_bom);
    assert!(
        plain.starts_with("p.vsg:1:12: unknown shape type"),
        "{plain}"
    );
    assert!(e.starts_with("p.vsg:1:12: unknown shape type"), "{e}");
}

#[test]
fn a_bom_inside_the_text_is_still_an_error() {
    let e = vsg::parse::parse("Axiom :: \u{FEFF}{j3d.terminal};").unwrap_err();
    assert!(e[0].message.contains("unexpected character"), "{e:?}");
}

#[test]
fn the_line_index_agrees_with_a_scan_of_the_text() {
    let src = "é\nab\n\n€x\ny";
    let index = vsg::diag::LineIndex::new(src);
    for at in 0..=src.len() {
        let mut start = at;
        while !src.is_char_boundary(start) {
            start -= 1;
        }
        let before = &src[..start];
        let line = before.matches('\n').count() + 1;
        let col = before.rsplit('\n').next().unwrap().chars().count() + 1;
        assert_eq!(index.line_col(src, at), (line, col), "at byte {at}");
    }
}

#[test]
fn rule_lines_of_a_large_program_are_right() {
    // 3000 rules; the model's rule_line of the chosen rule must be its line.
    let mut src = String::from("Axiom :: I(\"box\",{1,1,1}){s2999};\n");
    for i in 0..3000 {
        src += &format!("s{i} :: {{j3d.terminal}};\n");
    }
    let model = vsg::run(&src, &RunOptions::default()).unwrap();
    assert_eq!(model.nodes[1].rule_line, 1);
    let mut src = String::from("Axiom :: I(\"box\",{1,1,1}){s2999};\n");
    for i in 0..3000 {
        src += &format!("s{i} :: I(\"box\",{{1,1,1}}){{j3d.terminal}};\n");
    }
    let model = vsg::run(&src, &RunOptions::default()).unwrap();
    assert_eq!(model.nodes[2].rule_line, 3001);
}

#[test]
fn thousands_of_errors_show_the_first_hundred_and_count_the_rest() {
    let mut src = String::from("Axiom :: I(\"box\",{1,1,1}){a};\na :: {j3d.terminal};\n");
    for i in 0..1000 {
        src += &format!("b{i:04} :: I(\"pyramid\",{{1}}){{a}};\n");
    }
    let e = vsg::run(&src, &RunOptions::default())
        .unwrap_err()
        .render("p.vsg", &src);
    let headers = e.lines().filter(|l| l.starts_with("p.vsg:")).count();
    assert_eq!(headers, vsg::diag::MAX_RENDERED + 1);
    assert!(
        e.starts_with("p.vsg:3:12: unknown shape type"),
        "{}",
        &e[..200]
    );
    assert!(e.contains("p.vsg:102:12:"), "the 100th error is shown");
    assert!(!e.contains("p.vsg:103:12:"), "the 101st is not");
    assert!(
        e.trim_end().ends_with("p.vsg: and 900 more errors"),
        "{}",
        &e[e.len() - 200..]
    );
}
