//! `import "file" as name (args);`: namespaced symbols and floats, arguments, `--set` of an
//! imported float, messages in the imported file, missing files and cycles.

use std::collections::HashMap;

use vsg::RunOptions;
use vsg::import::Resolver;
use vsg::shape::Tessellation;
use vsg::stats::Stats;

struct Files(HashMap<&'static str, &'static str>);

impl Resolver for Files {
    fn load(&mut self, _from: &str, path: &str) -> Result<(String, String), String> {
        self.0
            .get(path)
            .map(|t| (path.to_string(), t.to_string()))
            .ok_or_else(|| format!("no file {path}"))
    }
}

const TOWER: &str = "float radius = 1;\nfloat height = 4;\n\
    Axiom :: I(\"cylinder\", {radius, height}){body};\n\
    body :: split(\"Y\", {~1, ~1}){floor, floor};\n\
    floor :: {j3d.terminal};\n";

fn files() -> Files {
    Files(HashMap::from([
        ("tower.vsg", TOWER),
        (
            "pair.vsg",
            "float gap = 10;\nimport \"tower.vsg\" as t (height = gap);\n\
             Axiom :: I(\"box\",{1,1,1}) T(gap,0,0) I(\"box\",{1,1,1}){t.Axiom, t.Axiom};\n",
        ),
        (
            "loop_a.vsg",
            "import \"loop_b.vsg\" as b;\nAxiom :: {b.Axiom};\n",
        ),
        (
            "loop_b.vsg",
            "import \"loop_a.vsg\" as a;\nAxiom :: {a.Axiom};\n",
        ),
        ("broken.vsg", "Axiom :: I(\"box\",{1,1,1}){gone};\n"),
    ]))
}

fn run(src: &str, options: &RunOptions) -> Result<vsg::Model, String> {
    vsg::run_with("main.vsg", src, options, &mut files()).map_err(|e| e.render("main.vsg", src))
}

fn stats(m: &vsg::Model) -> Stats {
    Stats::of(m, &Tessellation::default())
}

#[test]
fn imported_rules_run_under_their_alias_with_arguments() {
    let src = "float r = 2;\nimport \"tower.vsg\" as tower (radius = r);\n\
               Axiom :: {tower.Axiom};\n";
    let m = run(src, &RunOptions::default()).unwrap();
    let s = stats(&m);
    assert_eq!(s.by_symbol["tower.floor"], 2);
    assert_eq!(s.terminals, 2);
    let cylinder = vsg::shape::Primitive::new(vsg::shape::ShapeType::Cylinder, &[2.0, 4.0])
        .unwrap()
        .volume();
    assert!((s.volume.total - cylinder).abs() < 1e-9);
    // --set reaches the imported float and wins over the import's argument.
    let options = RunOptions {
        overrides: vec![("tower.radius".into(), 3.0)],
        ..Default::default()
    };
    let s = stats(&run(src, &options).unwrap());
    assert!((s.volume.total - 9.0 * std::f64::consts::PI * 4.0).abs() < 1e-9);
}

#[test]
fn nested_imports_nest_their_names() {
    let src = "import \"pair.vsg\" as p;\nAxiom :: {p.Axiom};\n";
    let s = stats(&run(src, &RunOptions::default()).unwrap());
    assert_eq!(s.by_symbol["p.t.floor"], 4);
    // height = gap = 10: two towers of radius 1 and height 10.
    assert!((s.volume.total - 2.0 * std::f64::consts::PI * 10.0).abs() < 1e-9);
}

#[test]
fn errors_point_into_the_right_file() {
    let e = run(
        "import \"nowhere.vsg\" as x;\nAxiom :: {x.Axiom};",
        &Default::default(),
    )
    .unwrap_err();
    assert!(
        e.contains("main.vsg:1:8: cannot import \"nowhere.vsg\": no file nowhere.vsg"),
        "{e}"
    );
    let e = run(
        "import \"broken.vsg\" as b;\nAxiom :: {b.Axiom};",
        &Default::default(),
    )
    .unwrap_err();
    assert!(
        e.contains("broken.vsg:1:27: symbol 'b.gone' has no rule"),
        "{e}"
    );
    let e = run(
        "import \"loop_a.vsg\" as a;\nAxiom :: {a.Axiom};",
        &Default::default(),
    )
    .unwrap_err();
    assert!(
        e.contains("loop_b.vsg:1:8: import cycle: loop_a.vsg -> loop_b.vsg -> loop_a.vsg"),
        "{e}"
    );
    let e = run(
        "import \"tower.vsg\" as t (width = 2);\nAxiom :: {t.Axiom};",
        &Default::default(),
    )
    .unwrap_err();
    assert!(
        e.contains(
            "main.vsg:1:26: \"tower.vsg\" declares no float 'width' (it declares: radius, height)"
        ),
        "{e}"
    );
}

#[test]
fn without_a_resolver_imports_are_refused() {
    let src = "import \"tower.vsg\" as t;\nAxiom :: {t.Axiom};";
    let e = vsg::run(src, &Default::default())
        .unwrap_err()
        .render("p.vsg", src);
    assert!(
        e.contains("p.vsg:1:8: cannot import \"tower.vsg\": imports are not available here"),
        "{e}"
    );
}

#[test]
fn rule_lines_are_lines_of_the_imported_file() {
    let src = "\n\nimport \"tower.vsg\" as tower;\nAxiom :: {tower.Axiom};\n";
    let m = run(src, &RunOptions::default()).unwrap();
    let floor = m.terminals().next().unwrap();
    assert_eq!(floor.rule_line, 4);
}

/// Files `f0.vsg`, `f1.vsg`, … each importing the next `fan` times up to `f{last}.vsg`: an
/// endless chain (`fan` 1) or an exponential tree (`fan` 2). Counts the loads.
struct Endless {
    fan: usize,
    last: usize,
    loads: usize,
}

impl Resolver for Endless {
    fn load(&mut self, _from: &str, path: &str) -> Result<(String, String), String> {
        self.loads += 1;
        let n: usize = path[1..path.len() - 4].parse().unwrap();
        if n == self.last {
            return Ok((path.to_string(), "Axiom :: {j3d.terminal};\n".into()));
        }
        let mut text = String::new();
        for k in 0..self.fan {
            text += &format!("import \"f{}.vsg\" as x{k};\n", n + 1);
        }
        text += "Axiom :: {x0.Axiom};\n";
        Ok((path.to_string(), text))
    }
}

#[test]
fn an_endless_chain_of_imports_stops_at_the_depth_limit() {
    let src = "import \"f0.vsg\" as x0;\nAxiom :: {x0.Axiom};\n";
    let mut files = Endless {
        fan: 1,
        last: usize::MAX,
        loads: 0,
    };
    let e = vsg::run_with("main.vsg", src, &RunOptions::default(), &mut files)
        .unwrap_err()
        .render("main.vsg", src);
    assert!(e.contains("imports nest more than 32 deep"), "{e}");
    assert_eq!(files.loads, vsg::import::MAX_IMPORT_DEPTH);
}

#[test]
fn imports_that_fan_out_stop_before_growing_exponentially() {
    let src = "import \"f0.vsg\" as x0;\nAxiom :: {x0.Axiom};\n";
    // 2^21 loads within the depth limit.
    let mut files = Endless {
        fan: 2,
        last: 20,
        loads: 0,
    };
    let e = vsg::run_with("main.vsg", src, &RunOptions::default(), &mut files)
        .unwrap_err()
        .render("main.vsg", src);
    assert!(e.contains("loads more than 2000 imports"), "{e}");
    assert!(
        files.loads <= vsg::import::MAX_IMPORTS + 1,
        "{}",
        files.loads
    );
}
