//! `castellan plan --batch DIR -o OUTDIR`: the plan parser (dissertation ch. 5) over every
//! drawing in a folder, in parallel, each drawing on its own so that one failure never stops
//! the rest; per-drawing outputs and a `summary.csv` row per file (issue 11).

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, anyhow, bail};
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;

use crate::images::png;
use crate::output::Outputs;

/// One drawing's line of `summary.csv`.
#[derive(Debug, Default)]
struct Row {
    file: String,
    success: bool,
    closed_outer_wall: bool,
    faces: usize,
    towers: usize,
    labels_found: usize,
    time_ms: f64,
    reason: String,
}

const HEADER: &str =
    "file,success,closed_outer_wall,faces,towers,labels_found,time_ms,failure_reason";

impl Row {
    fn csv(&self) -> String {
        format!(
            "{},{},{},{},{},{},{:.0},{}",
            quote(&self.file),
            self.success,
            self.closed_outer_wall,
            self.faces,
            self.towers,
            self.labels_found,
            self.time_ms,
            quote(&self.reason)
        )
    }
}

/// RFC 4180 quoting where a field needs it.
fn quote(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// Every regular file in `dir`, sorted by name (the summary's order does not depend on the
/// file system or on which thread finished first).
fn list_files(dir: &Path) -> Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    for entry in std::fs::read_dir(dir).with_context(|| format!("cannot read {}", dir.display()))? {
        let entry = entry.with_context(|| format!("cannot read {}", dir.display()))?;
        let path = entry.path();
        if path.is_file() {
            files.push(path);
        }
    }
    files.sort();
    Ok(files)
}

pub fn run(dir: &Path, out_dir: &Path, scale: Option<f64>, opts: &plan::Options) -> Result<()> {
    let files = list_files(dir)?;
    if files.is_empty() {
        bail!("{}: the folder holds no files to parse", dir.display());
    }
    std::fs::create_dir_all(out_dir)
        .with_context(|| format!("cannot create folder {}", out_dir.display()))?;
    let bar = ProgressBar::new(files.len() as u64);
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} drawings, {elapsed} ({eta} left)")
            .expect("the progress template is a constant"),
    );
    let rows: Vec<Row> = files
        .par_iter()
        .map(|path| {
            let row = one_drawing(path, out_dir, scale, opts);
            bar.inc(1);
            row
        })
        .collect();
    bar.finish_and_clear();

    let mut csv = String::from(HEADER);
    csv.push('\n');
    for r in &rows {
        csv.push_str(&r.csv());
        csv.push('\n');
    }
    let summary = out_dir.join("summary.csv");
    let mut outputs = Outputs::default();
    outputs.add(&summary, csv.into_bytes());
    outputs.commit()?;

    let ok = rows.iter().filter(|r| r.success).count();
    let closed = rows.iter().filter(|r| r.closed_outer_wall).count();
    let towered = rows.iter().filter(|r| r.towers > 0).count();
    for r in rows.iter().filter(|r| !r.success) {
        eprintln!("{}: failed: {}", r.file, r.reason);
    }
    eprintln!(
        "{} drawings: {ok} parsed, {closed} with a closed outer wall, {towered} with a tower, {} failed; summary in {}",
        rows.len(),
        rows.len() - ok,
        summary.display()
    );
    Ok(())
}

/// Parses one drawing and writes its outputs; every failure, a panic included, becomes the
/// row's reason instead of stopping the batch.
fn one_drawing(path: &Path, out_dir: &Path, scale: Option<f64>, opts: &plan::Options) -> Row {
    let file = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let started = Instant::now();
    let result = catch_unwind(AssertUnwindSafe(|| {
        parse_and_write(path, &file, out_dir, scale, opts)
    }))
    .unwrap_or_else(|_| Err(anyhow!("internal error (panic) while parsing")));
    let time_ms = started.elapsed().as_secs_f64() * 1e3;
    match result {
        Ok(mut row) => {
            row.time_ms = time_ms;
            row
        }
        Err(e) => Row {
            file,
            time_ms,
            reason: format!("{e:#}"),
            ..Row::default()
        },
    }
}

fn parse_and_write(
    path: &Path,
    file: &str,
    out_dir: &Path,
    scale: Option<f64>,
    opts: &plan::Options,
) -> Result<Row> {
    let img = crate::images::read_image(path)?;
    let parsed = plan::parse(&img, opts).map_err(|e| anyhow!("{e}"))?;
    let stem = Path::new(file)
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| file.to_string());
    let out = |suffix: &str| out_dir.join(format!("{stem}.{suffix}"));
    let mut outputs = Outputs::default();
    let doc = plan::output::plan_json(&parsed, scale);
    outputs.add(&out("plan.json"), serde_json::to_vec_pretty(&doc)?);
    let labels_path = out("labels.png");
    outputs.add(
        &labels_path,
        png(&plan::output::labels_image(&parsed), &labels_path)?,
    );
    let overlay_path = out("overlay.png");
    let over = plan::output::overlay(&parsed, &img.to_luma8());
    outputs.add(&overlay_path, png(&over, &overlay_path)?);
    outputs.add(&out("svg"), plan::output::svg(&parsed).into_bytes());
    outputs.commit()?;

    use plan::label::Label;
    let has = |l: Label| parsed.faces.iter().any(|f| f.label == l);
    let mut found = [false; 11];
    for f in &parsed.faces {
        found[f.label as usize] = true;
    }
    for e in &parsed.edges {
        found[e.label as usize] = true;
    }
    Ok(Row {
        file: file.to_string(),
        success: true,
        closed_outer_wall: has(Label::Courtyard),
        faces: parsed.faces.len(),
        towers: parsed.towers,
        labels_found: found.iter().filter(|&&f| f).count(),
        time_ms: 0.0,
        reason: parsed.warnings.join("; "),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn csv_fields_with_commas_and_quotes_are_quoted() {
        assert_eq!(quote("a.png"), "a.png");
        assert_eq!(quote("a, b"), "\"a, b\"");
        assert_eq!(quote("say \"x\""), "\"say \"\"x\"\"\"");
    }

    #[test]
    fn a_failed_row_has_its_reason_and_no_counts() {
        let r = Row {
            file: "x.png".into(),
            reason: "no walls".into(),
            ..Row::default()
        };
        assert_eq!(r.csv(), "x.png,false,false,0,0,0,0,no walls");
    }
}
