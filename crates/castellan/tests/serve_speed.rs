//! Speed of `castellan serve`'s overlays on a 1-megapixel photo (issue 10): the server's round
//! trip (request, stage, overlay and rectified image fetched) against the same stage run by the
//! `castellan rectify` and `castellan facade` commands on the same photo, and the live probability
//! map of the boxes (issue 21). Figures are printed,
//! never asserted (docs/serve.md, Measured). Ignored by default; run with
//! `cargo test -p castellan --release --test serve_speed -- --ignored --nocapture`.

mod serve_support;

use std::path::Path;
use std::process::Command;
use std::time::Instant;

use integrate::synth::Castle;
use serve_support::{Server, demo_project};

const RUNS: usize = 3;
/// Plan pixels per metre giving a photo of the demo keep of about one megapixel.
const PX_PER_M: f64 = 41.0;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1000.0
}

/// Runs the command `RUNS` times; the median wall time in ms.
fn time_command(dir: &Path, args: &[&str]) -> f64 {
    median(
        (0..RUNS)
            .map(|_| {
                let t = Instant::now();
                let out = Command::new(env!("CARGO_BIN_EXE_castellan"))
                    .args(args)
                    .current_dir(dir)
                    .output()
                    .unwrap();
                assert!(
                    out.status.success(),
                    "{args:?}: {}",
                    String::from_utf8_lossy(&out.stderr)
                );
                ms(t)
            })
            .collect(),
    )
}

/// POSTs to a stage `RUNS` times and fetches the files it names; medians of the round trip
/// and of the server's own stage time, in ms, and the bytes fetched.
fn time_stage(server: &Server, path: &str, files: &[&str]) -> (f64, f64, usize) {
    let mut round = vec![];
    let mut stage = vec![];
    let mut bytes = 0;
    for _ in 0..RUNS {
        let t = Instant::now();
        let (status, body) = server.request("POST", path, b"");
        assert_eq!(status, 200, "{}", String::from_utf8_lossy(&body));
        let v: serde_json::Value = serde_json::from_slice(&body).unwrap();
        bytes = 0;
        for f in files {
            let (status, file) = server.request("GET", v[f].as_str().unwrap(), b"");
            assert_eq!(status, 200);
            bytes += file.len();
        }
        round.push(ms(t));
        stage.push(v["ms"].as_f64().unwrap());
    }
    (median(round), median(stage), bytes)
}

#[test]
#[ignore = "a measurement: run with --ignored --nocapture (docs/serve.md)"]
fn overlays_of_a_megapixel_photo_against_the_commands() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = demo_project(tmp.path());
    let castle = Castle::default();
    // A perspective photo to rectify and an elevation (already rectified) for the façade stage,
    // so the server's stage and the command do the same work on the same pixels.
    let tilted = castle.photo(PX_PER_M, 0.12, 1);
    let elevation = castle.photo(PX_PER_M, 0.0, 1);
    let mut toml = std::fs::read_to_string(dir.join("PROJECT.toml")).unwrap();
    for (name, photo, rectified) in [("tilted", &tilted, false), ("elevation", &elevation, true)] {
        photo.image.save(dir.join(format!("{name}.png"))).unwrap();
        std::fs::write(
            dir.join(format!("{name}.training.json")),
            serde_json::to_vec(&photo.training).unwrap(),
        )
        .unwrap();
        toml.push_str(&format!(
            "\n[[facade]]\nimage = \"{name}.png\"\ntraining = \"{name}.training.json\"\nrectified = {rectified}\n"
        ));
    }
    std::fs::write(dir.join("PROJECT.toml"), toml).unwrap();
    let (w, h) = tilted.image.dimensions();
    let mpx = f64::from(w * h) / 1e6;

    let server = Server::start(&dir);
    let (rect_round, rect_stage, rect_bytes) = time_stage(
        &server,
        "/api/facades/tilted.png/rectify",
        &["overlay", "rectified"],
    );
    let rect_cli = time_command(
        &dir,
        &[
            "rectify",
            "tilted.png",
            "-o",
            "cli_rectified.png",
            "--overlay",
            "cli_lines.png",
        ],
    );
    let (fac_round, fac_stage, fac_bytes) =
        time_stage(&server, "/api/facades/elevation.png/facade", &["overlay"]);
    let fac_cli = time_command(
        &dir,
        &[
            "facade",
            "elevation.png",
            "--training",
            "elevation.training.json",
            "-o",
            "cli_facade.json",
            "--overlay",
            "cli_facade.png",
        ],
    );
    // Issue 21: the live probability map the page asks for after each box, on the same photo.
    let boxes = serde_json::to_vec(&elevation.training).unwrap();
    let preview = median(
        (0..RUNS)
            .map(|_| {
                let t = Instant::now();
                let (status, png) =
                    server.request("POST", "/api/facades/elevation.png/preview", &boxes);
                assert_eq!(status, 200, "{}", String::from_utf8_lossy(&png));
                ms(t)
            })
            .collect(),
    );
    let figures = serde_json::json!({
        "photo": format!("{w}x{h} ({mpx:.2} Mpx)"),
        "rectify": {"serve_round_trip_ms": rect_round, "serve_stage_ms": rect_stage,
                    "fetched_bytes": rect_bytes, "cli_ms": rect_cli},
        "facade": {"serve_round_trip_ms": fac_round, "serve_stage_ms": fac_stage,
                   "fetched_bytes": fac_bytes, "cli_ms": fac_cli},
        "preview": {"serve_round_trip_ms": preview},
    });
    eprintln!("serve speed figures: {figures}");
    assert!(mpx > 0.9 && mpx < 1.2, "{mpx} Mpx");
}

/// Issue 22: a relabel on a 1000-px plan — the correction sent, checked and saved, the labels
/// overlay redrawn from the kept parse and fetched — against parsing the plan again.
#[test]
#[ignore = "a measurement: run with --ignored --nocapture (docs/serve.md)"]
fn a_relabel_on_a_1000_px_plan_against_a_parse() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = demo_project(tmp.path());
    // plan::synth's castle at 1.25 ×: 1000 × 750 px.
    let (plan, _) = plan::synth::castle(3, 1.25, 1000, 750);
    plan.save(dir.join("big.png")).unwrap();
    std::fs::write(dir.join("PROJECT.toml"), "plan = \"big.png\"\n").unwrap();
    let server = Server::start(&dir);
    let t = Instant::now();
    let (status, body) = server.request("POST", "/api/plan", b"");
    assert_eq!(status, 200, "{}", String::from_utf8_lossy(&body));
    let parse = ms(t);
    let labels = ["chapel", "great_hall", "courtyard", "unknown_room"];
    let mut round = vec![];
    let mut server_ms = vec![];
    for i in 0..9 {
        let fix = serde_json::json!({"label": [{"point": [500, 380], "label": labels[i % labels.len()]}]});
        let t = Instant::now();
        let (status, body) = server.request("PUT", "/api/corrections", fix.to_string().as_bytes());
        assert_eq!(status, 200, "{}", String::from_utf8_lossy(&body));
        let v: serde_json::Value = serde_json::from_slice(&body).unwrap();
        let (status, _) = server.request("GET", v["overlay"].as_str().unwrap(), b"");
        assert_eq!(status, 200);
        round.push(ms(t));
        server_ms.push(v["ms"].as_f64().unwrap());
    }
    println!(
        "relabel on a 1000 × 750 plan: round trip median {:.0} ms (server {:.0} ms), the first parse {parse:.0} ms; ratio {:.2}",
        median(round.clone()),
        median(server_ms),
        median(round) / parse
    );
}
