//! Watershed by flooding (Meyer's priority-flood; the dissertation cites the algorithm of its
//! reference [5] for §4.2's masonry step): every regional minimum of a level image becomes a
//! basin and the basins grow in order of level until they meet. No watershed lines are kept:
//! each pixel joins the basin that reaches it first, which is enough for the colour merge.

/// Basin labels (1, 2, …; 0 outside `mask`) and the number of basins; a pixel reached by
/// several basins at once joins the first.
pub fn watershed(levels: &[u8], width: usize, height: usize, mask: &[bool]) -> (Vec<u32>, u32) {
    let (mut label, count) = regional_minima(levels, width, height, mask);
    flood(levels, width, height, mask, &mut label, |_, _| 0.0);
    (label, count)
}

fn neighbours(
    i: usize,
    width: usize,
    height: usize,
    mask: &[bool],
) -> impl Iterator<Item = usize> + '_ {
    let (x, y) = (i % width, i / width);
    let mut out = [usize::MAX; 4];
    if x > 0 {
        out[0] = i - 1;
    }
    if x + 1 < width {
        out[1] = i + 1;
    }
    if y > 0 {
        out[2] = i - width;
    }
    if y + 1 < height {
        out[3] = i + width;
    }
    out.into_iter().filter(move |&j| j != usize::MAX && mask[j])
}

/// The markers: every regional minimum (a plateau with no lower neighbour) labelled 1, 2, ….
pub fn regional_minima(
    levels: &[u8],
    width: usize,
    height: usize,
    mask: &[bool],
) -> (Vec<u32>, u32) {
    let n = width * height;
    assert_eq!(levels.len(), n, "levels must be width x height");
    assert_eq!(mask.len(), n, "mask must be width x height");
    let neighbours = |i: usize| neighbours(i, width, height, mask);
    let mut label = vec![0u32; n];
    let mut count = 0u32;
    // Regional minima: plateaus with no lower neighbour.
    let mut seen = vec![false; n];
    let mut plateau = Vec::new();
    for start in 0..n {
        if !mask[start] || seen[start] {
            continue;
        }
        let level = levels[start];
        plateau.clear();
        plateau.push(start);
        seen[start] = true;
        let mut minimum = true;
        let mut k = 0;
        while k < plateau.len() {
            let i = plateau[k];
            k += 1;
            for j in neighbours(i) {
                if levels[j] < level {
                    minimum = false;
                } else if levels[j] == level && !seen[j] {
                    seen[j] = true;
                    plateau.push(j);
                }
            }
        }
        if minimum {
            count += 1;
            for &i in &plateau {
                label[i] = count;
            }
        }
    }
    (label, count)
}

/// Grows the labelled markers over the unlabelled masked pixels in order of level. Among the
/// basins next to a pixel when it is flooded, the one with the lowest `cost(pixel, label)`
/// takes it (the first on ties).
pub fn flood(
    levels: &[u8],
    width: usize,
    height: usize,
    mask: &[bool],
    label: &mut [u32],
    cost: impl Fn(usize, u32) -> f64,
) {
    let n = width * height;
    let neighbours = |i: usize| neighbours(i, width, height, mask);
    // One FIFO per level; a pixel enters at the higher of its level and the level being
    // flooded, so a basin never climbs back down.
    let mut queues: Vec<std::collections::VecDeque<usize>> = vec![Default::default(); 256];
    let mut queued = vec![false; n];
    for i in 0..n {
        if label[i] != 0 {
            for j in neighbours(i) {
                if label[j] == 0 && !queued[j] {
                    queued[j] = true;
                    queues[levels[j] as usize].push_back(j);
                }
            }
        }
    }
    for level in 0..256 {
        while let Some(i) = queues[level].pop_front() {
            if label[i] == 0 {
                let mut best = (f64::INFINITY, 0);
                for l in neighbours(i).map(|j| label[j]).filter(|&l| l != 0) {
                    let c = cost(i, l);
                    if c < best.0 || best.1 == 0 {
                        best = (c, l);
                    }
                }
                label[i] = best.1;
            }
            for j in neighbours(i) {
                if label[j] == 0 && !queued[j] {
                    queued[j] = true;
                    queues[(levels[j] as usize).max(level)].push_back(j);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_basins_meet_at_the_ridge() {
        #[rustfmt::skip]
        let levels = [
            0, 1, 5, 1, 0,
            0, 1, 5, 1, 0,
            0, 1, 5, 1, 0u8,
        ];
        let (l, n) = watershed(&levels, 5, 3, &[true; 15]);
        assert_eq!(n, 2);
        for y in 0..3 {
            assert_eq!(l[y * 5], 1);
            assert_eq!(l[y * 5 + 1], 1);
            assert_eq!(l[y * 5 + 3], 2);
            assert_eq!(l[y * 5 + 4], 2);
            assert_ne!(l[y * 5 + 2], 0);
        }
    }

    #[test]
    fn the_cost_decides_who_takes_a_pixel_between_two_basins() {
        let levels = [0u8, 5, 0];
        let mut l = vec![1, 0, 2];
        flood(&levels, 3, 1, &[true; 3], &mut l, |_, b| {
            if b == 2 { 0.0 } else { 1.0 }
        });
        assert_eq!(l, vec![1, 2, 2]);
    }

    #[test]
    fn masked_pixels_stay_unlabelled_and_split_basins() {
        let levels = [0u8; 5];
        let mask = [true, true, false, true, true];
        let (l, n) = watershed(&levels, 5, 1, &mask);
        assert_eq!(n, 2);
        assert_eq!(l, vec![1, 1, 0, 2, 2]);
    }

    #[test]
    fn a_plateau_minimum_is_one_basin() {
        let levels = [3u8, 2, 2, 2, 3, 4, 1];
        let (l, n) = watershed(&levels, 7, 1, &[true; 7]);
        assert_eq!(n, 2);
        assert_eq!(&l[1..4], &[1, 1, 1]);
        assert_eq!(l[6], 2);
        assert_eq!((l[0], l[4]), (1, 1));
        assert_ne!(l[5], 0);
    }
}
