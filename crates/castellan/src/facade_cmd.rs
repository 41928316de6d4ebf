//! `castellan facade`: a rectified façade image and TRAINING.json → FACADE.json (façades, floors,
//! windows, the 18 parameters of §3.1.6), LABELS.png and an overlay; `--fix` applies the user's
//! corrections (issue 22, the keys of PROJECT.toml's `[facade.fix]`).

use anyhow::{Result, anyhow};
use clap::Args;
use facade::classify::{ClassifyParams, Method, Training};
use facade::fixes::FacadeFixes;
use facade::repeat::RepeatParams;
use facade::search::SearchParams;
use image::GrayImage;
use std::path::PathBuf;

use crate::images::png;
use crate::images::read_rgb;
use crate::output::Outputs;

pub fn run(args: &FacadeArgs) -> Result<()> {
    let file = args.image.display().to_string();
    let img = read_rgb(&args.image)?;
    let tfile = args.training.display().to_string();
    let training: Training = crate::text::read_json(&args.training, "a TRAINING.json")?;
    training
        .boxes(img.width() as usize, img.height() as usize)
        .map_err(|e| anyhow!("{tfile}: {e}"))?;
    let fixes: FacadeFixes = match &args.fix {
        Some(path) => {
            let fixes: FacadeFixes = crate::text::read_json(path, "a façade corrections file")?;
            fixes
                .validate(img.width(), img.height())
                .map_err(|e| anyhow!("{}: {e}", path.display()))?;
            fixes
        }
        None => FacadeFixes::default(),
    };
    let params = ClassifyParams::with(args.classifier, args.seed);
    let (ll, model, repeats) = crate::progress::with_spinner(
        "pixel classes (§3.1.2–3.1.4), repeated windows, façades, floors and windows (§3.1.5–3.1.7)",
        |_| {
            facade::parse_photo_with(
                &img,
                &training,
                &params,
                &SearchParams::default(),
                &RepeatParams {
                    grow: RepeatParams::default().grow.filter(|_| !args.boxes_as_drawn),
                    ..Default::default()
                },
                &fixes,
            )
        },
    )
    .map_err(|e| anyhow!("{file}: {e}"))?;
    let labels = model.labels();
    let mut outputs = Outputs::default();
    outputs.add(&args.output, serde_json::to_vec_pretty(&model)?);
    if let Some(lp) = &args.labels {
        let g = GrayImage::from_raw(model.width, model.height, labels.clone())
            .ok_or_else(|| anyhow!("label image size"))?;
        outputs.add(lp, png(&g, lp)?);
        // Issue 22: LABELS.png is an index image; a person views LABELS.view.png.
        let view = crate::images::view_path(lp);
        outputs.add(
            &view,
            png(
                &facade::draw::labels_view(model.width, model.height, &labels),
                &view,
            )?,
        );
    }
    if let Some(pp) = &args.probabilities {
        outputs.add(pp, png(&facade::draw::probability_overlay(&img, &ll), pp)?);
    }
    if let Some(op) = &args.overlay {
        outputs.add(op, png(&facade::draw::label_overlay(&img, &labels), op)?);
    }
    outputs.commit()?;
    // What looks implausible is said; the outputs are written as found.
    for w in facade::plausibility::check(&model, &training) {
        eprintln!("{file}: warning: {w}");
    }
    let windows: usize = model
        .facades
        .iter()
        .flat_map(|f| &f.floors)
        .map(|fl| fl.windows.len())
        .sum();
    // The window boxes were (or were grown into) whole windows: say how many repeats backed
    // the search.
    let grown = if training.whole_windows.is_empty() {
        "grown "
    } else {
        ""
    };
    let repeated = repeats.map_or(String::new(), |r| {
        format!(
            "; the {grown}windows' repeats proposed {} window(s) in {} column(s) and {} row(s)",
            r.windows.len(),
            r.columns.len(),
            r.rows.len()
        )
    });
    eprintln!(
        "{file}: {} façade(s), {} floor(s), {windows} window(s){repeated}; written to {}",
        model.facades.len(),
        model.facades.iter().map(|f| f.floors.len()).sum::<usize>(),
        args.output.display()
    );
    Ok(())
}

/// `castellan facade` flags.
#[derive(Debug, Args)]
pub struct FacadeArgs {
    /// The (rectified) façade image.
    pub image: PathBuf,
    /// User-drawn training boxes: {"classes": {"window": [[x0,y0,x1,y1], ...], "wall": [...], "background": [...]}}.
    #[arg(long, value_name = "TRAINING.json")]
    pub training: PathBuf,
    /// The façade trees with the 18 parameters of §3.1.6.
    #[arg(short = 'o', long = "output", value_name = "FACADE.json")]
    pub output: PathBuf,
    /// 8-bit label image: 0 background, 1 wall, 2 window.
    #[arg(long, value_name = "LABELS.png")]
    pub labels: Option<PathBuf>,
    /// Draw the façades, floors and windows over the image.
    #[arg(long, value_name = "OVERLAY.png")]
    pub overlay: Option<PathBuf>,
    /// The classifier's class probabilities over the image, before the search (§3.1.4):
    /// green window, magenta wall, red background, blended where the classifier is unsure.
    #[arg(long, value_name = "PROBABILITIES.png")]
    pub probabilities: Option<PathBuf>,
    /// Per-pixel classifier: forest (filter bank + random forest) or gmm (the dissertation's
    /// Gaussian mixtures on 18-D features, §3.1.3–3.1.4).
    #[arg(long, default_value = "forest", value_parser = crate::flags::classifier)]
    pub classifier: Method,
    /// Seed of the sampling of training pixels (and PCA pixels and EM for gmm, trees for forest).
    #[arg(long, default_value_t = 7)]
    pub seed: u64,
    /// Your corrections, in the image's pixels (the keys of PROJECT.toml's `[facade.fix]` as
    /// JSON): {"floor_lines": [y, …], "columns": [[left, right], …], "add_windows":
    /// [[x0, y0, x1, y1], …], "remove_windows": [[x, y], …], "blind_floors": [1, …]}; the search
    /// keeps the lines and columns given and finds the rest.
    #[arg(long, value_name = "FIX.json")]
    pub fix: Option<PathBuf>,
    /// Keep small window boxes as drawn (the text's user, §3.1.2). By default, when no box is
    /// a whole window, each window box is grown into the window it lies in on a first map and
    /// then trains as a whole window (its ring of wall, its repeats; docs/facade.md).
    #[arg(long)]
    pub boxes_as_drawn: bool,
}

#[cfg(test)]
mod flag_tests {
    use std::path::PathBuf;

    use super::FacadeArgs;
    use crate::flags::testing::parse;
    use facade::classify::Method;

    fn facade_args(extra: &[&str]) -> Result<FacadeArgs, clap::Error> {
        let mut argv = vec![
            "castellan",
            "facade",
            "f.png",
            "--training",
            "t.json",
            "-o",
            "f.json",
        ];
        argv.extend_from_slice(extra);
        parse::<FacadeArgs>(&argv[2..])
    }

    #[test]
    fn facade_training_and_output_are_required() {
        assert!(parse::<FacadeArgs>(&["f.png", "-o", "f.json"]).is_err());
        assert!(parse::<FacadeArgs>(&["f.png", "--training", "t.json"]).is_err());
        let a = facade_args(&[]).unwrap();
        assert_eq!(
            (a.training, a.output),
            (PathBuf::from("t.json"), PathBuf::from("f.json"))
        );
    }

    #[test]
    fn facade_labels_overlay_and_seed_flags() {
        let a = facade_args(&["--labels", "l.png", "--overlay", "o.png", "--seed", "9"]).unwrap();
        assert_eq!(a.labels, Some(PathBuf::from("l.png")));
        assert_eq!(a.overlay, Some(PathBuf::from("o.png")));
        assert_eq!(a.seed, 9);
    }

    #[test]
    fn facade_boxes_as_drawn_flag() {
        assert!(!facade_args(&[]).unwrap().boxes_as_drawn);
        assert!(facade_args(&["--boxes-as-drawn"]).unwrap().boxes_as_drawn);
    }

    #[test]
    fn facade_fix_flag() {
        assert_eq!(facade_args(&[]).unwrap().fix, None);
        let a = facade_args(&["--fix", "fix.json"]).unwrap();
        assert_eq!(a.fix, Some(PathBuf::from("fix.json")));
    }

    #[test]
    fn facade_probabilities_and_classifier_flags() {
        let a = facade_args(&[]).unwrap();
        assert_eq!((a.classifier, a.probabilities), (Method::Forest, None));
        let a = facade_args(&["--classifier", "gmm", "--probabilities", "p.png"]).unwrap();
        assert_eq!(a.classifier, Method::Gmm);
        assert_eq!(a.probabilities, Some(PathBuf::from("p.png")));
        let e = facade_args(&["--classifier", "GMMs"])
            .err()
            .unwrap()
            .to_string();
        assert!(e.contains("'GMMs' is not a classifier"), "{e}");
    }
}

/// Issue 4's bad inputs through the whole command: a clear error naming the file, nothing written.
#[cfg(test)]
mod bad_input_tests {
    use super::{FacadeArgs, Method, run};
    use image::{Rgb, RgbImage};

    /// Runs the command on `img` with TRAINING.json text `training`; returns the error text and
    /// whether FACADE.json was written.
    fn fails_with(img: &RgbImage, training: &str) -> (String, bool) {
        fails_with_fix(img, training, None)
    }

    /// [`fails_with`] with a corrections file's text.
    fn fails_with_fix(img: &RgbImage, training: &str, fix: Option<&str>) -> (String, bool) {
        let dir = tempfile::tempdir().unwrap();
        let (image, tfile) = (dir.path().join("f.png"), dir.path().join("t.json"));
        img.save(&image).unwrap();
        std::fs::write(&tfile, training).unwrap();
        let fix = fix.map(|text| {
            let path = dir.path().join("fix.json");
            std::fs::write(&path, text).unwrap();
            path
        });
        let output = dir.path().join("f.json");
        let args = FacadeArgs {
            image,
            training: tfile,
            output: output.clone(),
            labels: Some(dir.path().join("l.png")),
            overlay: None,
            probabilities: Some(dir.path().join("p.png")),
            classifier: Method::Forest,
            seed: 7,
            fix,
            boxes_as_drawn: false,
        };
        let err = run(&args).expect_err("bad input must fail");
        (
            format!("{err:#}"),
            output.exists()
                || dir.path().join("l.png").exists()
                || dir.path().join("p.png").exists(),
        )
    }

    fn two_tone() -> RgbImage {
        RgbImage::from_fn(60, 40, |x, _| {
            if x < 30 {
                Rgb([200, 150, 100])
            } else {
                Rgb([30, 40, 60])
            }
        })
    }

    #[test]
    fn empty_box_is_refused() {
        let (err, wrote) = fails_with(
            &two_tone(),
            r#"{"classes": {"window": [[40, 10, 40, 30]], "wall": [[2, 2, 20, 20]]}}"#,
        );
        assert!(
            err.contains("t.json") && err.contains("window box 0") && err.contains("zero area"),
            "{err}"
        );
        assert!(!wrote);
    }

    #[test]
    fn one_class_only_is_refused() {
        let (err, wrote) = fails_with(
            &two_tone(),
            r#"{"classes": {"window": [[40, 10, 50, 30]]}}"#,
        );
        assert!(
            err.contains("t.json") && err.contains("no wall boxes"),
            "{err}"
        );
        assert!(!wrote);
        let (err, _) = fails_with(&two_tone(), r#"{"classes": {}}"#);
        assert!(err.contains("no window boxes"), "{err}");
    }

    #[test]
    fn boxes_outside_the_image_are_refused() {
        let (err, wrote) = fails_with(
            &two_tone(),
            r#"{"classes": {"window": [[-50, -50, -10, -10]], "wall": [[2, 2, 20, 20]]}}"#,
        );
        assert!(
            err.contains("t.json") && err.contains("no pixels inside the 60x40"),
            "{err}"
        );
        assert!(!wrote);
    }

    #[test]
    fn single_colour_image_is_refused() {
        let flat = RgbImage::from_pixel(60, 40, Rgb([90, 90, 90]));
        let (err, wrote) = fails_with(
            &flat,
            r#"{"classes": {"window": [[40, 10, 50, 30]], "wall": [[2, 2, 20, 20]]}}"#,
        );
        assert!(
            err.contains("f.png") && err.contains("single colour"),
            "{err}"
        );
        assert!(!wrote);
    }

    #[test]
    fn malformed_training_is_refused() {
        let (err, wrote) = fails_with(&two_tone(), r#"{"classes": {"window": [[1, 2, 3]]}}"#);
        assert!(
            err.contains("t.json") && err.contains("not a TRAINING.json"),
            "{err}"
        );
        assert!(!wrote);
    }

    #[test]
    fn bad_corrections_are_refused_naming_the_file() {
        let training = r#"{"classes": {"window": [[40, 10, 50, 30]], "wall": [[2, 2, 20, 20]]}}"#;
        let (err, wrote) =
            fails_with_fix(&two_tone(), training, Some(r#"{"floor_lines": [10, 90]}"#));
        assert!(
            err.contains("fix.json")
                && err.contains("floor line 90 is below the façade (rectified height 40)"),
            "{err}"
        );
        assert!(!wrote);
        let (err, wrote) = fails_with_fix(&two_tone(), training, Some(r#"{"floors": [10]}"#));
        assert!(err.contains("fix.json") && err.contains("floors"), "{err}");
        assert!(!wrote);
    }
}
