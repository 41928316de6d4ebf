//! Parsing of castle plan drawings (Sui 2011, chapter 5).
pub mod binarize;
pub mod thin;
pub mod graph;
pub mod fit;
