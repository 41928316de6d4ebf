//! The project directory behind `castellan serve` (the PROJECT.toml contract, §6.1.1): reads and
//! atomic writes of PROJECT.toml, TRAINING.json files and uploads, with every name confined to
//! the directory, and one lock so concurrent requests change the project one at a time.

use std::path::{Component, Path, PathBuf};
use std::sync::{Mutex, MutexGuard, PoisonError};

use anyhow::{Context, Result, anyhow};
use facade::classify::Training;
use integrate::project::{FacadeEntry, Project, TrainingSource};

use crate::output::Outputs;

pub const PROJECT_FILE: &str = "PROJECT.toml";

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
        let text = match std::fs::read_to_string(&path) {
            Ok(t) => t,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
            Err(e) => return Err(anyhow!("cannot read {}: {e}", path.display())),
        };
        let project: Project =
            toml::from_str(&text).map_err(|e| anyhow!("{}: {}", path.display(), e.message()))?;
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
            out.add(&self.dir.join(PROJECT_FILE), p.to_toml().into_bytes());
        }
        out.commit()
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

    /// A façade's training boxes, from its file or inline; none yet is an empty set.
    pub fn training(&self, f: &FacadeEntry) -> Result<Training> {
        match &f.training {
            TrainingSource::Inline(t) => Ok(t.clone()),
            TrainingSource::File(name) => match self.existing(name)? {
                None => Ok(Training {
                    classes: Default::default(),
                }),
                Some(path) => {
                    let text = std::fs::read_to_string(&path)
                        .with_context(|| format!("cannot read {name}"))?;
                    serde_json::from_str(&text).map_err(|e| anyhow!("{name}: {e}"))
                }
            },
        }
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
    Project::from_toml(&complete.to_toml()).map(|_| ())
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
        p.scale = Some(-1.0);
        assert!(store.commit(Some(&p), vec![]).is_err());
        assert_eq!(store.load().unwrap().unwrap().scale, None);
        // A façade waiting for its correspondence is a valid state to save, not to reconstruct.
        p.scale = None;
        p.facades.push(integrate::project::FacadeEntry {
            image: "f.png".into(),
            training: TrainingSource::File("f.training.json".into()),
            lines: None,
            rectified: false,
            bbox: None,
            scale: None,
        });
        store.commit(Some(&p), vec![]).unwrap();
        assert_eq!(store.load().unwrap().unwrap().facades.len(), 1);
        p.facades.push(p.facades[0].clone());
        assert!(store.commit(Some(&p), vec![]).is_err());
    }
}
