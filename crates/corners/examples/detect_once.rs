//! Runs the detector once on one image, for instruction counts of detection alone:
//! `valgrind --tool=callgrind --toggle-collect='corners::detect::detect*' \
//!     target/release/examples/detect_once IMAGE` (with `RAYON_NUM_THREADS=1`).
fn main() {
    let path = std::env::args().nth(1).expect("usage: detect_once IMAGE");
    let img = image::open(&path).expect("readable image");
    let g = corners::Gray::from_dynamic(&img);
    let t = std::time::Instant::now();
    // FIRST_FIT_SLACK=s tries the first-fit gate (see `Params::first_fit_slack`).
    let params = corners::Params {
        first_fit_slack: std::env::var("FIRST_FIT_SLACK")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(corners::Params::default().first_fit_slack),
        ..corners::Params::default()
    };
    let found = corners::detect(&g, &params).expect("valid parameters");
    println!(
        "{} corners, {:.1} ms",
        found.corners.len(),
        t.elapsed().as_secs_f64() * 1e3
    );
}
