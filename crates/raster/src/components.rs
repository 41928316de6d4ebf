//! Connected components of a binary image: every region of one value labelled by flood fill,
//! with its size and bounding box found in the same pass. Used by the plan parser's
//! pre-processing and clean-up steps (§5.1.2), its faces (§5.1.4) and scale-bar finder, and by
//! the Gothic stage's window blobs and stones (§4.2).
//!
//! Used instead of imageproc's `connected_components`, which needs a converted copy of the
//! image and a second pass for sizes: pre-processing of the 3000 × 2000 benchmark scan went
//! from 0.75–0.96 s to about 0.4 s (`cargo run --release -p plan --example stage_times`,
//! noisy on shared cores).

use image::GrayImage;

/// Pixel connectivity of a region.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Connectivity {
    /// Left, right, up, down.
    Four,
    /// The four, and the diagonals.
    Eight,
}

/// The regions of an image. Labels run from 1 in the order of each region's first pixel in
/// raster order; label 0 is every pixel outside the regions, with size 0 and the empty box
/// `[u32::MAX, u32::MAX, 0, 0]`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Components {
    /// Label of every pixel, row-major.
    pub labels: Vec<u32>,
    /// Pixels of each label.
    pub sizes: Vec<usize>,
    /// Bounding box `[x0, y0, x1, y1]` (inclusive) of each label.
    pub bbox: Vec<[u32; 4]>,
}

/// The regions of the pixels of `img` equal to `value`.
pub fn components(img: &GrayImage, value: u8, conn: Connectivity) -> Components {
    let raw = img.as_raw();
    components_where(img.width() as usize, img.height() as usize, conn, |i| {
        raw[i] == value
    })
}

/// The regions of the pixels of a `width` × `height` grid for which `inside(i)` holds, `i`
/// the row-major index (masks kept as slices: window maps, class labels, skeletons).
pub fn components_where(
    width: usize,
    height: usize,
    conn: Connectivity,
    inside: impl Fn(usize) -> bool,
) -> Components {
    let (w, h) = (width, height);
    let mut labels = vec![0u32; w * h];
    let mut sizes = vec![0usize];
    let mut bbox = vec![[u32::MAX, u32::MAX, 0, 0]];
    let steps: &[(i64, i64)] = match conn {
        Connectivity::Four => &[(1, 0), (-1, 0), (0, 1), (0, -1)],
        Connectivity::Eight => &[
            (1, 0),
            (-1, 0),
            (0, 1),
            (0, -1),
            (1, 1),
            (1, -1),
            (-1, 1),
            (-1, -1),
        ],
    };
    let mut stack = Vec::new();
    for s in 0..w * h {
        if labels[s] != 0 || !inside(s) {
            continue;
        }
        let id = sizes.len() as u32;
        let (mut size, mut b) = (0usize, [u32::MAX, u32::MAX, 0, 0]);
        labels[s] = id;
        stack.push(s);
        // Each pixel is pushed at most once, so the walk is bounded by the image size.
        while let Some(i) = stack.pop() {
            let (x, y) = ((i % w) as i64, (i / w) as i64);
            size += 1;
            b = [
                b[0].min(x as u32),
                b[1].min(y as u32),
                b[2].max(x as u32),
                b[3].max(y as u32),
            ];
            for &(dx, dy) in steps {
                let (nx, ny) = (x + dx, y + dy);
                if nx < 0 || ny < 0 || nx >= w as i64 || ny >= h as i64 {
                    continue;
                }
                let j = ny as usize * w + nx as usize;
                if labels[j] == 0 && inside(j) {
                    labels[j] = id;
                    stack.push(j);
                }
            }
        }
        sizes.push(size);
        bbox.push(b);
    }
    Components {
        labels,
        sizes,
        bbox,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diagonal_neighbours_join_only_with_eight_connectivity() {
        let img = crate::literal::mask(&["#..#", ".#..", "....", "##.#"]);
        let four = components(&img, 255, Connectivity::Four);
        assert_eq!(four.sizes, vec![0, 1, 1, 1, 2, 1]);
        let eight = components(&img, 255, Connectivity::Eight);
        assert_eq!(eight.sizes, vec![0, 2, 1, 2, 1]);
        #[rustfmt::skip]
        assert_eq!(eight.labels, vec![
            1, 0, 0, 2,
            0, 1, 0, 0,
            0, 0, 0, 0,
            3, 3, 0, 4,
        ]);
        assert_eq!(eight.bbox[1], [0, 0, 1, 1]);
        assert_eq!(eight.bbox[3], [0, 3, 1, 3]);
        assert_eq!(eight.bbox[0], [u32::MAX, u32::MAX, 0, 0]);
    }

    #[test]
    fn background_regions_and_masks_label_alike() {
        // The paper of a ring: the outside and the hole, apart under 4-connectivity.
        let img = crate::literal::mask(&["#####", "#...#", "#####", "....."]);
        let paper = components(&img, 0, Connectivity::Four);
        assert_eq!(paper.sizes, vec![0, 3, 5]);
        assert_eq!(paper.bbox[1], [1, 1, 3, 1]);
        let raw = img.as_raw();
        let same = components_where(5, 4, Connectivity::Four, |i| raw[i] == 0);
        assert_eq!(same, paper);
    }

    #[test]
    fn an_empty_image_has_no_region() {
        let c = components(&GrayImage::new(0, 0), 0, Connectivity::Eight);
        assert_eq!((c.labels.len(), c.sizes, c.bbox.len()), (0, vec![0], 1));
    }
}
