//! Tests of the synthetic drawings: seeded, wall shares, clutter never on walls, styles.

use rand::SeedableRng;

use super::geometry::Rng;
use super::layout::{self, Layout};
use super::sheet::Sheet;
use super::*;

#[test]
fn synth_styles_same_seed_same_drawing() {
    let (a, b) = (generate(7, 300, 200), generate(7, 300, 200));
    assert_eq!(a.image, b.image);
    assert_eq!(a.walls, b.walls);
    let c = generate(8, 300, 200);
    assert!(a.image != c.image && a.walls != c.walls);
}

#[test]
fn synth_styles_wall_share_in_range() {
    for seed in 0..50 {
        let p = generate_with(
            seed,
            400,
            300,
            &StyleChoice {
                clean: true,
                ..Default::default()
            },
        );
        let share = p.walls.pixels().filter(|v| v.0[0] == 255).count() as f64 / (400.0 * 300.0);
        assert!(
            (0.01..0.4).contains(&share),
            "seed {seed}: wall share {share}"
        );
    }
}

#[test]
fn synth_styles_solid_walls_dark_and_clutter_outside() {
    let choice = StyleChoice {
        walls: Some(WallStyle::Solid),
        clean: true,
        ..Default::default()
    };
    for seed in 0..10 {
        let (sheet, style) = draw(seed, 500, 400, &choice);
        assert!(style.second.is_none());
        let walls = sheet.truth.count();
        let dark = (0..sheet.truth.m.len())
            .filter(|&i| sheet.truth.m[i] && sheet.img.as_raw()[i] < 60)
            .count();
        assert!(
            dark as f64 >= 0.99 * walls as f64,
            "seed {seed}: {dark} of {walls}"
        );
        assert!(sheet.clutter.count() > 0, "seed {seed}: no clutter");
        assert!(
            !sheet
                .truth
                .m
                .iter()
                .zip(&sheet.clutter.m)
                .any(|(a, b)| *a && *b)
        );
    }
}

#[test]
fn synth_styles_outlined_truth_covers_paper() {
    let choice = StyleChoice {
        walls: Some(WallStyle::Outlined),
        thickness: Some(10.0),
        clean: true,
        ..Default::default()
    };
    for seed in 0..5 {
        let p = generate_with(seed, 500, 400, &choice);
        let truth: Vec<u8> = p
            .walls
            .as_raw()
            .iter()
            .zip(p.image.as_raw())
            .filter(|(t, _)| **t == 255)
            .map(|(_, v)| *v)
            .collect();
        let light = truth.iter().filter(|v| **v > 200).count() as f64 / truth.len() as f64;
        assert!(light > 0.3, "seed {seed}: light share {light}");
        assert!(light < 0.9, "seed {seed}: light share {light}");
    }
}

#[test]
fn synth_styles_degraded_solid_walls_stay_darker_than_paper() {
    let choice = StyleChoice {
        walls: Some(WallStyle::Solid),
        ..Default::default()
    };
    for seed in 0..10 {
        let p = generate_with(seed, 400, 300, &choice);
        let (mut sum, mut n) = ([0f64; 2], [0f64; 2]);
        for (t, v) in p.walls.as_raw().iter().zip(p.image.as_raw()) {
            let k = (*t == 255) as usize;
            sum[k] += *v as f64;
            n[k] += 1.0;
        }
        let (paper, wall) = (sum[0] / n[0], sum[1] / n[1]);
        assert!(
            wall + 60.0 < paper,
            "seed {seed}: walls {wall:.0}, rest {paper:.0}"
        );
    }
}

#[test]
fn synth_styles_every_style_occurs() {
    let seen: Vec<WallStyle> = (0..40).map(|s| generate(s, 200, 150).style.walls).collect();
    for style in WALL_STYLES {
        assert!(seen.contains(&style), "{style:?} never drawn");
    }
}

#[test]
fn synth_styles_sizes() {
    for (w, h) in [(300, 200), (2000, 1500)] {
        let p = generate(3, w, h);
        assert_eq!(p.image.dimensions(), (w, h));
        assert_eq!(p.walls.dimensions(), (w, h));
    }
}

/// A clean sheet of `seed`'s castle (walls 6 px thick) with one kind of clutter drawn.
fn clutter_sheet(seed: u64, kind: fn(&mut Sheet, &Layout, &mut Rng)) -> Sheet {
    let mut rng = Rng::seed_from_u64(seed);
    let lay = layout::layout(&mut rng, 400, 300, 6.0);
    let mut sheet = Sheet::new(400, 300, &lay);
    kind(&mut sheet, &lay, &mut rng);
    sheet
}

/// Clutter pixels with a wall pixel beside them (4-neighbours).
fn touching(sheet: &Sheet) -> usize {
    let (w, truth, ink) = (sheet.truth.w, &sheet.truth.m, &sheet.clutter.m);
    (0..ink.len())
        .filter(|&i| {
            ink[i]
                && [i.wrapping_sub(1), i + 1, i.wrapping_sub(w), i + w]
                    .iter()
                    .any(|&j| truth.get(j) == Some(&true))
        })
        .count()
}

#[test]
fn synth_styles_wall_hachures_touch_the_walls_never_on_them() {
    for seed in 0..8 {
        let a = clutter_sheet(seed, super::moat::wall_hachures);
        let b = clutter_sheet(seed, super::moat::wall_hachures);
        assert_eq!(a.img, b.img, "seed {seed}: not deterministic");
        assert!(
            !a.truth.m.iter().zip(&a.clutter.m).any(|(t, c)| *t && *c),
            "seed {seed}: a hachure pixel on a wall"
        );
        let n = touching(&a);
        assert!(n >= 20, "seed {seed}: {n} hachure pixels touch a wall");
    }
}

#[test]
fn synth_styles_hachure_bands_follow_the_walls_never_on_them() {
    let mut touch = 0;
    for seed in 0..8 {
        let a = clutter_sheet(seed, super::moat::hachure_bands);
        let b = clutter_sheet(seed, super::moat::hachure_bands);
        assert_eq!(a.img, b.img, "seed {seed}: not deterministic");
        assert!(a.clutter.count() > 100, "seed {seed}: no bands");
        assert!(
            !a.truth.m.iter().zip(&a.clutter.m).any(|(t, c)| *t && *c),
            "seed {seed}: a band pixel on a wall"
        );
        touch += usize::from(touching(&a) > 0);
    }
    assert!(touch >= 2, "bands start at the wall on {touch} of 8 sheets");
}

#[test]
fn synth_styles_draw_the_scarps_against_walls_when_asked() {
    let scarps = StyleChoice {
        scarps: true,
        ..Default::default()
    };
    let drawn: Vec<Vec<Clutter>> = (0..40)
        .map(|s| generate_with(s, 200, 150, &scarps).style.clutter)
        .collect();
    for kind in [Clutter::WallHachures, Clutter::HachureBands] {
        let n = drawn.iter().filter(|c| c.contains(&kind)).count();
        assert!((3..30).contains(&n), "{kind:?} drawn on {n} of 40");
        let by_default = (0..40).any(|s| generate(s, 200, 150).style.clutter.contains(&kind));
        assert!(!by_default, "{kind:?} drawn without being asked");
    }
}

#[test]
fn synth_styles_scarp_zones_hold_their_strokes_and_the_paper_between() {
    for (seed, kind) in (0..6).flat_map(|s| {
        [
            (
                s,
                super::moat::wall_hachures as fn(&mut Sheet, &Layout, &mut Rng),
            ),
            (s, super::moat::hachure_bands),
        ]
    }) {
        let a = clutter_sheet(seed, kind);
        let (zone, ink, truth) = (&a.scarps.m, &a.clutter.m, &a.truth.m);
        assert!(
            !zone.iter().zip(truth).any(|(z, t)| *z && *t),
            "seed {seed}: a scarp zone on a wall"
        );
        let strokes = ink.iter().filter(|&&c| c).count();
        let held = ink.iter().zip(zone).filter(|(c, z)| **c && **z).count();
        // The ditch's outer edge is drawn beyond the strokes and is not in the zone.
        assert!(
            held * 10 >= strokes * 8,
            "seed {seed}: {held} of {strokes} stroke pixels in the zone"
        );
        let paper = zone.iter().zip(ink).filter(|(z, c)| **z && !**c).count();
        assert!(
            paper >= held / 2,
            "seed {seed}: {paper} paper pixels between {held}"
        );
    }
    let none = generate(3, 200, 150);
    assert!(
        none.scarps.pixels().all(|p| p[0] == 0),
        "a zone without scarps"
    );
}

#[test]
fn synth_styles_fittings_inside_the_curtain_never_on_walls_only_when_asked() {
    let asked = StyleChoice {
        furnishing: true,
        ..Default::default()
    };
    let drawn = (0..40)
        .filter(|&s| {
            generate_with(s, 200, 150, &asked)
                .style
                .clutter
                .contains(&Clutter::Furnishing)
        })
        .count();
    assert!((15..40).contains(&drawn), "fittings on {drawn} of 40");
    assert!(
        !(0..40).any(|s| generate(s, 200, 150)
            .style
            .clutter
            .contains(&Clutter::Furnishing)),
        "fittings drawn without being asked"
    );
    for seed in 0..8 {
        let a = clutter_sheet(seed, super::furnishing::furnishing);
        let b = clutter_sheet(seed, super::furnishing::furnishing);
        assert_eq!(a.img, b.img, "seed {seed}: not deterministic");
        let ink = a.clutter.count();
        assert!(ink > 100, "seed {seed}: {ink} fitting pixels");
        assert!(
            !a.truth.m.iter().zip(&a.clutter.m).any(|(t, c)| *t && *c),
            "seed {seed}: a fitting pixel on a wall"
        );
        // Fittings stand inside the curtain: their ink lies within the castle's box.
        let mut rng = Rng::seed_from_u64(seed);
        let lay = layout::layout(&mut rng, 400, 300, 6.0);
        let (c, r) = (lay.centre, lay.radius);
        let far = (0..a.clutter.m.len())
            .filter(|&i| a.clutter.m[i])
            .filter(|&i| {
                let (x, y) = ((i % 400) as f64, (i / 400) as f64);
                ((x - c.0) / r.0).hypot((y - c.1) / r.1) > 1.8
            })
            .count();
        assert!(far * 20 <= ink, "seed {seed}: {far} of {ink} far outside");
    }
}
