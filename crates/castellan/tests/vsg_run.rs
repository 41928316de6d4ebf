//! `castellan vsg run` as a user runs it: outputs appear on success, a clear message and no
//! output file on failure.

use std::path::Path;

use assert_cmd::Command;

fn examples() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

fn castellan() -> Command {
    Command::cargo_bin("castellan").unwrap()
}

/// `castellan vsg run PROGRAM -o OUTPUT`, ready for more flags.
fn vsg_run(program: &Path, output: &Path) -> Command {
    let mut c = castellan();
    c.args(["vsg", "run"]).arg(program).arg("-o").arg(output);
    c
}

/// Stderr of a failed run.
fn failure_message(c: &mut Command) -> String {
    let out = c.assert().failure();
    String::from_utf8_lossy(&out.get_output().stderr).into_owned()
}

/// Issue 24: the castle example as CityJSON and IFC, the root's children as its parts, and its
/// GLB with their property tables.
#[test]
fn writes_the_heritage_formats_with_the_roots_children_as_parts() {
    let dir = tempfile::tempdir().unwrap();
    let (glb, city, ifc) = (
        dir.path().join("castle.glb"),
        dir.path().join("castle.city.json"),
        dir.path().join("castle.ifc"),
    );
    vsg_run(&examples().join("castle.vsg"), &glb)
        .arg("--cityjson")
        .arg(&city)
        .arg("--ifc")
        .arg(&ifc)
        .assert()
        .success();
    let city: serde_json::Value = serde_json::from_slice(&std::fs::read(&city).unwrap()).unwrap();
    assert_eq!(city["type"], "CityJSON");
    assert_eq!(city["version"], "2.0");
    let objects = city["CityObjects"].as_object().unwrap();
    let building = &objects["castle"];
    assert_eq!(building["type"], "Building");
    // Four towers, four curtain walls and the keep.
    assert_eq!(building["children"].as_array().unwrap().len(), 9);
    let ifc = std::fs::read_to_string(&ifc).unwrap();
    assert!(ifc.contains("FILE_SCHEMA(('IFC4'));"));
    assert_eq!(ifc.matches("=IFCELEMENTASSEMBLY(").count(), 9);
    let glb = std::fs::read(&glb).unwrap();
    let json_len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    let json: serde_json::Value = serde_json::from_slice(&glb[20..20 + json_len]).unwrap();
    let tables = &json["extensions"]["EXT_structural_metadata"]["propertyTables"];
    assert_eq!(tables[0]["count"], 9);
}

#[test]
fn runs_rules_7_3_and_writes_every_output() {
    let dir = tempfile::tempdir().unwrap();
    let glb = dir.path().join("out/keep.glb");
    let obj = dir.path().join("out/keep.obj");
    let stats = dir.path().join("out/stats.json");
    castellan()
        .args(["vsg", "run"])
        .arg(examples().join("rules_7_3.vsg"))
        .arg("-o")
        .arg(&glb)
        .arg("--obj")
        .arg(&obj)
        .arg("--stats")
        .arg(&stats)
        .assert()
        .success();
    assert_eq!(&std::fs::read(&glb).unwrap()[..4], b"glTF");
    assert!(
        std::fs::read_to_string(&obj)
            .unwrap()
            .contains("mtllib keep.mtl")
    );
    assert!(dir.path().join("out/keep.mtl").exists());
    let s: serde_json::Value = serde_json::from_slice(&std::fs::read(&stats).unwrap()).unwrap();
    for field in [
        "terminals",
        "visible_terminals",
        "void_terminals",
        "nonterminals",
        "by_symbol",
        "volume",
        "triangles",
        "visible_volume",
    ] {
        assert!(s.get(field).is_some(), "STATS.json lacks {field}: {s}");
    }
    assert_eq!(s["terminals"], 29);
    assert!(s["volume"]["by_symbol"]["window"].as_f64().unwrap() > 0.0);
}

#[test]
fn same_seed_gives_identical_files() {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("p.vsg");
    std::fs::write(&src, "Axiom::I(\"box\",{20,1,1}){r};\nr::repeat(\"X\",{1}){s};\ns::{a}:0.5;\ns::{b}:0.5;\na::{j3d.terminal};\nb::appearance(\"color\",{1,0,0}){j3d.terminal};").unwrap();
    let out = |name: &str, seed: &str| {
        let p = dir.path().join(name);
        vsg_run(&src, &p).args(["--seed", seed]).assert().success();
        std::fs::read(p).unwrap()
    };
    assert_eq!(out("a.glb", "3"), out("b.glb", "3"));
    assert_ne!(out("a.glb", "3"), out("c.glb", "4"));
}

#[test]
fn set_changes_a_declared_float() {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("p.vsg");
    std::fs::write(
        &src,
        "float n = 3;\nAxiom::I(\"box\",{n,1,1}){r};\nr::repeat(\"X\",{1}){s};\ns::{j3d.terminal};",
    )
    .unwrap();
    let stats = dir.path().join("s.json");
    castellan()
        .args(["vsg", "run"])
        .arg(&src)
        .arg("-o")
        .arg(dir.path().join("m.glb"))
        .arg("--stats")
        .arg(&stats)
        .args(["--set", "n=5"])
        .assert()
        .success();
    let s: serde_json::Value = serde_json::from_slice(&std::fs::read(&stats).unwrap()).unwrap();
    assert_eq!(s["terminals"], 5);
}

#[test]
fn syntax_error_exits_non_zero_with_line_column_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("bad.vsg");
    std::fs::write(
        &src,
        "Axiom::I(\"box\",{1,2,3}){a};\na::split(\"X\",{1,,2}){b};\n",
    )
    .unwrap();
    let glb = dir.path().join("m.glb");
    let stderr = failure_message(&mut vsg_run(&src, &glb));
    assert!(stderr.contains("bad.vsg:2:17:"), "{stderr}");
    assert!(!glb.exists());
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        1,
        "a temporary file was left behind"
    );
}

#[test]
fn missing_program_is_a_clear_error() {
    let dir = tempfile::tempdir().unwrap();
    let stderr = failure_message(
        castellan()
            .args(["vsg", "run", "nowhere.vsg", "-o"])
            .arg(dir.path().join("m.glb")),
    );
    assert!(stderr.contains("cannot read nowhere.vsg"), "{stderr}");
}

#[test]
fn runaway_grammar_stops_at_max_depth() {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("loop.vsg");
    std::fs::write(
        &src,
        "Axiom::I(\"box\",{1,1,1}){A};\nA::repeat(\"X\",{1}){A};",
    )
    .unwrap();
    let glb = dir.path().join("m.glb");
    let stderr = failure_message(vsg_run(&src, &glb).args(["--max-depth", "20"]));
    assert!(
        stderr.contains("loop.vsg:2:1: production went deeper than 20 levels"),
        "{stderr}"
    );
    assert!(!glb.exists());
}

#[test]
fn runaway_repeat_stops_at_max_shapes() {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path().join("many.vsg");
    std::fs::write(
        &src,
        "Axiom::I(\"box\",{1,1,1}){A};\nA::repeat(\"X\",{0.0001}){B};\nB::{j3d.terminal};",
    )
    .unwrap();
    let stderr = failure_message(
        castellan()
            .args(["vsg", "run"])
            .arg(&src)
            .arg("-o")
            .arg(dir.path().join("m.glb"))
            .args(["--max-shapes", "5000"]),
    );
    assert!(
        stderr.contains(
            "many.vsg:2:4: repeat would create 10002 shapes, more than the limit of 4998"
        ),
        "{stderr}"
    );
}

fn library() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../library")
}

#[test]
fn preview_png_and_imports_beside_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("gate.png");
    castellan()
        .args(["vsg", "run"])
        .arg(library().join("gatehouse.vsg"))
        .arg("-o")
        .arg(dir.path().join("gate.glb"))
        .arg("--preview")
        .arg(&png)
        .args(["--preview-size", "64x48"])
        .assert()
        .success();
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    // IHDR: width and height, big-endian, after the 8-byte signature and 8-byte chunk header.
    assert_eq!(&bytes[16..24], &[0, 0, 0, 64, 0, 0, 0, 48]);
}

#[test]
fn imports_search_lib_directories_and_name_missing_files() {
    let dir = tempfile::tempdir().unwrap();
    let program = dir.path().join("walls.vsg");
    std::fs::write(
        &program,
        "import \"curtain_wall.vsg\" as wall (length = 12);\nAxiom :: {wall.Axiom};\n",
    )
    .unwrap();
    let stats = dir.path().join("s.json");
    let run = |lib: bool| {
        let mut c = castellan();
        c.args(["vsg", "run"])
            .arg(&program)
            .arg("-o")
            .arg(dir.path().join("w.glb"))
            .arg("--stats")
            .arg(&stats);
        if lib {
            c.arg("--lib").arg(library());
        }
        c.assert()
    };
    let out = run(false).failure();
    let err = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
    assert!(
        err.contains("walls.vsg:1:8: cannot import \"curtain_wall.vsg\": no such file"),
        "{err}"
    );
    run(true).success();
    let s: serde_json::Value = serde_json::from_slice(&std::fs::read(&stats).unwrap()).unwrap();
    // 12 m of wall: 5 merlons and 5 crenels.
    assert_eq!(s["by_symbol"]["wall.crenelGap"], 5);
}

#[test]
fn unreadable_texture_names_the_file_and_the_rule() {
    let dir = tempfile::tempdir().unwrap();
    let program = dir.path().join("t.vsg");
    std::fs::write(
        &program,
        "Axiom :: I(\"box\",{2,1,1}){row};\nrow :: repeat(\"X\", {1}){stone};\n\
         stone :: appearance(\"texture\", {\"good.png\"}){j3d.terminal};\n",
    )
    .unwrap();
    let glb = dir.path().join("t.glb");
    let run = || vsg_run(&program, &glb).assert();
    let out = run().failure();
    let err = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
    assert!(
        err.contains("t.vsg:3: cannot read texture 'good.png'"),
        "{err}"
    );
    assert!(err.contains("set for 'stone'"), "{err}");
    assert!(!glb.exists());
    std::fs::write(dir.path().join("good.png"), b"not a png").unwrap();
    run().failure();
    image::RgbImage::new(4, 4)
        .save(dir.path().join("good.png"))
        .unwrap();
    run().success();
}

#[test]
fn textures_are_embedded_in_the_glb() {
    let dir = tempfile::tempdir().unwrap();
    let program = dir.path().join("wall.vsg");
    std::fs::write(
        &program,
        "Axiom :: I(\"box\",{4,2,1}){row};\nrow :: repeat(\"X\", {1}){stone};\n\
         stone :: appearance(\"texture\", {\"brick.png\"}){j3d.terminal};\n",
    )
    .unwrap();
    let glb = dir.path().join("wall.glb");
    let run = || vsg_run(&program, &glb).assert();
    let out = run().failure();
    let err = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
    assert!(
        err.contains("wall.vsg:3: cannot read texture 'brick.png'"),
        "{err}"
    );
    assert!(!glb.exists());

    let brick = image::RgbImage::from_fn(8, 4, |x, y| {
        image::Rgb([150 + (x * 10) as u8, 60, 40 + y as u8])
    });
    let png = dir.path().join("brick.png");
    brick.save(&png).unwrap();
    run().success();
    let bytes = std::fs::read(&glb).unwrap();
    let json_len = u32::from_le_bytes(bytes[12..16].try_into().unwrap()) as usize;
    let json = String::from_utf8_lossy(&bytes[20..20 + json_len]);
    assert!(json.contains("\"mimeType\":\"image/png\""), "{json}");
    assert!(json.contains("\"baseColorTexture\""), "{json}");
    assert!(json.contains("\"TEXCOORD_0\""), "{json}");
    let file = std::fs::read(&png).unwrap();
    assert!(
        bytes[20 + json_len..]
            .windows(file.len())
            .any(|w| w == file),
        "the PNG is embedded byte for byte"
    );
}

// Issue 19: invalid geometry and hostile inputs fail with a clear message and write nothing.

#[test]
fn a_box_too_large_for_f32_is_refused_at_its_rule() {
    let dir = tempfile::tempdir().unwrap();
    let program = dir.path().join("huge.vsg");
    std::fs::write(
        &program,
        "Axiom :: I(\"box\",{1e308,1e308,1e308}){j3d.terminal};\n",
    )
    .unwrap();
    let glb = dir.path().join("m.glb");
    let obj = dir.path().join("m.obj");
    let e = failure_message(vsg_run(&program, &glb).arg("--obj").arg(&obj));
    assert!(
        e.contains("huge.vsg:1:10: box parameter length = 1e308"),
        "{e}"
    );
    assert!(!glb.exists() && !obj.exists());
}

#[test]
fn an_override_of_1e39_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let program = dir.path().join("w.vsg");
    std::fs::write(
        &program,
        "float w = 4;\nAxiom :: I(\"box\",{w,1,1}){j3d.terminal};\n",
    )
    .unwrap();
    let glb = dir.path().join("m.glb");
    let e = failure_message(vsg_run(&program, &glb).args(["--set", "w=1e39"]));
    assert!(e.contains("w.vsg:2:10:") && e.contains("1e39"), "{e}");
    assert!(!glb.exists());
}

#[cfg(unix)]
#[test]
fn an_endless_program_file_is_refused_by_its_size() {
    let dir = tempfile::tempdir().unwrap();
    let e = failure_message(&mut vsg_run(
        Path::new("/dev/zero"),
        &dir.path().join("m.glb"),
    ));
    assert!(e.contains("/dev/zero: larger than 16 MiB"), "{e}");
}

#[test]
fn invalid_utf8_in_a_program_is_reported_at_its_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let program = dir.path().join("bad.vsg");
    std::fs::write(&program, b"Axiom :: {a};\na :: \xFF{j3d.terminal};\n").unwrap();
    let e = failure_message(&mut vsg_run(&program, &dir.path().join("m.glb")));
    assert!(e.contains("bad.vsg:2:6: not UTF-8 text"), "{e}");
}

#[test]
fn a_program_with_a_bom_runs() {
    let dir = tempfile::tempdir().unwrap();
    let program = dir.path().join("bom.vsg");
    std::fs::write(
        &program,
        "\u{FEFF}Axiom :: I(\"box\",{1,2,3}){j3d.terminal};\n",
    )
    .unwrap();
    let glb = dir.path().join("m.glb");
    vsg_run(&program, &glb).assert().success();
    assert!(glb.exists());
}

#[cfg(unix)]
#[test]
fn import_of_a_device_file_says_what_it_is() {
    let dir = tempfile::tempdir().unwrap();
    let program = dir.path().join("dev.vsg");
    std::fs::write(
        &program,
        "import \"/dev/zero\" as z;\nAxiom :: I(\"box\",{1,1,1}){j3d.terminal};\n",
    )
    .unwrap();
    let e = failure_message(&mut vsg_run(&program, &dir.path().join("m.glb")));
    assert!(
        e.contains("dev.vsg:1:8: cannot import \"/dev/zero\": /dev/zero is a device or other special file, not a regular file"),
        "{e}"
    );
}

#[test]
fn import_of_a_folder_says_what_it_is() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("sub.vsg")).unwrap();
    let program = dir.path().join("main.vsg");
    std::fs::write(
        &program,
        "import \"sub.vsg\" as s;\nAxiom :: I(\"box\",{1,1,1}){j3d.terminal};\n",
    )
    .unwrap();
    let e = failure_message(&mut vsg_run(&program, &dir.path().join("m.glb")));
    assert!(e.contains("sub.vsg is a folder, not a regular file"), "{e}");
}

#[test]
fn an_imported_program_with_invalid_utf8_is_reported_at_its_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("sub.vsg"), b"// ok\n\xC3(").unwrap();
    let program = dir.path().join("main.vsg");
    std::fs::write(
        &program,
        "import \"sub.vsg\" as s;\nAxiom :: I(\"box\",{1,1,1}){j3d.terminal};\n",
    )
    .unwrap();
    let e = failure_message(&mut vsg_run(&program, &dir.path().join("m.glb")));
    assert!(e.contains("sub.vsg:2:1: not UTF-8 text"), "{e}");
}
