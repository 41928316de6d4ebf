//! Inputs read from files: one bounded read for every input, text or image (`read_bounded`), so
//! `/dev/zero` or a runaway file is refused instead of filling memory; and text inputs
//! (PROJECT.toml, TRAINING.json, LINES.json, VSG programs) as UTF-8 checked with the
//! line:column of the first bad byte. A leading byte-order mark, which Windows editors write,
//! is dropped rather than reported as an invisible character.

use std::io::Read;
use std::path::Path;

use anyhow::{Result, anyhow};

/// Largest text input accepted, in bytes. A generated VSG program for a large castle is about
/// 100 KB and a PROJECT.toml a few KB, so 16 MiB leaves room for hand-made extremes.
pub const MAX_TEXT_BYTES: u64 = 16 << 20;

/// Reads `path` as UTF-8 text of at most [`MAX_TEXT_BYTES`], naming the file in every error.
pub fn read_text(path: &Path) -> Result<String> {
    read_text_limited(path, MAX_TEXT_BYTES)
}

/// [`read_text`] with an explicit limit (tests).
pub fn read_text_limited(path: &Path, limit: u64) -> Result<String> {
    let bytes = read_bounded(
        path,
        limit,
        "the most castellan reads as text (is it the right file?)",
    )?;
    decode(&bytes).map_err(|e| anyhow!("{}:{e}", path.display()))
}

/// The bytes of any input file (text or image) of at most `limit` bytes: a longer or endless
/// one (`/dev/zero`) is refused after `limit + 1` bytes, saying it is larger than `limit`,
/// `the_most` (what the limit is).
pub fn read_bounded(path: &Path, limit: u64, the_most: &str) -> Result<Vec<u8>> {
    let name = path.display();
    let file = std::fs::File::open(path).map_err(|e| anyhow!("cannot read {name}: {e}"))?;
    if file.metadata().is_ok_and(|m| m.is_dir()) {
        return Err(anyhow!("cannot read {name}: it is a folder"));
    }
    let mut bytes = Vec::new();
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| anyhow!("cannot read {name}: {e}"))?;
    if bytes.len() as u64 > limit {
        return Err(anyhow!(
            "{name}: larger than {} MiB, {the_most}",
            limit >> 20
        ));
    }
    Ok(bytes)
}

/// A JSON file (`what` names the format, as "a TRAINING.json"), with errors at `file:line:col`.
pub fn read_json<T: serde::de::DeserializeOwned>(path: &Path, what: &str) -> Result<T> {
    let text = read_text(path)?;
    serde_json::from_str(&text).map_err(|e| {
        anyhow!(
            "{}:{}:{}: not {what}: {e}",
            path.display(),
            e.line(),
            e.column()
        )
    })
}

/// UTF-8 text of `bytes` without a leading byte-order mark, or `line:col: message` of the first
/// invalid byte (columns count characters, from 1).
pub fn decode(bytes: &[u8]) -> Result<String, String> {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    match std::str::from_utf8(bytes) {
        Ok(s) => Ok(s.to_owned()),
        Err(e) => {
            let good = std::str::from_utf8(&bytes[..e.valid_up_to()]).unwrap_or_default();
            let line = good.matches('\n').count() + 1;
            let col = good.rsplit('\n').next().unwrap_or("").chars().count() + 1;
            Err(format!(
                "{line}:{col}: not UTF-8 text (byte 0x{:02X}); save the file as UTF-8",
                bytes[e.valid_up_to()]
            ))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn invalid_utf8_is_reported_at_its_line_and_column() {
        assert_eq!(
            decode(b"ab\ncd\xFFe").unwrap_err(),
            "2:3: not UTF-8 text (byte 0xFF); save the file as UTF-8"
        );
        assert!(
            decode(b"\xC3\xA9\n\xC3\xA9x\x80")
                .unwrap_err()
                .starts_with("2:3:")
        );
    }

    #[test]
    fn a_byte_order_mark_is_dropped() {
        assert_eq!(decode(b"\xEF\xBB\xBFplan = 1").unwrap(), "plan = 1");
        assert_eq!(decode(b"plan").unwrap(), "plan");
    }

    #[test]
    fn an_endless_or_oversized_file_is_refused_naming_it() {
        #[cfg(unix)]
        {
            let e = read_text_limited(Path::new("/dev/zero"), 1 << 20).unwrap_err();
            assert!(
                e.to_string().contains("/dev/zero: larger than 1 MiB"),
                "{e}"
            );
        }
        let dir = tempfile::tempdir().unwrap();
        let f = dir.path().join("big.toml");
        std::fs::write(&f, vec![b'a'; (1 << 20) + 1]).unwrap();
        assert!(read_text_limited(&f, 1 << 20).is_err());
        std::fs::write(&f, vec![b'a'; 1 << 20]).unwrap();
        assert_eq!(read_text_limited(&f, 1 << 20).unwrap().len(), 1 << 20);
        let e = read_text(dir.path()).unwrap_err();
        assert!(e.to_string().contains("folder"), "{e}");
        let e = read_text(&dir.path().join("missing.json")).unwrap_err();
        assert!(e.to_string().contains("missing.json"), "{e}");
    }
}
