//! The working resolution: channels shrunk by area averaging before the filter bank, and
//! probability maps enlarged bilinearly after the forest. Features and prediction cost grow
//! with the pixel count, while façade classes are tens of pixels across, so a third of a
//! megapixel keeps them (docs/pixelclass.md has the measured accuracy cost).

use rayon::prelude::*;

use crate::channels::Channels;
use crate::forest::Probabilities;

/// For each output index along an axis of `n_in` → `n_out` (shrinking), the first input index
/// and the weights of the inputs it covers (an output pixel averages the input area it spans).
fn area_weights(n_in: usize, n_out: usize) -> Vec<(usize, Vec<f32>)> {
    let scale = n_in as f64 / n_out as f64;
    (0..n_out)
        .map(|o| {
            let (a, b) = (o as f64 * scale, (o + 1) as f64 * scale);
            let first = a.floor() as usize;
            let last = (b.ceil() as usize).min(n_in);
            let w: Vec<f32> = (first..last)
                .map(|i| ((b.min(i as f64 + 1.0) - a.max(i as f64)) / scale) as f32)
                .collect();
            (first, w)
        })
        .collect()
}

/// Shrinks every plane to `w` x `h` (each no larger than the input's) by area averaging.
pub fn shrink(ch: &Channels, w: usize, h: usize) -> Channels {
    let (wi, hi) = (ch.width, ch.height);
    let wx = area_weights(wi, w);
    let wy = area_weights(hi, h);
    let planes = ch
        .planes
        .par_iter()
        .map(|src| {
            // Rows first (wi → w), then columns (hi → h).
            let mut tmp = vec![0f32; w * hi];
            tmp.par_chunks_mut(w).enumerate().for_each(|(y, o)| {
                let row = &src[y * wi..(y + 1) * wi];
                for (v, (first, ws)) in o.iter_mut().zip(&wx) {
                    *v = ws.iter().zip(&row[*first..]).map(|(a, b)| a * b).sum();
                }
            });
            let mut out = vec![0f32; w * h];
            out.par_chunks_mut(w).enumerate().for_each(|(y, o)| {
                let (first, ws) = &wy[y];
                for (k, &wk) in ws.iter().enumerate() {
                    let r = &tmp[(first + k) * w..(first + k + 1) * w];
                    for (a, b) in o.iter_mut().zip(r) {
                        *a += wk * b;
                    }
                }
            });
            out
        })
        .collect();
    Channels {
        width: w,
        height: h,
        planes,
    }
}

/// Enlarges the maps to `w` x `h` bilinearly (pixel centres aligned, borders clamped). Each
/// pixel stays a convex combination of distributions, so it still sums to 1.
pub fn enlarge(p: &Probabilities, w: usize, h: usize) -> Probabilities {
    let c = p.classes;
    let axis = |n_out: usize, n_in: usize| -> Vec<(usize, usize, f32)> {
        (0..n_out)
            .map(|o| {
                let s = ((o as f32 + 0.5) * n_in as f32 / n_out as f32 - 0.5)
                    .clamp(0.0, (n_in - 1) as f32);
                let i0 = s.floor() as usize;
                (i0, (i0 + 1).min(n_in - 1), s - i0 as f32)
            })
            .collect()
    };
    let ax = axis(w, p.width);
    let ay = axis(h, p.height);
    let mut data = vec![0f32; w * h * c];
    data.par_chunks_mut(w * c).enumerate().for_each(|(y, out)| {
        let (y0, y1, fy) = ay[y];
        for (x, &(x0, x1, fx)) in ax.iter().enumerate() {
            let (a, b) = (p.get(x0, y0), p.get(x1, y0));
            let (cc, d) = (p.get(x0, y1), p.get(x1, y1));
            for k in 0..c {
                let top = a[k] + fx * (b[k] - a[k]);
                let bot = cc[k] + fx * (d[k] - cc[k]);
                out[x * c + k] = top + fy * (bot - top);
            }
        }
    });
    Probabilities {
        width: w,
        height: h,
        classes: c,
        data,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shrinking_averages_areas() {
        // 4x2 → 2x1: each output is the mean of a 2x2 block.
        let ch = Channels::new(4, 2, vec![vec![1.0, 3.0, 5.0, 7.0, 1.0, 3.0, 5.0, 7.0]]).unwrap();
        let s = shrink(&ch, 2, 1);
        assert_eq!(s.planes[0], vec![2.0, 6.0]);
        // A non-integer ratio keeps a constant constant and the mean the mean.
        let ch = Channels::new(7, 5, vec![(0..35).map(|i| i as f32).collect()]).unwrap();
        let s = shrink(&ch, 3, 2);
        let mean: f32 = s.planes[0].iter().sum::<f32>() / 6.0;
        assert!((mean - 17.0).abs() < 1e-4, "{mean}");
    }

    #[test]
    fn enlarging_keeps_distributions() {
        let p = Probabilities {
            width: 2,
            height: 1,
            classes: 2,
            data: vec![1.0, 0.0, 0.0, 1.0],
        };
        let e = enlarge(&p, 8, 3);
        assert_eq!(e.get(0, 1), &[1.0, 0.0]);
        assert_eq!(e.get(7, 2), &[0.0, 1.0]);
        for px in e.data.chunks(2) {
            assert!((px[0] + px[1] - 1.0).abs() < 1e-6);
        }
        assert!(e.get(3, 0)[0] > e.get(4, 0)[0]);
    }
}
