//! The user's corrections of a façade estimate (issue 22), in the pixels of the image searched
//! (the rectified photo): floor lines and window-column edges held fixed while the rest of
//! §3.1.6–3.1.7's search runs, windows added or removed, floors without windows. Pure data,
//! its checks ([`FacadeFixes::validate`]) and the window edits made after the search.

use serde::{Deserialize, Serialize};

pub use crate::error::FixError;
use crate::model::{Facade, MAX_COLUMNS, MAX_FLOORS};

/// Most windows a user adds or removes by hand on one photo.
pub const MAX_EDITED_WINDOWS: usize = 1000;

/// What the user corrected on one façade photo; every coordinate in pixels of the image the
/// search reads (x right, y down). Empty (the default) changes nothing.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FacadeFixes {
    /// The lines between floors, y from the top, top to bottom: the floors are exactly these
    /// (N_L = lines + 1 inside the façade); their windows are still searched.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub floor_lines: Option<Vec<f64>>,
    /// The window columns [left, right], left to right: every floor's windows are searched in
    /// these columns only.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub columns: Option<Vec<[f64; 2]>>,
    /// Windows [x0, y0, x1, y1] the search missed, added to the floor holding their centre.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub add_windows: Vec<[f64; 4]>,
    /// Points [x, y] inside windows the search invented: the window found there is removed.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub remove_windows: Vec<[f64; 2]>,
    /// Floors with no windows (a shop floor, a blind ground floor), counted from the ground:
    /// 1 is the ground floor.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub blind_floors: Vec<u32>,
}

/// One kind of correction, named as its key in PROJECT.toml's `[facade.fix]`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Correction {
    FloorLines,
    Columns,
    AddWindows,
    RemoveWindows,
    BlindFloors,
}

impl Correction {
    /// The key in `[facade.fix]`.
    pub fn key(self) -> &'static str {
        match self {
            Correction::FloorLines => "floor_lines",
            Correction::Columns => "columns",
            Correction::AddWindows => "add_windows",
            Correction::RemoveWindows => "remove_windows",
            Correction::BlindFloors => "blind_floors",
        }
    }

    /// The façade parameter it sets (what estimate.json's provenance names): the floors'
    /// heights, the window columns, the windows of each floor.
    pub fn parameter(self) -> &'static str {
        match self {
            Correction::FloorLines => "floors",
            Correction::Columns => "window_columns",
            Correction::AddWindows | Correction::RemoveWindows | Correction::BlindFloors => {
                "floor_windows"
            }
        }
    }
}

impl FacadeFixes {
    /// Nothing corrected.
    pub fn is_empty(&self) -> bool {
        *self == FacadeFixes::default()
    }

    /// The kinds of correction made, in the order of [`Correction`].
    pub fn corrections(&self) -> Vec<Correction> {
        [
            (self.floor_lines.is_some(), Correction::FloorLines),
            (self.columns.is_some(), Correction::Columns),
            (!self.add_windows.is_empty(), Correction::AddWindows),
            (!self.remove_windows.is_empty(), Correction::RemoveWindows),
            (!self.blind_floors.is_empty(), Correction::BlindFloors),
        ]
        .into_iter()
        .filter_map(|(made, c)| made.then_some(c))
        .collect()
    }

    /// Whether the fixes change the search itself (floors, columns, blind floors), not only
    /// the windows after it.
    pub fn constrains_search(&self) -> bool {
        self.floor_lines.is_some() || self.columns.is_some() || !self.blind_floors.is_empty()
    }

    /// Checks the fixes against an image of `width` × `height` pixels: floor lines inside it,
    /// top to bottom; columns inside it, left to right, disjoint; boxes non-empty and inside;
    /// blind floors among the floors.
    pub fn validate(&self, width: u32, height: u32) -> Result<(), FixError> {
        let (w, h) = (f64::from(width), f64::from(height));
        if let Some(lines) = &self.floor_lines {
            if lines.len() >= MAX_FLOORS as usize {
                return Err(FixError::TooManyFloorLines(lines.len(), MAX_FLOORS));
            }
            for (i, &y) in lines.iter().enumerate() {
                if !y.is_finite() {
                    return Err(FixError::FloorLineNotFinite(y));
                }
                if y <= 0.0 {
                    return Err(FixError::FloorLineAbove { y });
                }
                if y >= h {
                    return Err(FixError::FloorLineBelow { y, height });
                }
                if i > 0 && y <= lines[i - 1] {
                    return Err(FixError::FloorLinesUnsorted(y, lines[i - 1]));
                }
            }
        }
        if let Some(cols) = &self.columns {
            if cols.len() > MAX_COLUMNS as usize {
                return Err(FixError::TooManyColumns(cols.len(), MAX_COLUMNS));
            }
            for (i, &[left, right]) in cols.iter().enumerate() {
                let ok = left.is_finite() && right.is_finite() && 0.0 <= left && right <= w;
                if !ok || right <= left {
                    return Err(FixError::BadColumn {
                        index: i + 1,
                        left,
                        right,
                        width,
                    });
                }
                if i > 0 && left < cols[i - 1][1] {
                    return Err(FixError::ColumnsOverlap(i + 1));
                }
            }
        }
        let edited = self.add_windows.len().max(self.remove_windows.len());
        if edited > MAX_EDITED_WINDOWS {
            return Err(FixError::TooManyWindows(edited, MAX_EDITED_WINDOWS));
        }
        for (i, b) in self.add_windows.iter().enumerate() {
            let inside = b.iter().all(|v| v.is_finite())
                && b[0] >= 0.0
                && b[1] >= 0.0
                && b[2] <= w
                && b[3] <= h;
            if !inside || b[2] <= b[0] || b[3] <= b[1] {
                return Err(FixError::BadWindow {
                    index: i + 1,
                    b: *b,
                    width,
                    height,
                });
            }
        }
        for (i, p) in self.remove_windows.iter().enumerate() {
            let inside = p.iter().all(|v| v.is_finite())
                && (0.0..=w).contains(&p[0])
                && (0.0..=h).contains(&p[1]);
            if !inside {
                return Err(FixError::BadPoint {
                    index: i + 1,
                    p: *p,
                    width,
                    height,
                });
            }
        }
        for (i, &floor) in self.blind_floors.iter().enumerate() {
            if floor == 0 || floor > MAX_FLOORS {
                return Err(FixError::BlindFloorOutOfRange(floor, MAX_FLOORS));
            }
            if let Some(lines) = &self.floor_lines
                && floor as usize > lines.len() + 1
            {
                return Err(FixError::BlindFloorAboveTop {
                    floor,
                    floors: lines.len() + 1,
                });
            }
            if self.blind_floors[..i].contains(&floor) {
                return Err(FixError::BlindFloorTwice(floor));
            }
        }
        Ok(())
    }

    /// The constraints on the search of the façade rectangle `r` = [x0, y0, x1, y1], relative
    /// to its top-left corner: floor lines strictly inside its height, columns clipped to its
    /// width (those left with no width dropped).
    pub(crate) fn inside(&self, r: [usize; 4]) -> Constraints {
        let [x0, y0, x1, y1] = r;
        let (fw, fh) = (x1 - x0, y1 - y0);
        let lines = self.floor_lines.as_ref().map(|lines| {
            let mut rows: Vec<usize> = lines
                .iter()
                .map(|y| (y - y0 as f64).round())
                .filter(|&y| y > 0.0 && y < fh as f64)
                .map(|y| y as usize)
                .collect();
            rows.dedup();
            rows
        });
        let columns = self.columns.as_ref().map(|cols| {
            cols.iter()
                .map(|&[a, b]| {
                    let clip = |v: f64| (v - x0 as f64).round().clamp(0.0, fw as f64) as usize;
                    (clip(a), clip(b))
                })
                .filter(|(a, b)| b > a)
                .collect()
        });
        Constraints {
            lines,
            columns,
            blind: self.blind_floors.iter().map(|&f| f as usize).collect(),
        }
    }

    /// The window edits on one façade found by the search: windows containing a
    /// `remove_windows` point are removed, then `add_windows` whose centre is inside the façade
    /// are added to the floor holding their centre (kept top to bottom, left to right).
    pub fn edit_windows(&self, facade: &mut Facade) {
        for floor in &mut facade.floors {
            floor.windows.retain(|w| {
                !self
                    .remove_windows
                    .iter()
                    .any(|p| (w[0]..=w[2]).contains(&p[0]) && (w[1]..=w[3]).contains(&p[1]))
            });
        }
        let n = facade.floors.len();
        for b in &self.add_windows {
            let (cx, cy) = ((b[0] + b[2]) / 2.0, (b[1] + b[3]) / 2.0);
            if !(facade.bbox[0]..=facade.bbox[2]).contains(&cx) {
                continue;
            }
            // Floors are top to bottom and share their edges: the first whose bottom is below
            // the centre holds it.
            let Some(floor) = facade
                .floors
                .iter_mut()
                .enumerate()
                .find(|(i, f)| cy >= f.y0 && (cy < f.y1 || *i + 1 == n && cy <= f.y1))
                .map(|(_, f)| f)
            else {
                continue;
            };
            floor.windows.push(*b);
            floor
                .windows
                .sort_by(|p, q| p[0].total_cmp(&q[0]).then(p[1].total_cmp(&q[1])));
        }
    }
}

/// [`FacadeFixes`] as the search of one façade reads them: rows and columns relative to the
/// façade's top-left corner.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Constraints {
    /// Floor lines, top to bottom, strictly inside the façade.
    pub(crate) lines: Option<Vec<usize>>,
    /// Window columns [a, b), left to right.
    pub(crate) columns: Option<Vec<(usize, usize)>>,
    /// Floors without windows, from the ground (1 = ground floor).
    pub(crate) blind: Vec<usize>,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Floor;

    #[test]
    fn validation_names_the_value_at_fault() {
        let ok = FacadeFixes {
            floor_lines: Some(vec![100.0, 300.0]),
            columns: Some(vec![[10.0, 40.0], [40.0, 90.0]]),
            add_windows: vec![[1.0, 2.0, 3.0, 4.0]],
            remove_windows: vec![[5.0, 5.0]],
            blind_floors: vec![1, 3],
        };
        assert_eq!(ok.validate(200, 800), Ok(()));
        let with = |f: &dyn Fn(&mut FacadeFixes)| {
            let mut x = ok.clone();
            f(&mut x);
            x.validate(200, 800).unwrap_err().to_string()
        };
        assert_eq!(
            with(&|x| x.floor_lines = Some(vec![100.0, 1200.0])),
            "floor line 1200 is below the façade (rectified height 800)"
        );
        assert!(with(&|x| x.floor_lines = Some(vec![300.0, 100.0])).contains("top to bottom"));
        assert!(with(&|x| x.floor_lines = Some(vec![-1.0])).contains("above"));
        assert!(with(&|x| x.floor_lines = Some(vec![f64::NAN])).contains("not a number"));
        assert!(with(&|x| x.columns = Some(vec![[50.0, 40.0]])).contains("column 1"));
        assert!(with(&|x| x.columns = Some(vec![[10.0, 250.0]])).contains("0..200"));
        assert!(with(&|x| x.columns = Some(vec![[10.0, 50.0], [40.0, 60.0]])).contains("column 2"));
        assert!(with(&|x| x.add_windows = vec![[3.0, 2.0, 3.0, 4.0]]).contains("add_windows #1"));
        assert!(with(&|x| x.remove_windows.push([0.0, 900.0])).contains("remove_windows #2"));
        assert_eq!(
            with(&|x| x.blind_floors = vec![4]),
            "blind floor 4: the floor lines make only 3 floors"
        );
        assert!(with(&|x| x.blind_floors = vec![0]).contains("counted from 1"));
        assert!(with(&|x| x.blind_floors = vec![2, 2]).contains("twice"));
        assert!(FacadeFixes::default().is_empty());
        assert!(FacadeFixes::default().corrections().is_empty());
        assert!(!ok.is_empty() && ok.constrains_search());
        assert_eq!(ok.corrections().len(), 5);
        let keys: Vec<&str> = ok.corrections().iter().map(|c| c.key()).collect();
        assert_eq!(
            keys,
            [
                "floor_lines",
                "columns",
                "add_windows",
                "remove_windows",
                "blind_floors"
            ]
        );
    }

    #[test]
    fn constraints_are_relative_to_the_facade() {
        let f = FacadeFixes {
            floor_lines: Some(vec![5.0, 50.0, 80.0, 200.0]),
            columns: Some(vec![[0.0, 25.0], [30.0, 40.0], [150.0, 160.0]]),
            blind_floors: vec![2],
            ..Default::default()
        };
        let c = f.inside([20, 10, 120, 110]);
        // 5 is above the façade, 200 below; 50 and 80 are rows 40 and 70 of it.
        assert_eq!(c.lines, Some(vec![40, 70]));
        // [0, 25] clipped to [0, 5); [150, 160] is right of it.
        assert_eq!(c.columns, Some(vec![(0, 5), (10, 20)]));
        assert_eq!(c.blind, vec![2]);
    }

    #[test]
    fn window_edits_remove_and_add() {
        let floor = |y0: f64, y1: f64, xs: &[f64]| Floor {
            y0,
            y1,
            windows: xs
                .iter()
                .map(|&x| [x, y0 + 2.0, x + 5.0, y1 - 2.0])
                .collect(),
        };
        let mut facade = Facade {
            bbox: [0.0, 0.0, 100.0, 40.0],
            floors: vec![floor(0.0, 20.0, &[10.0, 30.0]), floor(20.0, 40.0, &[10.0])],
            params: crate::model::FacadeParams {
                x_fl: 0.0,
                y_ft: 0.0,
                x_fr: 100.0,
                y_fb: 40.0,
                h_1: 20.0,
                h: 0.0,
                h_nl: 20.0,
                n_l: 2,
                w_off: 10.0,
                w_w: 5.0,
                w_gap: 15.0,
                w_h: 0.0,
                w_grd: 0.0,
                w_h_ground: 16.0,
                w_grd_ground: 2.0,
                w_h_top: 16.0,
                w_grd_top: 2.0,
                n_w: 2,
            },
        };
        FacadeFixes {
            remove_windows: vec![[32.0, 10.0], [90.0, 30.0]],
            add_windows: vec![[50.0, 25.0, 60.0, 40.0], [200.0, 25.0, 210.0, 30.0]],
            ..Default::default()
        }
        .edit_windows(&mut facade);
        assert_eq!(facade.floors[0].windows, vec![[10.0, 2.0, 15.0, 18.0]]);
        assert_eq!(
            facade.floors[1].windows,
            vec![[10.0, 22.0, 15.0, 38.0], [50.0, 25.0, 60.0, 40.0]]
        );
    }
}
