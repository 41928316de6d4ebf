//! Atomic output: every file is written to a temporary file beside its destination and renamed
//! into place, so a failed run never leaves a half-written output.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

/// Files to write, committed together only after every one was produced in memory.
#[derive(Default)]
pub struct Outputs {
    files: Vec<(PathBuf, Vec<u8>)>,
}

impl Outputs {
    pub fn add(&mut self, path: &Path, bytes: Vec<u8>) {
        self.files.push((path.to_path_buf(), bytes));
    }

    /// Writes each file atomically (temp file + rename), creating parent folders.
    pub fn commit(self) -> Result<()> {
        let mut staged = Vec::with_capacity(self.files.len());
        for (path, bytes) in &self.files {
            let dir = match path.parent() {
                Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
                _ => PathBuf::from("."),
            };
            std::fs::create_dir_all(&dir)
                .with_context(|| format!("cannot create folder {}", dir.display()))?;
            let mut tmp = tempfile::NamedTempFile::new_in(&dir)
                .with_context(|| format!("cannot write in {}", dir.display()))?;
            tmp.write_all(bytes)
                .with_context(|| format!("cannot write {}", path.display()))?;
            // Temporary files are private (0600); outputs are ordinary files others may read.
            #[cfg(unix)]
            {
                use std::os::unix::fs::PermissionsExt;
                tmp.as_file()
                    .set_permissions(std::fs::Permissions::from_mode(0o644))
                    .with_context(|| format!("cannot write {}", path.display()))?;
            }
            staged.push((tmp, path));
        }
        for (tmp, path) in staged {
            tmp.persist(path)
                .with_context(|| format!("cannot write {}", path.display()))?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn commit_writes_all_files_and_leaves_no_temporaries() {
        let dir = tempfile::tempdir().unwrap();
        let mut out = Outputs::default();
        out.add(&dir.path().join("a/b.txt"), b"hello".to_vec());
        out.add(&dir.path().join("c.txt"), b"x".to_vec());
        out.commit().unwrap();
        assert_eq!(std::fs::read(dir.path().join("a/b.txt")).unwrap(), b"hello");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 2);
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let mode = std::fs::metadata(dir.path().join("c.txt"))
                .unwrap()
                .permissions()
                .mode();
            assert_eq!(mode & 0o777, 0o644);
        }
    }
}
