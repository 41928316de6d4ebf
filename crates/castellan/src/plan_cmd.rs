//! `castellan plan`: read a plan drawing, parse it (dissertation ch. 5), and write PLAN.json,
//! LABELS.png, the label overlay, the vector SVG and the extruded glTF model.

use std::path::PathBuf;
use std::time::Instant;

use clap::Args;

use anyhow::{Context, Result, anyhow};

use crate::output::Outputs;

use crate::images::png;

/// The parser's options from the command line; `--trim-ink` trims the learned ink only, so
/// with `--ink rules` it is refused rather than silently doing nothing.
fn options(args: &PlanArgs) -> Result<plan::Options> {
    if args.trim_ink && args.ink == plan::ink::InkMethod::Rules {
        return Err(anyhow!(
            "--trim-ink trims the learned wall ink; it does nothing with --ink rules, leave one of them out"
        ));
    }
    Ok(plan::Options {
        thin_lines: args
            .thin_lines
            .unwrap_or(plan::Options::default().thin_lines),
        hatching: args.hatching,
        hachures: args.hachures,
        dashes: !args.no_dashes,
        inner_ward_towers: !args.no_inner_towers,
        close_gates: !args.no_gates,
        trim_ink: args.trim_ink,
        one_building: args.one_building,
        ink: args.ink,
        ..Default::default()
    })
}

pub fn run(args: &PlanArgs) -> Result<()> {
    let options = options(args)?;
    let image = match (&args.batch, &args.image) {
        (Some(dir), _) => {
            return crate::plan_batch::run(dir, &args.output, args.metres_per_pixel, &options);
        }
        (None, Some(image)) => image,
        (None, None) => return Err(anyhow!("give a plan drawing or --batch DIR")),
    };
    let file = image.display().to_string();
    let img = crate::images::read_image(image)?;
    let started = Instant::now();
    let parsed = crate::progress::with_spinner("parsing the plan drawing (ch. 5)", |_| {
        plan::parse(&img, &options)
    })
    .map_err(|e| anyhow!("{file}: {e}"))?;
    let elapsed = started.elapsed();
    let given = plan::scale::GivenScale::from_options(args.metres_per_pixel, args.scale_bar_metres);
    let (model_scale, note) = plan::scale::ModelScale::decide(&parsed, given);
    let metres_per_pixel =
        (model_scale.units == plan::scale::Units::Metres).then_some(model_scale.units_per_pixel);

    let mut outputs = Outputs::default();
    let doc = plan::output::plan_json(&parsed, metres_per_pixel);
    outputs.add(&args.output, serde_json::to_vec_pretty(&doc)?);
    if let Some(path) = &args.labels {
        outputs.add(path, png(&plan::output::labels_image(&parsed), path)?);
        // Issue 22: LABELS.png is an index image; a person views LABELS.view.png.
        let view = crate::images::view_path(path);
        outputs.add(&view, png(&plan::output::labels_view(&parsed), &view)?);
    }
    if let Some(path) = &args.overlay {
        let over = plan::output::overlay(&parsed, &img.to_luma8());
        outputs.add(path, png(&over, path)?);
    }
    if let Some(path) = &args.walls {
        let over = plan::output::walls_overlay(&parsed, &img.to_luma8());
        outputs.add(path, png(&over, path)?);
    }
    if let Some(path) = &args.svg {
        outputs.add(path, plan::output::svg(&parsed).into_bytes());
    }
    if let Some(path) = &args.model {
        let src = plan::extrude::to_vsg(&parsed, &model_scale);
        let model = vsg::run(&src, &vsg::RunOptions::default()).map_err(|e| {
            anyhow!(
                "{}: internal error in the extrusion program: {}",
                path.display(),
                e.render("extrusion.vsg", &src).trim_end()
            )
        })?;
        let glb = vsg::export::to_glb(&model, &vsg::export::ExportOptions::default())
            .with_context(|| format!("cannot export {}", path.display()))?;
        outputs.add(path, glb);
    }
    outputs.commit()?;
    let count = |l: plan::label::Label| parsed.faces.iter().filter(|f| f.label == l).count();
    eprintln!(
        "{file}: {} x {} px, {} vertices, {} walls, {} faces ({} tower rooms), {} towers; parsed in {:.0} ms, written to {}",
        parsed.width,
        parsed.height,
        parsed.vertices.len(),
        parsed.edges.len(),
        parsed.faces.len(),
        count(plan::label::Label::TowerRoom),
        parsed.towers,
        elapsed.as_secs_f64() * 1e3,
        args.output.display()
    );
    for w in &parsed.warnings {
        eprintln!("{file}: warning: {w}");
    }
    match note {
        plan::scale::ScaleNote::Given => {}
        plan::scale::ScaleNote::Bar(how) => eprintln!("{file}: {how}"),
        plan::scale::ScaleNote::Assumed(how) if args.model.is_some() => {
            eprintln!("{file}: model in plan pixels; {how}")
        }
        plan::scale::ScaleNote::Assumed(_) => {}
        // Issue 22: a bar not found no longer stops the run; the outputs are in plan pixels.
        plan::scale::ScaleNote::BarNotFound { metres, assumed } => eprintln!(
            "{file}: warning: {}; give --scale METRES_PER_PIXEL, or click the bar's ends in `castellan serve` ({assumed})",
            plan::scale::no_bar_found(metres)
        ),
    }
    Ok(())
}

/// The label colours of the overlay and LABELS.view.png, for `castellan plan --help`.
fn label_legend() -> String {
    format!(
        "Label colours (the overlay, LABELS.view.png and the report's plan overlay; each picture also carries a key for the labels it shows; LABELS.png holds the index, 0 to 10, in this order):\n{}\n  scale bar frame      magenta (230, 0, 200)",
        plan::output::label_colours_text()
    )
}

/// `castellan plan` flags.
#[derive(Debug, Args)]
#[command(after_long_help = label_legend())]
pub struct PlanArgs {
    /// The plan drawing (PNG, JPEG or PNM).
    #[arg(required_unless_present = "batch")]
    pub image: Option<PathBuf>,
    /// Parse every drawing in this folder instead (in parallel); `-o` is then the output
    /// folder, which receives NAME.plan.json, NAME.labels.png, NAME.overlay.png, NAME.walls.png, NAME.svg
    /// per drawing and summary.csv (one row per file, failures with their reason).
    #[arg(long, value_name = "DIR", conflicts_with_all = ["image", "labels", "svg", "model", "overlay", "walls"])]
    pub batch: Option<PathBuf>,
    /// The parsed plan: vertices, labelled edges with fits, labelled faces with shapes
    /// (with --batch: the output folder).
    #[arg(short = 'o', long = "output", value_name = "PLAN.json")]
    pub output: PathBuf,
    /// 8-bit image of label indices (the legend of PLAN.json); LABELS.view.png beside it shows
    /// the labels in their colours with a key (colours: see --help).
    #[arg(long, value_name = "LABELS.png")]
    pub labels: Option<PathBuf>,
    /// The vectorised walls with their fitted lines and arcs.
    #[arg(long, value_name = "PLAN.svg")]
    pub svg: Option<PathBuf>,
    /// The §5.3 extruded model as binary glTF.
    #[arg(long, value_name = "MODEL.glb")]
    pub model: Option<PathBuf>,
    /// The drawing coloured by label, with a key of the labels it shows.
    #[arg(long, value_name = "OVERLAY.png")]
    pub overlay: Option<PathBuf>,
    /// The walls as read (red) over the drawing (grey): the learned wall ink, or the rules'
    /// threshold, after §5.1.2's open/close.
    #[arg(long, value_name = "WALLS.png")]
    pub walls: Option<PathBuf>,
    /// How the walls are read: `learned` (a wall-ink forest trained on synthetic and painted
    /// plans, issue 26), `network` (a small convolutional network trained on the same
    /// drawings: sharper walls, better on modern plans, fewer points right on castle plans) or
    /// `rules` (§5.1.2's threshold with the clean-up steps below, which act on it only; see
    /// docs/plan.md).
    #[arg(long, default_value = "learned", value_parser = crate::flags::ink)]
    pub ink: plan::ink::InkMethod,
    /// Drawing scale in metres per pixel; the model comes out in metres.
    #[arg(long = "scale", value_name = "METRES_PER_PIXEL", value_parser = crate::flags::metres_per_pixel)]
    pub metres_per_pixel: Option<f64>,
    /// Length in metres of the scale bar drawn on the plan: the bar is found in the drawing
    /// and the scale (metres per pixel) follows from its length in pixels.
    #[arg(long = "scale-bar", value_name = "METRES", value_parser = crate::flags::scale_bar_metres, conflicts_with_all = ["metres_per_pixel", "batch"])]
    pub scale_bar_metres: Option<f64>,
    /// Remove vault ribs: lines thinner than this fraction of the wall thickness drawn across
    /// a room that is round without them (0.3 finds Coucy's four corner towers round; off by
    /// default, see docs/plan.md).
    #[arg(long, value_name = "FRACTION", value_parser = crate::flags::fraction)]
    pub thin_lines: Option<f64>,
    /// The walls are drawn hatched: the paper between diagonal hatch strokes becomes wall
    /// (off by default: on plans with solid walls it takes hachured ditches for walls; see
    /// docs/plan.md).
    #[arg(long)]
    pub hatching: bool,
    /// Remove hachured slopes and moats: bands of short parallel thin strokes (off by
    /// default, see docs/plan.md).
    #[arg(long)]
    pub hachures: bool,
    /// Leave dotted and dashed lines as specks (by default chains of three or more
    /// collinear, evenly spaced dashes or dots are joined into a line; see docs/plan.md).
    #[arg(long)]
    pub no_dashes: bool,
    /// Count only the towers on the outer wall, as §5.1.6 (4) does (by default thick-walled
    /// towers bulging into a courtyard from a ward's wall count too; see docs/plan.md).
    #[arg(long)]
    pub no_inner_towers: bool,
    /// Leave gates and doors wider than two thirds of a wall open, as §5.1.2 does (by default
    /// a gap up to about twice the wall's thickness is plugged when that encloses a ward or a
    /// room; see docs/plan.md, "Gates").
    #[arg(long)]
    pub no_gates: bool,
    /// With the learned ink, give the walls' blur beyond the drawn ink and below even odds on
    /// the ink's map back to the rooms, courtyards and surroundings beside them after the
    /// parse, so that the labels and walls follow the drawing (off by default: the model then
    /// agrees with the plan less; see docs/plan.md, "Walls trimmed to the drawing").
    #[arg(long)]
    pub trim_ink: bool,
    /// The drawing shows one building (a measured survey), not a book page with several
    /// figures: keep every wall piece within six wall thicknesses of the castle, so that walls
    /// cut by windows and doors stay (by default only pieces within 3 % of the sheet join; on
    /// a book page this joins the next figure; see docs/plan.md, "One building").
    #[arg(long)]
    pub one_building: bool,
}

#[cfg(test)]
mod flag_tests {
    use std::path::PathBuf;

    use super::PlanArgs;
    use crate::flags::testing::parse;

    fn plan_args(extra: &[&str]) -> Result<PlanArgs, clap::Error> {
        let mut argv = vec!["castellan", "plan", "p.png", "-o", "plan.json"];
        argv.extend_from_slice(extra);
        parse::<PlanArgs>(&argv[2..])
    }

    #[test]
    fn plan_output_is_required() {
        assert!(parse::<PlanArgs>(&["p.png"]).is_err());
        let a = plan_args(&[]).unwrap();
        assert_eq!(a.output, PathBuf::from("plan.json"));
        assert_eq!(a.image, Some(PathBuf::from("p.png")));
    }

    #[test]
    fn plan_batch_flag_takes_a_folder_instead_of_an_image() {
        let a = parse::<PlanArgs>(&["--batch", "in", "-o", "out"]).unwrap();
        assert_eq!(a.batch, Some(PathBuf::from("in")));
        assert_eq!(a.image, None);
        assert!(parse::<PlanArgs>(&["-o", "out"]).is_err());
        assert!(plan_args(&["--batch", "in"]).is_err());
        assert!(parse::<PlanArgs>(&["--batch", "in", "-o", "o", "--svg", "s"]).is_err());
    }

    #[test]
    fn plan_labels_flag() {
        assert_eq!(
            plan_args(&["--labels", "l.png"]).unwrap().labels,
            Some(PathBuf::from("l.png"))
        );
    }

    #[test]
    fn plan_svg_flag() {
        assert_eq!(
            plan_args(&["--svg", "p.svg"]).unwrap().svg,
            Some(PathBuf::from("p.svg"))
        );
    }

    #[test]
    fn plan_model_flag() {
        assert_eq!(
            plan_args(&["--model", "m.glb"]).unwrap().model,
            Some(PathBuf::from("m.glb"))
        );
    }

    #[test]
    fn plan_overlay_flag() {
        assert_eq!(
            plan_args(&["--overlay", "o.png"]).unwrap().overlay,
            Some(PathBuf::from("o.png"))
        );
    }

    #[test]
    fn plan_scale_flag_is_positive() {
        assert_eq!(plan_args(&[]).unwrap().metres_per_pixel, None);
        assert_eq!(
            plan_args(&["--scale", "0.05"]).unwrap().metres_per_pixel,
            Some(0.05)
        );
        assert!(plan_args(&["--scale", "0"]).is_err());
        assert!(plan_args(&["--scale", "-1"]).is_err());
        assert!(plan_args(&["--scale", "nan"]).is_err());
        // Issue 19: a scale that would overflow the model is refused at the flag.
        let e = plan_args(&["--scale", "1e300"]).unwrap_err().to_string();
        assert!(
            e.contains("not a plausible scale in metres per pixel"),
            "{e}"
        );
        assert!(plan_args(&["--scale", "1e-9"]).is_err());
    }

    #[test]
    fn plan_ink_is_learned_or_rules_and_walls_names_a_picture() {
        use plan::ink::InkMethod;
        let a = plan_args(&[]).unwrap();
        assert_eq!((a.ink, a.walls), (InkMethod::Learned, None));
        let a = plan_args(&["--ink", "rules", "--walls", "w.png"]).unwrap();
        assert_eq!(
            (a.ink, a.walls),
            (InkMethod::Rules, Some(PathBuf::from("w.png")))
        );
        let a = plan_args(&["--ink", "network"]).unwrap();
        assert_eq!(a.ink, InkMethod::Network);
        let e = plan_args(&["--ink", "otsu"]).unwrap_err().to_string();
        assert!(e.contains("'otsu' is not a way to read walls"), "{e}");
    }

    #[test]
    fn plan_thin_lines_flag_is_a_fraction() {
        assert_eq!(plan_args(&[]).unwrap().thin_lines, None);
        assert_eq!(
            plan_args(&["--thin-lines", "0.3"]).unwrap().thin_lines,
            Some(0.3)
        );
        assert!(plan_args(&["--thin-lines", "1.5"]).is_err());
        assert!(plan_args(&["--thin-lines", "-0.1"]).is_err());
        assert!(plan_args(&["--thin-lines", "nan"]).is_err());
    }

    #[test]
    fn plan_clean_up_flags_are_off_unless_given() {
        let a = plan_args(&[]).unwrap();
        assert!(!a.hatching && !a.hachures && !a.no_dashes);
        let a = plan_args(&["--hatching", "--hachures", "--no-dashes"]).unwrap();
        assert!(a.hatching && a.hachures && a.no_dashes);
        assert!(plan_args(&["--no-dashes", "yes"]).is_err());
        assert!(plan_args(&["--dashes"]).is_err());
    }

    #[test]
    fn plan_inner_towers_are_on_unless_turned_off() {
        assert!(!plan_args(&[]).unwrap().no_inner_towers);
        assert!(plan_args(&["--no-inner-towers"]).unwrap().no_inner_towers);
        assert!(plan_args(&["--no-inner-towers", "yes"]).is_err());
        assert!(plan_args(&["--inner-towers"]).is_err());
    }

    #[test]
    fn plan_gates_are_plugged_unless_turned_off() {
        assert!(!plan_args(&[]).unwrap().no_gates);
        assert!(plan_args(&["--no-gates"]).unwrap().no_gates);
        assert!(plan_args(&["--no-gates", "yes"]).is_err());
        assert!(plan_args(&["--gates"]).is_err());
    }

    #[test]
    fn plan_walls_are_trimmed_only_when_asked() {
        assert!(!plan_args(&[]).unwrap().trim_ink);
        assert!(plan_args(&["--trim-ink"]).unwrap().trim_ink);
        assert!(plan_args(&["--trim-ink", "yes"]).is_err());
        assert!(
            super::options(&plan_args(&["--trim-ink"]).unwrap())
                .unwrap()
                .trim_ink
        );
        // The rules' walls have no blur to trim: the pair is refused, not ignored.
        let both = plan_args(&["--trim-ink", "--ink", "rules"]).unwrap();
        let err = super::options(&both).unwrap_err().to_string();
        assert!(
            err.contains("--trim-ink") && err.contains("--ink rules"),
            "{err}"
        );
    }

    #[test]
    fn plan_one_building_only_when_asked() {
        assert!(!plan_args(&[]).unwrap().one_building);
        assert!(plan_args(&["--one-building"]).unwrap().one_building);
        assert!(plan_args(&["--one-building", "yes"]).is_err());
        for ink in ["learned", "network", "rules"] {
            let a = plan_args(&["--one-building", "--ink", ink]).unwrap();
            assert!(super::options(&a).unwrap().one_building, "{ink}");
        }
        assert!(
            !super::options(&plan_args(&[]).unwrap())
                .unwrap()
                .one_building
        );
    }

    #[test]
    fn plan_scale_bar_flag_is_positive_and_excludes_scale() {
        assert_eq!(plan_args(&[]).unwrap().scale_bar_metres, None);
        assert_eq!(
            plan_args(&["--scale-bar", "30"]).unwrap().scale_bar_metres,
            Some(30.0)
        );
        assert!(plan_args(&["--scale-bar", "0"]).is_err());
        assert!(plan_args(&["--scale-bar", "30", "--scale", "0.1"]).is_err());
    }
}
