//! Tests of the detector's windows, fits, thresholds and suppression (detect.rs).

use super::*;

fn square(w: usize, x0: usize, x1: usize) -> Gray {
    let data = (0..w * w)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            if (x0..x1).contains(&x) && (x0..x1).contains(&y) {
                200.0
            } else {
                40.0
            }
        })
        .collect();
    Gray::new(w, w, data)
}

#[test]
fn a_bright_square_has_four_corners() {
    // Square covering pixels 20..44: its outline runs at 19.5 and 43.5.
    let c = detect(&square(64, 20, 44), &Params::default()).unwrap();
    assert_eq!(c.corners.len(), 4, "{:#?}", c.corners);
    for k in &c.corners {
        let ex = if k.x < 32.0 { 19.5 } else { 43.5 };
        let ey = if k.y < 32.0 { 19.5 } else { 43.5 };
        assert!(
            (k.x - ex).abs() < 1.0 && (k.y - ey).abs() < 1.0,
            "corner at ({}, {})",
            k.x,
            k.y
        );
        assert!(
            (k.psi - std::f64::consts::FRAC_PI_4).abs() < 0.15,
            "ψ {}",
            k.psi
        );
        // Both arms run along the square's sides, away from the corner.
        for v in k.directions {
            let inward = v[0] * (31.5 - k.x) + v[1] * (31.5 - k.y);
            assert!(inward > 0.0, "{:?} at ({}, {})", v, k.x, k.y);
            assert!(v[0].abs() > 0.99 || v[1].abs() > 0.99, "{v:?}");
        }
    }
}

#[test]
fn rectified_mode_keeps_axis_aligned_corners() {
    let p = Params {
        rectified: true,
        ..Params::default()
    };
    assert_eq!(detect(&square(64, 20, 44), &p).unwrap().corners.len(), 4);
}

#[test]
fn window_sums_match_a_direct_count() {
    let (w, h) = (23, 17);
    let mut e = EdgeMap {
        width: w,
        height: h,
        mag: vec![0.0; w * h],
        offset: vec![[0.0; 2]; w * h],
        orient: vec![[0.0; 2]; w * h],
        mean: 1.0,
    };
    for i in 0..w * h {
        if (i * 7919) % 5 < 2 {
            let t = i as f32 * 0.37;
            e.mag[i] = 2.0;
            e.orient[i] = [t.cos(), t.sin()];
        }
    }
    let sums = WindowSums::new(&e);
    for (x0, y0, x1, y1) in [
        (0, 0, 22, 16),
        (3, 4, 15, 16),
        (10, 0, 10, 0),
        (5, 9, 20, 12),
    ] {
        let mut want = [0.0f64; 3];
        for y in y0..=y1 {
            for x in x0..=x1 {
                let i = y * w + x;
                if e.mag[i] > 0.0 {
                    want[0] += 1.0;
                    want[1] += e.orient[i][0] as f64;
                    want[2] += e.orient[i][1] as f64;
                }
            }
        }
        let got = sums.sum(x0, y0, x1, y1);
        assert_eq!(got[0], want[0]);
        // Fixed point: at most half a unit (1/4096) of rounding per point.
        for k in 1..3 {
            assert!((got[k] - want[k]).abs() <= want[0] * 0.5 / 4096.0 + 1e-9);
        }
    }
}

#[test]
fn tiled_moments_and_cursor_gathering_give_the_windows_of_a_direct_scan() {
    // Two overlapping squares: many edge points per row, windows clipped at the border and
    // straddling the tiles of the moment tables.
    let (w, h) = (150usize, 90usize);
    let data = (0..w * h)
        .map(|i| {
            let (x, y) = ((i % w) % 75, (i / w) % 45);
            let a = (3..30).contains(&x) && (2..25).contains(&y);
            let b = (18..46).contains(&x) && (12..38).contains(&y);
            40.0 + 90.0 * a as u8 as f32 + 70.0 * b as u8 as f32
        })
        .collect();
    // Every window refitted (no first-fit gate), so every window gathers its points.
    let p = Params {
        max_coherence: 1.0,
        first_fit_slack: 0.0,
        duplicate_radius: 0.0,
        ..Params::default()
    };
    let edges = edge_map(&Gray::new(w, h, data), p.window, p.sigma, p.subpixel);
    let got = candidates(&edges, &p);
    let r = (p.window / 2) as isize;
    let mut want = Vec::new();
    for y in 0..h as isize {
        for x in 0..w as isize {
            if edges.mag[(y as usize) * w + x as usize] <= 0.0 {
                continue;
            }
            let mut all = Vec::new();
            for yy in (y - r).max(0)..=(y + r).min(h as isize - 1) {
                for xx in (x - r).max(0)..=(x + r).min(w as isize - 1) {
                    let i = yy as usize * w + xx as usize;
                    if edges.mag[i] > 0.0 {
                        let o = edges.offset[i];
                        let wt = (edges.mag[i] / edges.mean) as f64;
                        all.push([
                            xx as f64 + o[0] as f64 - x as f64,
                            yy as f64 + o[1] as f64 - y as f64,
                            wt * wt,
                        ]);
                    }
                }
            }
            if all.len() < p.window {
                continue;
            }
            let scale = r as f64;
            let mut first = Moments::default();
            for q in &all {
                first.add(q[0] / scale, q[1] / scale, q[2]);
            }
            // The plain §2.1.3 refit: keep the points near the first asymptotes, refit them.
            let gather = |win: &mut Window, h: &Asymptotes, d: f64| {
                win.clear();
                for q in &all {
                    if h.distance(0, q[0], q[1]).min(h.distance(1, q[0], q[1])) <= d {
                        win.push(q[0], q[1], q[2]);
                    }
                }
                let mut kept = Moments::default();
                for i in 0..win.len {
                    kept.add(win.x[i] / scale, win.y[i] / scale, win.w2[i]);
                }
                first.minus(&kept)
            };
            let mut win = Window::with_capacity(p.window * p.window, scale);
            if let Some(mut c) = evaluate(&mut win, &first, gather, r as f64, &p) {
                c.x += x as f64;
                c.y += y as f64;
                want.push(c);
            }
        }
    }
    assert!(want.len() >= 4, "{} candidates", want.len());
    // Tiles change the order of the candidates, and the moment tables their last digits.
    assert_eq!(got.len(), want.len());
    let close = |a: f64, b: f64| (a - b).abs() < 1e-7;
    for k in &want {
        let g = got
            .iter()
            .find(|g| close(g.x, k.x) && close(g.y, k.y))
            .unwrap_or_else(|| panic!("no candidate at ({}, {})", k.x, k.y));
        assert!(
            close(g.delta, k.delta) && close(g.psi, k.psi) && close(g.epsilon, k.epsilon),
            "{g:?} vs {k:?}"
        );
        assert_eq!(g.lambda, k.lambda, "{g:?} vs {k:?}");
    }
}

#[test]
fn the_first_fit_gate_only_removes_candidates() {
    // Overlapping rectangles, a tilted bar and a wedge: corners of many angles, T-junctions
    // and rounded blobs, so the gate has something to reject.
    let (w, h) = (160usize, 120usize);
    let data = (0..w * h)
        .map(|i| {
            let (x, y) = ((i % w) as f64, (i / w) as f64);
            let a = (10.0..60.0).contains(&x) && (8.0..50.0).contains(&y);
            let b = (35.0..90.0).contains(&x) && (30.0..75.0).contains(&y);
            let bar = ((x - 2.0 * y + 60.0) / 5f64.sqrt()).abs() < 6.0 && x > 95.0;
            let wedge = y > 80.0 && (x - 40.0).abs() < 0.4 * (y - 80.0);
            let disc = (x - 130.0).powi(2) + (y - 90.0).powi(2) < 200.0;
            40.0 + 80.0 * a as u8 as f32
                + 60.0 * b as u8 as f32
                + 90.0 * bar as u8 as f32
                + 70.0 * wedge as u8 as f32
                + 50.0 * disc as u8 as f32
        })
        .collect();
    let img = Gray::new(w, h, data);
    let plain = Params {
        first_fit_slack: 0.0,
        duplicate_radius: 0.0,
        ..Params::default()
    };
    let edges = edge_map(&img, plain.window, plain.sigma, plain.subpixel);
    let all = candidates(&edges, &plain);
    for slack in [1.0, 1.5, 2.0] {
        let gated = candidates(
            &edges,
            &Params {
                first_fit_slack: slack,
                ..plain.clone()
            },
        );
        assert!(gated.len() <= all.len());
        // A window the gate passes is refitted exactly as without it.
        for g in &gated {
            assert!(
                all.contains(g),
                "slack {slack}: {g:?} is not a plain candidate"
            );
        }
        if slack == 1.0 {
            assert!(gated.len() < all.len(), "the gate rejected nothing");
        }
    }
    assert!(all.len() > 20, "{} candidates", all.len());
}

#[test]
fn the_duplicate_skip_removes_only_repeats_of_found_candidates() {
    // Two overlapping squares: L-corners and T-junctions, each seen by many edge points.
    let (w, h) = (150usize, 90usize);
    let data = (0..w * h)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            let a = (13..60).contains(&x) && (12..55).contains(&y);
            let b = (38..120).contains(&x) && (30..78).contains(&y);
            40.0 + 90.0 * a as u8 as f32 + 70.0 * b as u8 as f32
        })
        .collect();
    let plain = Params {
        duplicate_radius: 0.0,
        ..Params::default()
    };
    let edges = edge_map(
        &Gray::new(w, h, data),
        plain.window,
        plain.sigma,
        plain.subpixel,
    );
    let all = candidates(&edges, &plain);
    assert!(all.len() > 20, "{} candidates", all.len());
    let radius = 1.5;
    let fewer = candidates(
        &edges,
        &Params {
            duplicate_radius: radius,
            ..plain.clone()
        },
    );
    assert!(fewer.len() < all.len(), "nothing was skipped");
    for c in &fewer {
        assert!(all.contains(c), "{c:?} is not a plain candidate");
    }
    // Every corner the suppression keeps without the skip still has a candidate nearby.
    let kept = suppress(fewer.clone(), plain.window);
    for c in suppress(all, plain.window) {
        assert!(
            kept.iter()
                .any(|k| (k.x - c.x).hypot(k.y - c.y) < 2.0 * radius),
            "lost the corner at ({}, {})",
            c.x,
            c.y
        );
    }
}

#[test]
fn suppression_keeps_the_smallest_delta() {
    let mk = |x: f64, delta: f64| Corner {
        x,
        y: 5.0,
        directions: [[1.0, 0.0], [0.0, 1.0]],
        epsilon: 0.1,
        lambda: 0.5,
        delta,
        psi: 0.78,
    };
    let kept = suppress(vec![mk(10.0, 0.2), mk(12.0, 0.1), mk(30.0, 0.3)], 13);
    let xs: Vec<f64> = kept.iter().map(|c| c.x).collect();
    assert_eq!(xs, vec![12.0, 30.0]);
}

#[test]
fn bad_params_are_reported() {
    let img = square(16, 4, 10);
    let p = Params {
        duplicate_radius: -1.0,
        ..Params::default()
    };
    assert!(p.validate().is_err());
    let p = Params {
        window: 4,
        ..Params::default()
    };
    assert!(detect(&img, &p).is_err());
    let p = Params {
        sigma: f64::NAN,
        ..Params::default()
    };
    assert!(detect(&img, &p).is_err());
}
