use std::collections::BTreeSet;

use super::*;

/// The boxes of the openings and enclosing arches of a sheet, for lookups by pixel.
fn in_some_box(sheet: &EngravingSheet, x: u32, y: u32) -> bool {
    let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
    sheet.elements.iter().filter(|e| !e.enclosing).any(|e| {
        let [x0, y0, x1, y1] = e.bbox;
        px >= x0 && px <= x1 && py >= y0 && py <= y1
    })
}

#[test]
fn same_seed_same_bytes() {
    let (a, b) = (generate(11, 300, 240), generate(11, 300, 240));
    assert_eq!(a.image, b.image);
    assert_eq!(a.openings, b.openings);
    assert_eq!(a.elements, b.elements);
    let c = generate(12, 300, 240);
    assert_ne!(a.image, c.image);
}

#[test]
fn sizes_are_respected() {
    for (w, h) in [
        (600, 600),
        (320, 480),
        (800, 300),
        (64, 64),
        (16, 16),
        (1, 1),
    ] {
        let s = generate(5, w, h);
        assert_eq!(s.image.dimensions(), (w, h));
        assert_eq!(s.openings.dimensions(), (w, h));
        for e in &s.elements {
            let [x0, y0, x1, y1] = e.bbox;
            assert!(
                x0 >= 0.0 && y0 >= 0.0 && x1 <= w as f64 && y1 <= h as f64,
                "{e:?} in {w}x{h}"
            );
            assert!(x0 < x1 && y0 < y1, "{e:?}");
        }
    }
}

#[test]
fn the_mask_is_the_openings_and_nothing_else() {
    for seed in 0..20 {
        let s = generate(seed, 600, 600);
        // Every opening has pixels, each the truth of this geometry.
        for e in s.elements.iter().filter(|e| !e.enclosing) {
            let [x0, y0, x1, y1] = e.bbox;
            let mut n = 0;
            for y in (y0.floor() as u32)..(y1.ceil() as u32).min(600) {
                for x in (x0.floor() as u32)..(x1.ceil() as u32).min(600) {
                    n += (s.openings.get_pixel(x, y)[0] == 255) as usize;
                }
            }
            assert!(n > 0, "seed {seed}: {e:?} has no mask pixels");
        }
        // Every mask pixel lies in an opening's box; the mask is binary.
        for (x, y, p) in s.openings.enumerate_pixels() {
            assert!(p[0] == 0 || p[0] == 255);
            if p[0] == 255 {
                assert!(
                    in_some_box(&s, x, y),
                    "seed {seed}: mask pixel ({x}, {y}) in no box"
                );
            }
        }
    }
}

#[test]
fn openings_never_overlap_except_children_in_their_arch() {
    for seed in 0..20 {
        let s = generate(seed, 600, 600);
        let open: Vec<&SheetElement> = s.elements.iter().filter(|e| !e.enclosing).collect();
        for (i, a) in open.iter().enumerate() {
            for b in &open[i + 1..] {
                let disjoint = a.bbox[2] <= b.bbox[0]
                    || b.bbox[2] <= a.bbox[0]
                    || a.bbox[3] <= b.bbox[1]
                    || b.bbox[3] <= a.bbox[1];
                assert!(disjoint, "seed {seed}: {a:?} overlaps {b:?}");
            }
        }
        // Enclosing arches' boxes overlap no opening but their own children.
        for (p, e) in s.elements.iter().enumerate().filter(|(_, e)| e.enclosing) {
            for o in s
                .elements
                .iter()
                .filter(|o| !o.enclosing && o.parent != Some(p))
            {
                let inside = o.bbox[0] >= e.bbox[0]
                    && o.bbox[2] <= e.bbox[2]
                    && o.bbox[1] >= e.bbox[1]
                    && o.bbox[3] <= e.bbox[3];
                assert!(!inside, "seed {seed}: {o:?} inside {e:?} but not its child");
            }
        }
    }
}

#[test]
fn parents_enclose_their_children() {
    let mut children = 0;
    for seed in 0..20 {
        let mut rng = Rng::seed_from_u64(seed);
        let style = style::Style::random(&mut rng);
        let scene = layout::compose(&mut rng, &style, 600, 600);
        let mut canvas = pen::Canvas::new(600, 600);
        layout::paint(&scene, &mut canvas);
        let placed = place::place(&mut rng, &style, &scene, &mut canvas);
        let sheet = generate(seed, 600, 600);
        assert_eq!(placed.len(), sheet.elements.len());
        for (o, e) in placed.iter().zip(&sheet.elements) {
            assert_eq!(o.theta.bbox(), e.bbox);
            let Some(p) = e.parent else { continue };
            children += 1;
            let parent = &placed[p];
            assert!(parent.enclosing && !o.enclosing);
            let (c, q) = (e.bbox, sheet.elements[p].bbox);
            assert!(
                c[0] >= q[0] && c[1] >= q[1] && c[2] <= q[2] && c[3] <= q[3],
                "seed {seed}"
            );
            for (x, y) in pixels_of(&o.theta, 600, 600) {
                assert!(
                    parent.theta.contains(x as f64 + 0.5, y as f64 + 0.5),
                    "seed {seed}"
                );
            }
        }
    }
    assert!(children > 0, "no enclosing arch over 20 seeds");
}

#[test]
fn twenty_seeds_vary_heads_fills_and_sizes() {
    let mut heads = BTreeSet::new();
    let mut fills = BTreeSet::new();
    let (mut narrow, mut wide) = (f64::MAX, 0.0f64);
    for seed in 0..20 {
        let mut rng = Rng::seed_from_u64(seed);
        let style = style::Style::random(&mut rng);
        let scene = layout::compose(&mut rng, &style, 600, 600);
        let mut canvas = pen::Canvas::new(600, 600);
        layout::paint(&scene, &mut canvas);
        for o in place::place(&mut rng, &style, &scene, &mut canvas) {
            if o.enclosing {
                continue;
            }
            heads.insert(format!("{:?}", o.head));
            fills.insert(o.fill.family());
            narrow = narrow.min(o.theta.w);
            wide = wide.max(o.theta.w);
        }
    }
    assert!(heads.len() >= 3, "{heads:?}");
    assert!(fills.len() >= 3, "{fills:?}");
    assert!(narrow <= 15.0 && wide >= 80.0, "widths {narrow}..{wide}");
}

#[test]
fn openings_are_dark_or_outlined_on_the_drawing() {
    // The drawing shows the truth: the mean grey inside the openings differs from the paper's.
    let s = generate(3, 600, 600);
    let (mut inside, mut n) = (0.0, 0.0);
    for (x, y, p) in s.openings.enumerate_pixels() {
        if p[0] == 255 {
            inside += s.image.get_pixel(x, y)[0] as f64;
            n += 1.0;
        }
    }
    let paper = s.image.get_pixel(2, 2)[0] as f64;
    assert!(
        n > 0.0 && inside / n < paper - 20.0,
        "{} vs {paper}",
        inside / n
    );
}
