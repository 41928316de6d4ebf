//! The STEP physical file encoding (ISO 10303-21) the IFC writer (`ifc.rs`, issue 24) writes
//! its entities in: numbered instances, strings, reals and the IFC GlobalIds. Kept apart from
//! the IFC mapping so the mapping reads as entities and the rules of the encoding, which a
//! reader enforces character by character, live in one place.

use std::collections::HashSet;
use std::fmt::Write;

use super::error::ExportError;

/// The DATA section being written: instances `#1`, `#2`, … in the order they are added, and
/// the GlobalIds handed out so far (each must be unique in the file).
pub(crate) struct Step {
    data: String,
    next: u64,
    guids: HashSet<String>,
}

/// A reference to an instance, `#n` in the file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Id(pub u64);

impl std::fmt::Display for Id {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "#{}", self.0)
    }
}

impl Step {
    pub fn new() -> Step {
        Step {
            data: String::new(),
            next: 1,
            guids: HashSet::new(),
        }
    }

    /// Writes `#n=ENTITY(args);` and returns `#n`. `args` is the encoded attribute list,
    /// built with [`string`], [`real`], [`list`] and `$` for unset optional attributes.
    pub fn add(&mut self, entity: &str, args: &str) -> Id {
        let id = Id(self.next);
        self.next += 1;
        // Formatting into a String cannot fail.
        let _ = writeln!(self.data, "{id}={entity}({args});");
        id
    }

    /// A GlobalId derived from `key` (the same key, the same id: files are reproducible and
    /// an element keeps its id from one export to the next), encoded as a string attribute.
    /// Should two keys hash alike, the later one is hashed again with a counter, so ids stay
    /// unique and still depend only on the order of the keys.
    pub fn guid(&mut self, key: &str) -> String {
        let mut attempt = 0u32;
        loop {
            let g = if attempt == 0 {
                ifc_guid(fnv1a_128(key.as_bytes()))
            } else {
                ifc_guid(fnv1a_128(format!("{key}#{attempt}").as_bytes()))
            };
            if self.guids.insert(g.clone()) {
                return format!("'{g}'");
            }
            attempt += 1;
        }
    }

    /// The whole file: the header (`description`, `name`, `timestamp` and the IFC4 schema)
    /// and the DATA section.
    pub fn finish(self, name: &str, timestamp: &str) -> String {
        let mut out = String::with_capacity(self.data.len() + 512);
        out.push_str("ISO-10303-21;\nHEADER;\n");
        // ReferenceView: tessellated geometry for coordination, which is what castellan has.
        out.push_str("FILE_DESCRIPTION(('ViewDefinition [ReferenceView_V1.2]'),'2;1');\n");
        let _ = writeln!(
            out,
            "FILE_NAME({},{},(''),(''),'castellan vsg {}','castellan','');",
            string(name),
            string(timestamp),
            env!("CARGO_PKG_VERSION"),
        );
        out.push_str("FILE_SCHEMA(('IFC4'));\nENDSEC;\nDATA;\n");
        out.push_str(&self.data);
        out.push_str("ENDSEC;\nEND-ISO-10303-21;\n");
        out
    }
}

/// A STEP string literal: apostrophes doubled, backslashes doubled, and every character that
/// is not printable ASCII encoded (ISO 10303-21 §6.4.3.3): runs of BMP characters as
/// `\X2\…\X0\` (4 hex digits each), of characters beyond it as `\X4\…\X0\` (8 each), so the
/// file itself is pure ASCII whatever the names.
pub(crate) fn string(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('\'');
    // The open run: 0 none, else its digits per character (4 in \X2\, 8 in \X4\).
    let mut run = 0;
    for c in s.chars() {
        let digits = match c {
            ' '..='~' => 0,
            c if (c as u32) < 0x1_0000 => 4,
            _ => 8,
        };
        if digits != run {
            if run != 0 {
                out.push_str("\\X0\\");
            }
            match digits {
                4 => out.push_str("\\X2\\"),
                8 => out.push_str("\\X4\\"),
                _ => {}
            }
            run = digits;
        }
        match c {
            '\'' => out.push_str("''"),
            '\\' => out.push_str("\\\\"),
            c if digits == 0 => out.push(c),
            c => {
                let _ = write!(out, "{:0w$X}", c as u32, w = digits);
            }
        }
    }
    if run != 0 {
        out.push_str("\\X0\\");
    }
    out.push('\'');
    out
}

/// A STEP real: always with a decimal point (`1.0`, `0.25`, `1.5E-7`), shortest digits that
/// read back as the same f64, or [`ExportError::NotFinite`] naming `what`.
pub(crate) fn real(v: f64, what: impl FnOnce() -> String) -> Result<String, ExportError> {
    if !v.is_finite() {
        return Err(ExportError::NotFinite {
            what: what(),
            value: vec![v],
        });
    }
    if v == 0.0 {
        return Ok("0.0".into()); // also −0
    }
    // `{:?}` is the shortest round-trip form, with an exponent (`1e-7`) for tiny and huge
    // values and a point otherwise; STEP wants a point in the mantissa and an upper-case E.
    let s = format!("{v:?}");
    Ok(match s.split_once('e') {
        Some((mantissa, exp)) if mantissa.contains('.') => format!("{mantissa}E{exp}"),
        Some((mantissa, exp)) => format!("{mantissa}.E{exp}"),
        None if s.contains('.') => s,
        None => s + ".",
    })
}

/// Encoded values as a STEP aggregate `(a,b,c)`.
pub(crate) fn list<I, T>(items: I) -> String
where
    I: IntoIterator<Item = T>,
    T: std::fmt::Display,
{
    let mut out = String::from("(");
    for (i, item) in items.into_iter().enumerate() {
        if i > 0 {
            out.push(',');
        }
        let _ = write!(out, "{item}");
    }
    out.push(')');
    out
}

/// 128-bit FNV-1a: small, stable across platforms and Rust versions (unlike `std`'s hasher),
/// and spreads short keys over all 128 bits.
fn fnv1a_128(bytes: &[u8]) -> u128 {
    const OFFSET: u128 = 0x6c62_272e_07bb_0142_62b8_2175_6295_c58d;
    const PRIME: u128 = 0x0000_0000_0100_0000_0000_0000_0000_013b;
    bytes
        .iter()
        .fold(OFFSET, |h, &b| (h ^ b as u128).wrapping_mul(PRIME))
}

/// IFC's compressed GUID: 128 bits as 22 characters of its own base-64 alphabet, the first
/// character carrying the top 2 bits and each of the other 21 six bits. The version and
/// variant bits of a name-based UUID are set, so the id is a well-formed UUID as well.
fn ifc_guid(hash: u128) -> String {
    const ALPHABET: &[u8; 64] = b"0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz_$";
    // Version 5 (name-based) in bits 76..80, variant 10 in bits 62..64.
    let v = (hash & !(0xf << 76) & !(0x3 << 62)) | (0x5 << 76) | (0x2 << 62);
    (0..22)
        .map(|i| {
            let shift = 6 * (21 - i);
            ALPHABET[((v >> shift) & 0x3f) as usize] as char
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strings_escape_apostrophes_backslashes_and_non_ascii() {
        assert_eq!(string("plain"), "'plain'");
        assert_eq!(string("Coucy's keep"), "'Coucy''s keep'");
        assert_eq!(string("a\\b"), "'a\\\\b'");
        assert_eq!(string("Château"), "'Ch\\X2\\00E2\\X0\\teau'");
        assert_eq!(string("été"), "'\\X2\\00E9\\X0\\t\\X2\\00E9\\X0\\'");
        assert_eq!(string("a\nb"), "'a\\X2\\000A\\X0\\b'");
        // Beyond the BMP: 8 digits in a run of its own.
        assert_eq!(string("é🏰"), "'\\X2\\00E9\\X0\\\\X4\\0001F3F0\\X0\\'");
    }

    #[test]
    fn reals_always_have_a_point_and_read_back_exactly() {
        let r = |v: f64| real(v, String::new).unwrap();
        assert_eq!(r(1.0), "1.0");
        assert_eq!(r(-2.0), "-2.0");
        assert_eq!(r(0.25), "0.25");
        assert_eq!(r(-0.0), "0.0");
        assert_eq!(r(1e-7), "1.E-7");
        assert_eq!(r(1.5e-7), "1.5E-7");
        assert_eq!(r(1e300), "1.E300");
        for v in [0.1, 1.0 / 3.0, 123456.789, 4.0e6 + 0.001, 1e-300] {
            let s = r(v).replace(".E", "E");
            assert_eq!(s.parse::<f64>().unwrap(), v);
        }
        assert!(matches!(
            real(f64::NAN, || "x".into()),
            Err(ExportError::NotFinite { .. })
        ));
        assert!(real(f64::INFINITY, || "x".into()).is_err());
    }

    #[test]
    fn guids_are_22_characters_unique_and_stable() {
        let mut s = Step::new();
        let a = s.guid("castle/keep1");
        let b = s.guid("castle/keep2");
        assert_eq!(a.len(), 24); // with the quotes
        assert_ne!(a, b);
        // The same key again gets a fresh id (a collision is resolved, never repeated).
        let again = s.guid("castle/keep1");
        assert_ne!(a, again);
        assert_eq!(Step::new().guid("castle/keep1"), a);
        // The first character carries 2 bits only.
        assert!("0123".contains(&a[1..2]));
    }
}
