//! Heights that travel (issue 25, §6.1.2's joint re-estimation extended to structures without a
//! photo): a tower whose height a façade measured lends it to the towers of the same shape and
//! size that no photo shows (the corner towers of a castle are drawn alike and built alike),
//! and the keep, when its height is the default, rises half as high again as the measured
//! towers. Each value's provenance names the structure it came from.

use crate::correspond::area;
use crate::estimate::{Footprint, Provenance, Role, Source, Structure};
use crate::structures::KEEP_OVER_TOWERS;

/// Towers are alike when their footprints' areas differ by less than this share.
const ALIKE_AREA: f64 = 0.35;

/// Measured on the structure itself (not lent, not a default).
fn measured(s: &Structure) -> bool {
    s.provenance
        .get("height")
        .is_some_and(|p| p.source() == Source::Measured)
}

fn same_shape(a: &Footprint, b: &Footprint) -> bool {
    matches!(
        (a, b),
        (Footprint::Circle { .. }, Footprint::Circle { .. })
            | (Footprint::Rectangle { .. }, Footprint::Rectangle { .. })
    )
}

/// Lends measured tower heights to the unmeasured towers alike and raises a default keep over
/// them. Structures with their own measurement keep it.
pub fn propagate(structures: &mut [Structure]) {
    let sources: Vec<usize> = (0..structures.len())
        .filter(|&i| structures[i].role == Role::Tower && measured(&structures[i]))
        .collect();
    if sources.is_empty() {
        return;
    }
    for i in 0..structures.len() {
        let t = &structures[i];
        if t.role != Role::Tower || measured(t) {
            continue;
        }
        let a = area(&t.footprint);
        // The measured tower nearest in size, if it is alike.
        let best = sources
            .iter()
            .filter(|&&j| same_shape(&structures[j].footprint, &t.footprint))
            .map(|&j| (j, (area(&structures[j].footprint) - a).abs() / a.max(1e-12)))
            .filter(|(_, d)| *d < ALIKE_AREA)
            .min_by(|x, y| x.1.total_cmp(&y.1));
        let Some((j, diff)) = best else {
            continue;
        };
        let (height, step) = {
            let src = &structures[j];
            let from = &src.provenance["height"];
            let mut lent = Provenance::new(
                &from.image,
                format!(
                    "issue 25 (§6.1.2 extended): the height of {}, measured ({}), lent to a tower of the same shape and size (areas {:.0} % apart)",
                    src.id,
                    from.step,
                    100.0 * diff
                ),
                None,
            );
            lent.lent_by = Some(src.id.clone());
            (src.height, lent)
        };
        structures[i].height = height;
        structures[i].provenance.insert("height".into(), step);
    }
    let measured_towers: Vec<f64> = sources.iter().map(|&j| structures[j].height).collect();
    let tallest = measured_towers.iter().copied().fold(f64::MIN, f64::max);
    for s in structures.iter_mut() {
        if s.role == Role::Keep && !measured(s) && KEEP_OVER_TOWERS * tallest > s.height {
            s.height = KEEP_OVER_TOWERS * tallest;
            s.provenance.insert(
                "height".into(),
                Provenance::new(
                    "default",
                    format!(
                        "the keep: {KEEP_OVER_TOWERS} × the tallest measured tower ({tallest:.2} units)"
                    ),
                    None,
                ),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use plan::label::Label;
    use std::collections::BTreeMap;

    fn tower(id: &str, radius: f64, height: Option<f64>) -> Structure {
        let mut provenance = BTreeMap::new();
        provenance.insert(
            "height".to_string(),
            match height {
                Some(_) => Provenance::new("elevation.png", "§6.1.2 façade height", None),
                None => Provenance::new("default", "§5.3 class height", None),
            },
        );
        Structure {
            id: id.into(),
            label: Label::TowerRoom,
            role: Role::Tower,
            kind: crate::estimate::Kind::HollowCylindrical,
            footprint: Footprint::Circle {
                center: [0.0, 0.0],
                radius,
            },
            height: height.unwrap_or(20.0),
            wall_thickness: 2.0,
            facades: vec![],
            children: vec![],
            roof: None,
            crenellated: None,
            provenance,
        }
    }

    #[test]
    fn a_measured_tower_lends_its_height_to_the_towers_alike_and_the_keep_rises_over_it() {
        let mut keep = tower("keep1", 16.0, None);
        keep.role = Role::Keep;
        keep.height = 30.0;
        let mut s = vec![
            tower("tower1", 11.5, Some(35.66)),
            tower("tower2", 11.0, None),
            tower("tower3", 6.0, None),
            keep,
        ];
        propagate(&mut s);
        assert_eq!(s[1].height, 35.66);
        assert_eq!(s[1].provenance["height"].image, "elevation.png");
        assert_eq!(s[1].provenance["height"].lent_by.as_deref(), Some("tower1"));
        assert_eq!(s[1].provenance["height"].source(), Source::Lent);
        // Half the radius: another kind of tower, it keeps its default.
        assert_eq!(s[2].height, 20.0);
        assert_eq!(s[3].height, 1.5 * 35.66);
    }

    #[test]
    fn without_a_measured_tower_nothing_moves() {
        let mut s = vec![tower("tower1", 11.0, None), tower("tower2", 11.0, None)];
        let before = s.clone();
        propagate(&mut s);
        assert_eq!(s, before);
    }
}
