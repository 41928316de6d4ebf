//! The settings of the search of §3.1.7, shared by the boundary, floor and joint searches.

/// Which façade grammar the search fits.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Grammar {
    /// §3.1.6 as written: N_w windows of one width at one pitch, the same columns in every
    /// floor, every grid cell a window; log-likelihood ratios summed unclipped.
    Text,
    /// Departures measured on CMP and Art-deco (issue 21, marked in `search/columns.rs`):
    /// window columns of any width at any position (still aligned from floor to floor), the
    /// ground, middle and top floors each with their own columns (shop floors, attics), a
    /// grid cell whose pixels favour wall left out (missing windows, doors), up to
    /// [`crate::model::MAX_COLUMNS`] columns.
    Columns,
    /// `Columns`' free columns, shared by every floor, and free window rows: one floor per
    /// window row, of any height (`search/rows.rs`).
    Rows,
    /// Whichever of the `Columns` and `Rows` fits explains more window evidence (the sum
    /// both maximise; `search/rows.rs`).
    #[default]
    ColumnsOrRows,
}

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
    /// The grammar fitted.
    pub grammar: Grammar,
    /// Per-pixel log-likelihood ratios (window − wall, façade − background) are clipped to
    /// [−clip, clip] before they are summed (not in the text, which sums ln P unbounded:
    /// a few pixels with extreme ratios then decide a whole rectangle). `f64::INFINITY`: the
    /// text.
    pub clip: f64,
    /// Each façade found costs this fraction of the image's area in merit (in clipped
    /// log-ratio units) in the boundary search: a prior against splitting one building into
    /// strips. 0: the text.
    pub facade_penalty: f64,
    /// `Grammar::Columns`: windows and the gaps between them are at least this fraction of
    /// the façade's width.
    pub min_window_frac: f64,
    /// `Grammar::Columns`: each window column costs this many pixels of evidence (clipped
    /// log-ratio) per window row.
    pub column_cost: f64,
    /// Subtracted from the window − wall log-ratio before it is clipped: ln of the prior odds
    /// of wall against window (0: equal priors, the text's maximum likelihood).
    pub window_bias: f64,
}

impl SearchParams {
    /// The search as the text describes it (§3.1.6–3.1.7).
    pub fn text() -> SearchParams {
        SearchParams {
            grammar: Grammar::Text,
            clip: f64::INFINITY,
            facade_penalty: 0.0,
            min_window_frac: 0.0,
            column_cost: 0.0,
            window_bias: 0.0,
            ..SearchParams::default()
        }
    }
}

impl Default for SearchParams {
    fn default() -> Self {
        SearchParams {
            max_peaks: 40,
            peak_separation: 3,
            merge_tolerance: 0.05,
            rounds: 3,
            min_facade_frac: 0.05,
            grammar: Grammar::ColumnsOrRows,
            clip: 1.0,
            facade_penalty: 0.02,
            min_window_frac: 0.02,
            column_cost: 0.0,
            window_bias: 0.0,
        }
    }
}
