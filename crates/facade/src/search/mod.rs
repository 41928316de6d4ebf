//! The global MLE search of §3.1.7: façade boundaries first (background vs façade, strip-wise
//! dynamic programme over gradient-peak split lines), then floors and windows inside each façade
//! (window vs wall, exhaustive search over gradient peaks). [`parse`] runs both;
//! [`parse_with`] under the user's corrections (issue 22, [`crate::fixes`]).

pub mod boundary;
pub mod columns;
pub mod floors;
mod gradients;
pub mod joint;
mod params;
pub mod rows;

use image::RgbImage;

pub use gradients::{Gradients, Integral, peaks};
pub use params::{Grammar, SearchParams};

use crate::classify::{Class, LogLikelihoods};
use crate::error::{FacadeError, Result};
use crate::fixes::FacadeFixes;
use crate::model::{FacadeModel, merit};

/// Parses a rectified façade image given its class log-likelihoods (§3.1.5–3.1.7).
pub fn parse(img: &RgbImage, ll: &LogLikelihoods, p: &SearchParams) -> Result<FacadeModel> {
    parse_with(img, ll, p, &FacadeFixes::default())
}

/// [`parse`] under the user's corrections `fixes` (issue 22), checked against the image first
/// ([`FacadeFixes::validate`]; a bad one is [`FacadeError::BadFixes`]). In every façade found,
/// the floor lines and column edges the user fixed are kept and only the rest is searched,
/// blind floors get no windows, then windows are removed and added
/// ([`FacadeFixes::edit_windows`]); the merit is that of the corrected model.
pub fn parse_with(
    img: &RgbImage,
    ll: &LogLikelihoods,
    p: &SearchParams,
    fixes: &FacadeFixes,
) -> Result<FacadeModel> {
    fixes
        .validate(img.width(), img.height())
        .map_err(FacadeError::BadFixes)?;
    let (w, h) = (img.width() as usize, img.height() as usize);
    if (w, h) != (ll.width, ll.height) {
        return Err(FacadeError::Numerical(format!(
            "log-likelihoods are {}x{}, the image {w}x{h}",
            ll.width, ll.height
        )));
    }
    let (Some(win), Some(wall)) = (ll.get(Class::Window), ll.get(Class::Wall)) else {
        return Err(FacadeError::BadTraining(
            "window and wall classes are required".into(),
        ));
    };
    let grads = Gradients::new(img);
    let rects = match ll.get(Class::Background) {
        Some(bg) => boundary::facade_boundaries(win, wall, bg, w, h, &grads, p),
        None => vec![[0, 0, w, h]],
    };
    // Departure (issue 21): the ratio clipped to [−clip, clip]; the text's search sums it whole.
    let d: Vec<f64> = win
        .iter()
        .zip(wall)
        .map(|(a, b)| ((a - b) as f64 - p.window_bias).clamp(-p.clip, p.clip))
        .collect();
    let di = Integral::new(&d, w, h);
    let facades = rects
        .iter()
        .map(|r| {
            let mut facade = match p.grammar {
                // Departure (issue 22, §3.1.6–3.1.7): a façade whose floors, columns or blind
                // floors the user fixed is fitted with the columns grammar whatever the
                // grammar asked, since the text's one width at one pitch cannot hold the
                // user's column edges nor its equal middle floors the user's floor lines.
                _ if fixes.constrains_search() => {
                    columns::fit_columns_with(*r, &di, &grads, p, &fixes.inside(*r))
                }
                Grammar::Text => joint::fit_floors(*r, &di, &grads, p).to_facade(),
                Grammar::Columns => columns::fit_columns(*r, &di, &grads, p),
                Grammar::Rows => rows::fit_rows(*r, &di, p),
                Grammar::ColumnsOrRows => rows::fit_columns_or_rows(*r, &di, &grads, p),
            };
            fixes.edit_windows(&mut facade);
            facade
        })
        .collect();
    let mut model = FacadeModel {
        width: w as u32,
        height: h as u32,
        facades,
        merit: 0.0,
    };
    model.merit = merit(&model.labels(), ll);
    Ok(model)
}

#[cfg(test)]
mod fixes_tests;
