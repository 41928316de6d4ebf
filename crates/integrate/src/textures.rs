//! Photo appearances (§7.2.2, figure 7.6): each mapped façade's rectified photo, cropped to the
//! façade, becomes the texture stretched over its wall; the largest stretch of plain wall in
//! each photo becomes a wall sample, tiled at its real size over walls without a photo.

use image::RgbImage;
use image::imageops::{FilterType, resize};

use crate::estimate::{Estimate, MappedFacade};
use crate::photo::{FacadeEstimate, crop};
use facade::classify::Class;

/// A texture image and the name the program uses for it.
pub struct Texture {
    pub name: String,
    pub image: RgbImage,
    /// Real size [width, height] of one repeat in model units, when known: a wall sample cut
    /// from a photo of known scale. `None` for photos stretched over their wall and for
    /// samples of unknown scale.
    pub size: Option<[f64; 2]>,
}

/// Longest side of a wall sample, in texels: 512 keeps a 10 m sample at ~5 cm a texel, the
/// joints of ashlar, at 1 MB a texture before PNG compression.
pub const MAX_SAMPLE_SIDE: u32 = 512;
/// Longest side of a façade photo stretched over its wall, in texels.
pub const MAX_PHOTO_SIDE: u32 = 2048;
/// A wall sample's longer side is at most this many times its shorter: the largest rectangle
/// of wall is often a band between two rows of windows, and a long thin sample shows its
/// repeats as stripes.
const MAX_ASPECT: u32 = 3;
/// Below this many pixels across, a stretch of wall shows too few stones to read as a wall
/// (the user's largest wall box is taken instead).
const MIN_SAMPLE_SIDE: u32 = 24;

/// The file name of `name` without folders and extension, with every character other than
/// ASCII letters, digits, `-` and `_` replaced by `_`: the one rule for the names of a photo's
/// outputs (overlays, textures), safe in URLs and on every file system.
pub fn safe_stem(name: &str) -> String {
    let file = name.rsplit(['/', '\\']).next().unwrap_or(name);
    let base = file.rsplit_once('.').map_or(file, |(b, _)| b);
    base.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// The façade photos, cropped to each mapped façade and resampled to power-of-two sides (the
/// photo is stretched over its wall whatever its pixel size, and power-of-two images mipmap
/// in every viewer, WebGL 1 included); sets `texture` on the mapped façades.
pub(crate) fn facade_textures(estimate: &mut Estimate, photos: &[FacadeEstimate]) -> Vec<Texture> {
    let mut out: Vec<Texture> = Vec::new();
    for s in &mut estimate.structures {
        for f in &mut s.facades {
            let Some(photo) = photos.iter().find(|p| p.name == f.image) else {
                continue;
            };
            let name = format!(
                "textures/{}_{}.png",
                safe_stem(&f.image),
                f.bbox
                    .map(|v| v.round() as i64)
                    .map(|v| v.to_string())
                    .join("_")
            );
            if !out.iter().any(|t| t.name == name) {
                // One pixel in from the boundary, which the search puts on the edge itself.
                let [x0, y0, x1, y1] = f.bbox;
                let Some(image) = crop(&photo.rectified, [x0 + 1.0, y0 + 1.0, x1 - 1.0, y1 - 1.0])
                else {
                    continue;
                };
                out.push(Texture {
                    name: name.clone(),
                    image: power_of_two(&image, MAX_PHOTO_SIDE),
                    size: None,
                });
            }
            f.texture = Some(name);
        }
    }
    out
}

/// One wall sample per photo with wall training boxes: the largest rectangle of plain wall
/// (wall in the façade model, wall by the classifier, inside the mapped façade) no longer
/// than [`MAX_ASPECT`] times its width, or the user's largest wall box when no such stretch
/// is [`MIN_SAMPLE_SIDE`] pixels across; made to tile without seams ([`seamless`]) and
/// resampled to power-of-two sides, with its real size
/// in model units from the façade's scale (s horizontally, s · s_yn vertically, §6.1.2) or
/// the photo's measured metres per pixel. Earlier samples were the wall boxes themselves,
/// 15–40 px crops tiled once per metre: a few stones stretched over a metre each, repeated
/// into static.
pub(crate) fn wall_samples(estimate: &Estimate, photos: &[FacadeEstimate]) -> Vec<Texture> {
    let mut out = Vec::new();
    for p in photos {
        let boxes: Vec<[f64; 4]> = p
            .training
            .classes
            .get(&Class::Wall)
            .into_iter()
            .flatten()
            .copied()
            .collect();
        if boxes.is_empty() {
            continue;
        }
        let mapped = mapped_facade(estimate, &p.name);
        let scale = units_per_pixel(estimate, p);
        let (w, h) = p.rectified.dimensions();
        let within = mapped.map_or([0.0, 0.0, f64::from(w), f64::from(h)], |f| f.bbox);
        let region = plain_wall(p, within)
            .filter(|r| r[2] - r[0] >= MIN_SAMPLE_SIDE && r[3] - r[1] >= MIN_SAMPLE_SIDE)
            .map(|r| r.map(f64::from))
            .or_else(|| {
                boxes.iter().copied().max_by(|a, b| {
                    let area = |r: &[f64; 4]| (r[2] - r[0]) * (r[3] - r[1]);
                    area(a).total_cmp(&area(b))
                })
            });
        let Some(image) = region.and_then(|r| crop(&p.rectified, r)) else {
            continue;
        };
        let image = seamless(&image);
        let size = scale.map(|[sx, sy]| {
            [
                f64::from(image.width()) * sx,
                f64::from(image.height()) * sy,
            ]
        });
        out.push(Texture {
            name: format!("textures/wall_{}.png", safe_stem(&p.name)),
            image: power_of_two(&image, MAX_SAMPLE_SIDE),
            size,
        });
    }
    out
}

/// The first façade mapped from photo `image`.
fn mapped_facade<'a>(estimate: &'a Estimate, image: &str) -> Option<&'a MappedFacade> {
    estimate
        .structures
        .iter()
        .flat_map(|s| &s.facades)
        .find(|f| f.image == image)
}

/// Model units per rectified pixel of photo `p`, across and up: the mapped façade's s and
/// s · s_yn (§6.1.2), else the metres per pixel the user measured.
fn units_per_pixel(estimate: &Estimate, p: &FacadeEstimate) -> Option<[f64; 2]> {
    match mapped_facade(estimate, &p.name) {
        Some(f) => Some([f.scale, f.scale * f.height_factor]),
        None => p
            .metres_per_pixel
            .map(|m| [m * estimate.scale.units_per_metre; 2]),
    }
}

/// Real size in model units of box `b` (photo pixels) of photo `image`, when it is a façade
/// photo of known scale: the box's corners taken to rectified pixels, whose extent the
/// façade's scale measures.
pub(crate) fn box_size(
    estimate: &Estimate,
    photos: &[FacadeEstimate],
    image: &str,
    b: [f64; 4],
) -> Option<[f64; 2]> {
    let p = photos.iter().find(|p| p.name == image)?;
    let [sx, sy] = units_per_pixel(estimate, p)?;
    let corners = [[b[0], b[1]], [b[2], b[1]], [b[0], b[3]], [b[2], b[3]]]
        .map(|c| p.to_rectified(c))
        .into_iter()
        .collect::<Option<Vec<_>>>()?;
    let extent = |k: usize| {
        let (lo, hi) = corners.iter().fold((f64::MAX, f64::MIN), |(lo, hi), c| {
            (lo.min(c[k]), hi.max(c[k]))
        });
        hi - lo
    };
    let size = [extent(0) * sx, extent(1) * sy];
    size.iter().all(|v| v.is_normal()).then_some(size)
}

/// `image` made to tile without seams: its last eighth across (and up) is folded onto its
/// start, fading from the far side's pixels at the first column (so the repeat continues
/// from the last column as the photo did) to the image's own at the eighth; the result is
/// that eighth narrower (and shorter). Sides under 8 pixels are left as they are.
fn seamless(image: &RgbImage) -> RgbImage {
    let fold = |img: &RgbImage, across: bool| -> RgbImage {
        let (w, h) = img.dimensions();
        let n = if across { w } else { h };
        let m = n / 8;
        if m == 0 {
            return img.clone();
        }
        let keep = n - m;
        let (ow, oh) = if across { (keep, h) } else { (w, keep) };
        RgbImage::from_fn(ow, oh, |x, y| {
            let k = if across { x } else { y };
            let here = *img.get_pixel(x, y);
            if k >= m {
                return here;
            }
            let far = if across {
                *img.get_pixel(x + keep, y)
            } else {
                *img.get_pixel(x, y + keep)
            };
            let t = f64::from(k) / f64::from(m);
            image::Rgb(std::array::from_fn(|c| {
                (f64::from(far[c]) * (1.0 - t) + f64::from(here[c]) * t).round() as u8
            }))
        })
    };
    fold(&fold(image, true), false)
}

/// The largest rectangle [x0, y0, x1, y1] (pixels, end exclusive) of pixels inside `within`
/// that the façade model labels wall and the classifier finds most likely wall, with neither
/// side longer than [`MAX_ASPECT`] times the other; `None` when the model, the classes and
/// the photo differ in size or no pixel qualifies.
fn plain_wall(p: &FacadeEstimate, within: [f64; 4]) -> Option<[u32; 4]> {
    let (w, h) = p.rectified.dimensions();
    let (wu, hu) = (w as usize, h as usize);
    let ll = &p.log_likelihoods;
    if (p.model.width, p.model.height) != (w, h) || (ll.width, ll.height) != (wu, hu) {
        return None;
    }
    let labels = p.model.labels();
    let classes = ll.initial_labels();
    let clamp = |v: f64, n: u32| v.round().clamp(0.0, f64::from(n)) as usize;
    let (x0, x1) = (clamp(within[0], w), clamp(within[2], w));
    let (y0, y1) = (clamp(within[1], h), clamp(within[3], h));
    let mask: Vec<bool> = (0..wu * hu)
        .map(|i| {
            let (x, y) = (i % wu, i / wu);
            (x0..x1).contains(&x)
                && (y0..y1).contains(&y)
                && labels[i] == Class::Wall as u8
                && classes[i] == Class::Wall
        })
        .collect();
    largest_rectangle(&mask, wu, hu, MAX_ASPECT)
}

/// The largest axis-aligned rectangle of `true` cells in a row-major `w` × `h` mask, each side
/// at most `max_aspect` times the other, as [x0, y0, x1, y1] with exclusive ends: every
/// maximal rectangle is the widest run of columns at least as tall as one column, on some
/// row (the histogram-stack method, O(w · h)), and trimming one to the aspect limit keeps it
/// inside the mask.
fn largest_rectangle(mask: &[bool], w: usize, h: usize, max_aspect: u32) -> Option<[u32; 4]> {
    let k = max_aspect.max(1) as usize;
    let mut heights = vec![0usize; w];
    let mut best: Option<((usize, usize), [usize; 4])> = None;
    let mut stack: Vec<usize> = Vec::with_capacity(w + 1);
    for y in 0..h {
        for (x, c) in heights.iter_mut().enumerate() {
            *c = if mask[y * w + x] { *c + 1 } else { 0 };
        }
        stack.clear();
        for x in 0..=w {
            let here = if x < w { heights[x] } else { 0 };
            while let Some(&top) = stack.last() {
                if heights[top] <= here {
                    break;
                }
                stack.pop();
                let tall = heights[top];
                let left = stack.last().map_or(0, |&l| l + 1);
                let wide = x - left;
                // Trimmed to the aspect limit, centred on the maximal rectangle; between equal
                // trimmed areas, the one cut from the larger stretch of wall, which leaves
                // the most wall around it.
                let (rw, rh) = (wide.min(k * tall), tall.min(k * wide));
                let area = (rw * rh, wide * tall);
                if best.is_none_or(|(a, _)| area > a) {
                    let rx = left + (wide - rw) / 2;
                    let ry = y + 1 - tall + (tall - rh) / 2;
                    best = Some((area, [rx, ry, rx + rw, ry + rh]));
                }
            }
            stack.push(x);
        }
    }
    best.filter(|(a, _)| a.0 > 0)
        .map(|(_, r)| r.map(|v| v as u32))
}

/// `image` resampled so each side is the power of two nearest its length (in ratio, so a side
/// changes by at most √2), at most the largest power of two within `max_side`: power-of-two textures mipmap in every viewer,
/// and a side rounded on its own changes the aspect, which the real size given with the
/// texture makes good.
pub fn power_of_two(image: &RgbImage, max_side: u32) -> RgbImage {
    let side = |n: u32| {
        let up = n.max(1).next_power_of_two();
        let down = (up / 2).max(1);
        // Nearest in ratio: `down` when n / down < up / n, that is n² < up · down.
        let nearest = if u64::from(n) * u64::from(n) < u64::from(up) * u64::from(down) {
            down
        } else {
            up
        };
        nearest.min(1 << (31 - max_side.max(1).leading_zeros()))
    };
    let (w, h) = (side(image.width()), side(image.height()));
    if (w, h) == image.dimensions() {
        return image.clone();
    }
    resize(image, w, h, FilterType::CatmullRom)
}

#[cfg(test)]
mod tests {
    use super::*;
    use facade::classify::LogLikelihoods;
    use facade::model::{Facade, FacadeModel, FacadeParams, Floor};

    #[test]
    fn names_are_file_safe_and_crops_stay_inside() {
        assert_eq!(safe_stem("photos/keep south.v2.jpg"), "keep_south_v2");
        let img = RgbImage::new(10, 8);
        assert_eq!(
            crop(&img, [2.0, 1.0, 20.0, 5.0]).unwrap().dimensions(),
            (8, 4)
        );
        assert!(crop(&img, [12.0, 1.0, 20.0, 5.0]).is_none());
    }

    #[test]
    fn the_largest_rectangle_keeps_to_the_mask_and_the_aspect_limit() {
        // 8 × 6: a 5 × 3 block of wall at (1, 1) and, apart from it, a long 8 × 1 band on the
        // last row.
        let (w, h) = (8, 6);
        let mask: Vec<bool> = (0..w * h)
            .map(|i| {
                let (x, y) = (i % w, i / w);
                ((1..6).contains(&x) && (1..4).contains(&y)) || y == 5
            })
            .collect();
        assert_eq!(largest_rectangle(&mask, w, h, 3), Some([1, 1, 6, 4]));
        // The band alone is 8 × 1, trimmed to 3 × 1 by the aspect limit, centred.
        let band: Vec<bool> = (0..w * h).map(|i| i / w == 5).collect();
        assert_eq!(largest_rectangle(&band, w, h, 3), Some([2, 5, 5, 6]));
        assert_eq!(largest_rectangle(&band, w, h, 8), Some([0, 5, 8, 6]));
        assert_eq!(largest_rectangle(&vec![false; w * h], w, h, 3), None);
    }

    #[test]
    fn a_seamless_sample_continues_across_its_repeat() {
        // 16 × 8 with a colour per pixel: an eighth (2 columns, 1 row) is folded onto the start.
        let img = RgbImage::from_fn(16, 8, |x, y| image::Rgb([x as u8 * 10, y as u8 * 20, 5]));
        let out = seamless(&img);
        assert_eq!(out.dimensions(), (14, 7));
        // The first column is the far side's: the repeat continues from column 13 to 14.
        assert_eq!(out.get_pixel(0, 3), &image::Rgb([140, 60, 5]));
        // Halfway through the fold: half column 15, half column 1.
        assert_eq!(out.get_pixel(1, 3), &image::Rgb([80, 60, 5]));
        assert_eq!(out.get_pixel(13, 3), &image::Rgb([130, 60, 5]));
        // Up the image the same way: row 0 is the photo's row 7.
        assert_eq!(out.get_pixel(5, 0), &image::Rgb([50, 140, 5]));
        assert_eq!(out.get_pixel(5, 6), &image::Rgb([50, 120, 5]));
        // Too small to fold: unchanged.
        assert_eq!(seamless(&RgbImage::new(7, 5)).dimensions(), (7, 5));
    }

    #[test]
    fn textures_get_power_of_two_sides() {
        let sized = |w, h, max| power_of_two(&RgbImage::new(w, h), max).dimensions();
        assert_eq!(sized(300, 120, 512), (256, 128));
        // √2 · 128 ≈ 181.02 is the tie: 181 rounds down, 182 up.
        assert_eq!(sized(181, 182, 512), (128, 256));
        assert_eq!(sized(1500, 40, 512), (512, 32));
        assert_eq!(sized(1500, 40, 600), (512, 32));
        assert_eq!(sized(64, 64, 512), (64, 64));
        assert_eq!(sized(1, 3, 512), (1, 4));
    }

    /// A 200 × 120 photo at 5 cm a pixel: a façade over x 20..180, y 10..110 with one window
    /// (60..100 × 30..60); the classifier finds wall everywhere but x < 40.
    fn photo() -> FacadeEstimate {
        let (w, h) = (200usize, 120usize);
        let params = FacadeParams {
            x_fl: 20.0,
            y_ft: 10.0,
            x_fr: 180.0,
            y_fb: 110.0,
            h_1: 100.0,
            h: 0.0,
            h_nl: 0.0,
            n_l: 1,
            w_off: 40.0,
            w_w: 40.0,
            w_gap: 0.0,
            w_h: 0.0,
            w_grd: 0.0,
            w_h_ground: 30.0,
            w_grd_ground: 50.0,
            w_h_top: 0.0,
            w_grd_top: 0.0,
            n_w: 1,
        };
        let facade = Facade {
            bbox: [20.0, 10.0, 180.0, 110.0],
            floors: vec![Floor {
                y0: 10.0,
                y1: 110.0,
                windows: vec![[60.0, 30.0, 100.0, 60.0]],
            }],
            params,
        };
        let wall: Vec<f32> = (0..w * h)
            .map(|i| if i % w < 40 { -5.0 } else { -1.0 })
            .collect();
        let other = vec![-2.0f32; w * h];
        let mut training = facade::classify::Training::default();
        training
            .classes
            .insert(Class::Wall, vec![[120.0, 70.0, 140.0, 90.0]]);
        FacadeEstimate {
            name: "keep.png".into(),
            homography: nalgebra::Matrix3::identity(),
            rectification: None,
            rectified: RgbImage::from_fn(w as u32, h as u32, |x, y| {
                image::Rgb([x as u8, y as u8, 7])
            }),
            training,
            log_likelihoods: LogLikelihoods {
                width: w,
                height: h,
                maps: [Some(other.clone()), Some(wall), Some(other)],
            },
            model: FacadeModel {
                width: w as u32,
                height: h as u32,
                facades: vec![facade],
                merit: 0.0,
            },
            metres_per_pixel: Some(0.05),
            fixes: Default::default(),
        }
    }

    fn estimate() -> Estimate {
        Estimate {
            scale: plan::scale::ModelScale::metric(0.1),
            plan: crate::estimate::PlanSource {
                image: "plan.png".into(),
                width: 10,
                height: 10,
                towers: 0,
            },
            structures: Vec::new(),
            assumptions: Vec::new(),
        }
    }

    #[test]
    fn a_wall_sample_is_the_largest_plain_wall_at_its_real_size() {
        let samples = wall_samples(&estimate(), &[photo()]);
        assert_eq!(samples.len(), 1);
        let t = &samples[0];
        assert_eq!(t.name, "textures/wall_keep.png");
        // Plain wall: x 40..180 (the classifier), y 10..110, minus the window x 60..100 ×
        // y 30..60: the largest piece is x 100..180 × y 10..110 (80 × 100 px); folded to tile
        // (an eighth off each way) 70 × 88 px, 3.5 m × 4.4 m.
        let [sw, sh] = t.size.unwrap();
        assert!(
            (sw - 3.5).abs() < 1e-9 && (sh - 4.4).abs() < 1e-9,
            "{sw} × {sh}"
        );
        // 70 × 88 px → 64 × 64 texels; the colours say where it was cut from: the first texel
        // continues the piece's last column and row (x 170, y 98).
        assert_eq!(t.image.dimensions(), (64, 64));
        let corner = t.image.get_pixel(0, 0);
        assert!(
            (160..=172).contains(&corner[0]) && (88..=100).contains(&corner[1]),
            "{corner:?}"
        );
        // The user's wall box in photo pixels, at the same scale: 20 × 20 px, 1 m × 1 m.
        let size = box_size(
            &estimate(),
            &[photo()],
            "keep.png",
            [120.0, 70.0, 140.0, 90.0],
        );
        assert_eq!(size, Some([1.0, 1.0]));
        assert_eq!(
            box_size(&estimate(), &[photo()], "other.png", [0.0; 4]),
            None
        );
    }

    #[test]
    fn without_plain_wall_the_largest_wall_box_is_the_sample() {
        let mut p = photo();
        // The classifier finds no wall anywhere.
        p.log_likelihoods.maps[Class::Wall as usize] = Some(vec![-9.0; 200 * 120]);
        p.metres_per_pixel = None;
        let samples = wall_samples(&estimate(), &[p]);
        assert_eq!(samples[0].image.dimensions(), (16, 16));
        assert_eq!(samples[0].size, None, "no scale, no real size");
    }
}
