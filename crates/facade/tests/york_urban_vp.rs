//! Vanishing-point accuracy on the York Urban DB (Denis, Elder, Estrada, ECCV 2008): the angle
//! between our vanishing directions and the ground truth, through the published calibration.
//! Skips when ../shared/data is absent.

use std::path::PathBuf;

use facade::rectify::{RectifyParams, find_vanishing_points};
use nalgebra::{Matrix3, Vector3};

fn data_dir() -> Option<PathBuf> {
    let d = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data/york_urban_db");
    d.is_dir().then_some(d)
}

/// The 3x3 `vp` matrix of a *GroundTruthVP_CamParams.mat (uncompressed MAT v5, column-major).
fn read_vp(bytes: &[u8]) -> Option<Matrix3<f64>> {
    let tag: [u8; 16] = [1, 0, 2, 0, b'v', b'p', 0, 0, 9, 0, 0, 0, 72, 0, 0, 0];
    let at = bytes.windows(16).position(|w| w == tag)? + 16;
    let v: Vec<f64> = (0..9)
        .map(|i| f64::from_le_bytes(bytes[at + 8 * i..at + 8 * i + 8].try_into().unwrap()))
        .collect();
    Some(Matrix3::from_column_slice(&v))
}

fn angle(a: &Vector3<f64>, b: &Vector3<f64>) -> f64 {
    (a.dot(b).abs() / (a.norm() * b.norm()))
        .min(1.0)
        .acos()
        .to_degrees()
}

#[test]
fn vanishing_points_match_the_york_urban_ground_truth() {
    let Some(dir) = data_dir() else {
        eprintln!("skipping: ../shared/data/york_urban_db not found");
        return;
    };
    // cameraParameters.mat: f = 6.05317 mm / 0.00896875 mm/px, pp = (307.551, 251.454).
    let f = 6.05317 / 0.00896875;
    let k = Matrix3::new(f, 0.0, 307.551, 0.0, f, 251.454, 0.0, 0.0, 1.0);
    let ki = k.try_inverse().unwrap();
    let mut scenes: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.is_dir())
        .collect();
    scenes.sort();
    let (mut errs_v, mut errs_h, mut failed) = (Vec::new(), Vec::new(), 0);
    for s in &scenes {
        let name = s.file_name().unwrap().to_string_lossy().to_string();
        let img = image::open(s.join(format!("{name}.jpg")))
            .unwrap()
            .to_rgb8();
        let gt =
            read_vp(&std::fs::read(s.join(format!("{name}GroundTruthVP_CamParams.mat"))).unwrap())
                .expect("vp matrix");
        // Camera y points up in the ground truth; image y points down.
        let gt: Vec<Vector3<f64>> = (0..3)
            .map(|i| Vector3::new(gt[(0, i)], -gt[(1, i)], gt[(2, i)]))
            .collect();
        let Ok(r) = find_vanishing_points(&img, &RectifyParams::default()) else {
            failed += 1;
            continue;
        };
        let dv = ki * Vector3::from(r.vertical_vp);
        let dh = ki * Vector3::from(r.horizontal_vp);
        let iv = (0..3)
            .max_by(|&a, &b| gt[a][1].abs().total_cmp(&gt[b][1].abs()))
            .unwrap();
        errs_v.push(angle(&dv, &gt[iv]));
        let eh = (0..3)
            .filter(|&i| i != iv)
            .map(|i| angle(&dh, &gt[i]))
            .fold(f64::INFINITY, f64::min);
        errs_h.push(eh);
    }
    let med = |v: &mut Vec<f64>| {
        v.sort_by(|a, b| a.total_cmp(b));
        v[v.len() / 2]
    };
    let n = errs_v.len();
    let within = |v: &[f64], t: f64| v.iter().filter(|e| **e < t).count();
    let (wv, wh) = (within(&errs_v, 2.0), within(&errs_h, 2.0));
    let (mv, mh) = (med(&mut errs_v), med(&mut errs_h));
    eprintln!(
        "York Urban: {} scenes, {failed} without two families; vertical VP median {mv:.2}°, {wv}/{n} within 2°; horizontal VP median {mh:.2}°, {wh}/{n} within 2°",
        scenes.len()
    );
    assert!(failed * 10 <= scenes.len(), "{failed} failures");
    assert!(
        wv * 10 >= n * 7 && wh * 10 >= n * 7,
        "too few within 2°: {wv} {wh} of {n}"
    );
    assert!(mv < 1.0 && mh < 1.5, "medians {mv} {mh}");
}
