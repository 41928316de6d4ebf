//! Issue 19: geometry that is not finite or too large for the 32-bit floats of glTF and OBJ is
//! refused at the rule that makes it (`shape::MAX_COORDINATE`), and the exporters refuse
//! non-finite data rather than writing `null` or `inf`.

use vsg::export::{ExportOptions, to_glb, to_obj};
use vsg::{Error, RunOptions};

fn error_of(src: &str, options: &RunOptions) -> String {
    match vsg::run(src, options) {
        Ok(_) => panic!("expected an error for:\n{src}"),
        Err(e) => e.render("p.vsg", src),
    }
}

fn error(src: &str) -> String {
    error_of(src, &RunOptions::default())
}

fn set(name: &str, value: f64) -> RunOptions {
    RunOptions {
        overrides: vec![(name.into(), value)],
        ..Default::default()
    }
}

#[test]
fn a_box_too_large_for_f32_is_refused_at_its_rule() {
    let e = error("// huge\nAxiom :: I(\"box\",{1e308,1e308,1e308}){j3d.terminal};\n");
    assert!(e.starts_with("p.vsg:2:10: box parameter length"), "{e}");
    assert!(e.contains("32-bit"), "{e}");
}

#[test]
fn a_box_just_past_the_bound_is_refused_and_one_at_it_is_not() {
    let at = vsg::shape::MAX_COORDINATE;
    let ok = format!("Axiom :: I(\"box\",{{{at},1,1}}){{j3d.terminal}};");
    assert!(vsg::run(&ok, &RunOptions::default()).is_ok());
    let past = format!("Axiom :: I(\"box\",{{{},1,1}}){{j3d.terminal}};", at * 1.01);
    assert!(error(&past).contains("box parameter length"));
}

#[test]
fn an_override_of_1e39_is_refused() {
    let src = "float w = 4;\nAxiom :: I(\"box\",{w,1,1}){j3d.terminal};\n";
    let e = error_of(src, &set("w", 1e39));
    assert!(e.starts_with("p.vsg:2:10:"), "{e}");
    assert!(e.contains("1e39") && e.contains("32-bit"), "{e}");
}

#[test]
fn an_override_that_is_not_finite_is_refused() {
    let src = "float w = 4;\nAxiom :: I(\"box\",{w,1,1}){j3d.terminal};\n";
    for v in [f64::NAN, f64::INFINITY] {
        match vsg::run(src, &set("w", v)) {
            Err(Error::Override(m)) => assert!(m.contains("not a finite number"), "{m}"),
            other => panic!("expected an override error, got {other:?}"),
        }
    }
}

#[test]
fn a_parallelepiped_whose_offsets_add_past_the_bound_is_refused() {
    let e = error("Axiom :: I(\"parallelepiped\",{1e7,1,1,1e7,0,0}){j3d.terminal};");
    assert!(e.contains("would measure 2e7 m along X"), "{e}");
}

#[test]
fn a_translation_out_of_bounds_is_refused_at_its_rule() {
    let e = error("Axiom :: I(\"box\",{1,1,1}){a};\na :: T(2e7, 0, 0){j3d.terminal};\n");
    assert!(
        e.starts_with("p.vsg:2:1: 'a' would be placed at (20000000, 0, 0)"),
        "{e}"
    );
}

#[test]
fn translations_that_add_up_to_infinity_are_refused() {
    let e = error("Axiom :: T(1e308,0,0) T(1e308,0,0) I(\"box\",{1,1,1}){j3d.terminal};");
    assert!(e.contains("would be placed at (inf"), "{e}");
}

#[test]
fn a_shape_moved_out_of_bounds_step_by_step_is_refused() {
    // Each step is small; their sum is not.
    let e = error_of(
        "Axiom :: I(\"box\",{1,1,1}){a};\na :: T(4e6, 0, 0){a};\n",
        &RunOptions::default(),
    );
    assert!(
        e.starts_with("p.vsg:2:1:") && e.contains("would be placed at"),
        "{e}"
    );
}

#[test]
fn boolean_operands_out_of_bounds_are_refused_before_the_boolean() {
    let e = error(
        "Axiom :: I(\"box\",{1,1,1}) T(1e308,0,0) T(1e308,0,0) I(\"box\",{1,1,1}) union(){u};\nu :: {j3d.terminal};\n",
    );
    assert!(e.contains("'an operand' would be placed at"), "{e}");
}

#[test]
fn a_model_at_the_bound_exports_finite_numbers() {
    let src = "Axiom :: T(1e7, -1e7, 1e7) R(0.3, 0.2, 0.1) I(\"box\",{1e7,1e7,1e7}){j3d.terminal};";
    let model = vsg::run(src, &RunOptions::default()).unwrap();
    let glb = to_glb(&model, &ExportOptions::default()).unwrap();
    let json_len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    let json = std::str::from_utf8(&glb[20..20 + json_len]).unwrap();
    assert!(!json.contains("null"), "{json}");
    let (obj, _) = to_obj(&model, &ExportOptions::default(), "m.mtl").unwrap();
    assert!(!obj.contains("inf") && !obj.contains("NaN"), "{obj}");
}

#[test]
fn the_exporters_refuse_a_model_moved_out_of_f32_range_by_hand() {
    let mut model = vsg::run(
        "Axiom :: I(\"box\",{1,1,1}){a};\na :: {j3d.terminal};",
        &RunOptions::default(),
    )
    .unwrap();
    // A library user can edit the model after production; the exporters check again.
    let far = nalgebra::Translation3::new(1e39, 0.0, 0.0);
    for node in &mut model.nodes[1..] {
        node.local = nalgebra::Isometry3::from_parts(far, node.local.rotation);
        node.world = node.local;
    }
    let e = to_glb(&model, &ExportOptions::default()).unwrap_err();
    assert!(e.to_string().contains("translation of node 1"), "{e}");
    let e = to_obj(&model, &ExportOptions::default(), "m.mtl").unwrap_err();
    assert!(
        e.to_string()
            .contains("not a finite number the file can store (32-bit floats in glTF and OBJ"),
        "{e}"
    );
}

#[test]
fn huge_and_tiny_numbers_in_messages_are_written_in_scientific_notation() {
    let e =
        error("Axiom :: I(\"box\",{1,1,1}) appearance(\"color\", {1e300, 0, 0}){j3d.terminal};");
    assert!(e.contains("appearance value 1e300 is outside 0..1"), "{e}");
    let e = error("Axiom :: I(\"box\",{-1e-300,1,1}){j3d.terminal};");
    assert!(e.contains("length = -1e-300 is invalid"), "{e}");
    let e = error(
        "Axiom :: I(\"box\",{2,1,1}){a};\na :: split(\"X\", {1e-300, 1}){b, b};\nb :: {j3d.terminal};",
    );
    assert!(e.contains("add up to 1, but the box measures 2"), "{e}");
}

#[test]
fn a_tessellation_finer_than_the_cap_meshes_as_the_cap() {
    use vsg::shape::{Primitive, ShapeType, Tessellation};
    let cylinder = Primitive::new(ShapeType::Cylinder, &[1.0, 2.0]).unwrap();
    let capped = cylinder.mesh(&Tessellation {
        segments: Tessellation::MAX_SEGMENTS,
    });
    let asked = cylinder.mesh(&Tessellation { segments: u32::MAX });
    assert_eq!(asked.triangles.len(), capped.triangles.len());
}
