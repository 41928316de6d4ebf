//! Annotation aid for the development set (issue 11): draws a coordinate grid over a plan
//! drawing so that points can be read off by eye — red lines every 100 px, blue every 50 px,
//! thin grey every 10 px.
//!
//! `cargo run -p plan --example annotation_grid -- IN.png OUT.png`

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let [_, input, output] = args.as_slice() else {
        eprintln!("usage: annotation_grid IN OUT.png");
        std::process::exit(2);
    };
    let img = match image::open(input) {
        Ok(i) => i.to_luma8(),
        Err(e) => {
            eprintln!("{input}: {e}");
            std::process::exit(1);
        }
    };
    let (w, h) = img.dimensions();
    let out = image::RgbImage::from_fn(w, h, |x, y| {
        let g = img.get_pixel(x, y)[0];
        let on = |step: u32| x % step == 0 || y % step == 0;
        if on(100) {
            image::Rgb([255, 0, 0])
        } else if on(50) {
            image::Rgb([0, 0, 255])
        } else if on(10) {
            image::Rgb([g / 2 + 100, g / 2 + 100, g / 2 + 100])
        } else {
            image::Rgb([g, g, g])
        }
    });
    if let Err(e) = out.save(output) {
        eprintln!("{output}: {e}");
        std::process::exit(1);
    }
}
