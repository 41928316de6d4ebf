//! The masks a scale bar is looked for in (ink apart from the castle, the castle's ink, the
//! open sheet), read along rows: columns are read as the rows of the transposed masks.

/// The masks, read along rows: position `along` (x) on line `line` (y).
pub(super) struct Grid<'a> {
    pub(super) ink: &'a [bool],
    pub(super) castle: &'a [bool],
    pub(super) open: &'a [bool],
    pub(super) w: usize,
    pub(super) h: usize,
}

impl Grid<'_> {
    /// Length of a line and the number of lines.
    pub(super) fn dims(&self) -> (usize, usize) {
        (self.w, self.h)
    }

    fn index(&self, along: usize, line: isize) -> Option<usize> {
        if line < 0 || line as usize >= self.h || along >= self.w {
            return None;
        }
        Some(line as usize * self.w + along)
    }

    /// Ink at position `along` on line `line`; outside the image is paper.
    pub(super) fn at(&self, along: usize, line: isize) -> bool {
        self.index(along, line).is_some_and(|i| self.ink[i])
    }

    /// Any ink at the position, the castle's included.
    pub(super) fn any_ink_at(&self, along: usize, line: isize) -> bool {
        self.index(along, line)
            .is_some_and(|i| self.ink[i] || self.castle[i])
    }

    /// The castle's own ink at the position.
    pub(super) fn castle_at(&self, along: usize, line: isize) -> bool {
        self.index(along, line).is_some_and(|i| self.castle[i])
    }

    /// Open sheet at the position; outside the image counts as open.
    pub(super) fn open_at(&self, along: usize, line: isize) -> bool {
        self.index(along, line).is_none_or(|i| self.open[i])
    }
}
