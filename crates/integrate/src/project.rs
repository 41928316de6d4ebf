//! PROJECT.toml (§6.1.1): the plan drawing, the façade photos with their training boxes and
//! optional rectification lines, and the user's correspondences between façades and plan
//! shapes. Parsing is pure (text in, typed project out); errors name the entry at fault.

use facade::classify::Training;
use facade::fixes::FacadeFixes;
use plan::scale::GivenScale;
use serde::{Deserialize, Serialize};

use crate::corrections::{ScaleLine, StructureFix};

/// A whole reconstruction project; paths are relative to the PROJECT.toml file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Project {
    /// The plan drawing.
    pub plan: String,
    /// Metres per plan pixel (the key `scale`); the model comes out in metres when given.
    #[serde(default, rename = "scale", skip_serializing_if = "Option::is_none")]
    pub metres_per_pixel: Option<f64>,
    /// Length in metres of the scale bar drawn on the plan: the bar is found in the drawing
    /// (`plan::scalebar`) and the scale follows from its length in pixels. Instead of `scale`.
    #[serde(default, rename = "scale_bar", skip_serializing_if = "Option::is_none")]
    pub scale_bar_metres: Option<f64>,
    /// Thin lines (vault ribs) removed from round rooms of the plan before parsing, as a
    /// fraction of the wall thickness (`castellan plan --thin-lines`); off when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thin_lines: Option<f64>,
    /// The plan's walls are drawn hatched: the paper between diagonal hatch strokes is filled
    /// before parsing (`castellan plan --hatching`); off when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub hatching: Option<bool>,
    /// The plan shows one building (a measured survey), not a book page with several figures:
    /// wall pieces within six wall thicknesses of the castle are kept (`castellan plan
    /// --one-building`); off when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub one_building: Option<bool>,
    /// After the parse, the learned walls are trimmed to the drawn ink and to even odds on the
    /// ink's map, so they follow the drawing (`castellan plan --trim-ink`); off when absent.
    /// Not with `ink = "rules"`, whose walls have no blur to trim.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub trim_ink: Option<bool>,
    /// How the plan's walls are read: `learned` (the default when absent: the learned wall
    /// ink) or `rules` (§5.1.2's threshold and the clean-up rules; `castellan plan --ink`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ink: Option<plan::ink::InkMethod>,
    /// The user's "wall" / "not wall" strokes on the plan drawing (its pixels), which refine
    /// the learned wall ink for this drawing (`castellan serve`'s plan step).
    #[serde(default, rename = "ink_stroke", skip_serializing_if = "Vec::is_empty")]
    pub ink_strokes: Vec<plan::ink::refine::InkStroke>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub seed: Option<u64>,
    /// The scale from two plan points and the length between them (`castellan serve`'s scale
    /// tool); it wins over `scale` and `scale_bar`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scale_line: Option<ScaleLine>,
    /// Where the drawing stands on a map (`[site]`: EPSG code, origin, north), for the
    /// CityJSON and IFC files' placement (issue 24).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub site: Option<crate::heritage::Site>,
    /// The user's corrections of the plan's regions (issue 22), by plan pixel.
    #[serde(default, rename = "label", skip_serializing_if = "Vec::is_empty")]
    pub label_fixes: Vec<plan::corrections::LabelFix>,
    /// Towers the parser missed or invented.
    #[serde(default, rename = "tower", skip_serializing_if = "Vec::is_empty")]
    pub tower_fixes: Vec<plan::corrections::TowerFix>,
    /// Regions that are one.
    #[serde(default, rename = "merge", skip_serializing_if = "Vec::is_empty")]
    pub merges: Vec<plan::corrections::MergeFix>,
    /// Heights, roofs, crenellation and the keep, by plan pixel.
    #[serde(default, rename = "structure", skip_serializing_if = "Vec::is_empty")]
    pub structure_fixes: Vec<StructureFix>,
    #[serde(default, rename = "facade", skip_serializing_if = "Vec::is_empty")]
    pub facades: Vec<FacadeEntry>,
    /// Gothic façade photos (ch. 4): their arches and stones replace the wall they map to.
    #[serde(default, rename = "gothic", skip_serializing_if = "Vec::is_empty")]
    pub gothics: Vec<GothicEntry>,
    #[serde(
        default,
        rename = "correspondence",
        skip_serializing_if = "Vec::is_empty"
    )]
    pub correspondences: Vec<Correspondence>,
    /// Sample regions cut from the photos as random per-shape textures (§7.2.2, figure 7.6).
    #[serde(default, rename = "texture", skip_serializing_if = "Vec::is_empty")]
    pub textures: Vec<TextureSamples>,
}

/// One façade photo.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FacadeEntry {
    pub image: String,
    /// A TRAINING.json file, or the boxes inline (`training = { classes = { … } }`).
    pub training: TrainingSource,
    /// Rectification segments (the LINES.json contract) replacing the automatic ones.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lines: Option<String>,
    /// The photo is already a rectified elevation: skip §3.1.1.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub rectified: bool,
    /// The façade's outline [x0, y0, x1, y1] in the photo's pixels, drawn by the user: the
    /// façade search then stays inside it and skips §3.1.5's boundary search (which splits an
    /// engraved elevation's shading into strips; docs/gallery.md).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bbox: Option<[f64; 4]>,
    /// Metres per pixel of a measured elevation (from its scale bar): the façade is then scaled
    /// by it instead of by the plan width it is mapped to (§6.1.2's s = w_p / w_f). The key is
    /// `scale`.
    #[serde(default, rename = "scale", skip_serializing_if = "Option::is_none")]
    pub metres_per_pixel: Option<f64>,
    /// The user's corrections of the façade estimate (issue 22), the `[facade.fix]` table: floor
    /// lines, window columns, windows added and removed, floors without windows, in pixels of
    /// the rectified photo (of its part inside `bbox` when given); checked against its size
    /// when the photo is estimated.
    #[serde(default, skip_serializing_if = "FacadeFixes::is_empty")]
    pub fix: FacadeFixes,
}

fn is_box(b: &[f64; 4]) -> bool {
    b.iter().all(|v| v.is_finite()) && b[2] > b[0] && b[3] > b[1]
}

/// A Gothic façade photo (ch. 4): no training boxes; the façade is the part of the
/// (rectified) photo inside `bbox`, or all of it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GothicEntry {
    pub image: String,
    /// The façade's extent [x0, y0, x1, y1] in the photo's pixels.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bbox: Option<[f64; 4]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lines: Option<String>,
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub rectified: bool,
    /// The user's corrections of the detected elements (issue 22; `[[gothic.element]]`), in
    /// the rectified photo's pixels: an element picked by a point inside it, deleted or given
    /// its springing line, apex, width, centre or sill; or an element added.
    #[serde(default, rename = "element", skip_serializing_if = "Vec::is_empty")]
    pub elements: Vec<facade::gothic::ElementCorrection>,
}

/// How errors and provenance name one Gothic element correction (indices from 0).
pub fn gothic_element_entry(gothic: usize, element: usize, image: &str) -> String {
    format!(
        "[[gothic]] #{} element #{} (image = \"{image}\")",
        gothic + 1,
        element + 1
    )
}

/// Where a façade's training boxes come from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum TrainingSource {
    File(String),
    Inline(Training),
}

/// §6.1.1: a point inside a façade of a photo and one point inside a plan shape (two, start
/// and end counter-clockwise, for an arc of a circle).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Correspondence {
    pub facade: String,
    pub facade_point: [f64; 2],
    pub plan_points: Vec<[f64; 2]>,
}

/// The classes texture samples can be given for (an unknown class is refused when
/// PROJECT.toml is parsed, at its line and column).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum TextureClass {
    /// Walls without a photo of their own pick one of these per shape.
    Wall,
}

/// Texture samples of one semantic class: boxes [x0, y0, x1, y1] in a photo.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TextureSamples {
    pub class: TextureClass,
    pub image: String,
    pub boxes: Vec<[f64; 4]>,
}

/// A project that cannot be used, with the entry at fault.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum ProjectError {
    #[error("{line}:{column}: {message}")]
    Syntax {
        line: usize,
        column: usize,
        message: String,
    },
    #[error("{0}")]
    Invalid(String),
}

impl Project {
    /// How the plan drawing is parsed: every command that parses a project's plan (reconstruct,
    /// the server's plan stage) uses these, so its overlay and its model agree.
    pub fn plan_options(&self) -> plan::Options {
        plan::Options {
            thin_lines: self.thin_lines.unwrap_or(0.0),
            hatching: self.hatching.unwrap_or(false),
            one_building: self.one_building.unwrap_or(false),
            trim_ink: self.trim_ink.unwrap_or(false),
            ink: self.ink.unwrap_or_default(),
            ink_strokes: self.ink_strokes.clone(),
            seed: self.seed.unwrap_or(0),
            ..Default::default()
        }
    }

    /// What the project says of the drawing's scale: the clicked `scale_line` first, then
    /// `scale_bar`, then `scale`.
    pub fn given_scale(&self) -> GivenScale {
        match &self.scale_line {
            Some(line) => GivenScale::from_options(Some(line.metres_per_pixel()), None),
            None => GivenScale::from_options(self.metres_per_pixel, self.scale_bar_metres),
        }
    }

    /// The plan's corrections, in the order they apply.
    pub fn plan_fixes(&self) -> plan::corrections::PlanFixes<'_> {
        plan::corrections::PlanFixes {
            merges: &self.merges,
            labels: &self.label_fixes,
            towers: &self.tower_fixes,
        }
    }

    /// Parses and checks a PROJECT.toml text.
    pub fn from_toml(text: &str) -> Result<Project, ProjectError> {
        let project = Project::parse_unchecked(text)?;
        project.check()?;
        Ok(project)
    }

    /// Parses a PROJECT.toml text without the checks of [`Project::from_toml`]: for a project
    /// still being made (`serve` saves one before every façade has its correspondence).
    pub fn parse_unchecked(text: &str) -> Result<Project, ProjectError> {
        toml::from_str(text).map_err(|e| {
            let (line, column) = e
                .span()
                .map(|s| line_column(text, s.start))
                .unwrap_or((1, 1));
            ProjectError::Syntax {
                line,
                column,
                message: e.message().trim().to_string(),
            }
        })
    }

    /// The project as TOML text (what `serve` saves).
    pub fn to_toml(&self) -> String {
        toml::to_string_pretty(self).unwrap_or_default()
    }

    fn check(&self) -> Result<(), ProjectError> {
        let bad = |m: String| Err(ProjectError::Invalid(m));
        if self.plan.trim().is_empty() {
            return bad("plan: the plan drawing's file name is empty".into());
        }
        if let Some(s) = self.metres_per_pixel
            && let Err(why) =
                plan::scale::check_range(s, &plan::scale::METRES_PER_PIXEL, "metres per plan pixel")
        {
            return bad(format!("scale = {s}: {why}"));
        }
        if let Some(m) = self.scale_bar_metres {
            if let Err(why) = plan::scale::check_range(
                m,
                &plan::scale::SCALE_BAR_METRES,
                "scale-bar length in metres",
            ) {
                return bad(format!("scale_bar = {m}: {why}"));
            }
            if self.metres_per_pixel.is_some() {
                return bad("give either scale (metres per pixel) or scale_bar (the drawn bar's length in metres), not both".into());
            }
        }
        if let Some(Err(why)) = self.scale_line.as_ref().map(ScaleLine::check) {
            return bad(format!("scale_line: {why}"));
        }
        if let Some(Err(why)) = self.site.as_ref().map(crate::heritage::Site::check) {
            return bad(format!("[site] {why}"));
        }
        if let Some(t) = self.thin_lines
            && !(0.0..=1.0).contains(&t)
        {
            return bad(format!(
                "thin_lines = {t}: a fraction of the wall thickness, from 0 to 1"
            ));
        }
        if self.trim_ink == Some(true) && self.ink == Some(plan::ink::InkMethod::Rules) {
            return bad("trim_ink = true trims the learned wall ink; it does nothing with ink = \"rules\", leave one of them out".into());
        }
        // The drawing's size is checked when it is parsed; here, everything else.
        if let Err(e) = plan::ink::refine::check(&self.ink_strokes, u32::MAX, u32::MAX) {
            return bad(format!("[[ink_stroke]]: {e}"));
        }
        let mut images: Vec<&str> = self.facades.iter().map(|f| f.image.as_str()).collect();
        images.extend(self.gothics.iter().map(|g| g.image.as_str()));
        let entry = |kind: &str, i: usize, image: &str, problem: &str| {
            bad(format!(
                "[[{kind}]] #{} (image = \"{image}\"): {problem}",
                i + 1
            ))
        };
        let mapped = |image: &str| self.correspondences.iter().any(|c| c.facade == image);
        const TWICE: &str = "this image is listed twice";
        const UNMAPPED: &str = "no [[correspondence]] maps this façade to a plan shape";
        const NOT_A_BOX: &str = "bbox must be [x0, y0, x1, y1] with x1 > x0 and y1 > y0";
        for (i, g) in self.gothics.iter().enumerate() {
            if images.iter().filter(|n| **n == g.image).count() > 1 {
                return entry("gothic", i, &g.image, TWICE);
            }
            if !mapped(&g.image) {
                return entry("gothic", i, &g.image, UNMAPPED);
            }
            if g.bbox.is_some_and(|b| !is_box(&b)) {
                return entry("gothic", i, &g.image, NOT_A_BOX);
            }
            for (j, c) in g.elements.iter().enumerate() {
                if let Err(why) = c.action() {
                    return bad(format!("{}: {why}", gothic_element_entry(i, j, &g.image)));
                }
            }
        }
        for (i, f) in self.facades.iter().enumerate() {
            if let Some(Err(why)) = f.metres_per_pixel.map(|m| {
                plan::scale::check_range(m, &plan::scale::METRES_PER_PIXEL, "metres per pixel")
            }) {
                return entry("facade", i, &f.image, &format!("scale: {why}"));
            }
            if f.bbox.is_some_and(|b| !is_box(&b)) {
                return entry("facade", i, &f.image, NOT_A_BOX);
            }
            if self.facades[..i].iter().any(|g| g.image == f.image) {
                return entry("facade", i, &f.image, TWICE);
            }
        }
        for (i, c) in self.correspondences.iter().enumerate() {
            let at = format!("[[correspondence]] #{} (facade = \"{}\")", i + 1, c.facade);
            if !images.contains(&c.facade.as_str()) {
                return bad(format!(
                    "{at}: no [[facade]] or [[gothic]] entry has this image"
                ));
            }
            if !(1..=2).contains(&c.plan_points.len()) {
                return bad(format!(
                    "{at}: plan_points takes one point (two, start and end counter-clockwise, for an arc of a circle); found {}",
                    c.plan_points.len()
                ));
            }
            let finite = |p: &[f64; 2]| p.iter().all(|v| v.is_finite());
            if !finite(&c.facade_point) || !c.plan_points.iter().all(finite) {
                return bad(format!("{at}: points must be finite pixel coordinates"));
            }
        }
        for (i, f) in self.facades.iter().enumerate() {
            if !mapped(&f.image) {
                return entry("facade", i, &f.image, UNMAPPED);
            }
        }
        for (i, t) in self.textures.iter().enumerate() {
            if t.boxes.is_empty() {
                return bad(format!(
                    "[[texture]] #{} (image = \"{}\"): no boxes",
                    i + 1,
                    t.image
                ));
            }
        }
        Ok(())
    }
}

fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, column)
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"
plan = "plan.png"
scale = 0.05
seed = 7

[[facade]]
image = "keep_south.jpg"
training = "keep_south.training.json"

[[facade]]
image = "keep_east.jpg"
training = { classes = { window = [[10, 10, 20, 20]], wall = [[0, 0, 5, 5]] } }
rectified = true

[[correspondence]]
facade = "keep_south.jpg"
facade_point = [412, 300]
plan_points = [[640, 820]]

[[correspondence]]
facade = "keep_east.jpg"
facade_point = [100, 100]
plan_points = [[10, 10], [20, 20]]
"#;

    #[test]
    fn the_contract_example_parses() {
        let p = Project::from_toml(GOOD).unwrap();
        assert_eq!(p.plan, "plan.png");
        assert_eq!(p.metres_per_pixel, Some(0.05));
        assert_eq!(p.facades.len(), 2);
        assert!(matches!(p.facades[0].training, TrainingSource::File(_)));
        assert!(matches!(p.facades[1].training, TrainingSource::Inline(_)));
        assert!(p.facades[1].rectified);
        assert_eq!(p.correspondences[1].plan_points.len(), 2);
        assert_eq!(Project::from_toml(&p.to_toml()).unwrap(), p, "round trip");
    }

    #[test]
    fn syntax_errors_have_line_and_column() {
        let e = Project::from_toml("plan = \"a.png\"\nscale = [oops\n").unwrap_err();
        let ProjectError::Syntax { line, .. } = e else {
            panic!("{e:?}")
        };
        assert_eq!(line, 2);
        let e = Project::from_toml("plan = \"a.png\"\nscael = 1\n").unwrap_err();
        assert!(e.to_string().starts_with("2:1:"), "{e}");
    }

    #[test]
    fn entries_at_fault_are_named() {
        let missing = GOOD.replace("facade = \"keep_east.jpg\"", "facade = \"nope.jpg\"");
        let e = Project::from_toml(&missing).unwrap_err().to_string();
        assert!(
            e.contains("[[correspondence]] #2") && e.contains("nope.jpg"),
            "{e}"
        );
        let three = GOOD.replace("[[10, 10], [20, 20]]", "[[1, 1], [2, 2], [3, 3]]");
        let e = Project::from_toml(&three).unwrap_err().to_string();
        assert!(e.contains("plan_points"), "{e}");
        let e = Project::from_toml(&GOOD.replace("0.05", "-1"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("scale"), "{e}");
        let both = with_line("scale_bar = 50");
        let e = Project::from_toml(&both).unwrap_err().to_string();
        assert!(e.contains("not both"), "{e}");
        let bar = GOOD.replace("scale = 0.05", "scale_bar = 50");
        assert_eq!(
            Project::from_toml(&bar).unwrap().scale_bar_metres,
            Some(50.0)
        );
        let e = Project::from_toml(&GOOD.replace("scale = 0.05", "scale_bar = -2"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("scale_bar"), "{e}");
        let ribs = with_line("thin_lines = 0.3");
        let ribbed = Project::from_toml(&ribs).unwrap();
        assert_eq!(ribbed.thin_lines, Some(0.3));
        assert_eq!(ribbed.plan_options().thin_lines, 0.3);
        let plain = Project::from_toml(GOOD).unwrap().plan_options();
        assert_eq!(plain.thin_lines, plan::Options::default().thin_lines);
        assert!(!plain.hatching);
        let hatched = with_line("hatching = true");
        assert!(
            Project::from_toml(&hatched)
                .unwrap()
                .plan_options()
                .hatching
        );
        let e = Project::from_toml(&with_line("thin_lines = 2"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("thin_lines = 2"), "{e}");
    }

    /// [`GOOD`] with `line` after its scale, so on line 4.
    fn with_line(line: &str) -> String {
        GOOD.replace("scale = 0.05", &format!("scale = 0.05\n{line}"))
    }

    /// A boolean plan key: off when absent, `key = true` reaches the plan options (`get`) and
    /// survives a save, and `key = bad` is refused at `position` as not a boolean.
    fn boolean_plan_key(
        key: &str,
        get: impl Fn(&plan::Options) -> bool,
        bad: &str,
        position: &str,
    ) {
        assert!(
            !get(&Project::from_toml(GOOD).unwrap().plan_options()),
            "{key}"
        );
        let p = Project::from_toml(&with_line(&format!("{key} = true"))).unwrap();
        assert!(get(&p.plan_options()), "{key}");
        assert_eq!(Project::from_toml(&p.to_toml()).unwrap(), p);
        let e = Project::from_toml(&with_line(&format!("{key} = {bad}")))
            .unwrap_err()
            .to_string();
        // Named by its line and column, as every bad value of PROJECT.toml is.
        assert!(e.contains(position) && e.contains("boolean"), "{e}");
    }

    #[test]
    fn trim_ink_reaches_the_plan_options_and_not_with_the_rules() {
        boolean_plan_key("trim_ink", |o| o.trim_ink, "\"yes\"", "4:12");
        let network = with_line("trim_ink = true\nink = \"network\"");
        assert!(
            Project::from_toml(&network)
                .unwrap()
                .plan_options()
                .trim_ink
        );
        let rules = with_line("trim_ink = true\nink = \"rules\"");
        let e = Project::from_toml(&rules).unwrap_err().to_string();
        assert!(e.contains("trim_ink") && e.contains("rules"), "{e}");
    }

    #[test]
    fn one_building_reaches_the_plan_options_and_must_be_a_boolean() {
        boolean_plan_key("one_building", |o| o.one_building, "1", "4:16");
    }

    #[test]
    fn the_ink_method_and_the_users_ink_strokes_reach_the_plan_options() {
        use plan::ink::InkMethod;
        assert_eq!(
            Project::from_toml(GOOD).unwrap().plan_options().ink,
            InkMethod::Learned
        );
        let rules = with_line("ink = \"rules\"");
        assert_eq!(
            Project::from_toml(&rules).unwrap().plan_options().ink,
            InkMethod::Rules
        );
        let network = with_line("ink = \"network\"");
        assert_eq!(
            Project::from_toml(&network).unwrap().plan_options().ink,
            InkMethod::Network
        );
        let e = Project::from_toml(&with_line("ink = \"otsu\""))
            .unwrap_err()
            .to_string();
        assert!(e.contains("otsu"), "{e}");
        let stroked = format!(
            "{GOOD}\n[[ink_stroke]]\nwall = false\nradius = 3\npoints = [[10, 12], [40, 12]]\n"
        );
        let p = Project::from_toml(&stroked).unwrap();
        assert_eq!(p.plan_options().ink_strokes.len(), 1);
        assert!(!p.plan_options().ink_strokes[0].wall);
        // Saved and read again, the strokes survive.
        assert_eq!(Project::from_toml(&p.to_toml()).unwrap(), p);
        let e = Project::from_toml(&stroked.replace("radius = 3", "radius = -1"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("[[ink_stroke]]") && e.contains("ink stroke 0"),
            "{e}"
        );
    }

    /// Issue 19: `scale = 1e300` once surfaced as an internal error of the generated program.
    #[test]
    fn an_implausible_scale_is_refused_naming_the_entry() {
        for bad in ["scale = 1e300", "scale = 1e-300", "scale = inf"] {
            let e = Project::from_toml(&GOOD.replace("scale = 0.05", bad))
                .unwrap_err()
                .to_string();
            assert!(
                e.contains("scale = ") && e.contains("not a plausible"),
                "{e}"
            );
        }
        let e = Project::from_toml(&GOOD.replace("scale = 0.05", "scale_bar = 1e12"))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("scale_bar = ") && e.contains("not a plausible"),
            "{e}"
        );
        assert!(Project::from_toml(&GOOD.replace("scale = 0.05", "scale = 100")).is_ok());
    }

    /// Issue 11: a measured elevation's outline and scale are checked like the plan's.
    #[test]
    fn facade_outline_and_scale_are_checked() {
        let with =
            |extra: &str| GOOD.replace("rectified = true", &format!("rectified = true\n{extra}"));
        let p = Project::from_toml(&with("bbox = [1, 2, 30, 40]\nscale = 0.126")).unwrap();
        assert_eq!(p.facades[1].bbox, Some([1.0, 2.0, 30.0, 40.0]));
        assert_eq!(p.facades[1].metres_per_pixel, Some(0.126));
        assert_eq!(Project::from_toml(&p.to_toml()).unwrap(), p, "round trip");
        let e = Project::from_toml(&with("bbox = [30, 2, 1, 40]"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("[[facade]] #2") && e.contains("bbox"), "{e}");
        let e = Project::from_toml(&with("scale = 0"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("[[facade]] #2") && e.contains("scale"), "{e}");
    }

    /// Issue 22: the user's façade corrections, a `[facade.fix]` table under its entry.
    #[test]
    fn facade_fixes_parse_and_round_trip() {
        let fixed = GOOD.replace(
            "rectified = true\n",
            "rectified = true\n\n[facade.fix]\nfloor_lines = [120, 240.5]\ncolumns = [[10, 40], [60, 90]]\nadd_windows = [[5, 5, 15, 20]]\nremove_windows = [[70, 130]]\nblind_floors = [1]\n",
        );
        let p = Project::from_toml(&fixed).unwrap();
        let fix = &p.facades[1].fix;
        assert_eq!(fix.floor_lines, Some(vec![120.0, 240.5]));
        assert_eq!(fix.columns, Some(vec![[10.0, 40.0], [60.0, 90.0]]));
        assert_eq!(fix.add_windows, vec![[5.0, 5.0, 15.0, 20.0]]);
        assert_eq!(fix.remove_windows, vec![[70.0, 130.0]]);
        assert_eq!(fix.blind_floors, vec![1]);
        assert!(p.facades[0].fix.is_empty());
        let text = p.to_toml();
        assert!(text.contains("[facade.fix]"), "{text}");
        assert!(!text.contains("remove_windows = []"), "{text}");
        assert_eq!(Project::from_toml(&text).unwrap(), p, "round trip");
        let e = Project::from_toml(&fixed.replace("blind_floors", "blind_floor"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("blind_floor"), "{e}");
    }
}
