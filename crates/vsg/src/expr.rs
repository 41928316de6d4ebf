//! Evaluation of VSG expressions (§7.1): declared variables and arrays, the current shape's
//! attributes in conditions, maths functions, and `rand(lo, hi)` drawn from the seeded stream.

use std::collections::HashMap;

use rand::RngExt;
use rand_chacha::ChaCha8Rng;

use crate::ast::{BinaryOp, Expr, Ident, UnaryOp};
use crate::diag::{Diagnostic, num};

/// A declared value.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Scalar(f64),
    Array(Vec<f64>),
}

/// Attributes of the shape a rule is applied to, readable by name in conditions and
/// expressions: `sx sy sz` (local bounding-box size), `px py pz` (world position of its
/// centre), `volume`, `depth` (root 0), `index` (among siblings, from 0), `siblings` (count).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ShapeAttrs {
    pub size: [f64; 3],
    pub position: [f64; 3],
    pub volume: f64,
    pub depth: u32,
    pub index: u32,
    pub siblings: u32,
}

impl ShapeAttrs {
    /// The attribute names, for error messages.
    pub const NAMES: &'static str = "sx, sy, sz, px, py, pz, volume, depth, index, siblings";

    fn get(&self, name: &str) -> Option<f64> {
        Some(match name {
            "sx" => self.size[0],
            "sy" => self.size[1],
            "sz" => self.size[2],
            "px" => self.position[0],
            "py" => self.position[1],
            "pz" => self.position[2],
            "volume" => self.volume,
            "depth" => self.depth as f64,
            "index" => self.index as f64,
            "siblings" => self.siblings as f64,
            _ => return None,
        })
    }
}

/// Everything an expression can read: declarations, the current shape, the random stream.
pub struct Scope<'a> {
    pub vars: &'a HashMap<String, Value>,
    pub shape: Option<&'a ShapeAttrs>,
    pub rng: &'a mut ChaCha8Rng,
}

const FUNCTIONS: &str = "sin, cos, tan, asin, acos, atan, atan2, sqrt, abs, floor, ceil, round, \
     min, max, pow, exp, ln, log10, clamp, rad, deg, rand";

impl Scope<'_> {
    /// Evaluates to a finite number, or explains why not at the offending span.
    pub fn eval(&mut self, expr: &Expr) -> Result<f64, Diagnostic> {
        let v = self.eval_raw(expr)?;
        if v.is_finite() {
            Ok(v)
        } else {
            Err(Diagnostic::new(
                format!("expression evaluates to {v}, not a finite number"),
                expr.span(),
                "this expression",
            ))
        }
    }

    /// Evaluates as a condition: non-zero is true.
    pub fn truth(&mut self, expr: &Expr) -> Result<bool, Diagnostic> {
        Ok(self.eval(expr)? != 0.0)
    }

    fn eval_raw(&mut self, expr: &Expr) -> Result<f64, Diagnostic> {
        Ok(match expr {
            Expr::Number(v, _) => *v,
            Expr::Bool(b, _) => *b as u8 as f64,
            Expr::Var(id) => self.variable(id)?,
            Expr::Index { array, index, span } => {
                let i = self.eval(index)?;
                let values = match self.vars.get(&array.name) {
                    Some(Value::Array(values)) => values,
                    Some(Value::Scalar(_)) => {
                        return Err(Diagnostic::new(
                            format!("'{}' is a float, not an array", array.name),
                            array.span,
                            "cannot be indexed",
                        ));
                    }
                    None => return Err(unknown_variable(array)),
                };
                if i < 0.0 || i.fract() != 0.0 || i as usize >= values.len() {
                    return Err(Diagnostic::new(
                        format!(
                            "index {} is out of range for '{}', which has {} elements (0..{})",
                            num(i),
                            array.name,
                            values.len(),
                            values.len().saturating_sub(1)
                        ),
                        *span,
                        "out of range",
                    ));
                }
                values[i as usize]
            }
            Expr::Unary { op, operand, .. } => {
                let v = self.eval(operand)?;
                match op {
                    UnaryOp::Neg => -v,
                    UnaryOp::Not => (v == 0.0) as u8 as f64,
                }
            }
            Expr::Binary { op, lhs, rhs, span } => {
                // && and || short-circuit so a guard like `depth > 0 && ...` can protect the rest.
                let a = self.eval(lhs)?;
                match op {
                    BinaryOp::And if a == 0.0 => return Ok(0.0),
                    BinaryOp::Or if a != 0.0 => return Ok(1.0),
                    _ => {}
                }
                let b = self.eval(rhs)?;
                let truth = |x: bool| x as u8 as f64;
                match op {
                    BinaryOp::Add => a + b,
                    BinaryOp::Sub => a - b,
                    BinaryOp::Mul => a * b,
                    BinaryOp::Div | BinaryOp::Rem if b == 0.0 => {
                        return Err(Diagnostic::new("division by zero", *span, "divides by 0"));
                    }
                    BinaryOp::Div => a / b,
                    BinaryOp::Rem => a % b,
                    BinaryOp::Lt => truth(a < b),
                    BinaryOp::Le => truth(a <= b),
                    BinaryOp::Gt => truth(a > b),
                    BinaryOp::Ge => truth(a >= b),
                    BinaryOp::Eq => truth(a == b),
                    BinaryOp::Ne => truth(a != b),
                    BinaryOp::And | BinaryOp::Or => truth(b != 0.0),
                }
            }
            Expr::Call {
                function,
                args,
                span,
            } => self.call(function, args, *span)?,
        })
    }

    fn variable(&self, id: &Ident) -> Result<f64, Diagnostic> {
        match self.vars.get(&id.name) {
            Some(Value::Scalar(v)) => return Ok(*v),
            Some(Value::Array(values)) => {
                return Err(Diagnostic::new(
                    format!(
                        "'{}' is an array of {}; index it, e.g. {}[0]",
                        id.name,
                        values.len(),
                        id.name
                    ),
                    id.span,
                    "array used as a number",
                ));
            }
            None => {}
        }
        if let Some(v) = self.shape.and_then(|s| s.get(&id.name)) {
            return Ok(v);
        }
        match id.name.as_str() {
            "PI" | "pi" => Ok(std::f64::consts::PI),
            _ => Err(unknown_variable(id)),
        }
    }

    fn call(
        &mut self,
        function: &Ident,
        args: &[Expr],
        span: crate::ast::Span,
    ) -> Result<f64, Diagnostic> {
        let name = function.name.as_str();
        let arity = match name {
            "atan2" | "pow" | "rand" => 2..=2,
            "clamp" => 3..=3,
            "min" | "max" => 1..=usize::MAX,
            "sin" | "cos" | "tan" | "asin" | "acos" | "atan" | "sqrt" | "abs" | "floor"
            | "ceil" | "round" | "exp" | "ln" | "log10" | "rad" | "deg" => 1..=1,
            _ => {
                return Err(Diagnostic::new(
                    format!("unknown function '{name}'; functions are {FUNCTIONS}"),
                    function.span,
                    "unknown function",
                ));
            }
        };
        if !arity.contains(&args.len()) {
            let expected = if arity.start() == arity.end() {
                arity.start().to_string()
            } else {
                format!("at least {}", arity.start())
            };
            return Err(Diagnostic::new(
                format!("{name} takes {expected} argument(s), found {}", args.len()),
                span,
                "wrong number of arguments",
            ));
        }
        let mut x = Vec::with_capacity(args.len());
        for a in args {
            x.push(self.eval(a)?);
        }
        Ok(match name {
            "sin" => x[0].sin(),
            "cos" => x[0].cos(),
            "tan" => x[0].tan(),
            "asin" => x[0].asin(),
            "acos" => x[0].acos(),
            "atan" => x[0].atan(),
            "atan2" => x[0].atan2(x[1]),
            "sqrt" => x[0].sqrt(),
            "abs" => x[0].abs(),
            "floor" => x[0].floor(),
            "ceil" => x[0].ceil(),
            "round" => x[0].round(),
            "exp" => x[0].exp(),
            "ln" => x[0].ln(),
            "log10" => x[0].log10(),
            "rad" => x[0].to_radians(),
            "deg" => x[0].to_degrees(),
            "pow" => x[0].powf(x[1]),
            "clamp" => x[0].max(x[1]).min(x[2]),
            "min" => x.iter().copied().fold(f64::INFINITY, f64::min),
            "max" => x.iter().copied().fold(f64::NEG_INFINITY, f64::max),
            "rand" => {
                let (lo, hi) = (x[0].min(x[1]), x[0].max(x[1]));
                if lo == hi {
                    lo
                } else if (hi - lo).is_finite() {
                    self.rng.random_range(lo..hi)
                } else {
                    // A range wider than f64 (rand(-1e308, 1e308)) would make random_range
                    // panic; interpolating never overflows.
                    let u: f64 = self.rng.random();
                    (lo * (1.0 - u) + hi * u).clamp(lo, hi)
                }
            }
            _ => unreachable!("arity table and dispatch list the same functions"),
        })
    }
}

fn unknown_variable(id: &Ident) -> Diagnostic {
    Diagnostic::new(
        format!(
            "unknown variable '{}'; declare it with `float {} = ...;` (shape attributes are {})",
            id.name,
            id.name,
            ShapeAttrs::NAMES
        ),
        id.span,
        "not declared",
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ast::Span;
    use rand::SeedableRng;

    fn num(v: f64) -> Expr {
        Expr::Number(v, Span::default())
    }

    fn var(name: &str, at: usize) -> Expr {
        Expr::Var(Ident {
            name: name.into(),
            span: Span::new(at, at + name.len()),
        })
    }

    fn bin(op: BinaryOp, a: Expr, b: Expr) -> Expr {
        Expr::Binary {
            op,
            lhs: Box::new(a),
            rhs: Box::new(b),
            span: Span::default(),
        }
    }

    fn with_scope<T>(f: impl FnOnce(&mut Scope) -> T) -> T {
        let mut vars = HashMap::new();
        vars.insert("w".to_string(), Value::Scalar(4.0));
        vars.insert("a".to_string(), Value::Array(vec![1.0, 2.0, 3.0]));
        let attrs = ShapeAttrs {
            size: [5.0, 10.0, 3.0],
            depth: 2,
            ..Default::default()
        };
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        f(&mut Scope {
            vars: &vars,
            shape: Some(&attrs),
            rng: &mut rng,
        })
    }

    #[test]
    fn arithmetic_variables_and_attributes() {
        let e = bin(
            BinaryOp::Mul,
            var("w", 0),
            bin(BinaryOp::Sub, var("sy", 0), num(1.0)),
        );
        assert_eq!(with_scope(|s| s.eval(&e)).unwrap(), 36.0);
    }

    #[test]
    fn index_out_of_range_names_the_array() {
        let e = Expr::Index {
            array: Ident {
                name: "a".into(),
                span: Span::new(0, 1),
            },
            index: Box::new(num(3.0)),
            span: Span::new(0, 4),
        };
        let err = with_scope(|s| s.eval(&e)).unwrap_err();
        assert!(
            err.message.contains("out of range for 'a'"),
            "{}",
            err.message
        );
    }

    #[test]
    fn unknown_variable_is_an_error_at_its_span() {
        let err = with_scope(|s| s.eval(&var("height", 7))).unwrap_err();
        assert_eq!(err.span, Span::new(7, 13));
        assert!(err.message.contains("unknown variable 'height'"));
    }

    #[test]
    fn division_by_zero_is_an_error() {
        let e = bin(BinaryOp::Div, num(1.0), num(0.0));
        assert!(with_scope(|s| s.eval(&e)).is_err());
    }

    #[test]
    fn and_short_circuits() {
        let e = bin(
            BinaryOp::And,
            num(0.0),
            bin(BinaryOp::Div, num(1.0), num(0.0)),
        );
        assert_eq!(with_scope(|s| s.eval(&e)).unwrap(), 0.0);
    }

    #[test]
    fn rand_over_a_range_wider_than_f64_is_a_number_in_it() {
        let call = Expr::Call {
            function: Ident {
                name: "rand".into(),
                span: Span::default(),
            },
            args: vec![num(1e308), num(-1e308)],
            span: Span::default(),
        };
        for _ in 0..100 {
            let r = with_scope(|s| s.eval(&call)).unwrap();
            assert!((-1e308..=1e308).contains(&r), "{r}");
        }
    }

    #[test]
    fn functions_and_arity() {
        let call = |name: &str, args: Vec<Expr>| Expr::Call {
            function: Ident {
                name: name.into(),
                span: Span::default(),
            },
            args,
            span: Span::default(),
        };
        assert_eq!(
            with_scope(|s| s.eval(&call("max", vec![num(1.0), num(7.0), num(3.0)]))).unwrap(),
            7.0
        );
        assert!(with_scope(|s| s.eval(&call("sqrt", vec![]))).is_err());
        assert!(with_scope(|s| s.eval(&call("sqrt", vec![num(-1.0)]))).is_err());
        let r = with_scope(|s| s.eval(&call("rand", vec![num(2.0), num(3.0)]))).unwrap();
        assert!((2.0..3.0).contains(&r));
    }
}
