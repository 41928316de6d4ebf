//! Image files in and out for every command: decoding with bounded size (a huge or hostile file
//! is refused before it is decoded into memory) and PNG encoding for outputs and overlays.

use std::path::Path;

use anyhow::{Context, Result, anyhow};

/// Largest side accepted, in pixels: far above any scan or photo castellan works on.
pub const MAX_SIDE: u32 = 20_000;
/// Most bytes a decoder may allocate.
pub const MAX_ALLOC: u64 = 2 << 30;

/// Reads any supported image (PNG, JPEG, PNM), naming the file in every error.
pub fn read_image(path: &Path) -> Result<image::DynamicImage> {
    let name = path.display();
    let mut reader = image::ImageReader::open(path)
        .with_context(|| format!("cannot read {name}"))?
        .with_guessed_format()
        .with_context(|| format!("cannot read {name}"))?;
    let mut limits = image::Limits::default();
    limits.max_image_width = Some(MAX_SIDE);
    limits.max_image_height = Some(MAX_SIDE);
    limits.max_alloc = Some(MAX_ALLOC);
    reader.limits(limits);
    reader
        .decode()
        .map_err(|e| anyhow!("{name}: not a readable image ({e})"))
}

/// PNG bytes of an 8-bit image buffer; `path` names the output in errors.
pub fn png<P, C>(img: &image::ImageBuffer<P, C>, path: &Path) -> Result<Vec<u8>>
where
    P: image::PixelWithColorType,
    [P::Subpixel]: image::EncodableLayout,
    C: std::ops::Deref<Target = [P::Subpixel]>,
{
    let mut buf = std::io::Cursor::new(Vec::new());
    img.write_to(&mut buf, image::ImageFormat::Png)
        .with_context(|| format!("cannot encode {}", path.display()))?;
    Ok(buf.into_inner())
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
