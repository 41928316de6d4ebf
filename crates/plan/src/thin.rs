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

/// Thins `m` in place to a one-pixel skeleton. Only border pixels can match an element (each
/// needs an off 4-neighbour), so each pass looks at the current border alone: the cost is that
/// of the pixels removed, not of the image times the wall thickness. Returns the passes made.
pub fn thin(m: &mut Mask) -> usize {
    let els = elements();
    let w = m.width as usize;
    let is_border = |m: &Mask, i: usize| {
        let r = m.ring(i);
        m.data[i] == 1 && (r[0] == 0 || r[2] == 0 || r[4] == 0 || r[6] == 0)
    };
    let mut cand: Vec<usize> = (0..m.data.len()).filter(|&i| is_border(m, i)).collect();
    let mut stamp = vec![0u32; m.data.len()];
    let mut round = 0u32;
    // Each full round removes at least one layer, so it ends within max(w, h) rounds.
    let max_rounds = (m.width.max(m.height) as usize) + 2;
    let mut rounds = 0;
    while rounds < max_rounds {
        rounds += 1;
        let mut changed = false;
        for e in &els {
            let del: Vec<usize> = cand
                .iter()
                .copied()
                .filter(|&i| m.data[i] == 1 && hits(m, i, e))
                .collect();
            if del.is_empty() {
                continue;
            }
            changed = true;
            for &i in &del {
                m.data[i] = 0;
            }
            round += 1;
            let mut next = Vec::with_capacity(cand.len() + del.len());
            let push = |i: usize, next: &mut Vec<usize>, stamp: &mut Vec<u32>| {
                if stamp[i] != round && m.data[i] == 1 {
                    stamp[i] = round;
                    next.push(i);
                }
            };
            for &i in &cand {
                push(i, &mut next, &mut stamp);
            }
            for &i in &del {
                let (x, y) = ((i % w) as i32, (i / w) as i32);
                for (dx, dy) in NEIGHBOURS {
                    let (nx, ny) = (x + dx, y + dy);
                    if nx >= 0 && ny >= 0 && nx < m.width as i32 && ny < m.height as i32 {
                        push(ny as usize * w + nx as usize, &mut next, &mut stamp);
                    }
                }
            }
            next.retain(|&i| is_border(m, i));
            cand = next;
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

    #[test]
    fn staircase_corner_is_removed() {
        let mut m = mask(&["#....", ".##..", "..#..", "..#.."]);
        remove_staircase(&mut m);
        assert_eq!(show(&m), ["#....", ".#...", "..#..", "..#.."]);
    }
}
