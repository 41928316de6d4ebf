//! One-dimensional layout of split and repeat lengths along a shape's extent (§7.1.1, figure
//! 7.1): relative (`~`) lengths take what absolute ones leave, and repeat tiles a pattern from
//! an offset, the piece before the offset taking the cycle's last symbol.

use crate::diag::num;

/// Pieces shorter than this fraction of the extent are not created by `repeat` (they are merged
/// into their neighbour), so floating-point noise never yields sliver shapes.
pub const SLIVER_FRACTION: f64 = 1e-6;

/// A length as written: absolute, or a relative weight (`~w`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Len {
    Absolute(f64),
    Relative(f64),
}

#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum PartitionError {
    #[error(
        "absolute lengths add up to {}, more than the extent {}, leaving nothing for the ~ lengths",
        num(*.absolute),
        num(*.extent)
    )]
    NoRoomForRelative { absolute: f64, extent: f64 },
    #[error("length #{index} is {}; lengths must be positive", num(*.value))]
    NonPositive { index: usize, value: f64 },
    #[error(
        "repeat offset {} must lie in [0, {}), the extent along the axis",
        num(*.offset),
        num(*.extent)
    )]
    BadOffset { offset: f64, extent: f64 },
    #[error(
        "repeat would create {} shapes, more than the limit of {limit}",
        count(*.pieces)
    )]
    TooManyPieces { pieces: f64, limit: usize },
}

/// A piece count: whole numbers written out, astronomical ones in scientific notation.
fn count(n: f64) -> String {
    if n < 1e15 { format!("{n}") } else { num(n) }
}

fn check_positive(lengths: &[Len]) -> Result<(), PartitionError> {
    for (index, l) in lengths.iter().enumerate() {
        let value = match *l {
            Len::Absolute(v) | Len::Relative(v) => v,
        };
        if !(value > 0.0 && value.is_finite()) {
            return Err(PartitionError::NonPositive { index, value });
        }
    }
    Ok(())
}

/// Resolves `~` lengths for a split: each relative weight gets its share of the extent the
/// absolute lengths leave. Without relative lengths the lengths are returned as written (the
/// shape checks that they fit).
pub fn resolve_split(extent: f64, lengths: &[Len]) -> Result<Vec<f64>, PartitionError> {
    check_positive(lengths)?;
    let absolute: f64 = lengths
        .iter()
        .map(|l| if let Len::Absolute(v) = l { *v } else { 0.0 })
        .sum();
    let weights: f64 = lengths
        .iter()
        .map(|l| if let Len::Relative(w) = l { *w } else { 0.0 })
        .sum();
    if weights == 0.0 {
        return Ok(lengths
            .iter()
            .map(|l| if let Len::Absolute(v) = l { *v } else { 0.0 })
            .collect());
    }
    let free = extent - absolute;
    if free <= SLIVER_FRACTION * extent {
        return Err(PartitionError::NoRoomForRelative { absolute, extent });
    }
    Ok(lengths
        .iter()
        .map(|l| match *l {
            Len::Absolute(v) => v,
            Len::Relative(w) => free * w / weights,
        })
        .collect())
}

/// Lays a repeat pattern over `[0, extent]` as in figure 7.1: tiles start at `offset`; the part
/// before it is one piece with the pattern's last symbol; a partial tile at the far end takes
/// the next symbol of the cycle. Relative lengths make the pattern float: it is stretched so a
/// whole number of cycles fills what follows the offset. Returns `(length, pattern index)`.
pub fn repeat(
    extent: f64,
    pattern: &[Len],
    offset: f64,
    max_pieces: usize,
) -> Result<Vec<(f64, usize)>, PartitionError> {
    check_positive(pattern)?;
    if !(offset >= 0.0 && offset < extent) {
        return Err(PartitionError::BadOffset { offset, extent });
    }
    let sliver = SLIVER_FRACTION * extent;
    let span = extent - offset;
    let nominal: f64 = pattern
        .iter()
        .map(|l| match *l {
            Len::Absolute(v) | Len::Relative(v) => v,
        })
        .sum();
    let lengths: Vec<f64> = if pattern.iter().any(|l| matches!(l, Len::Relative(_))) {
        let cycles = (span / nominal).round().max(1.0);
        resolve_split(span / cycles, pattern)?
    } else {
        pattern
            .iter()
            .map(|l| if let Len::Absolute(v) = l { *v } else { 0.0 })
            .collect()
    };
    let cycle: f64 = lengths.iter().sum();
    let estimate = span / cycle * lengths.len() as f64 + 2.0;
    if estimate > max_pieces as f64 {
        return Err(PartitionError::TooManyPieces {
            pieces: estimate.ceil(),
            limit: max_pieces,
        });
    }
    let mut out = Vec::with_capacity(estimate as usize);
    if offset > sliver {
        out.push((offset, lengths.len() - 1));
    }
    // Positions come from multiplication, not accumulation, so long repeats do not drift.
    let mut prefix = Vec::with_capacity(lengths.len() + 1);
    prefix.push(0.0);
    for l in &lengths {
        prefix.push(prefix.last().unwrap() + l);
    }
    let mut start = offset;
    'tiles: for k in 0.. {
        for j in 0..lengths.len() {
            let end = (offset + k as f64 * cycle + prefix[j + 1]).min(extent);
            if extent - end <= sliver {
                out.push((extent - start, j));
                break 'tiles;
            }
            out.push((end - start, j));
            start = end;
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use Len::*;

    #[test]
    fn figure_7_1_repeat_gives_b2_b1_b2_b1_b2_b1() {
        let pieces = repeat(7.0, &[Absolute(2.0), Absolute(1.0)], 0.5, 100).unwrap();
        let symbols: Vec<usize> = pieces.iter().map(|p| p.1).collect();
        assert_eq!(symbols, vec![1, 0, 1, 0, 1, 0]);
        let lengths: Vec<f64> = pieces.iter().map(|p| p.0).collect();
        assert_eq!(lengths, vec![0.5, 2.0, 1.0, 2.0, 1.0, 0.5]);
    }

    #[test]
    fn exact_fit_has_no_partial_piece() {
        let pieces = repeat(10.0, &[Absolute(2.0)], 0.0, 100).unwrap();
        assert_eq!(pieces.len(), 5);
        assert!(pieces.iter().all(|p| (p.0 - 2.0).abs() < 1e-12 && p.1 == 0));
    }

    #[test]
    fn near_exact_fit_does_not_make_a_sliver() {
        // 0.1 * 30 is not exactly 3.0 in floating point.
        let pieces = repeat(3.0, &[Absolute(0.1)], 0.0, 100).unwrap();
        assert_eq!(pieces.len(), 30);
        assert!((pieces.iter().map(|p| p.0).sum::<f64>() - 3.0).abs() < 1e-12);
    }

    #[test]
    fn rules_7_3_window_row_starts_with_the_offset_wall() {
        // midWallS :: repeat("Z",{18,30},40){window, brickWall} over 200.
        let pieces = repeat(200.0, &[Absolute(18.0), Absolute(30.0)], 40.0, 100).unwrap();
        assert_eq!(pieces[0], (40.0, 1));
        assert_eq!(pieces[1], (18.0, 0));
        assert_eq!(pieces.last().unwrap().1, 0);
        assert!((pieces.iter().map(|p| p.0).sum::<f64>() - 200.0).abs() < 1e-9);
        assert_eq!(pieces.iter().filter(|p| p.1 == 0).count(), 4);
    }

    #[test]
    fn relative_pattern_floats_to_a_whole_number_of_cycles() {
        let pieces = repeat(10.0, &[Relative(1.0), Absolute(0.5)], 0.0, 100).unwrap();
        assert_eq!(pieces.len(), 14);
        assert!((pieces[0].0 - (10.0 / 7.0 - 0.5)).abs() < 1e-12);
    }

    #[test]
    fn runaway_repeat_is_refused_before_allocating() {
        let err = repeat(1.0, &[Absolute(1e-9)], 0.0, 1000).unwrap_err();
        assert!(matches!(err, PartitionError::TooManyPieces { .. }));
    }

    #[test]
    fn offset_outside_the_extent_is_an_error() {
        assert!(repeat(1.0, &[Absolute(0.5)], 1.0, 10).is_err());
        assert!(repeat(1.0, &[Absolute(0.5)], -0.1, 10).is_err());
    }

    #[test]
    fn split_shares_free_length_among_relative_weights() {
        let l = resolve_split(10.0, &[Absolute(2.0), Relative(1.0), Relative(3.0)]).unwrap();
        assert_eq!(l, vec![2.0, 2.0, 6.0]);
        assert!(resolve_split(1.0, &[Absolute(2.0), Relative(1.0)]).is_err());
    }
}
