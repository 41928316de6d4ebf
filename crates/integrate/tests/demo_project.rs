//! The demo project shipped in examples/demo/ is the synthetic castle of `integrate::synth`:
//! this test checks that the shipped files are what the generator makes (pixel for pixel), and
//! `REGENERATE=1 cargo test -p integrate --test demo_project` rewrites them.

use std::path::PathBuf;

use integrate::synth::Castle;

fn demo_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples/demo")
}

/// Every file of the demo project: name and bytes (PNG files compared decoded).
fn generate() -> Vec<(String, Vec<u8>)> {
    let c = Castle::default();
    let encode = |img: image::DynamicImage| {
        let mut buf = std::io::Cursor::new(Vec::new());
        img.write_to(&mut buf, image::ImageFormat::Png).unwrap();
        buf.into_inner()
    };
    let mut files = vec![(
        "plan.png".to_string(),
        encode(image::DynamicImage::ImageLuma8(c.plan())),
    )];
    let shots = [
        ("keep_south_near", 20.0, 0.12, 1),
        ("keep_south_far", 13.0, 0.08, 2),
    ];
    let mut toml = String::from(
        "# The demo castle (integrate::synth): a curtain wall with two round towers and a keep,\n# drawn by castellan, and two perspective photos of the keep's south façade at different\n# scales. Training boxes and points are in each photo's pixels.\nplan = \"plan.png\"\nscale = 0.1  # metres per plan pixel\nseed = 7\n",
    );
    for (name, ppm, tilt, seed) in shots {
        let p = c.photo(ppm, tilt, seed);
        files.push((
            format!("{name}.png"),
            encode(image::DynamicImage::ImageRgb8(p.image)),
        ));
        files.push((
            format!("{name}.training.json"),
            serde_json::to_vec_pretty(&p.training).unwrap(),
        ));
        toml += &format!(
            "\n[[facade]]\nimage = \"{name}.png\"\ntraining = \"{name}.training.json\"\n\n[[correspondence]]\nfacade = \"{name}.png\"\nfacade_point = [{:.1}, {:.1}]\nplan_points = [[{:.1}, {:.1}]]\n",
            p.facade_point[0],
            p.facade_point[1],
            c.keep_south_point()[0],
            c.keep_south_point()[1]
        );
    }
    files.push(("PROJECT.toml".into(), toml.into_bytes()));
    let truth = serde_json::json!({
        "keep": {
            "height_m": c.keep_height,
            "width_m": c.keep_width(),
            "floors": c.floors,
            "windows_per_floor": c.windows,
            "window_width_m": c.window_width,
            "window_height_m": c.window_height,
        },
        "towers": c.towers.iter().map(|(p, r)| serde_json::json!({
            "center_m": [p[0] * c.metres_per_pixel, p[1] * c.metres_per_pixel],
            "outer_radius_m": (r + c.wall_px / 2.0) * c.metres_per_pixel,
        })).collect::<Vec<_>>(),
    });
    files.push((
        "TRUTH.json".into(),
        serde_json::to_vec_pretty(&truth).unwrap(),
    ));
    files
}

#[test]
fn shipped_demo_project_is_the_generators() {
    let dir = demo_dir();
    let files = generate();
    if std::env::var_os("REGENERATE").is_some() {
        std::fs::create_dir_all(&dir).unwrap();
        for (name, bytes) in &files {
            std::fs::write(dir.join(name), bytes).unwrap();
        }
        return;
    }
    for (name, bytes) in &files {
        let shipped = std::fs::read(dir.join(name))
            .unwrap_or_else(|e| panic!("examples/demo/{name}: {e} (REGENERATE=1 writes it)"));
        if name.ends_with(".png") {
            let a = image::load_from_memory(&shipped).unwrap();
            let b = image::load_from_memory(bytes).unwrap();
            assert!(a == b, "examples/demo/{name} differs from the generator's");
        } else {
            assert_eq!(
                String::from_utf8_lossy(&shipped),
                String::from_utf8_lossy(bytes),
                "examples/demo/{name}"
            );
        }
    }
}
