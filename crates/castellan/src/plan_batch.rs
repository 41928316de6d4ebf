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
use crate::output::FolderWriter;

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

/// Every entry of `dir`, sorted by name (the summary's order does not depend on the file
/// system or on which thread finished first), each with the reason it is not parsed, if any:
/// folders are not searched, and links that lead nowhere, FIFOs and devices are not opened (a
/// FIFO would block the batch), but each gets its row in summary.csv.
fn list_entries(dir: &Path) -> Result<Vec<(PathBuf, Option<String>)>> {
    let mut entries = Vec::new();
    for entry in std::fs::read_dir(dir).with_context(|| format!("cannot read {}", dir.display()))? {
        let entry = entry.with_context(|| format!("cannot read {}", dir.display()))?;
        let path = entry.path();
        let skip = match std::fs::metadata(&path) {
            Err(e) if std::fs::symlink_metadata(&path).is_ok_and(|m| m.is_symlink()) => {
                Some(format!("a link that leads to no file ({e})"))
            }
            Err(e) => Some(format!("cannot read ({e})")),
            Ok(m) if m.is_dir() => Some("a folder: sub-folders are not searched".to_string()),
            Ok(m) if !m.is_file() => {
                Some("not a regular file (a FIFO, socket or device): not opened".to_string())
            }
            Ok(_) => None,
        };
        entries.push((path, skip));
    }
    entries.sort();
    Ok(entries)
}

/// The output stem of each file: its name without the extension, or the whole name where two
/// files share a stem (`same.png` and `same.jpg` give `same.png.plan.json` and
/// `same.jpg.plan.json` rather than overwriting each other).
fn output_stems(files: &[&Path]) -> Vec<String> {
    let stems: Vec<String> = files
        .iter()
        .map(|p| {
            p.file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default()
        })
        .collect();
    let mut count: std::collections::HashMap<&str, usize> = Default::default();
    for s in &stems {
        *count.entry(s).or_default() += 1;
    }
    files
        .iter()
        .zip(&stems)
        .map(|(p, s)| {
            if count[s.as_str()] > 1 {
                file_name(p)
            } else {
                s.clone()
            }
        })
        .collect()
}

pub fn run(
    dir: &Path,
    out_dir: &Path,
    metres_per_pixel: Option<f64>,
    opts: &plan::Options,
) -> Result<()> {
    let entries = list_entries(dir)?;
    if entries.iter().all(|(_, skip)| skip.is_some()) {
        bail!("{}: the folder holds no files to parse", dir.display());
    }
    let files: Vec<&Path> = entries.iter().map(|(p, _)| p.as_path()).collect();
    let stems = output_stems(&files);
    let writer = FolderWriter::begin(out_dir)?;
    let bar = ProgressBar::new(entries.len() as u64);
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} drawings, {elapsed} ({eta} left)")
            .expect("the progress template is a constant"),
    );
    bar.enable_steady_tick(std::time::Duration::from_millis(500));
    let rows: Vec<Row> = entries
        .par_iter()
        .zip(&stems)
        .map(|((path, skip), stem)| {
            let row = match skip {
                None => one_drawing(path, stem, &writer, metres_per_pixel, opts),
                Some(reason) => Row {
                    file: file_name(path),
                    reason: reason.clone(),
                    ..Row::default()
                },
            };
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
    writer.write_group(vec![(summary.clone(), csv.into_bytes())])?;
    writer.finish()?;

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
fn one_drawing(
    path: &Path,
    stem: &str,
    writer: &FolderWriter,
    metres_per_pixel: Option<f64>,
    opts: &plan::Options,
) -> Row {
    let file = file_name(path);
    let started = Instant::now();
    let result = catch_unwind(AssertUnwindSafe(|| {
        parse_and_write(path, &file, stem, writer, metres_per_pixel, opts)
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
    stem: &str,
    writer: &FolderWriter,
    metres_per_pixel: Option<f64>,
    opts: &plan::Options,
) -> Result<Row> {
    let img = crate::images::read_image(path)?;
    let parsed = plan::parse(&img, opts).map_err(|e| anyhow!("{e}"))?;
    let out = |suffix: &str| PathBuf::from(format!("{stem}.{suffix}"));
    let doc = plan::output::plan_json(&parsed, metres_per_pixel);
    let labels_path = out("labels.png");
    let overlay_path = out("overlay.png");
    let walls_path = out("walls.png");
    let grey = img.to_luma8();
    let over = plan::output::overlay(&parsed, &grey);
    let walls = plan::output::walls_overlay(&parsed, &grey);
    writer.write_group(vec![
        (out("plan.json"), serde_json::to_vec_pretty(&doc)?),
        (
            labels_path.clone(),
            png(&plan::output::labels_image(&parsed), &labels_path)?,
        ),
        (overlay_path.clone(), png(&over, &overlay_path)?),
        (walls_path.clone(), png(&walls, &walls_path)?),
        (out("svg"), plan::output::svg(&parsed).into_bytes()),
    ])?;

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

fn file_name(path: &Path) -> String {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_sharing_a_stem_get_outputs_named_after_their_whole_name() {
        let files = [
            Path::new("d/same.png"),
            Path::new("d/same.jpg"),
            Path::new("d/other.png"),
        ];
        assert_eq!(output_stems(&files), ["same.png", "same.jpg", "other"]);
    }

    #[cfg(unix)]
    #[test]
    fn links_folders_and_fifos_each_get_a_reason_and_are_not_opened() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        std::fs::write(d.join("a.png"), b"x").unwrap();
        std::fs::create_dir(d.join("sub")).unwrap();
        std::os::unix::fs::symlink(d.join("missing.png"), d.join("dangling.png")).unwrap();
        std::os::unix::fs::symlink(d.join("loop2"), d.join("loop1")).unwrap();
        std::os::unix::fs::symlink(d.join("loop1"), d.join("loop2")).unwrap();
        let status = std::process::Command::new("mkfifo")
            .arg(d.join("pipe.png"))
            .status()
            .unwrap();
        assert!(status.success());
        let entries = list_entries(d).unwrap();
        let reason = |n: &str| {
            entries
                .iter()
                .find(|(p, _)| p.file_name().unwrap() == n)
                .unwrap()
                .1
                .clone()
        };
        assert_eq!(entries.len(), 6);
        assert_eq!(reason("a.png"), None);
        assert!(reason("sub").unwrap().contains("folder"));
        assert!(reason("dangling.png").unwrap().contains("leads to no file"));
        assert!(reason("loop1").unwrap().contains("leads to no file"));
        assert!(reason("pipe.png").unwrap().contains("FIFO"));
    }

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
