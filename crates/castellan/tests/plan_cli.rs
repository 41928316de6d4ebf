//! `castellan plan` as a user runs it on a shipped public-domain drawing: every output appears
//! and follows the PLAN.json / LABELS.png contract; bad input gives one message and no file.

use std::path::Path;

use assert_cmd::Command;

fn castellan() -> Command {
    Command::cargo_bin("castellan").unwrap()
}

#[test]
fn parses_sully_and_writes_every_output() {
    let dir = tempfile::tempdir().unwrap();
    let input =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/plans/sully-sur-loire.png");
    let out = |n: &str| dir.path().join(n);
    castellan()
        .arg("plan")
        .arg(&input)
        .arg("-o")
        .arg(out("plan.json"))
        .arg("--labels")
        .arg(out("labels.png"))
        .arg("--overlay")
        .arg(out("overlay.png"))
        .arg("--svg")
        .arg(out("plan.svg"))
        .arg("--model")
        .arg(out("model.glb"))
        .arg("--walls")
        .arg(out("walls.png"))
        .assert()
        .success();
    let doc: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out("plan.json")).unwrap()).unwrap();
    // The walls as read: red over grey, the drawing's size, some wall and some not.
    let walls = image::open(out("walls.png")).unwrap().to_rgb8();
    let red = walls.pixels().filter(|p| p[0] > 150 && p[1] < 100).count();
    assert!(red > 0 && red < walls.len() / 3, "{red} wall pixels");
    let names: Vec<&str> = (0..11)
        .map(|i| doc["legend"][i.to_string()].as_str().unwrap())
        .collect();
    assert_eq!(names[0], "castle_surroundings");
    assert_eq!(names[4], "tower_room");
    assert_eq!(names[10], "unknown_wall");
    let (w, h) = (
        doc["width"].as_u64().unwrap(),
        doc["height"].as_u64().unwrap(),
    );
    let labels = image::open(out("labels.png")).unwrap().to_luma8();
    assert_eq!(
        (u64::from(labels.width()), u64::from(labels.height())),
        (w, h)
    );
    assert!(labels.pixels().all(|p| p[0] < 11));
    assert!(
        doc["faces"]
            .as_array()
            .unwrap()
            .iter()
            .any(|f| f["label"] == "courtyard")
    );
    // Sully's concentric moat lines are read as wall by the learned ink, which joins the
    // towers to the moat (docs/plan.md, "Learned wall ink"); the rules find three or more.
    assert!(doc["towers"].as_u64().unwrap() >= 1);
    // The plan document of Sully read with `--ink INK`.
    let plan_with_ink = |ink: &str| -> serde_json::Value {
        let json = out(&format!("{ink}.json"));
        castellan()
            .args(["plan", "--ink", ink, "-o"])
            .arg(&json)
            .arg(&input)
            .assert()
            .success();
        serde_json::from_slice(&std::fs::read(json).unwrap()).unwrap()
    };
    let rules = plan_with_ink("rules");
    assert!(rules["towers"].as_u64().unwrap() >= 3);
    // The wall-ink network reads the moat lines as paper and finds Sully's round towers (7 of
    // its 6 in session 28, a courtyard and the great hall).
    let net = plan_with_ink("network");
    assert!(net["towers"].as_u64().unwrap() >= 4, "{}", net["towers"]);
    let labels: Vec<&str> = net["faces"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|f| f["label"].as_str())
        .collect();
    assert!(labels.contains(&"courtyard") && labels.contains(&"tower_room"));
    // Every edge has points and a fit, read either way (the rules' document once shadowed
    // `doc`, so only its edges were checked).
    for e in [&doc, &rules]
        .iter()
        .flat_map(|d| d["edges"].as_array().unwrap())
    {
        assert!(!e["points"].as_array().unwrap().is_empty());
        assert!(["line", "arc"].contains(&e["fit"]["type"].as_str().unwrap()));
    }
    assert!(
        std::fs::read_to_string(out("plan.svg"))
            .unwrap()
            .starts_with("<svg")
    );
    assert_eq!(&std::fs::read(out("model.glb")).unwrap()[..4], b"glTF");
    assert_eq!(image::open(out("overlay.png")).unwrap().width() as u64, w);
}

#[test]
fn blank_page_fails_with_one_message_and_no_output() {
    let dir = tempfile::tempdir().unwrap();
    let blank = dir.path().join("blank.png");
    image::GrayImage::from_pixel(120, 80, image::Luma([250]))
        .save(&blank)
        .unwrap();
    let json = dir.path().join("plan.json");
    let assert = castellan()
        .arg("plan")
        .arg(&blank)
        .arg("-o")
        .arg(&json)
        .assert()
        .failure();
    let err = String::from_utf8_lossy(&assert.get_output().stderr).into_owned();
    assert!(
        err.contains("blank.png") && err.contains("no walls"),
        "{err}"
    );
    assert!(!json.exists());
}

#[test]
fn unreadable_image_names_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("notes.png");
    std::fs::write(&bad, b"not an image").unwrap();
    let assert = castellan()
        .arg("plan")
        .arg(&bad)
        .arg("-o")
        .arg(dir.path().join("p.json"))
        .assert()
        .failure();
    let err = String::from_utf8_lossy(&assert.get_output().stderr).into_owned();
    assert!(err.contains("notes.png"), "{err}");
}

#[test]
fn batch_parses_the_good_drawing_and_reports_the_two_bad_files() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("in");
    std::fs::create_dir(&input).unwrap();
    // The synthetic castle has six towers (plan::synth::castle).
    let (castle, _) = plan::synth::castle(3, 0.5, 600, 450);
    castle.save(input.join("castle.png")).unwrap();
    image::GrayImage::from_pixel(120, 80, image::Luma([250]))
        .save(input.join("blank.png"))
        .unwrap();
    std::fs::write(input.join("notes.txt"), b"not an image").unwrap();
    let out = dir.path().join("out");
    let assert = castellan()
        .args(["plan", "--batch"])
        .arg(&input)
        .arg("-o")
        .arg(&out)
        .assert()
        .success();
    let err = String::from_utf8_lossy(&assert.get_output().stderr).into_owned();
    assert!(err.contains("3 drawings: 1 parsed"), "{err}");

    let csv = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    let rows: Vec<Vec<&str>> = csv.lines().map(|l| l.splitn(8, ',').collect()).collect();
    assert_eq!(
        rows[0].join(","),
        "file,success,closed_outer_wall,faces,towers,labels_found,time_ms,failure_reason"
    );
    assert_eq!(rows.len(), 4, "{csv}");
    // Sorted by name: blank.png, castle.png, notes.txt.
    assert_eq!(&rows[1][..3], &["blank.png", "false", "false"]);
    assert!(rows[1][7].contains("no walls"), "{csv}");
    assert_eq!(&rows[2][..3], &["castle.png", "true", "true"]);
    // The row reports the parse: the library's count for the same drawing. (The castle has
    // six towers; at half scale a letter against its north-east curtain reads as a seventh,
    // a tower drawn as thick ink: docs/plan.md, "Towers drawn as thick ink".)
    let towers: usize = rows[2][4].parse().unwrap();
    let parsed = plan::parse(
        &image::DynamicImage::ImageLuma8(castle),
        &Default::default(),
    );
    assert_eq!(towers, parsed.unwrap().towers, "{csv}");
    assert!((6..=7).contains(&towers), "{csv}");
    assert!(rows[2][5].parse::<usize>().unwrap() >= 5, "{csv}");
    assert_eq!(&rows[3][..2], &["notes.txt", "false"]);
    assert!(rows[3][7].contains("not a readable image"), "{csv}");

    for suffix in ["plan.json", "labels.png", "overlay.png", "walls.png", "svg"] {
        assert!(out.join(format!("castle.{suffix}")).exists(), "{suffix}");
        assert!(!out.join(format!("blank.{suffix}")).exists(), "{suffix}");
    }
}

#[test]
fn batch_of_an_empty_folder_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let assert = castellan()
        .args(["plan", "--batch"])
        .arg(dir.path())
        .arg("-o")
        .arg(dir.path().join("out"))
        .assert()
        .failure();
    let err = String::from_utf8_lossy(&assert.get_output().stderr).into_owned();
    assert!(err.contains("no files"), "{err}");
}

#[test]
fn scale_bar_gives_metres_per_pixel_and_its_absence_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    // A square enclosure with a round tower, on clean paper (no grid lines to touch the bar).
    let mut canvas = plan::synth::Canvas::new(600, 450);
    canvas.poly(
        &[(150.0, 80.0), (450.0, 80.0), (450.0, 330.0), (150.0, 330.0)],
        10.0,
    );
    canvas.round_tower((450.0, 80.0), 30.0, 9.0);
    let mut castle = canvas.0;
    let with_bar = dir.path().join("with_bar.png");
    castle.save(dir.path().join("no_bar.png")).unwrap();
    // A 200-px ruled bar with ticks every 40 px, below the castle.
    for x in 50..250u32 {
        castle.put_pixel(x, 420, image::Luma([0]));
        if (x - 50) % 40 == 0 || x == 249 {
            for y in 414..=420 {
                castle.put_pixel(x, y, image::Luma([0]));
            }
        }
    }
    castle.save(&with_bar).unwrap();
    let json = dir.path().join("plan.json");
    let assert = castellan()
        .arg("plan")
        .arg(&with_bar)
        .arg("-o")
        .arg(&json)
        .args(["--scale-bar", "40"])
        .assert()
        .success();
    let err = String::from_utf8_lossy(&assert.get_output().stderr).into_owned();
    assert!(err.contains("200 px = 40 m"), "{err}");
    let doc: serde_json::Value = serde_json::from_slice(&std::fs::read(&json).unwrap()).unwrap();
    assert!(
        (doc["scale"].as_f64().unwrap() - 0.2).abs() < 1e-9,
        "{}",
        doc["scale"]
    );
    assert_eq!(doc["scale_bar"]["length_px"], 200);

    let json2 = dir.path().join("plan2.json");
    let assert = castellan()
        .arg("plan")
        .arg(dir.path().join("no_bar.png"))
        .arg("-o")
        .arg(&json2)
        .args(["--scale-bar", "40"])
        .assert()
        .success();
    // Issue 22: no bar is a warning, and the plan is written in plan pixels.
    let err = String::from_utf8_lossy(&assert.get_output().stderr).into_owned();
    assert!(
        err.contains("no_bar.png: warning: no scale bar found for the 40 m given")
            && err.contains("continuing in plan pixels; give --scale METRES_PER_PIXEL"),
        "{err}"
    );
    let doc: serde_json::Value = serde_json::from_slice(&std::fs::read(&json2).unwrap()).unwrap();
    assert!(doc["scale"].is_null(), "{}", doc["scale"]);
}

/// Issue 20: without a scale, `plan --model` and `reconstruct` took a metre differently (1/100
/// of the drawing against the outer walls' thickness as 2.5 m). One rule now decides it
/// (`plan::scale::ModelScale::decide`); both commands report it and use it.
#[test]
fn plan_model_and_reconstruct_take_the_same_metre_without_a_scale() {
    let dir = tempfile::tempdir().unwrap();
    let drawing =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/plans/sully-sur-loire.png");
    std::fs::copy(&drawing, dir.path().join("plan.png")).unwrap();
    let plan = castellan()
        .arg("plan")
        .arg(dir.path().join("plan.png"))
        .arg("-o")
        .arg(dir.path().join("plan.json"))
        .arg("--model")
        .arg(dir.path().join("model.glb"))
        .assert()
        .success();
    let stderr = String::from_utf8_lossy(&plan.get_output().stderr).into_owned();
    let said = stderr
        .lines()
        .find(|l| l.contains("model in plan pixels"))
        .unwrap_or_else(|| panic!("the assumption is reported: {stderr}"));
    let per_metre: f64 = said
        .rsplit("1 m = ")
        .next()
        .and_then(|s| s.trim_end_matches(" px").parse().ok())
        .unwrap_or_else(|| panic!("a metre in pixels: {said}"));

    std::fs::write(dir.path().join("PROJECT.toml"), "plan = \"plan.png\"\n").unwrap();
    castellan()
        .arg("reconstruct")
        .arg(dir.path().join("PROJECT.toml"))
        .arg("-o")
        .arg(dir.path().join("out"))
        .assert()
        .success();
    let estimate: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("out/estimate.json")).unwrap())
            .unwrap();
    assert_eq!(estimate["units"], "px");
    let upm = estimate["units_per_metre"].as_f64().unwrap();
    assert!(
        (upm - per_metre).abs() < 0.005,
        "plan --model: 1 m = {per_metre} px; reconstruct: {upm}"
    );
    assert!(
        estimate["assumptions"][0]
            .as_str()
            .unwrap()
            .contains(said.split("model in plan pixels; ").nth(1).unwrap()),
        "{estimate}"
    );
    // The model's tallest walls are the §5.3 tower walls, 20 m in plan pixels.
    let glb = std::fs::read(dir.path().join("model.glb")).unwrap();
    let gltf = gltf_json_chunk(&glb);
    let top = gltf["accessors"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|a| a["max"].as_array().map(|m| m[1].as_f64().unwrap()))
        .fold(f64::NEG_INFINITY, f64::max);
    assert!(
        top <= 20.0 * upm * 1.001,
        "top {top} vs 20 m = {}",
        20.0 * upm
    );
}

/// The JSON chunk of a binary glTF.
fn gltf_json_chunk(glb: &[u8]) -> serde_json::Value {
    let len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    serde_json::from_slice(&glb[20..20 + len]).unwrap()
}
