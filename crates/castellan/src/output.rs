//! Atomic output: a run's files appear together or not at all, and the leftovers of a run that
//! was killed are cleaned up by the next run that writes to the same place.
//!
//! - A command that writes an output folder (`reconstruct`, `demo`, `plan --batch`) builds the
//!   whole new folder beside the old one (`.castellan-PID-NAME.new`) and swaps the two in one
//!   step (`renameat2(RENAME_EXCHANGE)` on Linux; elsewhere two renames that the next run
//!   completes if it finds them half done). Files of the old folder that this run does not
//!   write are carried into the new one as hard links, so nothing of the user's is lost.
//! - A command that writes files named by flags (they may lie in different folders) writes each
//!   to a temporary file beside its destination, then a journal of the renames, then renames
//!   them: a run killed during the renames is completed by the next run (roll forward), one
//!   killed before the journal leaves only temporaries, which the next run removes.
//!
//! Every leftover is named `.castellan-PID-…` after the process that made it; one whose process
//! is still alive is never touched.

use std::collections::HashSet;
use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, anyhow};

/// The prefix of every temporary name castellan leaves while writing.
const PREFIX: &str = ".castellan-";

/// Temporary files and staging folders of this process, removed if it is interrupted.
static IN_PROGRESS: std::sync::Mutex<Vec<PathBuf>> = std::sync::Mutex::new(Vec::new());

fn in_progress() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    IN_PROGRESS
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// On Ctrl-C or SIGTERM, removes this process's temporaries before it exits (status 130), so
/// an interrupted run leaves nothing behind; `kill -9` cannot be caught, and what it leaves is
/// swept by the next run.
pub fn clean_up_on_interrupt() {
    let _ = ctrlc::set_handler(|| {
        for path in in_progress().drain(..) {
            if path.is_dir() {
                let _ = std::fs::remove_dir_all(&path);
            } else {
                let _ = std::fs::remove_file(&path);
            }
        }
        eprintln!("interrupted: outputs left as they were");
        std::process::exit(130);
    });
}

/// Files to write, committed together only after every one was produced in memory.
#[derive(Default)]
pub struct Outputs {
    files: Vec<(PathBuf, Vec<u8>)>,
    /// The output folder that holds every file, replaced as a whole (see the module doc).
    folder: Option<PathBuf>,
}

impl Outputs {
    /// Outputs that all lie inside `folder`, which the commit replaces in one step.
    pub fn folder(folder: &Path) -> Outputs {
        Outputs {
            files: Vec::new(),
            folder: Some(folder.to_path_buf()),
        }
    }

    pub fn add(&mut self, path: &Path, bytes: Vec<u8>) {
        self.files.push((path.to_path_buf(), bytes));
    }

    /// Writes every file (see the module doc), creating parent folders.
    pub fn commit(self) -> Result<()> {
        match &self.folder {
            Some(folder) => {
                let writer = FolderWriter::begin(folder)?;
                writer.write_group(self.files)?;
                writer.finish()
            }
            None => commit_files(&self.files),
        }
    }
}

/// An output folder written in groups of files (a batch writes one group per drawing, from
/// several threads) and replaced as a whole by [`FolderWriter::finish`]. Where the folder
/// cannot be swapped (see [`swappable`]) each group is committed file by file instead.
pub struct FolderWriter {
    dest: PathBuf,
    staged: Option<StagedFolder>,
}

impl FolderWriter {
    pub fn begin(dest: &Path) -> Result<FolderWriter> {
        let staged = if swappable(dest) {
            Some(StagedFolder::begin(dest)?)
        } else {
            None
        };
        Ok(FolderWriter {
            dest: dest.to_path_buf(),
            staged,
        })
    }

    /// Writes files given by their paths inside the folder (`dest.join(rel)` is also accepted).
    pub fn write_group(&self, files: Vec<(PathBuf, Vec<u8>)>) -> Result<()> {
        let rel = |p: &Path| p.strip_prefix(&self.dest).unwrap_or(p).to_path_buf();
        match &self.staged {
            Some(staged) => {
                for (path, bytes) in &files {
                    staged.write(&rel(path), bytes)?;
                }
                Ok(())
            }
            None => {
                let files: Vec<_> = files
                    .into_iter()
                    .map(|(p, b)| (self.dest.join(rel(&p)), b))
                    .collect();
                commit_files(&files)
            }
        }
    }

    pub fn finish(self) -> Result<()> {
        match self.staged {
            Some(staged) => staged.finish(),
            None => Ok(()),
        }
    }
}

/// Whether `folder` can be replaced by a rename: not a symbolic link (the link would be
/// replaced by a folder), and not the current folder or one of its ancestors (the shell would
/// be left in the old, deleted folder). Other folders get the per-file commit.
fn swappable(folder: &Path) -> bool {
    if std::fs::symlink_metadata(folder).is_ok_and(|m| m.file_type().is_symlink()) {
        return false;
    }
    let (Ok(cwd), Ok(real)) = (std::env::current_dir(), folder.canonicalize()) else {
        return true; // a folder that does not exist yet cannot hold the current folder
    };
    !cwd.starts_with(real)
}

/// A new output folder being built beside its destination; [`StagedFolder::finish`] swaps it in.
/// Dropped unfinished (an error), it is removed and the destination is left as it was.
pub struct StagedFolder {
    dest: PathBuf,
    staging: PathBuf,
    finished: bool,
}

impl StagedFolder {
    /// Starts a new version of `dest`, first cleaning up what killed runs left beside it.
    pub fn begin(dest: &Path) -> Result<StagedFolder> {
        let parent = parent_of(dest);
        std::fs::create_dir_all(&parent)
            .with_context(|| format!("cannot create folder {}", parent.display()))?;
        sweep(&parent);
        let name = dest
            .file_name()
            .ok_or_else(|| anyhow!("{}: not a folder name", dest.display()))?
            .to_string_lossy()
            .into_owned();
        let staging = parent.join(format!("{PREFIX}{}-{name}.new", std::process::id()));
        if staging.exists() {
            std::fs::remove_dir_all(&staging)
                .with_context(|| format!("cannot remove {}", staging.display()))?;
        }
        std::fs::create_dir(&staging)
            .with_context(|| format!("cannot write in {}", parent.display()))?;
        in_progress().push(staging.clone());
        Ok(StagedFolder {
            dest: dest.to_path_buf(),
            staging,
            finished: false,
        })
    }

    /// Writes `rel` (a path inside the folder); safe to call from several threads.
    pub fn write(&self, rel: &Path, bytes: &[u8]) -> Result<()> {
        let path = self.staging.join(rel);
        let shown = self.dest.join(rel);
        if let Some(dir) = path.parent() {
            std::fs::create_dir_all(dir)
                .with_context(|| format!("cannot create folder for {}", shown.display()))?;
        }
        std::fs::write(&path, bytes).with_context(|| format!("cannot write {}", shown.display()))
    }

    /// Carries over the old folder's other files and swaps the new folder in.
    pub fn finish(mut self) -> Result<()> {
        let dest_exists = std::fs::symlink_metadata(&self.dest).is_ok();
        if dest_exists {
            if !self.dest.is_dir() {
                return Err(anyhow!(
                    "{}: exists and is not a folder; choose another output folder",
                    self.dest.display()
                ));
            }
            carry_over(&self.dest, &self.staging, Path::new("")).with_context(|| {
                format!("cannot keep the other files of {}", self.dest.display())
            })?;
            swap(&self.staging, &self.dest)?;
            // The staging name now holds the old folder.
            let _ = std::fs::remove_dir_all(&self.staging);
        } else {
            std::fs::rename(&self.staging, &self.dest)
                .with_context(|| format!("cannot write {}", self.dest.display()))?;
        }
        self.finished = true;
        Ok(())
    }
}

impl Drop for StagedFolder {
    fn drop(&mut self) {
        if !self.finished {
            let _ = std::fs::remove_dir_all(&self.staging);
        }
        in_progress().retain(|p| *p != self.staging);
    }
}

/// Hard-links (or copies) every file of `old` that the new folder lacks into it.
fn carry_over(old: &Path, new: &Path, rel: &Path) -> std::io::Result<()> {
    for entry in std::fs::read_dir(old.join(rel))? {
        let entry = entry?;
        let name = entry.file_name();
        if name.to_string_lossy().starts_with(PREFIX) {
            continue;
        }
        let rel = rel.join(&name);
        let (from, to) = (old.join(&rel), new.join(&rel));
        let kind = entry.file_type()?;
        if kind.is_dir() {
            if !to.exists() {
                std::fs::create_dir(&to)?;
            }
            if to.is_dir() {
                carry_over(old, new, &rel)?;
            }
        } else if std::fs::symlink_metadata(&to).is_err() {
            if kind.is_symlink() {
                #[cfg(unix)]
                std::os::unix::fs::symlink(std::fs::read_link(&from)?, &to)?;
            } else if std::fs::hard_link(&from, &to).is_err() {
                std::fs::copy(&from, &to)?;
            }
        }
    }
    Ok(())
}

/// Exchanges the folders `new` and `dest` (both exist): afterwards `dest` is the new folder and
/// `new` the old one.
#[cfg(target_os = "linux")]
fn swap(new: &Path, dest: &Path) -> Result<()> {
    use rustix::fs::{CWD, RenameFlags, renameat_with};
    match renameat_with(CWD, new, CWD, dest, RenameFlags::EXCHANGE) {
        Ok(()) => Ok(()),
        // Some file systems cannot exchange; two renames then, as elsewhere.
        Err(rustix::io::Errno::INVAL | rustix::io::Errno::NOSYS) => swap_by_renames(new, dest),
        Err(e) => Err(anyhow!("cannot replace {}: {e}", dest.display())),
    }
}

#[cfg(not(target_os = "linux"))]
fn swap(new: &Path, dest: &Path) -> Result<()> {
    swap_by_renames(new, dest)
}

/// `dest` → `.castellan-PID-NAME.old`, `new` → `dest`, the old one → `new`'s name. A run killed
/// between the first two renames is completed by [`sweep`].
fn swap_by_renames(new: &Path, dest: &Path) -> Result<()> {
    let old = new.with_extension("old");
    std::fs::rename(dest, &old).with_context(|| format!("cannot replace {}", dest.display()))?;
    std::fs::rename(new, dest).with_context(|| format!("cannot replace {}", dest.display()))?;
    std::fs::rename(&old, new).with_context(|| format!("cannot remove {}", old.display()))
}

/// Writes files each to a temporary file beside it, journals the renames, renames.
fn commit_files(files: &[(PathBuf, Vec<u8>)]) -> Result<()> {
    let pid = std::process::id();
    let mut swept = HashSet::new();
    let mut staged = Vec::with_capacity(files.len());
    for (path, bytes) in files {
        let dir = parent_of(path);
        std::fs::create_dir_all(&dir)
            .with_context(|| format!("cannot create folder {}", dir.display()))?;
        if swept.insert(dir.clone()) {
            sweep(&dir);
        }
        let mut tmp = tempfile::Builder::new()
            .prefix(&format!("{PREFIX}{pid}-"))
            .suffix(".tmp")
            .tempfile_in(&dir)
            .with_context(|| format!("cannot write in {}", dir.display()))?;
        in_progress().push(tmp.path().to_path_buf());
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
    let journal = match staged.first() {
        Some((_, first)) if staged.len() > 1 => {
            let mut text = String::new();
            for (tmp, path) in &staged {
                let dest = absolute(path);
                text.push_str(&format!("{}\t{}\n", tmp.path().display(), dest.display()));
            }
            let journal = parent_of(first).join(format!("{PREFIX}{pid}.journal"));
            std::fs::write(&journal, text)
                .with_context(|| format!("cannot write in {}", parent_of(first).display()))?;
            Some(journal)
        }
        _ => None,
    };
    let temporaries: Vec<PathBuf> = staged.iter().map(|(t, _)| t.path().to_path_buf()).collect();
    // Past this point an interrupt must not remove the temporaries: the journal finishes them.
    in_progress().retain(|p| !temporaries.contains(p));
    let result = staged.into_iter().try_for_each(|(tmp, path)| {
        tmp.persist(path)
            .map(|_| ())
            .with_context(|| format!("cannot write {}", path.display()))
    });
    if let Some(j) = journal {
        let _ = std::fs::remove_file(j);
    }
    result
}

/// Cleans up what dead castellan processes left in `dir`: journals are rolled forward, half-done
/// folder swaps completed, then their temporaries and staging folders removed. Best effort: a
/// leftover that cannot be removed is left for the next run.
pub fn sweep(dir: &Path) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut leftovers: Vec<(String, PathBuf)> = entries
        .flatten()
        .filter_map(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            let rest = name.strip_prefix(PREFIX)?;
            let pid: u32 = rest.split(['-', '.']).next()?.parse().ok()?;
            (!alive(pid)).then(|| (name, e.path()))
        })
        .collect();
    // Journals first (they name the temporaries to keep), then folder swaps, then the rest.
    leftovers.sort_by_key(|(name, _)| !name.ends_with(".journal"));
    for (name, path) in &leftovers {
        if name.ends_with(".journal") {
            roll_forward(path);
        } else if let Some(stem) = name.strip_suffix(".old") {
            // Killed between the two renames of `swap_by_renames`: the destination is missing
            // and the complete new folder waits under `.new`.
            let dest_name = stem.split_once('-').and_then(|(_, r)| r.split_once('-'));
            if let Some((_, dest_name)) = dest_name {
                let dest = dir.join(dest_name);
                let new = path.with_extension("new");
                if !dest.exists() {
                    let back = if new.is_dir() { &new } else { path };
                    let _ = std::fs::rename(back, &dest);
                }
            }
        }
    }
    for (_, path) in leftovers {
        if path.is_dir() {
            let _ = std::fs::remove_dir_all(&path);
        } else {
            let _ = std::fs::remove_file(&path);
        }
    }
}

/// Completes the renames a journal lists whose temporary file is still there.
fn roll_forward(journal: &Path) {
    let Ok(text) = std::fs::read_to_string(journal) else {
        return;
    };
    for line in text.lines() {
        if let Some((tmp, dest)) = line.split_once('\t')
            && Path::new(tmp).is_file()
        {
            let _ = std::fs::rename(tmp, dest);
        }
    }
}

/// Whether process `pid` may still be running (then its files are left alone).
fn alive(pid: u32) -> bool {
    if pid == std::process::id() {
        return true;
    }
    #[cfg(unix)]
    {
        match i32::try_from(pid)
            .ok()
            .and_then(rustix::process::Pid::from_raw)
        {
            Some(p) => !matches!(
                rustix::process::test_kill_process(p),
                Err(rustix::io::Errno::SRCH)
            ),
            None => false,
        }
    }
    #[cfg(not(unix))]
    {
        true // no cheap test: leftovers stay (they are hidden files)
    }
}

fn parent_of(path: &Path) -> PathBuf {
    match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

fn absolute(path: &Path) -> PathBuf {
    std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    /// A pid that is certainly not running: a child that has exited and been reaped.
    fn dead_pid() -> u32 {
        let mut child = std::process::Command::new("true").spawn().unwrap();
        let pid = child.id();
        child.wait().unwrap();
        pid
    }

    #[test]
    fn commit_writes_all_files_and_leaves_no_temporaries() {
        let dir = tempfile::tempdir().unwrap();
        let mut out = Outputs::default();
        out.add(&dir.path().join("a/b.txt"), b"hello".to_vec());
        out.add(&dir.path().join("c.txt"), b"x".to_vec());
        out.commit().unwrap();
        assert_eq!(std::fs::read(dir.path().join("a/b.txt")).unwrap(), b"hello");
        assert_eq!(names(dir.path()), ["a", "c.txt"]);
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

    #[test]
    fn a_folder_is_replaced_whole_and_keeps_the_files_the_run_does_not_write() {
        let root = tempfile::tempdir().unwrap();
        let out_dir = root.path().join("out");
        std::fs::create_dir_all(out_dir.join("overlays")).unwrap();
        std::fs::write(out_dir.join("model.glb"), b"old model").unwrap();
        std::fs::write(out_dir.join("index.html"), b"old report").unwrap();
        std::fs::write(out_dir.join("overlays/notes.txt"), b"mine").unwrap();
        let mut out = Outputs::folder(&out_dir);
        out.add(&out_dir.join("model.glb"), b"new model".to_vec());
        out.add(&out_dir.join("overlays/plan.png"), b"png".to_vec());
        out.commit().unwrap();
        assert_eq!(
            std::fs::read(out_dir.join("model.glb")).unwrap(),
            b"new model"
        );
        assert_eq!(
            std::fs::read(out_dir.join("index.html")).unwrap(),
            b"old report"
        );
        assert_eq!(
            std::fs::read(out_dir.join("overlays/notes.txt")).unwrap(),
            b"mine"
        );
        assert_eq!(
            std::fs::read(out_dir.join("overlays/plan.png")).unwrap(),
            b"png"
        );
        assert_eq!(names(root.path()), ["out"], "no staging folder is left");
    }

    #[test]
    fn a_failed_folder_run_leaves_the_old_folder_untouched() {
        let root = tempfile::tempdir().unwrap();
        let out_dir = root.path().join("out");
        std::fs::create_dir_all(&out_dir).unwrap();
        std::fs::write(out_dir.join("model.glb"), b"old").unwrap();
        {
            let staged = StagedFolder::begin(&out_dir).unwrap();
            staged.write(Path::new("model.glb"), b"half").unwrap();
            // dropped without finish: an error in the middle of the run
        }
        assert_eq!(std::fs::read(out_dir.join("model.glb")).unwrap(), b"old");
        assert_eq!(names(root.path()), ["out"]);
    }

    #[test]
    fn leftovers_of_a_killed_run_are_cleaned_up_by_the_next_run() {
        let dir = tempfile::tempdir().unwrap();
        let pid = dead_pid();
        // A killed per-file run: temporaries without a journal are dropped.
        std::fs::write(dir.path().join(format!(".castellan-{pid}-abc.tmp")), b"x").unwrap();
        // A killed folder run: its staging folder is dropped.
        std::fs::create_dir(dir.path().join(format!(".castellan-{pid}-out.new"))).unwrap();
        // A live process's temporaries are left alone.
        let own = format!(".castellan-{}-live.tmp", std::process::id());
        std::fs::write(dir.path().join(&own), b"y").unwrap();
        let mut out = Outputs::default();
        out.add(&dir.path().join("plan.json"), b"{}".to_vec());
        out.commit().unwrap();
        assert_eq!(names(dir.path()), vec![own, "plan.json".to_string()]);
    }

    #[test]
    fn a_run_killed_during_its_renames_is_completed_by_the_next_run() {
        let dir = tempfile::tempdir().unwrap();
        let pid = dead_pid();
        let (a, b) = (dir.path().join("a.json"), dir.path().join("b.png"));
        std::fs::write(&a, b"new a").unwrap(); // already renamed before the kill
        std::fs::write(&b, b"old b").unwrap();
        let tmp_b = dir.path().join(format!(".castellan-{pid}-q.tmp"));
        std::fs::write(&tmp_b, b"new b").unwrap();
        let journal = format!(
            "{}\t{}\n{}\t{}\n",
            dir.path().join(format!(".castellan-{pid}-p.tmp")).display(),
            a.display(),
            tmp_b.display(),
            b.display()
        );
        std::fs::write(
            dir.path().join(format!(".castellan-{pid}.journal")),
            journal,
        )
        .unwrap();
        sweep(dir.path());
        assert_eq!(std::fs::read(&b).unwrap(), b"new b");
        assert_eq!(names(dir.path()), ["a.json", "b.png"]);
    }

    #[test]
    fn a_folder_swap_killed_between_its_renames_is_completed() {
        let dir = tempfile::tempdir().unwrap();
        let pid = dead_pid();
        let new = dir.path().join(format!(".castellan-{pid}-out.new"));
        let old = dir.path().join(format!(".castellan-{pid}-out.old"));
        std::fs::create_dir(&new).unwrap();
        std::fs::write(new.join("model.glb"), b"new").unwrap();
        std::fs::create_dir(&old).unwrap();
        std::fs::write(old.join("model.glb"), b"old").unwrap();
        sweep(dir.path());
        assert_eq!(
            std::fs::read(dir.path().join("out/model.glb")).unwrap(),
            b"new"
        );
        assert_eq!(names(dir.path()), ["out"]);
    }

    #[test]
    fn the_current_folder_and_links_are_not_swapped() {
        let cwd = std::env::current_dir().unwrap();
        assert!(!swappable(&cwd));
        assert!(!swappable(Path::new(".")));
        let root = tempfile::tempdir().unwrap();
        assert!(swappable(&root.path().join("new")));
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink(root.path(), root.path().join("link")).unwrap();
            assert!(!swappable(&root.path().join("link")));
        }
    }
}
