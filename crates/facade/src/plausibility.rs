//! Plausibility of a fitted façade model (issue 21): a search always returns a tree, and on a
//! map that called most of the photo window it returns confident nonsense — one window as
//! wide as the façade, or windows over most of it (on CMP, 8 of 42 photos get 2.5–5 times as
//! much window as the truth; docs/facade.md, "Where the tree's windows go wrong"). None of this
//! is in the dissertation (§3.1.7 trusts the map); these checks only warn, naming what looks
//! wrong and the fix, and the model is written as before. A window wider than half its façade
//! above the ground floor was tried as a check too and dropped: with whole-window boxes it
//! fired on good models (a glazed attic band).
//! Pure: the model and the user's boxes in, typed warnings out.

use crate::classify::{Class, Training};
use crate::model::FacadeModel;

/// A façade whose windows cover more than this share of its rectangle is more glass than
/// wall: no masonry façade is, so the map has most likely called wall window.
pub const MAX_WINDOW_SHARE: f64 = 0.5;

/// What looks wrong. [`std::fmt::Display`] says what and how to fix it.
#[derive(Debug, Clone, PartialEq)]
pub enum FacadeWarning {
    /// The user drew window boxes and the model has no window.
    NoWindows { boxes: usize },
    /// Façade `facade` (0-based, FACADE.json order) is more than [`MAX_WINDOW_SHARE`] window.
    WindowsCoverFacade { facade: usize, share: f64 },
    /// More than half of the window boxes the user drew (the window boxes, then the whole
    /// windows) have their centre in no window of the model: the model contradicts the user.
    /// One box missed of three is often a shop or door window the grid has no place for, so a
    /// single miss is not said.
    BoxesNotWindows { missed: Vec<[f64; 4]>, of: usize },
}

impl std::fmt::Display for FacadeWarning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        const FIX: &str = "look at the probability overlay (--probabilities) and add wall boxes where it shows wall as window, or outline one whole window";
        match self {
            FacadeWarning::NoWindows { boxes } => write!(
                f,
                "no window was found, though {boxes} window box(es) were drawn: the map may call the windows wall — look at the probability overlay (--probabilities), draw the window boxes on the glass, or outline one whole window"
            ),
            FacadeWarning::WindowsCoverFacade { facade, share } => write!(
                f,
                "the windows cover {:.0} % of façade {} (more than {:.0} %): the map has most likely called wall window; {FIX}",
                100.0 * share,
                facade + 1,
                100.0 * MAX_WINDOW_SHARE
            ),
            FacadeWarning::BoxesNotWindows { missed, of } => {
                let boxes: Vec<String> = missed
                    .iter()
                    .map(|b| format!("[{:.0}, {:.0}, {:.0}, {:.0}]", b[0], b[1], b[2], b[3]))
                    .collect();
                write!(
                    f,
                    "{} of the {of} window boxes lie in no window of the model ({}): the search followed the map's windows elsewhere; add wall boxes where the map is wrong, or correct the model (add a window or a column)",
                    missed.len(),
                    boxes.join(", ")
                )
            }
        }
    }
}

/// The checks, façade by façade, then the user's window boxes against the model.
pub fn check(model: &FacadeModel, training: &Training) -> Vec<FacadeWarning> {
    let mut out = Vec::new();
    let boxes: Vec<[f64; 4]> = training
        .classes
        .get(&Class::Window)
        .into_iter()
        .flatten()
        .chain(&training.whole_windows)
        .copied()
        .collect();
    let windows: Vec<[f64; 4]> = model
        .facades
        .iter()
        .flat_map(|f| &f.floors)
        .flat_map(|fl| fl.windows.iter().copied())
        .collect();
    if windows.is_empty() {
        if !boxes.is_empty() {
            out.push(FacadeWarning::NoWindows { boxes: boxes.len() });
        }
        return out;
    }
    for (i, f) in model.facades.iter().enumerate() {
        let [x0, y0, x1, y1] = f.bbox;
        let (fw, fh) = ((x1 - x0).max(1.0), (y1 - y0).max(1.0));
        let glass: f64 = f
            .floors
            .iter()
            .flat_map(|fl| &fl.windows)
            .map(|w| (w[2] - w[0]).max(0.0) * (w[3] - w[1]).max(0.0))
            .sum();
        let share = glass / (fw * fh);
        if share > MAX_WINDOW_SHARE {
            out.push(FacadeWarning::WindowsCoverFacade { facade: i, share });
        }
    }
    let missed: Vec<[f64; 4]> = boxes
        .iter()
        .filter(|b| {
            let (cx, cy) = (0.5 * (b[0] + b[2]), 0.5 * (b[1] + b[3]));
            !windows
                .iter()
                .any(|w| (w[0]..w[2]).contains(&cx) && (w[1]..w[3]).contains(&cy))
        })
        .copied()
        .collect();
    if 2 * missed.len() > boxes.len() {
        out.push(FacadeWarning::BoxesNotWindows {
            missed,
            of: boxes.len(),
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Facade, FacadeModel, FacadeParams, Floor};

    /// A 100 × 90 façade of three floors (30 px each), windows as given per floor (top first).
    fn model(floors: [Vec<[f64; 4]>; 3]) -> FacadeModel {
        let facade = Facade {
            bbox: [0.0, 0.0, 100.0, 90.0],
            floors: floors
                .into_iter()
                .enumerate()
                .map(|(k, windows)| Floor {
                    y0: 30.0 * k as f64,
                    y1: 30.0 * (k + 1) as f64,
                    windows,
                })
                .collect(),
            params: FacadeParams {
                x_fl: 0.0,
                y_ft: 0.0,
                x_fr: 100.0,
                y_fb: 90.0,
                h_1: 30.0,
                h: 30.0,
                h_nl: 30.0,
                n_l: 3,
                w_off: 15.0,
                w_w: 20.0,
                w_gap: 30.0,
                w_h: 15.0,
                w_grd: 7.0,
                w_h_ground: 15.0,
                w_grd_ground: 7.0,
                w_h_top: 15.0,
                w_grd_top: 7.0,
                n_w: 2,
            },
        };
        FacadeModel {
            width: 100,
            height: 90,
            facades: vec![facade],
            merit: 0.0,
        }
    }

    /// Two 20 × 15 windows per floor, at x 15–35 and 65–85.
    fn grid() -> FacadeModel {
        let row = |y: f64| vec![[15.0, y, 35.0, y + 15.0], [65.0, y, 85.0, y + 15.0]];
        model([row(8.0), row(38.0), row(68.0)])
    }

    fn training(windows: &[[f64; 4]]) -> Training {
        let mut t = Training::default();
        t.classes.insert(Class::Window, windows.to_vec());
        t.classes.insert(Class::Wall, vec![[40.0, 5.0, 50.0, 15.0]]);
        t
    }

    #[test]
    fn a_grid_of_windows_holding_the_users_boxes_is_plausible() {
        let t = training(&[[20.0, 40.0, 29.0, 49.0], [70.0, 10.0, 79.0, 19.0]]);
        assert_eq!(check(&grid(), &t), vec![]);
    }

    #[test]
    fn a_shop_front_as_wide_as_the_facade_is_not_warned() {
        // The ground floor holds a 90 × 28 window: 600 + 600 + 2 520 px of glass over 9 000
        // (0.41, under the share).
        let row = |y: f64| vec![[15.0, y, 35.0, y + 15.0], [65.0, y, 85.0, y + 15.0]];
        let shop = model([row(8.0), row(38.0), vec![[5.0, 61.0, 95.0, 89.0]]]);
        assert_eq!(check(&shop, &training(&[[20.0, 40.0, 29.0, 49.0]])), vec![]);
    }

    #[test]
    fn windows_over_most_of_the_facade_are_warned() {
        let band = |y: f64| vec![[2.0, y, 48.0, y + 28.0], [52.0, y, 98.0, y + 28.0]];
        let m = model([band(1.0), band(31.0), band(61.0)]);
        let w = check(&m, &training(&[[20.0, 40.0, 29.0, 49.0]]));
        // 6 × 46 × 28 = 7 728 px of 9 000.
        assert_eq!(w.len(), 1);
        match &w[0] {
            FacadeWarning::WindowsCoverFacade { facade, share } => {
                assert_eq!(*facade, 0);
                assert!((share - 7728.0 / 9000.0).abs() < 1e-12);
            }
            other => panic!("{other:?}"),
        }
        assert!(w[0].to_string().contains("86 % of façade 1"));
    }

    #[test]
    fn most_boxes_outside_every_window_and_a_model_without_windows_are_warned() {
        // One box of three on the wall between windows: not said.
        let mut t = training(&[[20.0, 40.0, 29.0, 49.0], [40.0, 60.0, 49.0, 69.0]]);
        t.whole_windows.push([64.0, 67.0, 86.0, 84.0]);
        assert_eq!(check(&grid(), &t), vec![]);
        // Two of three: said, with the two boxes.
        t.whole_windows[0] = [40.0, 5.0, 60.0, 20.0];
        assert_eq!(
            check(&grid(), &t),
            vec![FacadeWarning::BoxesNotWindows {
                missed: vec![[40.0, 60.0, 49.0, 69.0], [40.0, 5.0, 60.0, 20.0]],
                of: 3
            }]
        );
        let empty = model([vec![], vec![], vec![]]);
        assert_eq!(
            check(&empty, &t),
            vec![FacadeWarning::NoWindows { boxes: 3 }]
        );
        // No window boxes, no windows: nothing contradicts the user.
        assert_eq!(check(&empty, &Training::default()), vec![]);
    }
}
