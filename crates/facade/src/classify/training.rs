//! TRAINING.json (§3.1.2): the semantic classes and the user's boxes, checked against the
//! image and clipped to it. What every stage that reads boxes (the façade and Gothic commands,
//! the pipeline, the server) refuses, naming the class or whole window and the box's index.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::error::{FacadeError, Result};

/// The semantic classes; the discriminant is the LABELS.png value.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Class {
    Background = 0,
    Wall = 1,
    Window = 2,
}

impl Class {
    pub const ALL: [Class; 3] = [Class::Background, Class::Wall, Class::Window];
    pub fn name(self) -> &'static str {
        match self {
            Class::Background => "background",
            Class::Wall => "wall",
            Class::Window => "window",
        }
    }
}

/// TRAINING.json: `{"classes": {"window": [[x0, y0, x1, y1], ...], "wall": [...],
/// "background": [...]}, "whole_windows": [[x0, y0, x1, y1], ...]}`, rectangles in pixels of
/// the image (§3.1.2); `whole_windows` is optional.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Training {
    /// Boxes by class; an unknown class name is refused when the file is parsed, at its line
    /// and column.
    pub classes: BTreeMap<Class, Vec<[f64; 4]>>,
    /// Windows the user outlined whole, frame included (issue 21; not the text's user, who
    /// draws inside a class): each is a window box, the ring just outside it trains the wall,
    /// and they are the templates whose repeats back the search (`crate::repeat`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub whole_windows: Vec<[f64; 4]>,
}

/// A training box clipped to the image: x0..x1, y0..y1 (exclusive ends).
pub type PixelBox = [usize; 4];

/// Most boxes one TRAINING.json may hold, over all classes. The classifier samples
/// `samples_per_box` pixels of every box and fits one mixture component per box (§3.1.3), so
/// its memory and time grow with the count: 200 000 boxes took 1.9 GB. A user draws tens;
/// 1000 leaves room for generated sets and keeps the façade stage within a few MB of samples.
pub const MAX_BOXES: usize = 1000;

impl Training {
    /// Checks the boxes against the image and returns them per class, clipped to it. Window and
    /// wall are required; background is optional (without it the whole image is one façade).
    /// Refused, naming the class and the box's index: more than
    /// [`MAX_BOXES`] boxes, a coordinate that is not finite, an inverted box (x1 < x0 or
    /// y1 < y0), a box of zero area and a box with no pixel inside the image. A box that
    /// overlaps an edge is clipped (a box dragged past the photo's edge means "up to the edge").
    pub fn boxes(&self, width: usize, height: usize) -> Result<BTreeMap<Class, Vec<PixelBox>>> {
        let out = self.checked(width, height)?;
        for need in [Class::Window, Class::Wall] {
            if !out.contains_key(&need) {
                return Err(FacadeError::BadTraining(format!(
                    "no {} boxes: window and wall boxes are required (background is optional)",
                    need.name()
                )));
            }
        }
        Ok(out)
    }

    /// The checks of [`Training::boxes`] without requiring window and wall boxes: what a set
    /// still being drawn must pass (an editor saves it before every class has its boxes).
    pub fn validate(&self, width: usize, height: usize) -> Result<()> {
        self.checked(width, height).map(|_| ())
    }

    /// The whole windows ([`Training::whole_windows`]) clipped to the image, each checked as
    /// [`Training::validate`] checks it (the callers have validated the whole set).
    pub fn whole_window_boxes(&self, width: usize, height: usize) -> Result<Vec<PixelBox>> {
        self.whole_windows
            .iter()
            .enumerate()
            .map(|(i, b)| clip(b, "whole window", i, width, height))
            .collect()
    }

    /// Every class box checked and clipped, the whole windows among the window boxes (after
    /// the class's own).
    fn checked(&self, width: usize, height: usize) -> Result<BTreeMap<Class, Vec<PixelBox>>> {
        let count: usize =
            self.classes.values().map(Vec::len).sum::<usize>() + self.whole_windows.len();
        if count > MAX_BOXES {
            return Err(FacadeError::BadTraining(format!(
                "{count} boxes, more than the limit of {MAX_BOXES}"
            )));
        }
        let mut out = BTreeMap::new();
        for (&class, boxes) in &self.classes {
            let name = class.name();
            let mut v = Vec::new();
            for (i, b) in boxes.iter().enumerate() {
                v.push(clip(b, name, i, width, height)?);
            }
            if !v.is_empty() {
                out.insert(class, v);
            }
        }
        for (i, b) in self.whole_windows.iter().enumerate() {
            let b = clip(b, "whole window", i, width, height)?;
            out.entry(Class::Window).or_default().push(b);
        }
        Ok(out)
    }
}

/// One box checked and clipped to the image; errors name it as `{name} box {i}`.
fn clip(b: &[f64; 4], name: &str, i: usize, width: usize, height: usize) -> Result<PixelBox> {
    let bad = |why: &str| FacadeError::BadTraining(format!("{name} box {i} {b:?} {why}"));
    if !b.iter().all(|c| c.is_finite()) {
        return Err(bad("has a coordinate that is not a finite number"));
    }
    let [x0, y0, x1, y1] = *b;
    if x1 < x0 || y1 < y0 {
        return Err(bad(
            "is inverted ([x0, y0, x1, y1] needs x0 <= x1 and y0 <= y1)",
        ));
    }
    if x1 == x0 || y1 == y0 {
        return Err(bad("has zero area"));
    }
    let cx0 = x0.max(0.0).round() as usize;
    let cy0 = y0.max(0.0).round() as usize;
    let cx1 = (x1.min(width as f64)).round().max(0.0) as usize;
    let cy1 = (y1.min(height as f64)).round().max(0.0) as usize;
    if cx1 <= cx0 || cy1 <= cy0 {
        return Err(bad(&format!(
            "has no pixels inside the {width}x{height} image"
        )));
    }
    Ok([cx0, cy0, cx1, cy1])
}
