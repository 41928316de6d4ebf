//! Façade boundaries (§3.1.7, figure 3.5): background vs façade. Vertical strips between
//! gradient-peak split lines; the best top and bottom per run of strips; a dynamic programme that
//! merges strips bottom-up into façades; then adjacent façades with close edges are merged.

use super::gradients::{Gradients, Integral};
use super::params::SearchParams;

/// Façade rectangles [x0, y0, x1, y1] (exclusive ends), left to right.
pub fn facade_boundaries(
    win: &[f32],
    wall: &[f32],
    bg: &[f32],
    w: usize,
    h: usize,
    grads: &Gradients,
    p: &SearchParams,
) -> Vec<[usize; 4]> {
    // The façade class is the equal-weight mixture of window and wall; a façade rectangle R
    // changes the merit by Σ_{k∈R} (ln P_k,facade − ln P_k,background).
    let d: Vec<f64> = win
        .iter()
        .zip(wall)
        .zip(bg)
        .map(|((&a, &b), &c)| {
            let (a, b) = (a as f64, b as f64);
            let m = a.max(b);
            let r = m + ((a - m).exp() + (b - m).exp()).ln() - std::f64::consts::LN_2 - c as f64;
            // Departure (issue 21): clipped like the window − wall ratio.
            r.clamp(-p.clip, p.clip)
        })
        .collect();
    let di = Integral::new(&d, w, h);
    let xs = grads.x_peaks([0, 0, w, h], p);
    let ys = grads.y_peaks([0, 0, w, h], p);
    let s = xs.len() - 1;
    let penalty = p.facade_penalty * (w * h) as f64;
    // best_run[i][j]: the best (gain, top, bottom) of one façade spanning strips i..j.
    let best_run = |i: usize, j: usize| -> (f64, usize, usize) {
        let (x0, x1) = (xs[i], xs[j]);
        let mut best = (f64::NEG_INFINITY, 0, 0);
        for (a, &t) in ys.iter().enumerate() {
            for &b in &ys[a + 1..] {
                let g = di.sum(x0, t, x1, b);
                if g > best.0 {
                    best = (g, t, b);
                }
            }
        }
        best
    };
    // Dynamic programme over strips: score[j] is the best labelling of strips 0..j, each strip
    // either background or part of a façade spanning a run of strips (bottom-up merge).
    let mut score = vec![0f64; s + 1];
    let mut back: Vec<Option<(usize, usize, usize)>> = vec![None; s + 1];
    for j in 1..=s {
        score[j] = score[j - 1];
        back[j] = None;
        for i in 0..j {
            let (g, t, b) = best_run(i, j);
            // Departure (issue 21): each façade costs `facade_penalty` × the image's area, so
            // that a few background-like pixels (a dormer's roof, a pilaster) do not split one
            // building into strips of one window column each. 0 in the text.
            let g = g - penalty;
            if g > 0.0 && score[i] + g > score[j] {
                score[j] = score[i] + g;
                back[j] = Some((i, t, b));
            }
        }
    }
    let mut rects = Vec::new();
    let mut j = s;
    while j > 0 {
        match back[j] {
            Some((i, t, b)) => {
                rects.push([xs[i], t, xs[j], b]);
                j = i;
            }
            None => j -= 1,
        }
    }
    rects.reverse();
    let (mw, mh) = (p.min_facade_frac * w as f64, p.min_facade_frac * h as f64);
    merge_adjacent(rects, (p.merge_tolerance * h as f64).max(1.0))
        .into_iter()
        .filter(|r| (r[2] - r[0]) as f64 >= mw && (r[3] - r[1]) as f64 >= mh)
        .collect()
}

/// The over-segmentation merge: neighbours that touch and whose tops and bottoms are within
/// `tol` pixels become one façade (their union).
pub fn merge_adjacent(rects: Vec<[usize; 4]>, tol: f64) -> Vec<[usize; 4]> {
    let mut out: Vec<[usize; 4]> = Vec::new();
    for r in rects {
        if let Some(last) = out.last_mut() {
            let touch = last[2] >= r[0];
            let close = (last[1] as f64 - r[1] as f64).abs() <= tol
                && (last[3] as f64 - r[3] as f64).abs() <= tol;
            if touch && close {
                *last = [
                    last[0].min(r[0]),
                    last[1].min(r[1]),
                    last[2].max(r[2]),
                    last[3].max(r[3]),
                ];
                continue;
            }
        }
        out.push(r);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn merges_only_close_neighbours() {
        let r = merge_adjacent(
            vec![[0, 10, 20, 90], [20, 12, 40, 91], [40, 40, 60, 90]],
            5.0,
        );
        assert_eq!(r, vec![[0, 10, 40, 91], [40, 40, 60, 90]]);
    }
}
