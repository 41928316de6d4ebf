//! The project directory behind `castellan serve` (the PROJECT.toml contract, §6.1.1): reads and
//! atomic writes of PROJECT.toml, TRAINING.json files and uploads, with every name confined to
//! the directory, one lock so concurrent requests change the project one at a time, and the
//! project's version (the page's ETag). A hand-written PROJECT.toml keeps its comments and
//! layout: each save patches the user's document with the new values (toml_edit).

use std::path::{Component, Path, PathBuf};
use std::sync::{Mutex, MutexGuard, PoisonError};

use anyhow::{Context, Result, anyhow};
use integrate::project::{Project, TrainingSource};

use crate::output::Outputs;

pub const PROJECT_FILE: &str = "PROJECT.toml";

/// The plan cleaning (clean.rs): remembers the uploaded drawing and the strokes, so the user can
/// undo any of them: the cleaned image is always the original's binary image with every stroke
/// painted again. Part of the project's version.
pub const CLEANING_FILE: &str = "plan_cleaning.json";

/// One served project directory.
pub struct Store {
    /// Canonical, so a resolved file can be checked to lie inside it.
    pub dir: PathBuf,
    lock: Mutex<()>,
}

impl Store {
    /// Opens `dir`, creating it when missing; an existing PROJECT.toml must parse.
    pub fn open(dir: &Path) -> Result<Store> {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("cannot create the project folder {}", dir.display()))?;
        let dir = dir
            .canonicalize()
            .with_context(|| format!("cannot open the project folder {}", dir.display()))?;
        let store = Store {
            dir,
            lock: Mutex::new(()),
        };
        store.load()?;
        Ok(store)
    }

    /// Held for the whole of any request that reads or changes the project.
    pub fn lock(&self) -> MutexGuard<'_, ()> {
        self.lock.lock().unwrap_or_else(PoisonError::into_inner)
    }

    /// The project, or None before a plan drawing was uploaded.
    pub fn load(&self) -> Result<Option<Project>> {
        let path = self.dir.join(PROJECT_FILE);
        if !path.exists() {
            return Ok(None);
        }
        let text = crate::text::read_text(&path)?;
        let project =
            Project::parse_unchecked(&text).map_err(|e| anyhow!("{}:{e}", path.display()))?;
        check_in_progress(&project).map_err(|e| anyhow!("{}:{e}", path.display()))?;
        Ok(Some(project))
    }

    /// The project, or an error telling the user to upload a plan first.
    pub fn require(&self) -> Result<Project> {
        self.load()?
            .ok_or_else(|| anyhow!("the project has no plan drawing yet: upload one first"))
    }

    /// Writes the files (names relative to the project) and the project together, each atomically.
    pub fn commit(&self, project: Option<&Project>, files: Vec<(String, Vec<u8>)>) -> Result<()> {
        let mut out = Outputs::default();
        for (name, bytes) in files {
            out.add(&self.path(&name)?, bytes);
        }
        if let Some(p) = project {
            check_in_progress(p).map_err(|e| anyhow!("{PROJECT_FILE}:{e}"))?;
            let path = self.dir.join(PROJECT_FILE);
            let old = path
                .exists()
                .then(|| crate::text::read_text(&path))
                .transpose()?;
            let text = match old {
                Some(old) => patched(&old, p),
                None => p.to_toml(),
            };
            out.add(&path, text.into_bytes());
        }
        out.commit()
    }

    /// The version of what the page edits: PROJECT.toml, plan_cleaning.json and every
    /// façade's TRAINING.json and LINES.json, hashed. Any change to one, by the server or by
    /// hand, gives another version; the page sends it back as If-Match.
    pub fn version(&self) -> String {
        use std::hash::{Hash, Hasher};
        let mut h = std::hash::DefaultHasher::new();
        let mut add = |name: &str| {
            name.hash(&mut h);
            let bytes = self
                .existing(name)
                .ok()
                .flatten()
                .and_then(|p| std::fs::read(p).ok());
            bytes.hash(&mut h);
        };
        add(PROJECT_FILE);
        add(CLEANING_FILE);
        if let Ok(Some(p)) = self.load() {
            for f in &p.facades {
                if let TrainingSource::File(t) = &f.training {
                    add(t);
                }
                if let Some(l) = &f.lines {
                    add(l);
                }
            }
        }
        format!("\"{:016x}\"", h.finish())
    }

    /// `name`, or `STEM-2.EXT`, `STEM-3.EXT`… the first that names no file in the project (and,
    /// for a façade renamed so, whose training and lines files do not exist either, so no old
    /// boxes attach to the new photo).
    pub fn fresh_name(&self, name: &str, facade: bool) -> Result<String> {
        let taken =
            |n: &str| -> Result<bool> { Ok(std::fs::symlink_metadata(self.path(n)?).is_ok()) };
        if !taken(name)? {
            return Ok(name.to_string());
        }
        let (stem, ext) = match name.rsplit_once('.') {
            Some((s, e)) if !s.is_empty() => (s, format!(".{e}")),
            _ => (name, String::new()),
        };
        for k in 2..10_000 {
            let candidate = format!("{stem}-{k}{ext}");
            let s = format!("{stem}-{k}");
            if taken(&candidate)?
                || (facade
                    && (taken(&format!("{s}.training.json"))?
                        || taken(&format!("{s}.lines.json"))?))
            {
                continue;
            }
            return Ok(candidate);
        }
        Err(anyhow!(
            "no free file name like {name} in the project folder"
        ))
    }

    /// A name inside the project as a path; anything that could leave the folder is refused.
    pub fn path(&self, name: &str) -> Result<PathBuf> {
        let rel = relative(name)
            .ok_or_else(|| anyhow!("\"{name}\" is not a file name inside the project folder"))?;
        Ok(self.dir.join(rel))
    }

    /// An existing file inside the project, following symbolic links only if they stay inside.
    pub fn existing(&self, name: &str) -> Result<Option<PathBuf>> {
        let path = self.path(name)?;
        match path.canonicalize() {
            Ok(real) if real.starts_with(&self.dir) && real.is_file() => Ok(Some(real)),
            Ok(real) if !real.starts_with(&self.dir) => Err(anyhow!(
                "\"{name}\" is not a file name inside the project folder"
            )),
            _ => Ok(None),
        }
    }
}

/// The files the project names, read through the store's confinement: the pipeline's stages
/// (`integrate::pipeline`) read the served project through this, as `reconstruct` reads a folder.
impl integrate::pipeline::Files for Store {
    fn image(&self, name: &str) -> Result<image::DynamicImage, String> {
        let path = self.path(name).map_err(|e| format!("{e:#}"))?;
        crate::images::read_image(&path).map_err(|e| format!("{e:#}"))
    }

    fn json<T: serde::de::DeserializeOwned>(&self, name: &str, what: &str) -> Result<T, String> {
        let path = self.path(name).map_err(|e| format!("{e:#}"))?;
        crate::text::read_json(&path, what).map_err(|e| format!("{e:#}"))
    }
}

/// The PROJECT.toml checks of `integrate::project` except one: a façade may still lack its
/// correspondence, since the user adds photos before clicking correspondences (the project is
/// saved after every action). `castellan reconstruct` refuses such a project, naming the façade.
fn check_in_progress(p: &Project) -> Result<(), integrate::project::ProjectError> {
    let mut complete = p.clone();
    let mapped = |image: &str| p.correspondences.iter().any(|c| c.facade == image);
    if p.facades
        .iter()
        .enumerate()
        .any(|(i, f)| p.facades[..i].iter().any(|g| g.image == f.image))
    {
        return Err(integrate::project::ProjectError::Invalid(
            "a [[facade]] image is listed twice".into(),
        ));
    }
    complete.facades.retain(|f| mapped(&f.image));
    complete.gothics.retain(|g| mapped(&g.image));
    Project::from_toml(&complete.to_toml()).map(|_| ())
}

/// `p` written over the user's PROJECT.toml `old`: values that did not change keep their text,
/// comments and place; changed ones take the new value with the old one's surrounding comments;
/// new keys and tables are appended. If the patched text would not read back as `p` (a layout
/// the patch cannot follow), the plain `to_toml` text is written instead.
fn patched(old: &str, p: &Project) -> String {
    let plain = p.to_toml();
    let (Ok(mut doc), Ok(new)) = (
        old.parse::<toml_edit::DocumentMut>(),
        plain.parse::<toml_edit::DocumentMut>(),
    ) else {
        return plain;
    };
    patch_table(doc.as_table_mut(), new.as_table());
    let text = doc.to_string();
    match toml::from_str::<Project>(&text) {
        Ok(back) if back.to_toml() == plain => text,
        _ => plain,
    }
}

fn patch_table(old: &mut dyn toml_edit::TableLike, new: &dyn toml_edit::TableLike) {
    let gone: Vec<String> = old
        .iter()
        .map(|(k, _)| k.to_string())
        .filter(|k| !new.contains_key(k))
        .collect();
    for k in gone {
        old.remove(&k);
    }
    for (k, v) in new.iter() {
        match old.get_mut(k) {
            Some(item) => patch_item(item, v),
            None => {
                old.insert(k, compacted(v));
            }
        }
    }
}

fn patch_item(old: &mut toml_edit::Item, new: &toml_edit::Item) {
    use toml_edit::Item;
    if let (Some(o), Some(n)) = (old.as_array_of_tables_mut(), new.as_array_of_tables()) {
        let keep = o.len().min(n.len());
        for (i, t) in n.iter().enumerate().take(keep) {
            if let Some(ot) = o.get_mut(i) {
                patch_table(ot, t);
            }
        }
        while o.len() > n.len() {
            o.remove(o.len() - 1);
        }
        for t in n.iter().skip(keep) {
            if let Item::Table(t) = compacted(&Item::Table(t.clone())) {
                o.push(t);
            }
        }
        return;
    }
    if let (Some(o), Some(n)) = (old.as_table_like_mut(), new.as_table_like()) {
        patch_table(o, n);
        return;
    }
    if let (Some(o), Some(n)) = (old.as_value(), new.as_value()) {
        if same_value(o, n) {
            return;
        }
        let Item::Value(mut v) = compacted(new) else {
            return;
        };
        *v.decor_mut() = o.decor().clone();
        *old = Item::Value(v);
        return;
    }
    *old = compacted(new);
}

/// `item` with its arrays and inline tables on one line each (`[[320.0, 303.0]]`), as a person
/// writes them, rather than one number a line.
fn compacted(i: &toml_edit::Item) -> toml_edit::Item {
    fn value(v: &mut toml_edit::Value) {
        match v {
            toml_edit::Value::Array(a) => {
                a.iter_mut().for_each(value);
                a.fmt();
                a.set_trailing_comma(false);
                a.set_trailing("");
            }
            toml_edit::Value::InlineTable(t) => {
                t.iter_mut().for_each(|(_, v)| value(v));
                t.fmt();
            }
            _ => {}
        }
    }
    // A new table keeps no position from the plain text it came from: placed by the old
    // document's numbering, a new `[[gothic.element]]` would be written before its own
    // `[[gothic]]` (a duplicate key); without one it follows the table written before it.
    fn table(t: &mut toml_edit::Table) {
        t.set_position(None);
        t.iter_mut().for_each(|(_, i)| item(i));
    }
    fn item(i: &mut toml_edit::Item) {
        match i {
            toml_edit::Item::Value(v) => value(v),
            toml_edit::Item::Table(t) => table(t),
            toml_edit::Item::ArrayOfTables(a) => a.iter_mut().for_each(table),
            toml_edit::Item::None => {}
        }
    }
    let mut out = i.clone();
    item(&mut out);
    out
}

/// Whether two TOML values are equal as data (`255` and `255.0`, `[1,2]` and `[ 1, 2 ]`):
/// PROJECT.toml's numbers are all read as f64, and the user's integers must stay as written.
fn same_value(a: &toml_edit::Value, b: &toml_edit::Value) -> bool {
    use toml::Value as V;
    fn same(a: &V, b: &V) -> bool {
        match (a, b) {
            (V::Integer(i), V::Float(f)) | (V::Float(f), V::Integer(i)) => *i as f64 == *f,
            (V::Array(x), V::Array(y)) => {
                x.len() == y.len() && x.iter().zip(y).all(|(a, b)| same(a, b))
            }
            (V::Table(x), V::Table(y)) => {
                x.len() == y.len() && x.iter().all(|(k, a)| y.get(k).is_some_and(|b| same(a, b)))
            }
            _ => a == b,
        }
    }
    let data = |v: &toml_edit::Value| {
        let mut v = v.clone();
        v.decor_mut().clear();
        toml::from_str::<toml::Table>(&format!("v = {v}"))
            .ok()
            .and_then(|mut t| t.remove("v"))
    };
    matches!((data(a), data(b)), (Some(x), Some(y)) if same(&x, &y))
}

/// `name` as a relative path of plain components; absolute paths, `..`, `.`-prefixed
/// (hidden) components and backslashes are refused.
pub fn relative(name: &str) -> Option<PathBuf> {
    if name.is_empty() || name.contains(['\\', '\0']) {
        return None;
    }
    let mut out = PathBuf::new();
    for c in Path::new(name).components() {
        match c {
            Component::Normal(s) if !s.to_string_lossy().starts_with('.') => out.push(s),
            _ => return None,
        }
    }
    (!out.as_os_str().is_empty()).then_some(out)
}

/// A safe file name for an upload: the client's base name reduced to `[A-Za-z0-9._-]`, ending
/// in an extension of the format the bytes decoded as.
pub fn upload_name(client_name: &str, format: image::ImageFormat) -> String {
    let base = client_name.rsplit(['/', '\\']).next().unwrap_or("");
    let mut name: String = base
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '.' | '-' | '_') {
                c
            } else {
                '_'
            }
        })
        .collect::<String>()
        .trim_start_matches('.')
        .chars()
        .take(100)
        .collect();
    if name.is_empty() {
        name = "upload".into();
    }
    let extensions = format.extensions_str();
    let ext = Path::new(&name)
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    if !ext.is_some_and(|e| extensions.contains(&e.as_str())) {
        name.push('.');
        name.push_str(extensions.first().copied().unwrap_or("img"));
    }
    name
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_that_leave_the_folder_are_refused() {
        for bad in [
            "",
            "../x",
            "a/../../x",
            "/etc/passwd",
            ".git/config",
            "a\\..\\x",
            "./x",
        ] {
            assert!(relative(bad).is_none(), "{bad}");
        }
        assert_eq!(
            relative("out/model.glb"),
            Some(PathBuf::from("out/model.glb"))
        );
    }

    #[test]
    fn upload_names_are_sanitised_and_carry_the_decoded_format() {
        use image::ImageFormat::{Jpeg, Png};
        assert_eq!(
            upload_name("C:\\photos\\keep south.JPG", Jpeg),
            "keep_south.JPG"
        );
        assert_eq!(upload_name("../../evil.sh", Png), "evil.sh.png");
        assert_eq!(upload_name("..", Png), "upload.png");
    }

    #[test]
    fn a_symbolic_link_out_of_the_project_is_not_served() {
        let outside = tempfile::tempdir().unwrap();
        std::fs::write(outside.path().join("secret"), b"x").unwrap();
        let dir = tempfile::tempdir().unwrap();
        let store = Store::open(dir.path()).unwrap();
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink(outside.path().join("secret"), dir.path().join("link"))
                .unwrap();
            assert!(store.existing("link").is_err());
        }
        std::fs::write(dir.path().join("inside"), b"y").unwrap();
        assert!(store.existing("inside").unwrap().is_some());
        assert!(store.existing("missing").unwrap().is_none());
    }

    #[test]
    fn an_invalid_project_is_never_written() {
        let dir = tempfile::tempdir().unwrap();
        let store = Store::open(dir.path()).unwrap();
        assert!(store.load().unwrap().is_none());
        let mut p = Project::from_toml("plan = \"p.png\"").unwrap();
        store.commit(Some(&p), vec![]).unwrap();
        assert_eq!(store.load().unwrap().unwrap().plan, "p.png");
        p.metres_per_pixel = Some(-1.0);
        assert!(store.commit(Some(&p), vec![]).is_err());
        assert_eq!(store.load().unwrap().unwrap().metres_per_pixel, None);
        // A façade waiting for its correspondence is a valid state to save, not to reconstruct.
        p.metres_per_pixel = None;
        p.facades.push(integrate::project::FacadeEntry {
            image: "f.png".into(),
            training: TrainingSource::File("f.training.json".into()),
            lines: None,
            rectified: false,
            bbox: None,
            metres_per_pixel: None,
            fix: Default::default(),
        });
        store.commit(Some(&p), vec![]).unwrap();
        assert_eq!(store.load().unwrap().unwrap().facades.len(), 1);
        p.facades.push(p.facades[0].clone());
        assert!(store.commit(Some(&p), vec![]).is_err());
    }
}
