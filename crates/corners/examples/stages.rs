//! Times the stages of the detector on one image:
//! `cargo run --release -p corners --example stages IMAGE` (three rounds, wall-clock).
//!
//! `stages IMAGE LAST` runs once and stops after stage LAST (`decode`, `smooth`, `edges`,
//! `candidates`, `suppress`), so that instruction counts of the stages follow by difference:
//! `RAYON_NUM_THREADS=1 valgrind --tool=callgrind target/release/examples/stages IMAGE edges`.
use std::time::Instant;

const STAGES: [&str; 5] = ["decode", "smooth", "edges", "candidates", "suppress"];

fn main() {
    let mut args = std::env::args().skip(1);
    let path = args.next().expect("usage: stages IMAGE [LAST]");
    let last = args.next();
    let img = image::open(&path).expect("readable image");
    let g = corners::Gray::from_dynamic(&img);
    let p = corners::Params::default();
    if let Some(last) = last {
        let stop = STAGES
            .iter()
            .position(|s| *s == last)
            .expect("LAST is one of decode, smooth, edges, candidates, suppress");
        let mut left = 0;
        if stop == 1 {
            let s = corners::edge::smooth(&g, &corners::edge::gaussian_kernel(p.window, p.sigma));
            left = s.data.len();
        } else if stop >= 2 {
            let e = corners::edge::edge_map(&g, p.window, p.sigma, p.subpixel);
            left = e.count();
            if stop >= 3 {
                let c = corners::detect::candidates(&e, &p);
                left = c.len();
                if stop >= 4 {
                    left = corners::detect::suppress(c, p.window).len();
                }
            }
        }
        println!("{last}: {left}");
        return;
    }
    for _ in 0..3 {
        let t = Instant::now();
        let _s = corners::edge::smooth(&g, &corners::edge::gaussian_kernel(p.window, p.sigma));
        println!("smooth {:.1} ms", t.elapsed().as_secs_f64() * 1e3);
        let t = Instant::now();
        let e = corners::edge::edge_map(&g, p.window, p.sigma, p.subpixel);
        let t1 = t.elapsed();
        let c = corners::detect::candidates(&e, &p);
        let t2 = t.elapsed();
        let k = corners::detect::suppress(c.clone(), p.window);
        let t3 = t.elapsed();
        println!(
            "edges {} pts {:.1} ms; candidates {} {:.1} ms; kept {} {:.1} ms",
            e.count(),
            t1.as_secs_f64() * 1e3,
            c.len(),
            (t2 - t1).as_secs_f64() * 1e3,
            k.len(),
            (t3 - t2).as_secs_f64() * 1e3
        );
    }
}
