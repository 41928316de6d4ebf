//! Production semantics (§7.1.1, §7.1.3): conditions, probabilities with a seed, overrides,
//! transformations, relative lengths, and the kept semantic tree.

use vsg::RunOptions;
use vsg::shape::Tessellation;
use vsg::stats::Stats;
use vsg::tree::NodeState;

fn stats(src: &str, options: &RunOptions) -> Stats {
    let m = vsg::run(src, options).unwrap_or_else(|e| panic!("{}", e.render("t.vsg", src)));
    Stats::of(&m, &Tessellation::default())
}

const STOCHASTIC: &str = r#"
Axiom :: I("box", {100, 1, 1}){row};
row :: repeat("X", {1}){stone};
stone :: {mossy} : 0.3;
stone :: {clean} : 0.7;
mossy :: appearance("color", {0.2, 0.5, 0.2}){j3d.terminal};
clean :: {j3d.terminal};
"#;

#[test]
fn same_seed_same_model_other_seed_other_model() {
    let choices = |seed| {
        let m = vsg::run(
            STOCHASTIC,
            &RunOptions {
                seed,
                ..Default::default()
            },
        )
        .unwrap();
        m.terminals()
            .map(|n| m.symbol(n).to_string())
            .collect::<Vec<_>>()
    };
    assert_eq!(choices(7), choices(7));
    assert_ne!(choices(7), choices(8));
    let a = stats(
        STOCHASTIC,
        &RunOptions {
            seed: 7,
            ..Default::default()
        },
    );
    let mossy = a.by_symbol["mossy"];
    assert!((15..=45).contains(&mossy), "{mossy} of 100 with p = 0.3");
}

#[test]
fn conditions_read_shape_attributes() {
    let src = r#"
Axiom :: I("box", {10, 6, 1}){wall};
wall :: repeat("Y", {1}){course};
course : index % 2 == 0 : {even};
course : index % 2 == 1 && sy > 0.5 : {odd};
even :: {j3d.terminal};
odd :: {j3d.terminal};
"#;
    let s = stats(src, &RunOptions::default());
    assert_eq!((s.by_symbol["even"], s.by_symbol["odd"]), (3, 3));
}

#[test]
fn set_overrides_a_declared_float() {
    let src = "float n = 4;\nAxiom :: I(\"box\", {n, 1, 1}){w};\nw :: repeat(\"X\", {1}){s};\ns :: {j3d.terminal};";
    assert_eq!(stats(src, &RunOptions::default()).terminals, 4);
    let s = stats(
        src,
        &RunOptions {
            overrides: vec![("n".into(), 9.0)],
            ..Default::default()
        },
    );
    assert_eq!(s.terminals, 9);
    assert!((s.volume.total - 9.0).abs() < 1e-12);
}

#[test]
fn relative_lengths_share_what_is_left() {
    let src = "Axiom :: I(\"box\", {10, 1, 1}){w};\nw :: split(\"X\", {2, ~1, ~3}){a, b, c};\na :: {j3d.terminal};\nb :: {j3d.terminal};\nc :: {j3d.terminal};";
    let s = stats(src, &RunOptions::default());
    assert!((s.volume.by_symbol["b"] - 2.0).abs() < 1e-12);
    assert!((s.volume.by_symbol["c"] - 6.0).abs() < 1e-12);
}

#[test]
fn transforms_compose_down_the_tree() {
    let src = r#"
Axiom :: T(10, 0, 0) R(0, 1.5707963267948966, 0) I("box", {4, 1, 2}){w};
w :: split("X", {1, 3}){a, b};
a :: {j3d.terminal};
b :: {j3d.terminal};
"#;
    let m = vsg::run(src, &RunOptions::default()).unwrap();
    let a = m.nodes.iter().find(|n| m.symbol(n) == "a").unwrap();
    // a's centre is 1.5 along the box's local -x, which the rotation about y turns into +z.
    let p = a.world.translation.vector;
    assert!((p.x - 10.0).abs() < 1e-9 && (p.z - 1.5).abs() < 1e-9, "{p}");
}

#[test]
fn several_instantiations_bind_successors_in_order() {
    let src = r#"
Axiom :: I("box", {1, 1, 1}) T(5, 0, 0) I("sphere", {2}){cube, ball};
cube :: {j3d.terminal};
ball :: {j3d.terminal};
"#;
    let m = vsg::run(src, &RunOptions::default()).unwrap();
    let ball = m.nodes.iter().find(|n| m.symbol(n) == "ball").unwrap();
    assert_eq!(ball.shape.unwrap().kind, vsg::shape::ShapeType::Sphere);
    assert_eq!(ball.world.translation.x, 5.0);
}

#[test]
fn non_terminals_are_kept_with_their_rule_lines() {
    let src = "Axiom :: I(\"box\", {2, 1, 1}){w};\nw :: split(\"X\", {1, 1}){a, a};\na :: void(){j3d.terminal};";
    let m = vsg::run(src, &RunOptions::default()).unwrap();
    let w = &m.nodes[1];
    assert_eq!(
        (m.symbol(w), w.state, w.rule_line, w.child_count),
        ("w", NodeState::NonTerminal, 1, 2)
    );
    let a = &m.nodes[w.first_child as usize];
    assert_eq!(
        (a.state, a.rule_line, a.depth),
        (NodeState::VoidTerminal, 2, 2)
    );
}

#[test]
fn split_along_every_radial_direction_conserves_volume() {
    let src = r#"
Axiom :: I("cylinder", {3, 2}) T(10, 0, 0) I("sphere", {2}) T(20, 0, 0) I("conicFrustum", {3, 2, 1}){c, s, f};
c :: split("Theta", {~1, ~1, ~1}){p, p, p};
s :: split("Phi", {~1, ~2}){p, p};
f :: split("R", {1, 2}){p, p};
p :: {j3d.terminal};
"#;
    let s = stats(src, &RunOptions::default());
    let whole = std::f64::consts::PI * 9.0 * 2.0
        + 4.0 / 3.0 * std::f64::consts::PI * 8.0
        + std::f64::consts::PI * 2.0 / 3.0 * (9.0 + 3.0 + 1.0);
    assert_eq!(s.terminals, 7);
    assert!(
        (s.volume.total - whole).abs() < 1e-9 * whole,
        "{} vs {whole}",
        s.volume.total
    );
}

#[test]
fn densities_give_masses_per_symbol() {
    let src = "Axiom :: I(\"box\",{4,3,2}){wall};\n\
               wall :: split(\"X\",{1,~1}){stone, gap};\n\
               stone :: appearance(\"density\", 2400){j3d.terminal};\n\
               gap :: void(){j3d.terminal};";
    let s = stats(src, &RunOptions::default());
    let mass = s.mass.as_ref().expect("a density was given");
    assert!((mass.total - 6.0 * 2400.0).abs() < 1e-9);
    assert_eq!(mass.by_symbol.len(), 1);
    assert!((mass.by_symbol["stone"] - 14400.0).abs() < 1e-9);
    let json = serde_json::to_value(&s).unwrap();
    assert_eq!(json["mass"]["by_symbol"]["stone"], 14400.0);
    // Without densities there is no mass field.
    let plain = stats(
        "Axiom :: I(\"box\",{1,1,1}){j3d.terminal};",
        &RunOptions::default(),
    );
    assert!(serde_json::to_value(&plain).unwrap().get("mass").is_none());
    let bad = "Axiom :: I(\"box\",{1,1,1}) appearance(\"density\", -1){j3d.terminal};";
    let e = vsg::run(bad, &RunOptions::default())
        .unwrap_err()
        .render("d.vsg", bad);
    assert!(
        e.contains("d.vsg:1:49: density -1 must be a positive number of kg/m³"),
        "{e}"
    );
}

#[test]
fn texture_lists_pick_one_photograph_per_shape_from_the_seed() {
    let src = "Axiom :: I(\"box\",{30,1,1}){row};\n\
               row :: repeat(\"X\", {1}){stone};\n\
               stone :: appearance(\"texture\", {\"a.png\", \"b.png\", \"c.png\"}){j3d.terminal};";
    let picks = |seed| {
        let m = vsg::run(
            src,
            &RunOptions {
                seed,
                ..Default::default()
            },
        )
        .unwrap();
        m.terminals()
            .map(|n| m.appearance(n).texture.clone().unwrap())
            .collect::<Vec<_>>()
    };
    let first = picks(3);
    assert_eq!(first.len(), 30);
    for name in ["a.png", "b.png", "c.png"] {
        assert!(first.iter().any(|t| t == name), "{name} never picked");
    }
    assert_eq!(first, picks(3));
    assert_ne!(first, picks(4));
}

/// A photo stretched over a wall, and behind its outer skin `texture ""` takes it off again,
/// so the wall's back face does not show the photo (reconstruct's façade walls).
#[test]
fn an_empty_texture_takes_a_photo_off_the_back_of_a_wall() {
    let src = "Axiom :: I(\"box\",{4,3,1}){wall};\n\
               wall :: appearance(\"photo\", \"f.png\") split(\"Z\", {~19, ~1}){back, skin};\n\
               back :: appearance(\"texture\", \"\"){j3d.terminal};\n\
               skin :: {j3d.terminal};";
    let m = vsg::run(src, &RunOptions::default()).unwrap();
    let looks: Vec<(Option<String>, bool)> = m
        .terminals()
        .map(|n| {
            let a = m.appearance(n);
            (a.texture.clone(), a.texture_frame.is_some())
        })
        .collect();
    assert_eq!(looks, vec![(None, false), (Some("f.png".into()), true)]);
}
