//! Issue 22: the user's façade corrections (`[facade.fix]` in PROJECT.toml) honoured by the
//! pipeline on the bundled synthetic castle (examples/demo): floor lines moved, a floor without
//! windows, a window removed and one added, in the photo's estimate, in estimate.json (with
//! "user" as their source) and in the generated program; a bad correction names its entry.

use facade::fixes::FacadeFixes;
use facade::model::Facade;
use integrate::estimate::Source;
use integrate::pipeline::{self, InMemory};
use integrate::project::Project;

mod common;

/// The near photo's façade (the one its correspondence points at) under `fix`.
fn near_facade(project: &Project, files: &InMemory, fix: &FacadeFixes) -> (Facade, (u32, u32)) {
    let mut project = project.clone();
    project.facades[0].fix = fix.clone();
    let (e, _) =
        pipeline::estimate_photo(&project, 0, files, &pipeline::Options::default()).unwrap();
    let q = e
        .to_rectified(project.correspondences[0].facade_point)
        .unwrap();
    let k = integrate::correspond::facade_at(&e.model, q).unwrap();
    (e.model.facades[k].clone(), e.rectified.dimensions())
}

fn per_floor(f: &Facade) -> Vec<usize> {
    f.floors.iter().map(|fl| fl.windows.len()).collect()
}

fn centre(w: &[f64; 4]) -> [f64; 2] {
    [(w[0] + w[2]) / 2.0, (w[1] + w[3]) / 2.0]
}

#[test]
fn reconstruct_honours_every_kind_of_facade_correction() {
    let (project, files) = common::example("demo");
    let (found, _) = near_facade(&project, &files, &FacadeFixes::default());
    assert!(found.floors.len() >= 3, "{:?}", per_floor(&found));

    // Floor lines: the search's own, the first dragged 4 px down; the floors are exactly there.
    let mut lines: Vec<f64> = found.floors[1..].iter().map(|f| f.y0).collect();
    lines[0] += 4.0;
    let lines_only = FacadeFixes {
        floor_lines: Some(lines.clone()),
        ..Default::default()
    };
    let (moved, _) = near_facade(&project, &files, &lines_only);
    let tops: Vec<f64> = moved.floors[1..].iter().map(|f| f.y0).collect();
    let bottoms: Vec<f64> = moved.floors[..moved.floors.len() - 1]
        .iter()
        .map(|f| f.y1)
        .collect();
    assert_eq!(tops, lines);
    assert_eq!(bottoms, lines);

    // The ground floor blind: no windows there, the floors above keep theirs.
    let blind = FacadeFixes {
        blind_floors: vec![1],
        ..lines_only.clone()
    };
    let (shop, _) = near_facade(&project, &files, &blind);
    let mut expected = per_floor(&moved);
    *expected.last_mut().unwrap() = 0;
    assert_eq!(per_floor(&shop), expected);

    // A window of the top floor removed, one added to the second floor from the top.
    let top_window = shop.floors[0].windows[0];
    let second = &shop.floors[1];
    let added = [
        second.windows[0][0],
        second.y0 + 1.0,
        second.windows[0][2],
        second.y0 + 3.0,
    ];
    let all = FacadeFixes {
        remove_windows: vec![centre(&top_window)],
        add_windows: vec![added],
        ..blind.clone()
    };
    let (edited, _) = near_facade(&project, &files, &all);
    expected[0] -= 1;
    expected[1] += 1;
    assert_eq!(per_floor(&edited), expected);
    assert!(!edited.floors[0].windows.contains(&top_window));
    assert!(edited.floors[1].windows.contains(&added));

    // The whole pipeline: estimate.json's floors are the corrected ones, bottom-up, and the
    // user is the source of each corrected parameter.
    let mut fixed = project.clone();
    fixed.facades[0].fix = all.clone();
    // Through PROJECT.toml's text, as `castellan reconstruct` reads it.
    let fixed = Project::from_toml(&fixed.to_toml()).unwrap();
    assert_eq!(fixed.facades[0].fix, all);
    let r = pipeline::reconstruct(&fixed, &files, &pipeline::Options::default(), &|_| {}).unwrap();
    let keep = r
        .estimate
        .structures
        .iter()
        .find(|s| s.facades.iter().any(|f| f.image == "keep_south_near.png"))
        .unwrap();
    let k_near = keep
        .facades
        .iter()
        .position(|f| f.image == "keep_south_near.png")
        .unwrap();
    let near = &keep.facades[k_near];
    let bottom_up: Vec<u32> = near.floors.iter().map(|f| f.windows).collect();
    let mut want: Vec<u32> = expected.iter().map(|&n| n as u32).collect();
    want.reverse();
    assert_eq!(bottom_up, want);
    eprintln!("windows per floor, bottom-up: {bottom_up:?}; floor lines {lines:?}");
    assert!(
        !near.joint,
        "a corrected façade is not re-estimated jointly"
    );
    // Floor heights in proportion to the user's lines (one vertical scale for the façade).
    let px: Vec<f64> = edited.floors.iter().rev().map(|f| f.y1 - f.y0).collect();
    let k = near.floors[0].height / px[0];
    for (f, h) in near.floors.iter().zip(&px) {
        assert!(
            (f.height - h * k).abs() < 1e-6 * k.max(1.0),
            "{} vs {h}",
            f.height
        );
    }
    for (parameter, key) in [("floors", "floor_lines"), ("floor_windows", "blind_floors")] {
        let p = keep
            .provenance
            .get(&format!(
                "facade.keep_south_near.png.{}.{parameter}",
                near.side
            ))
            .unwrap_or_else(|| panic!("{parameter} in {:?}", keep.provenance.keys()));
        assert_eq!(p.source(), Source::User);
        assert_eq!(p.step, format!("[[facade]] #1 fix.{key}"));
    }
    // The generated program builds the blind ground floor as plain wall.
    let ground = format!("{}Facade{}Floor1 ::", keep.id, k_near + 1);
    let ground_rule = r
        .program
        .lines()
        .find(|l| l.starts_with(&ground))
        .unwrap_or_else(|| panic!("no ground floor rule in\n{}", r.program));
    assert!(!ground_rule.contains("Row"), "{ground_rule}");
    // The top floor, a window removed, has its own row of the windows left.
    let fid = format!("{}Facade{}", keep.id, k_near + 1);
    let top = near.floors.len();
    let row = format!("{fid}Row{top} ::");
    let top_row = r
        .program
        .lines()
        .find(|l| l.starts_with(&row))
        .unwrap_or_else(|| panic!("no {row} in\n{}", r.program));
    let openings = top_row.matches(&format!("{fid}Window")).count();
    assert_eq!(openings, want[top - 1] as usize, "{top_row}");
    assert!(
        r.program
            .contains(&format!("{fid}Floor{top} :: split(\"Y\""))
            && r.program.contains(&format!(", {fid}Row{top}, ")),
        "the top floor uses its own row"
    );
}

#[test]
fn a_bad_correction_names_its_entry_and_nothing_runs() {
    let (mut project, files) = common::example("demo");
    project.facades[1].fix.floor_lines = Some(vec![40.0, 5000.0]);
    let e = pipeline::reconstruct(&project, &files, &pipeline::Options::default(), &|_| {})
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.starts_with("[[facade]] #2 (image = \"keep_south_far.png\"): ")
            && e.contains("floor line 5000 is below the façade (rectified height "),
        "{e}"
    );
    project.facades[1].fix = FacadeFixes {
        blind_floors: vec![2, 2],
        ..Default::default()
    };
    let e = pipeline::estimate_photo(&project, 1, &files, &pipeline::Options::default())
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("blind floor 2 is listed twice"), "{e}");
}
