//! Photo appearances (§7.2.2, figure 7.6): each mapped façade's rectified photo, cropped to the
//! façade, becomes the texture stretched over its wall; crops of the user's wall boxes become
//! the sample set from which walls without a photo pick one per shape.

use image::RgbImage;

use crate::estimate::Estimate;
use crate::photo::{FacadeEstimate, crop};

/// A texture image and the name the program uses for it.
pub struct Texture {
    pub name: String,
    pub image: RgbImage,
}

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

/// The façade photos, cropped to each mapped façade; sets `texture` on the mapped façades.
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
                    image,
                });
            }
            f.texture = Some(name);
        }
    }
    out
}

/// Crops of every wall training box of every photo (rectified pixels), and their mean width in
/// model units where the photo is mapped (for the real-scale projection of the samples).
pub(crate) fn wall_samples(
    estimate: &Estimate,
    photos: &[FacadeEstimate],
) -> (Vec<Texture>, Option<f64>) {
    let mut out = Vec::new();
    let mut widths = Vec::new();
    for p in photos {
        let scale = estimate
            .structures
            .iter()
            .flat_map(|s| &s.facades)
            .find(|f| f.image == p.name)
            .map(|f| f.scale);
        for (k, b) in p
            .training
            .classes
            .get(&facade::classify::Class::Wall)
            .into_iter()
            .flatten()
            .enumerate()
        {
            if let Some(image) = crop(&p.rectified, *b) {
                if let Some(s) = scale {
                    widths.push(f64::from(image.width()) * s);
                }
                out.push(Texture {
                    name: format!("textures/wall_{}_{}.png", safe_stem(&p.name), k + 1),
                    image,
                });
            }
        }
    }
    let mean = (!widths.is_empty()).then(|| widths.iter().sum::<f64>() / widths.len() as f64);
    (out, mean)
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
