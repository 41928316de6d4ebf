pub fn parse(_src: &str) -> Result<crate::ast::Program, Vec<crate::diag::Diagnostic>> { unimplemented!() }
