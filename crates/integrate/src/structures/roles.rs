//! What each plan shape is to a heritage expert (issue 25, §6.1.3 and §7.2.2's library): the
//! keep, the towers, the gates they flank, the ranges built against the curtain and the rooms
//! of the wards.

use crate::estimate::Role;

/// A plan shape that could be the keep.
#[derive(Debug, Clone, Copy)]
pub(super) struct Candidate {
    /// Footprint area, model units².
    pub area: f64,
    /// Wall thickness, model units.
    pub thickness: f64,
    /// A tower room or a tower drawn solid.
    pub tower: bool,
    /// Round, or a rectangle no longer than `SQUAREISH` times its width.
    pub compact: bool,
    /// On the castle's outline (one of its walls borders the surroundings).
    pub on_curtain: bool,
}

/// A keep among towers is this many times the median tower's area …
const KEEP_OVER_TOWERS: f64 = 1.5;
/// … and a rectangle is compact (a tower or keep, not a hall) up to this aspect.
pub(super) const SQUAREISH: f64 = 2.0;
/// A keep standing free in a ward has walls at least this share of the curtain's thickness.
const FREE_KEEP_WALL: f64 = 0.8;

/// The keep (§7.2.2's donjon): the largest compact shape, when it is clearly larger than the
/// towers and its walls at least as thick as theirs, or when it stands free in a ward with walls
/// as thick as a curtain's. At most one.
pub(super) fn keep(candidates: &[Candidate], curtain_thickness: Option<f64>) -> Option<usize> {
    let (largest, l) = candidates
        .iter()
        .enumerate()
        .filter(|(_, c)| c.compact)
        .max_by(|a, b| a.1.area.total_cmp(&b.1.area))?;
    let towers: Vec<&Candidate> = candidates
        .iter()
        .enumerate()
        .filter(|(i, c)| *i != largest && c.tower && c.compact)
        .map(|(_, c)| c)
        .collect();
    let median = |f: fn(&Candidate) -> f64| median(towers.iter().map(|c| f(c)).collect());
    let (tower_area, tower_wall) = (median(|c| c.area), median(|c| c.thickness));
    let above_towers = match (tower_area, tower_wall) {
        (Some(a), Some(t)) => l.area >= KEEP_OVER_TOWERS * a && l.thickness >= t,
        _ => false,
    };
    let free_standing = !l.on_curtain
        && curtain_thickness.is_some_and(|t| l.thickness >= FREE_KEEP_WALL * t)
        && tower_area.is_none_or(|a| l.area >= a);
    (above_towers || free_standing).then_some(largest)
}

/// Two towers flank a gate when the gap between them is at most this share of their summed
/// radii: measured over the 34 shared plans, the one pair this close is the Porte
/// Narbonnaise's at Carcassonne (gap 7.3 m), its passage between them.
const GATE_GAP: f64 = 0.75;

/// The pairs of towers (centre, radius) close enough to flank a gate, nearest first, each tower
/// in one pair at most.
pub(super) fn gates(towers: &[([f64; 2], f64)]) -> Vec<[usize; 2]> {
    let mut pairs: Vec<(f64, [usize; 2])> = Vec::new();
    for i in 0..towers.len() {
        for j in i + 1..towers.len() {
            let ((a, ra), (b, rb)) = (towers[i], towers[j]);
            let gap = (a[0] - b[0]).hypot(a[1] - b[1]) - ra - rb;
            if gap > 0.0 && gap <= GATE_GAP * (ra + rb) {
                pairs.push((gap, [i, j]));
            }
        }
    }
    pairs.sort_by(|x, y| x.0.total_cmp(&y.0));
    let mut used = vec![false; towers.len()];
    let mut out = Vec::new();
    for (_, [i, j]) in pairs {
        if !used[i] && !used[j] {
            used[i] = true;
            used[j] = true;
            out.push([i, j]);
        }
    }
    out
}

/// A tower room whose walls are thinner than this share of the towers' median wall is a
/// building drawn round (a detached chapel, a lodge), not a tower.
const TOWER_WALL: f64 = 0.6;

pub(super) fn thin_for_a_tower(thickness: f64, towers_median: Option<f64>) -> bool {
    towers_median.is_some_and(|m| thickness < TOWER_WALL * m)
}

/// The median of some values (the upper one of an even count).
pub(super) fn median(mut v: Vec<f64>) -> Option<f64> {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied()
}

/// A room's role: against the curtain it is a range, else a room of its ward.
pub(super) fn room(on_curtain: bool) -> Role {
    if on_curtain { Role::Range } else { Role::Room }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c(area: f64, thickness: f64, tower: bool, on_curtain: bool) -> Candidate {
        Candidate {
            area,
            thickness,
            tower,
            compact: true,
            on_curtain,
        }
    }

    #[test]
    fn the_largest_thick_walled_shape_among_towers_is_the_keep() {
        // Coucy: four corner towers and the donjon, twice their area, with thicker walls.
        let towers = [c(40.0, 4.5, true, true); 4];
        let mut all = towers.to_vec();
        all.push(c(80.0, 6.8, false, false));
        assert_eq!(keep(&all, Some(4.0)), Some(4));
        // As large but thin-walled and on the curtain: a hall, not a keep.
        all[4] = c(80.0, 2.0, false, true);
        assert_eq!(keep(&all, Some(4.0)), None);
        // Towers alike: none of them is the keep.
        assert_eq!(keep(&towers, Some(4.0)), None);
    }

    #[test]
    fn two_towers_close_together_flank_a_gate_and_each_flanks_one() {
        let t = |x: f64| ([x, 0.0], 5.0);
        // Gaps: 6 (≤ 7.5), then 4 from the second to a third; 40 to a fourth.
        let towers = [t(0.0), t(16.0), t(30.0), t(80.0)];
        assert_eq!(gates(&towers), [[1, 2]]);
        assert!(gates(&[t(0.0), t(18.0)]).is_empty(), "gap 8 > 7.5");
        assert!(gates(&[t(0.0), t(9.0)]).is_empty(), "overlapping");
    }

    #[test]
    fn a_thick_walled_tower_alone_in_its_ward_is_the_keep() {
        assert_eq!(keep(&[c(50.0, 4.0, false, false)], Some(4.0)), Some(0));
        // On the outline, or thin-walled: a room.
        assert_eq!(keep(&[c(50.0, 4.0, false, true)], Some(4.0)), None);
        assert_eq!(keep(&[c(50.0, 1.0, false, false)], Some(4.0)), None);
        // A long hall is not compact, whatever its walls.
        let hall = Candidate {
            compact: false,
            ..c(90.0, 5.0, false, false)
        };
        assert_eq!(keep(&[hall], Some(4.0)), None);
    }
}
