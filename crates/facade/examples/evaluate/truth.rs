//! The data sets' ground truth as class labels (`facade::eval`'s classes): CMP's palette
//! masks, Art-deco's label grids, LabelMeFacade's colour masks (carried through §3.1.1's
//! rectification with their photo).

use std::path::{Path, PathBuf};

use facade::eval::IGNORE;

pub fn data() -> PathBuf {
    match std::env::var("FACADE_DATA") {
        Ok(d) => PathBuf::from(d),
        Err(_) => Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data"),
    }
}

/// CMP masks are palette PNGs; the image crate expands them to RGB, so map the palette back.
pub fn cmp_truth(path: &Path) -> Option<Vec<u8>> {
    let img = image::open(path).ok()?.to_rgb8();
    Some(facade::eval::cmp_classes(&img))
}

/// Art-deco labels: Door 0, Shop 1, Balcony 2, Window 3, Wall 4, Sky 5, Roof 6, -1 void.
pub fn artdeco_truth(path: &Path) -> Option<Vec<u8>> {
    let text = std::fs::read_to_string(path).ok()?;
    Some(
        text.split_whitespace()
            .map(|v| match v.parse::<i32>() {
                Ok(3) => 2,
                Ok(0 | 1 | 2 | 4) => 1,
                Ok(5 | 6) => 0,
                _ => IGNORE,
            })
            .collect(),
    )
}

/// LabelMeFacade colours (RGB PNG, PROVENANCE.md): window 0:0:128 → window; building 128:0:0
/// and door 128:128:0 → wall; sky, road, pavement, vegetation and car → background; "various"
/// 0:0:0 and anything else is ignored.
fn labelme_truth(path: &Path) -> Option<Vec<u8>> {
    let img = image::open(path).ok()?.to_rgb8();
    Some(
        img.pixels()
            .map(|p| match p.0 {
                [0, 0, 128] => 2,
                [128, 0, 0] | [128, 128, 0] => 1,
                [0, 128, 128] | [128, 64, 0] | [128, 128, 128] | [0, 128, 0] | [128, 0, 128] => 0,
                _ => IGNORE,
            })
            .collect(),
    )
}

/// A LabelMeFacade photo (oblique) and its labels through the automatic rectification of
/// §3.1.1, as `castellan reconstruct` rectifies a photo: the photo warped bilinearly and
/// written to `dir` (for `run`), the labels carried nearest-neighbour, pixels from outside the
/// photo ignored.
pub fn rectified_labelme(
    photo: &Path,
    labels: &Path,
    dir: &Path,
) -> Result<(PathBuf, Vec<u8>), String> {
    let img = image::open(photo).map_err(|e| e.to_string())?.to_rgb8();
    let truth = labelme_truth(labels).ok_or("unreadable labels")?;
    let (w, h) = (img.width() as usize, img.height() as usize);
    if truth.len() != w * h {
        return Err("labels and photo differ in size".into());
    }
    let r = facade::rectify::rectify(&img, &facade::rectify::RectifyParams::default())
        .map_err(|e| e.to_string())?;
    let warped = r.warp(&img).map_err(|e| e.to_string())?;
    let back = r.h.try_inverse().ok_or("singular homography")?;
    let (rw, rh) = (r.width as usize, r.height as usize);
    let mut out = vec![IGNORE; rw * rh];
    for y in 0..rh {
        for x in 0..rw {
            let Some((u, v)) = facade::rectify::apply(&back, x as f64, y as f64) else {
                continue;
            };
            let (u, v) = (u.round(), v.round());
            // Black in the warp: beyond the photo or past its vanishing line.
            if u >= 0.0
                && v >= 0.0
                && u < w as f64
                && v < h as f64
                && warped.get_pixel(x as u32, y as u32).0 != [0, 0, 0]
            {
                out[y * rw + x] = truth[v as usize * w + u as usize];
            }
        }
    }
    let stem = photo.file_stem().unwrap_or_default().to_string_lossy();
    let path = dir.join(format!("{stem}.png"));
    warped.save(&path).map_err(|e| e.to_string())?;
    Ok((path, out))
}
