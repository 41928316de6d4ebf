//! Times the stages of the detector on one image: `cargo run --release -p corners --example stages IMAGE`.
use std::time::Instant;

fn main() {
    let path = std::env::args().nth(1).expect("usage: stages IMAGE");
    let img = image::open(&path).expect("readable image");
    let g = corners::Gray::from_dynamic(&img);
    let p = corners::Params::default();
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
