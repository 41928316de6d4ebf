//! One photo's façade steps in one call, so that the façade command, the pipeline and the
//! evaluation run the same ones: classify → repeats (when the user drew whole windows) →
//! search.

use image::RgbImage;

use crate::classify::{
    Class, ClassifyParams, LogLikelihoods, Training, classify_prepared, prepare,
};
use crate::error::Result;
use crate::fixes::FacadeFixes;
use crate::grow::{GrowParams, grow_on};
use crate::model::FacadeModel;
use crate::repeat::{RepeatParams, Repeats, evidence, find_repeats};
use crate::search::{SearchParams, parse_with};

/// Classifies `img` from `training`, and, when `rp.evidence > 0` and the user outlined whole
/// windows ([`Training::whole_windows`]), finds the windows' repeats ([`find_repeats`]) and adds them to the window evidence ([`evidence`]); then
/// searches the façade model. Returns the log-likelihoods the search read, the model, and the
/// repeats (`None` when the step did not run).
pub fn parse_photo(
    img: &RgbImage,
    training: &Training,
    cp: &ClassifyParams,
    sp: &SearchParams,
    rp: &RepeatParams,
) -> Result<(LogLikelihoods, FacadeModel, Option<Repeats>)> {
    parse_photo_with(img, training, cp, sp, rp, &FacadeFixes::default())
}

/// [`parse_photo`] under the user's corrections of the façade (issue 22), honoured by the
/// search ([`parse_with`]); they are checked against the image before anything runs.
pub fn parse_photo_with(
    img: &RgbImage,
    training: &Training,
    cp: &ClassifyParams,
    sp: &SearchParams,
    rp: &RepeatParams,
    fixes: &FacadeFixes,
) -> Result<(LogLikelihoods, FacadeModel, Option<Repeats>)> {
    fixes
        .validate(img.width(), img.height())
        .map_err(crate::error::FacadeError::BadFixes)?;
    let (ll, repeats) = classify_with_repeats(img, training, cp, rp)?;
    let model = parse_with(img, &ll, sp, fixes)?;
    Ok((ll, model, repeats))
}

/// The first two steps of [`parse_photo`]: the class log-likelihoods with the repeats' window
/// evidence added (what the search reads, and what `castellan serve` shows live), and the
/// repeats when the step ran.
///
/// When the user drew no whole window and `rp.grow` is set, the small window boxes are grown
/// into whole windows on a first map ([`grow_on`]); those that stay window-sized replace
/// their boxes as whole windows, and the classifier runs again with them (their ring of wall
/// and their repeats, as if the user had outlined them).
pub fn classify_with_repeats(
    img: &RgbImage,
    training: &Training,
    cp: &ClassifyParams,
    rp: &RepeatParams,
) -> Result<(LogLikelihoods, Option<Repeats>)> {
    let grow = rp.grow.filter(|_| training.whole_windows.is_empty());
    // The second classification trains on the same photo: its features are made once.
    let prepared = match grow {
        Some(_) => prepare(img, cp)?,
        None => None,
    };
    let mut ll = classify_prepared(img, prepared.as_ref(), training, cp)?;
    let grown = grow.and_then(|g| grown_training(img, training, &ll, &g));
    if let Some(t) = &grown {
        ll = classify_prepared(img, prepared.as_ref(), t, cp)?;
    }
    let training = grown.as_ref().unwrap_or(training);
    let repeats = whole_windows(img, training)
        .filter(|_| rp.evidence > 0.0)
        .map(|wins| {
            let r = find_repeats(img, &wins, rp);
            evidence(&mut ll, &r, rp.evidence);
            r
        });
    Ok((ll, repeats))
}

/// `training` with each window box that grows into a window on `ll` replaced by the grown box
/// as a whole window; `None` when none does.
fn grown_training(
    img: &RgbImage,
    training: &Training,
    ll: &LogLikelihoods,
    g: &GrowParams,
) -> Option<Training> {
    let (w, h) = (img.width() as usize, img.height() as usize);
    let drawn = training.classes.get(&Class::Window)?;
    let clipped = training.boxes(w, h).ok()?.remove(&Class::Window)?;
    let grown = grow_on(img, ll, &clipped, g)?;
    if grown.iter().all(Option::is_none) {
        return None;
    }
    let mut t = training.clone();
    let kept: Vec<[f64; 4]> = drawn
        .iter()
        .zip(&grown)
        .filter(|(_, g)| g.is_none())
        .map(|(b, _)| *b)
        .collect();
    if kept.is_empty() {
        t.classes.remove(&Class::Window);
    } else {
        t.classes.insert(Class::Window, kept);
    }
    t.whole_windows = grown
        .into_iter()
        .flatten()
        .map(|b| b.map(|v| v as f64))
        .collect();
    Some(t)
}

/// The windows the user outlined whole, if any.
fn whole_windows(img: &RgbImage, training: &Training) -> Option<Vec<[f64; 4]>> {
    let wins = training
        .whole_window_boxes(img.width() as usize, img.height() as usize)
        .ok()?;
    (!wins.is_empty()).then(|| wins.iter().map(|b| b.map(|v| v as f64)).collect())
}
