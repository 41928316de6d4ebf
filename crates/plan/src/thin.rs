//! Skeleton by iterated morphological hit-or-miss thinning (§5.1.3): eight structuring elements
//! applied in turn until nothing changes, then one pass removing the redundant corner pixels
//! of diagonal steps so that every curve pixel has exactly two neighbours.

/// A binary raster, row-major, 1 = on.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Mask {
    pub width: u32,
    pub height: u32,
    pub data: Vec<u8>,
}

/// The eight neighbours, clockwise from north (dx, dy).
pub const NEIGHBOURS: [(i32, i32); 8] = [
    (0, -1),
    (1, -1),
    (1, 0),
    (1, 1),
    (0, 1),
    (-1, 1),
    (-1, 0),
    (-1, -1),
];

impl Mask {
    pub fn new(width: u32, height: u32) -> Mask {
        Mask {
            width,
            height,
            data: vec![0; width as usize * height as usize],
        }
    }

    /// On pixels are those of `img` equal to 255.
    pub fn from_gray(img: &image::GrayImage) -> Mask {
        Mask {
            width: img.width(),
            height: img.height(),
            data: img.pixels().map(|p| u8::from(p[0] == 255)).collect(),
        }
    }

    /// The smallest box `[x0, y0, x1, y1]` (inclusive) holding every on pixel; `None` when
    /// none is on.
    pub fn bounding_box(&self) -> Option<[u32; 4]> {
        let mut bb: Option<[u32; 4]> = None;
        for (y, row) in self.data.chunks(self.width as usize).enumerate() {
            if let (Some(x0), Some(x1)) = (
                row.iter().position(|&v| v == 1),
                row.iter().rposition(|&v| v == 1),
            ) {
                let (x0, x1, y) = (x0 as u32, x1 as u32, y as u32);
                bb = Some(match bb {
                    None => [x0, y, x1, y],
                    Some(b) => [b[0].min(x0), b[1], b[2].max(x1), y],
                });
            }
        }
        bb
    }

    #[inline]
    pub fn get(&self, x: i32, y: i32) -> u8 {
        if x < 0 || y < 0 || x >= self.width as i32 || y >= self.height as i32 {
            0
        } else {
            self.data[y as usize * self.width as usize + x as usize]
        }
    }

    /// The 8 neighbour values of pixel index `i`, in [`NEIGHBOURS`] order.
    #[inline]
    pub fn ring(&self, i: usize) -> [u8; 8] {
        let (x, y) = (
            (i % self.width as usize) as i32,
            (i / self.width as usize) as i32,
        );
        NEIGHBOURS.map(|(dx, dy)| self.get(x + dx, y + dy))
    }

    /// Number of on neighbours of pixel index `i`.
    pub fn count(&self, i: usize) -> u32 {
        self.ring(i).iter().map(|&v| u32::from(v)).sum()
    }
}

/// 0 → must be off, 1 → must be on, 2 → don't care; rows top to bottom.
type Element = [[u8; 3]; 3];

const B1: Element = [[0, 0, 0], [2, 1, 2], [1, 1, 1]];
const B2: Element = [[2, 0, 0], [1, 1, 0], [2, 1, 2]];

fn rotate(e: Element) -> Element {
    let mut r = [[2; 3]; 3];
    for (y, row) in e.iter().enumerate() {
        for (x, &v) in row.iter().enumerate() {
            r[x][2 - y] = v;
        }
    }
    r
}

/// The eight elements: B1, B2 and their rotations by 90°, in the order they are applied.
fn elements() -> [Element; 8] {
    let mut out = [B1; 8];
    let (mut a, mut b) = (B1, B2);
    for k in 0..4 {
        out[2 * k] = a;
        out[2 * k + 1] = b;
        a = rotate(a);
        b = rotate(b);
    }
    out
}

/// Whether on pixel `i` matches element `e` (what [`matches`] tabulates; checked in debug builds).
fn hits(m: &Mask, i: usize, e: &Element) -> bool {
    let (x, y) = ((i % m.width as usize) as i32, (i / m.width as usize) as i32);
    for (dy, row) in e.iter().enumerate() {
        for (dx, &want) in row.iter().enumerate() {
            if want != 2 && m.get(x + dx as i32 - 1, y + dy as i32 - 1) != want {
                return false;
            }
        }
    }
    true
}

/// The 8 neighbours of pixel index `i` as the bits of a byte, bit k for [`NEIGHBOURS`]`[k]`.
#[inline]
fn code(m: &Mask, i: usize) -> u8 {
    let (w, h) = (m.width as usize, m.height as usize);
    let (x, y) = (i % w, i / w);
    if x > 0 && y > 0 && x + 1 < w && y + 1 < h {
        let d = &m.data;
        let (n, s) = (i - w, i + w);
        d[n] | d[n + 1] << 1
            | d[i + 1] << 2
            | d[s + 1] << 3
            | d[s] << 4
            | d[s - 1] << 5
            | d[i - 1] << 6
            | d[n - 1] << 7
    } else {
        m.ring(i)
            .iter()
            .enumerate()
            .fold(0, |c, (k, &v)| c | v << k)
    }
}

/// For each neighbourhood code, the elements an on pixel with those neighbours matches (bit k
/// for element k).
fn matches(els: &[Element; 8]) -> [u8; 256] {
    let mut t = [0u8; 256];
    for (c, bits) in t.iter_mut().enumerate() {
        for (k, e) in els.iter().enumerate() {
            // The element's cell of each neighbour (dx, dy) is row dy + 1, column dx + 1.
            let hit = NEIGHBOURS.iter().enumerate().all(|(b, &(dx, dy))| {
                let want = e[(dy + 1) as usize][(dx + 1) as usize];
                want == 2 || want == ((c >> b) & 1) as u8
            });
            *bits |= u8::from(hit) << k;
        }
    }
    t
}

/// Thins `m` in place to a one-pixel skeleton. Each element removes, at once, every on pixel
/// that matches it; a pixel's match can only change when a neighbour goes, so each element
/// keeps a list of the pixels that matched it when last looked at (all of them at the start,
/// then the neighbours of each removed pixel): the cost is that of the pixels removed, not of
/// the image or its border times the passes. Returns the passes made.
pub fn thin(m: &mut Mask) -> usize {
    let els = elements();
    let matches = matches(&els);
    let (w, h) = (m.width as usize, m.height as usize);
    let mut pending: [Vec<usize>; 8] = Default::default();
    let queue = |m: &Mask, i: usize, pending: &mut [Vec<usize>; 8]| {
        let bits = matches[code(m, i) as usize];
        for (k, list) in pending.iter_mut().enumerate() {
            if bits >> k & 1 == 1 {
                list.push(i);
            }
        }
    };
    for i in 0..m.data.len() {
        if m.data[i] == 1 {
            queue(m, i, &mut pending);
        }
    }
    // `stamp[i] == step`: pixel i was already taken (or queued) in this step.
    let mut stamp = vec![0u32; m.data.len()];
    let mut step = 0u32;
    // Each full round removes at least one layer, so it ends within max(w, h) rounds.
    let max_rounds = w.max(h) + 2;
    let mut rounds = 0;
    while rounds < max_rounds {
        rounds += 1;
        let mut changed = false;
        for k in 0..8 {
            step += 1;
            let mut del = std::mem::take(&mut pending[k]);
            del.retain(|&i| {
                let take = m.data[i] == 1
                    && stamp[i] != step
                    && matches[code(m, i) as usize] >> k & 1 == 1;
                if take {
                    stamp[i] = step;
                }
                take
            });
            debug_assert!(del.iter().all(|&i| hits(m, i, &els[k])));
            if del.is_empty() {
                continue;
            }
            changed = true;
            for &i in &del {
                m.data[i] = 0;
            }
            step += 1;
            for &i in &del {
                let (x, y) = ((i % w) as i32, (i / w) as i32);
                for (dx, dy) in NEIGHBOURS {
                    let (nx, ny) = (x + dx, y + dy);
                    if nx >= 0 && ny >= 0 && nx < w as i32 && ny < h as i32 {
                        let j = ny as usize * w + nx as usize;
                        if m.data[j] == 1 && stamp[j] != step {
                            stamp[j] = step;
                            queue(m, j, &mut pending);
                        }
                    }
                }
            }
        }
        if !changed {
            break;
        }
    }
    remove_staircase(m);
    rounds
}

/// Crossing number: off→on transitions around the 8-neighbourhood.
pub fn crossings(r: &[u8; 8]) -> u32 {
    (0..8)
        .map(|k| u32::from(r[k] == 0 && r[(k + 1) % 8] == 1))
        .sum()
}

/// Removes a pixel with two perpendicular on 4-neighbours when its other neighbours stay
/// 8-connected without it (two or three neighbours in one run): the corner of a diagonal step,
/// redundant for 8-connectivity. Sequential, so a step loses one pixel, never two.
pub fn remove_staircase(m: &mut Mask) {
    for i in 0..m.data.len() {
        if m.data[i] == 0 {
            continue;
        }
        let r = m.ring(i);
        let n: u32 = r.iter().map(|&v| u32::from(v)).sum();
        let corner = (0..4).any(|k| r[2 * k] == 1 && r[(2 * k + 2) % 8] == 1);
        if corner && (n == 2 || (n == 3 && crossings(&r) == 1)) {
            m.data[i] = 0;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mask(rows: &[&str]) -> Mask {
        let mut m = Mask::new(rows[0].len() as u32, rows.len() as u32);
        for (y, r) in rows.iter().enumerate() {
            for (x, c) in r.bytes().enumerate() {
                m.data[y * m.width as usize + x] = u8::from(c == b'#');
            }
        }
        m
    }

    fn show(m: &Mask) -> Vec<String> {
        m.data
            .chunks(m.width as usize)
            .map(|r| r.iter().map(|&v| if v == 1 { '#' } else { '.' }).collect())
            .collect()
    }

    #[test]
    fn the_bounding_box_holds_every_on_pixel_and_no_more() {
        let m = mask(&["......", "...#..", ".#....", "....#.", "......"]);
        assert_eq!(m.bounding_box(), Some([1, 1, 4, 3]));
        assert_eq!(mask(&["#"]).bounding_box(), Some([0, 0, 0, 0]));
        assert_eq!(mask(&["...", "..."]).bounding_box(), None);
    }

    #[test]
    fn elements_are_eight_distinct_rotations() {
        let e = elements();
        for i in 0..8 {
            for j in 0..i {
                assert_ne!(e[i], e[j]);
            }
        }
        assert_eq!(rotate(rotate(rotate(rotate(B2)))), B2);
    }

    #[test]
    fn thick_bar_thins_to_a_line() {
        let mut m = mask(&[
            "............",
            ".##########.",
            ".##########.",
            ".##########.",
            "............",
        ]);
        thin(&mut m);
        let s = show(&m);
        // The middle row carries the line; only corner spurs may leave it.
        assert_eq!(&s[2][3..9], "######", "{s:?}");
        assert_eq!(&s[1][3..9], "......", "{s:?}");
        assert_eq!(&s[3][3..9], "......", "{s:?}");
        assert!(m.data.iter().filter(|&&v| v == 1).count() <= 14, "{s:?}");
    }

    #[test]
    fn ring_stays_a_closed_loop() {
        let mut m = mask(&[
            "..........",
            ".########.",
            ".########.",
            ".##....##.",
            ".##....##.",
            ".########.",
            ".########.",
            "..........",
        ]);
        thin(&mut m);
        // One pixel thick: no 2 × 2 block of on pixels.
        for y in 0..7 {
            for x in 0..9 {
                let block = m.get(x, y) + m.get(x + 1, y) + m.get(x, y + 1) + m.get(x + 1, y + 1);
                assert!(block < 4, "{:?}", show(&m));
            }
        }
        // The hole stays enclosed: no 4-connected path of off pixels from it to the border.
        let mut seen = vec![false; m.data.len()];
        let mut stack = vec![0usize];
        while let Some(i) = stack.pop() {
            if seen[i] || m.data[i] == 1 {
                continue;
            }
            seen[i] = true;
            let (x, y) = ((i % 10) as i32, (i / 10) as i32);
            for (dx, dy) in [(1, 0), (-1, 0), (0, 1), (0, -1)] {
                let (nx, ny) = (x + dx, y + dy);
                if (0..10).contains(&nx) && (0..8).contains(&ny) {
                    stack.push((ny * 10 + nx) as usize);
                }
            }
        }
        assert!(!seen[4 * 10 + 4], "{:?}", show(&m));
    }

    /// §5.1.3 as written: every element over every pixel, until a round removes nothing.
    fn thin_reference(m: &mut Mask) -> usize {
        let els = elements();
        let mut rounds = 0;
        loop {
            rounds += 1;
            let mut changed = false;
            for e in &els {
                let del: Vec<usize> = (0..m.data.len())
                    .filter(|&i| m.data[i] == 1 && hits(m, i, e))
                    .collect();
                changed |= !del.is_empty();
                for i in del {
                    m.data[i] = 0;
                }
            }
            if !changed {
                break;
            }
        }
        remove_staircase(m);
        rounds
    }

    #[test]
    fn thinning_by_lists_is_thinning_by_passes() {
        use rand::{RngExt, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        for (w, h) in [(1, 1), (3, 9), (40, 30), (75, 61)] {
            for p in [0.3, 0.6, 0.9] {
                let mut m = Mask::new(w, h);
                for v in &mut m.data {
                    *v = u8::from(rng.random_bool(p));
                }
                // Thick blocks, so that thinning takes several rounds.
                for _ in 0..4 {
                    let (x0, y0) = (rng.random_range(0..w), rng.random_range(0..h));
                    for y in y0..(y0 + 14).min(h) {
                        for x in x0..(x0 + 20).min(w) {
                            m.data[(y * w + x) as usize] = 1;
                        }
                    }
                }
                let mut want = m.clone();
                let rounds = thin_reference(&mut want);
                assert_eq!(thin(&mut m), rounds);
                assert_eq!(m, want);
            }
        }
    }

    #[test]
    fn staircase_corner_is_removed() {
        let mut m = mask(&["#....", ".##..", "..#..", "..#.."]);
        remove_staircase(&mut m);
        assert_eq!(show(&m), ["#....", ".#...", "..#..", "..#.."]);
    }
}
