pub mod ast;
pub mod diag;
pub mod export;
pub mod mesh;
pub mod parse;
pub mod shape;
pub mod tree;
