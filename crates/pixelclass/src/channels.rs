//! Planar float images: the classifier's input. Colour photos become CIELAB, scaled to about
//! [0, 1]: its lightness carries the edges and texture the filters look for, apart from the
//! chroma, and its distances follow perceived colour better than RGB's (docs/pixelclass.md
//! has the measured difference on the façade sets).

use image::{GrayImage, RgbImage};
use rayon::prelude::*;

use crate::error::{PixelClassError, Result};

/// `planes[c][y * width + x]`: one row-major plane per channel.
#[derive(Debug, Clone, PartialEq)]
pub struct Channels {
    pub width: usize,
    pub height: usize,
    pub planes: Vec<Vec<f32>>,
}

impl Channels {
    /// Checks that every plane holds `width * height` values and that there is at least one.
    pub fn new(width: usize, height: usize, planes: Vec<Vec<f32>>) -> Result<Channels> {
        if planes.is_empty() {
            return Err(PixelClassError::BadInput {
                what: "channels".into(),
                why: "no planes".into(),
            });
        }
        if let Some((c, p)) = planes
            .iter()
            .enumerate()
            .find(|(_, p)| p.len() != width * height)
        {
            return Err(PixelClassError::BadInput {
                what: format!("channel {c}"),
                why: format!("{} values for a {width}x{height} image", p.len()),
            });
        }
        Ok(Channels {
            width,
            height,
            planes,
        })
    }

    /// sRGB → CIELAB (D65): L / 100, a / 200 + ½, b / 200 + ½.
    pub fn from_rgb(img: &RgbImage) -> Channels {
        let (w, h) = (img.width() as usize, img.height() as usize);
        // sRGB decoding per 8-bit value, once.
        let lin: Vec<f32> = (0..256)
            .map(|v| {
                let c = v as f32 / 255.0;
                if c <= 0.04045 {
                    c / 12.92
                } else {
                    ((c + 0.055) / 1.055).powf(2.4)
                }
            })
            .collect();
        let mut planes = vec![vec![0f32; w * h]; 3];
        let [l, a, b] = planes.as_mut_slice() else {
            unreachable!()
        };
        let raw = img.as_raw();
        l.par_chunks_mut(w.max(1))
            .zip(a.par_chunks_mut(w.max(1)))
            .zip(b.par_chunks_mut(w.max(1)))
            .enumerate()
            .for_each(|(y, ((lr, ar), br))| {
                for x in 0..w {
                    let p = &raw[(y * w + x) * 3..(y * w + x) * 3 + 3];
                    let lab = lab(lin[p[0] as usize], lin[p[1] as usize], lin[p[2] as usize]);
                    lr[x] = lab[0] / 100.0;
                    ar[x] = lab[1] / 200.0 + 0.5;
                    br[x] = lab[2] / 200.0 + 0.5;
                }
            });
        Channels {
            width: w,
            height: h,
            planes,
        }
    }

    /// Plain RGB in [0, 1]: measured against CIELAB in docs/pixelclass.md (much worse on the
    /// façade sets), kept for that comparison and for inputs already in RGB terms.
    pub fn from_rgb_linear_scale(img: &RgbImage) -> Channels {
        let (w, h) = (img.width() as usize, img.height() as usize);
        let planes = (0..3)
            .map(|c| img.pixels().map(|p| p[c] as f32 / 255.0).collect())
            .collect();
        Channels {
            width: w,
            height: h,
            planes,
        }
    }

    /// One plane, grey value / 255.
    pub fn from_gray(img: &GrayImage) -> Channels {
        Channels {
            width: img.width() as usize,
            height: img.height() as usize,
            planes: vec![img.as_raw().iter().map(|&v| v as f32 / 255.0).collect()],
        }
    }

    pub fn len(&self) -> usize {
        self.width * self.height
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

/// Linear sRGB → CIELAB under D65.
fn lab(r: f32, g: f32, b: f32) -> [f32; 3] {
    let x = (0.412_456_4 * r + 0.357_576_1 * g + 0.180_437_5 * b) / 0.950_47;
    let y = 0.212_672_9 * r + 0.715_152_2 * g + 0.072_175 * b;
    let z = (0.019_333_9 * r + 0.119_192 * g + 0.950_304_1 * b) / 1.088_83;
    let f = |t: f32| {
        const D: f32 = 6.0 / 29.0;
        if t > D * D * D {
            t.cbrt()
        } else {
            t / (3.0 * D * D) + 4.0 / 29.0
        }
    };
    let (fx, fy, fz) = (f(x), f(y), f(z));
    [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)]
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::Rgb;

    #[test]
    fn lab_of_white_black_and_red() {
        let mut img = RgbImage::new(3, 1);
        img.put_pixel(0, 0, Rgb([255, 255, 255]));
        img.put_pixel(1, 0, Rgb([0, 0, 0]));
        img.put_pixel(2, 0, Rgb([255, 0, 0]));
        let c = Channels::from_rgb(&img);
        let at = |i: usize| [c.planes[0][i], c.planes[1][i], c.planes[2][i]];
        let near = |a: [f32; 3], b: [f32; 3]| a.iter().zip(b).all(|(u, v)| (u - v).abs() < 2e-3);
        assert!(near(at(0), [1.0, 0.5, 0.5]), "{:?}", at(0));
        assert!(near(at(1), [0.0, 0.5, 0.5]), "{:?}", at(1));
        // Red: L 53.24, a 80.09, b 67.20 (the standard sRGB table).
        assert!(
            near(at(2), [0.5324, 80.09 / 200.0 + 0.5, 67.20 / 200.0 + 0.5]),
            "{:?}",
            at(2)
        );
    }

    #[test]
    fn planes_of_the_wrong_length_are_refused() {
        let e = Channels::new(3, 2, vec![vec![0.0; 6], vec![0.0; 5]]).unwrap_err();
        assert!(e.to_string().contains("channel 1"), "{e}");
        assert!(Channels::new(3, 2, vec![]).is_err());
    }
}
