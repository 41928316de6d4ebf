//! Image files in and out for every command: decoding with bounded size (a huge or hostile file
//! is refused before it is decoded into memory) and PNG encoding for outputs and overlays.

use std::path::Path;

use anyhow::{Context, Result, anyhow};

/// The pixel budget of every command and of `castellan serve`: the most pixels an input image
/// may have. 40 Mpx takes a 300-dpi scan of an A2 sheet and a 7 300 × 5 500 photo; larger images
/// are refused before they are decoded, with a message naming the image and the budget. It
/// bounds peak memory: measured at the budget, the façade stage (ch. 3's 18 features a pixel)
/// peaks at about 4 GB, every other command under 2 GB (docs/limits.md has the table).
pub const PIXEL_BUDGET: u64 = 40_000_000;
/// Largest side accepted, in pixels (a 20 000 × 2 000 panorama still fits the budget).
pub const MAX_SIDE: u32 = 20_000;
/// Most bytes a decoder may allocate: the budget's pixels at 4 channels of 16 bits (320 MB), and
/// some.
pub const MAX_ALLOC: u64 = 512 << 20;
/// Largest image file read, in bytes (a 40 Mpx 16-bit RGBA PNG stored without compression).
pub const MAX_FILE_BYTES: u64 = 512 << 20;

/// Reads any supported image (PNG, JPEG, PNM), naming the file in every error.
pub fn read_image(path: &Path) -> Result<image::DynamicImage> {
    let name = path.display().to_string();
    Ok(decode(&read_file(path)?, &name)?.0)
}

/// An image file as RGB, read as [`read_image`] reads it.
pub fn read_rgb(path: &Path) -> Result<image::RgbImage> {
    Ok(read_image(path)?.to_rgb8())
}

/// An image file's bytes, undecoded, refusing files over [`MAX_FILE_BYTES`] (and endless ones
/// like /dev/zero).
pub fn read_file(path: &Path) -> Result<Vec<u8>> {
    crate::text::read_bounded(
        path,
        MAX_FILE_BYTES,
        "the largest image file castellan reads",
    )
}

/// Decodes image bytes (`name` names them in errors) within the pixel budget, returning the
/// format found. The size is read from the header and checked before any pixel is decoded.
pub fn decode(bytes: &[u8], name: &str) -> Result<(image::DynamicImage, image::ImageFormat)> {
    let reader = image::ImageReader::new(std::io::Cursor::new(bytes))
        .with_guessed_format()
        .with_context(|| format!("cannot read {name}"))?;
    let format = reader.format().ok_or_else(|| {
        anyhow!("{name}: not a readable image (castellan reads PNG, JPEG and PNM)")
    })?;
    let (w, h) = reader
        .into_dimensions()
        .map_err(|e| anyhow!("{name}: not a readable image ({e})"))?;
    check_budget(w, h, name)?;
    if format == image::ImageFormat::Jpeg && !jpeg_is_complete(bytes) {
        return Err(anyhow!(
            "{name}: the JPEG file is cut short (no end-of-image marker after its last scan); \
             copy it again from its source"
        ));
    }
    let mut reader = image::ImageReader::with_format(std::io::Cursor::new(bytes), format);
    reader.limits(limits());
    let img = reader
        .decode()
        .map_err(|e| anyhow!("{name}: not a readable image ({e})"))?;
    Ok((img, format))
}

/// An image over the pixel budget: its own error type, so that `serve` can answer it apart
/// from an image that does not decode (413, not 415) without reading the header twice.
#[derive(Debug)]
pub struct OverBudget {
    name: String,
    width: u32,
    height: u32,
}

impl std::fmt::Display for OverBudget {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (name, w, h) = (&self.name, self.width, self.height);
        write!(
            f,
            "{name}: {w} × {h} pixels ({:.1} Mpx) is over castellan's pixel budget of {} Mpx \
             (at most {MAX_SIDE} px a side); scale the image down first",
            (u64::from(w) * u64::from(h)) as f64 / 1e6,
            PIXEL_BUDGET / 1_000_000
        )
    }
}

impl std::error::Error for OverBudget {}

/// Refuses a `w` × `h` image over the pixel budget or [`MAX_SIDE`].
pub fn check_budget(w: u32, h: u32, name: &str) -> Result<(), OverBudget> {
    let pixels = u64::from(w) * u64::from(h);
    if pixels > PIXEL_BUDGET || w > MAX_SIDE || h > MAX_SIDE {
        return Err(OverBudget {
            name: name.to_string(),
            width: w,
            height: h,
        });
    }
    Ok(())
}

/// The decoder limits that go with the budget.
fn limits() -> image::Limits {
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_SIDE);
    limits.max_image_height = Some(MAX_SIDE);
    limits.max_alloc = Some(MAX_ALLOC);
    limits
}

/// Whether a JPEG stream ends: an end-of-image marker (FF D9) after the start of its last scan
/// (FF DA). The decoder fills a truncated scan with grey without an error, so it is checked
/// here. Inside entropy-coded data FF is always followed by 00 or a restart marker, so FF D9
/// can only be the real end.
fn jpeg_is_complete(bytes: &[u8]) -> bool {
    let last_scan = bytes.windows(2).rposition(|w| w == [0xFF, 0xDA]);
    match last_scan {
        None => false,
        Some(i) => bytes[i..].windows(2).any(|w| w == [0xFF, 0xD9]),
    }
}

/// PNG bytes of an 8-bit image buffer; `path` names the output in errors.
pub fn png<P, C>(img: &image::ImageBuffer<P, C>, path: &Path) -> Result<Vec<u8>>
where
    P: image::PixelWithColorType,
    [P::Subpixel]: image::EncodableLayout,
    C: std::ops::Deref<Target = [P::Subpixel]>,
{
    integrate::pipeline::encode_png(img)
        .map_err(|e| anyhow::anyhow!("cannot encode {}: {e}", path.display()))
}

/// Where the person-viewable version of an index image goes (issue 22): `LABELS.png` →
/// `LABELS.view.png`, beside it.
pub fn view_path(path: &Path) -> std::path::PathBuf {
    let stem = path.file_stem().unwrap_or_default().to_string_lossy();
    path.with_file_name(format!("{stem}.view.png"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_view_of_an_index_image_sits_beside_it() {
        assert_eq!(
            view_path(Path::new("out/LABELS.png")),
            Path::new("out/LABELS.view.png")
        );
        assert_eq!(view_path(Path::new("m")), Path::new("m.view.png"));
    }

    #[test]
    fn png_round_trips() {
        let img = image::GrayImage::from_raw(2, 1, vec![0, 255]).unwrap();
        let bytes = png(&img, Path::new("x.png")).unwrap();
        let back = image::load_from_memory(&bytes).unwrap().to_luma8();
        assert_eq!(back.into_raw(), vec![0, 255]);
    }

    #[test]
    fn unreadable_and_oversized_files_are_errors_naming_the_file() {
        let dir = tempfile::tempdir().unwrap();
        let junk = dir.path().join("junk.png");
        std::fs::write(&junk, b"not an image").unwrap();
        assert!(
            read_image(&junk)
                .unwrap_err()
                .to_string()
                .contains("junk.png")
        );
        // A valid header claiming 30000 x 1 pixels is refused before decoding.
        let wide = dir.path().join("wide.pgm");
        std::fs::write(&wide, b"P5\n30000 1\n255\n").unwrap();
        let e = format!("{:#}", read_image(&wide).unwrap_err());
        assert!(e.contains("wide.pgm"), "{e}");
    }

    /// A 570 KB PNG of 20 000 × 20 000 grey pixels once took 3–7 GB in every command.
    #[test]
    fn an_image_over_the_pixel_budget_is_refused_before_decoding() {
        let dir = tempfile::tempdir().unwrap();
        let big = dir.path().join("big.pgm");
        // 20 000 x 20 000 declared, no pixel data: only the header may be read.
        std::fs::write(&big, b"P5\n20000 20000\n255\n").unwrap();
        let e = format!("{:#}", read_image(&big).unwrap_err());
        assert!(
            e.contains("big.pgm: 20000 × 20000 pixels (400.0 Mpx) is over"),
            "{e}"
        );
        assert!(e.contains("budget of 40 Mpx"), "{e}");
        // Exactly the budget passes the check, one row more does not.
        assert!(check_budget(8_000, 5_000, "x").is_ok());
        assert!(check_budget(8_000, 5_001, "x").is_err());
        assert!(check_budget(20_001, 1, "x").is_err());
    }

    #[test]
    fn a_truncated_jpeg_is_refused() {
        let img =
            image::RgbImage::from_fn(64, 48, |x, y| image::Rgb([x as u8 * 3, y as u8 * 5, 90]));
        let mut buf = std::io::Cursor::new(Vec::new());
        img.write_to(&mut buf, image::ImageFormat::Jpeg).unwrap();
        let whole = buf.into_inner();
        assert!(decode(&whole, "ok.jpg").is_ok());
        let cut = &whole[..whole.len() * 2 / 3];
        let e = format!("{:#}", decode(cut, "cut.jpg").unwrap_err());
        assert!(e.contains("cut.jpg: the JPEG file is cut short"), "{e}");
        // A PNG cut short is an error of the decoder itself.
        let mut buf = std::io::Cursor::new(Vec::new());
        img.write_to(&mut buf, image::ImageFormat::Png).unwrap();
        let png = buf.into_inner();
        assert!(decode(&png[..png.len() / 2], "cut.png").is_err());
    }
}
