//! What a scale bar looks like, in pixels and shares: the thresholds of the scan (`scan`) and
//! of the ticks and the paper around them (`ticks`), chosen on the development set's bars
//! (`tests/data/scalebars.json`).

/// How far from the line, in pixels, the paper must be clear for the line to count as thin
/// (a bar up to 2 × CLEAR − 1 px thick); ticks and lettering that reach this far leave gaps.
pub(super) const CLEAR: usize = 4;
/// Shortest bar (px): on shorter lines a pixel is more than 2.5 % of the scale, and the short
/// lines that pass the other tests were edges of buildings.
pub(super) const MIN_LENGTH: f64 = 40.0;
/// The longest gap (ticks, numerals touching the line, breaks in the engraving) a bar may have.
pub(super) const MAX_GAP: usize = 6;
/// Share of the bar's length where the thin line is seen.
pub(super) const MIN_COVER: f64 = 0.8;
/// Graduations a bar must show (its two ends and at least one division) …
pub(super) const MIN_TICKS: usize = 3;
/// … at most one per this many pixels (hachures and hatching are denser).
pub(super) const MIN_TICK_SPACING: usize = 6;
/// A line end without a tick is the bar's end when it lies at most this many units past the
/// outer tick (Armitage's plain halves are five units) …
pub(super) const MAX_PLAIN_UNITS: f64 = 6.0;
/// … of at least this many pixels …
pub(super) const MIN_PLAIN_UNIT: f64 = 12.0;
/// … and the ticks span this share of the line (Armitage's 0–300 ft bars may show ticks
/// only up to 100).
pub(super) const MIN_TICKED_SHARE: f64 = 0.3;
/// Share of the gaps between ticks that must be whole multiples or fractions of the unit.
pub(super) const MIN_EVEN: f64 = 0.75;
/// Ticks are short strokes: ink that runs on this far from the line is a crossing line.
pub(super) const MAX_TICK: usize = 14;
/// Share of the bar's length (ticks aside) with clear paper for 10 px on its clearer side …
pub(super) const MIN_CLEAR_SIDE: f64 = 0.9;
/// … and on its other side, where the numerals are.
pub(super) const MIN_LETTERED_SIDE: f64 = 0.4;
/// With lettering on both sides: share of the clearer side free within 10 px …
pub(super) const MIN_LETTERED_BOTH: f64 = 0.6;
/// … and of both sides free 16–30 px out.
pub(super) const MIN_FAR_CLEAR_BOTH: f64 = 0.7;
/// Distances from the line (px) beyond its numerals, where the paper must be clear …
pub(super) const FAR: (isize, isize) = (16, 30);
/// … along this share of the bar: buildings' outlines have walls there.
pub(super) const MIN_FAR_CLEAR: f64 = 0.7;
/// Ticks a vertical bar must show, every gap a whole multiple or fraction of the unit …
pub(super) const MIN_VERTICAL_TICKS: usize = 5;
/// … and ticks that must have numerals beside them.
pub(super) const MIN_NUMBERED: usize = 3;
/// How close the castle's walls may come to a bar.
pub(super) const CASTLE_MARGIN: usize = 8;
/// Share of the bar's length along which the paper on one side is the open sheet around the
/// drawing (connected to the sheet's border), not a room or courtyard of the castle.
pub(super) const MIN_OPEN: f64 = 0.6;
