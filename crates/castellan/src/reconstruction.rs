//! A reconstruction written to a folder, for `castellan reconstruct`, `castellan demo` and
//! `castellan serve`: reads PROJECT.toml and the files it names (with the binary's bounded
//! reads and pixel budget), runs `integrate::pipeline` with a progress bar, and writes OUTDIR
//! whole (built beside it and swapped in at the end, so a failed run leaves it as it was) with
//! the HTML report.

use std::path::{Path, PathBuf};

use anyhow::{Result, anyhow};
use integrate::pipeline::{self, Files, Progress, Stage};
use integrate::project::{Project, ProjectError};
use plan::scale::ScaleNote;

use crate::images::read_image;
use crate::output::Outputs;

/// What a reconstruction produced, for the commands' closing lines.
pub struct Summary {
    pub estimate: integrate::estimate::Estimate,
    pub stages: Vec<(Stage, f64)>,
    pub terminals: usize,
    pub report: PathBuf,
    pub model: PathBuf,
    /// What looks implausible (`integrate::plausibility`), also printed to stderr.
    pub warnings: Vec<String>,
}

pub fn print_summary(s: &Summary) {
    let times: Vec<String> = s
        .stages
        .iter()
        .map(|(k, v)| format!("{} {v:.0} ms", k.name()))
        .collect();
    eprintln!(
        "{} structures: {}",
        s.estimate.structures.len(),
        integrate::summary::line(&s.estimate)
    );
    eprintln!(
        "{} façade(s) mapped, {} terminals; {}",
        s.estimate
            .structures
            .iter()
            .map(|x| x.facades.len())
            .sum::<usize>(),
        s.terminals,
        times.join(", ")
    );
    eprintln!(
        "report: {}\nmodel:  {}",
        s.report.display(),
        s.model.display()
    );
}

/// The files a PROJECT.toml names, read from its folder with the binary's bounded reads.
pub struct FolderFiles {
    pub dir: PathBuf,
}

impl Files for FolderFiles {
    fn image(&self, name: &str) -> Result<image::DynamicImage, String> {
        read_image(&self.dir.join(name)).map_err(|e| format!("{e:#}"))
    }

    fn json<T: serde::de::DeserializeOwned>(&self, name: &str, what: &str) -> Result<T, String> {
        crate::text::read_json(&self.dir.join(name), what).map_err(|e| format!("{e:#}"))
    }
}

/// Reads PROJECT.toml, runs the pipeline (`integrate::pipeline`) and writes OUTDIR whole.
pub fn reconstruct(
    project_path: &Path,
    outdir: &Path,
    options: &pipeline::Options,
) -> Result<Summary> {
    let name = project_path.display().to_string();
    let text = crate::text::read_text(project_path)?;
    // A syntax error names its line:column, which joins the file's name as `file:line:column`.
    let project = Project::from_toml(&text).map_err(|e| match e {
        ProjectError::Syntax { .. } => anyhow!("{name}:{e}"),
        ProjectError::Invalid(_) => anyhow!("{name}: {e}"),
    })?;
    let files = FolderFiles {
        dir: project_path.parent().unwrap_or(Path::new("")).to_path_buf(),
    };
    let bar = crate::progress::bar(pipeline::steps(&project));
    let r = pipeline::reconstruct(&project, &files, options, &|p| match p {
        Progress::Started(stage) => bar.set_message(stage.describe()),
        Progress::Step => bar.inc(1),
    })
    .map_err(|e| anyhow!("{name}: {e}"))?;
    bar.finish_and_clear();
    if let ScaleNote::Bar(how) = &r.scale_note {
        eprintln!("{name}: plan {how}");
    }
    // Issue 22: what looks implausible is said, and the run still writes its outputs.
    for w in &r.warnings {
        eprintln!("{name}: warning: {w}");
    }
    let mut outputs = Outputs::folder(outdir);
    for (file, bytes) in r.files()? {
        outputs.add(&outdir.join(file), bytes);
    }
    let report = crate::report::html(&project, &r);
    outputs.add(&outdir.join("index.html"), report.into_bytes());
    outputs.commit()?;
    Ok(Summary {
        estimate: r.estimate,
        stages: r.stages,
        terminals: r.exports.terminals,
        report: outdir.join("index.html"),
        model: outdir.join("model.glb"),
        warnings: r.warnings.iter().map(ToString::to_string).collect(),
    })
}
