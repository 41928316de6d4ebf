//! The settings of the search of §3.1.7, shared by the boundary, floor and joint searches.

/// Search settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SearchParams {
    /// Gradient peaks kept as candidate split lines, per direction.
    pub max_peaks: usize,
    /// Peaks closer than this (pixels) to a stronger one are dropped.
    pub peak_separation: usize,
    /// Adjacent façades whose top and bottom edges differ by less than this fraction of the
    /// image height are merged (the over-segmentation merge of figure 3.5).
    pub merge_tolerance: f64,
    /// Rounds of the alternating floor / window search.
    pub rounds: usize,
    /// Façades narrower or lower than this fraction of the image are dropped (slivers left by
    /// misclassified pixels; not in the text).
    pub min_facade_frac: f64,
}

impl Default for SearchParams {
    fn default() -> Self {
        SearchParams {
            max_peaks: 40,
            peak_separation: 3,
            merge_tolerance: 0.05,
            rounds: 3,
            min_facade_frac: 0.05,
        }
    }
}
