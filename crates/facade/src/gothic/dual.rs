//! Forward-mode derivatives for the contour of §4.1: the contour geometry (element.rs) is written
//! once over [`Real`], evaluated with `f64` for the likelihood of eq. 4.2 and with [`Dual`] for
//! ∂p/∂Θ and ∂ds/∂Θ in the analytic gradient of the optimiser (optimise.rs).

use std::ops::{Add, Div, Mul, Neg, Sub};

/// The arithmetic the contour construction needs.
pub trait Real:
    Copy
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    fn constant(v: f64) -> Self;
    fn value(self) -> f64;
    fn sqrt(self) -> Self;
    fn cos(self) -> Self;
    fn sin(self) -> Self;
    /// acos of the argument clamped to [−1, 1] (flat outside, as the clamp makes it).
    fn acos_clamped(self) -> Self;
    /// asin of the argument clamped to [−1, 1].
    fn asin_clamped(self) -> Self;
    fn hypot(self, other: Self) -> Self;
    fn scale(self, k: f64) -> Self {
        self * Self::constant(k)
    }
}

impl Real for f64 {
    fn constant(v: f64) -> Self {
        v
    }
    fn value(self) -> f64 {
        self
    }
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    fn cos(self) -> Self {
        f64::cos(self)
    }
    fn sin(self) -> Self {
        f64::sin(self)
    }
    fn acos_clamped(self) -> Self {
        self.clamp(-1.0, 1.0).acos()
    }
    fn asin_clamped(self) -> Self {
        self.clamp(-1.0, 1.0).asin()
    }
    fn hypot(self, other: Self) -> Self {
        f64::hypot(self, other)
    }
    fn scale(self, k: f64) -> Self {
        self * k
    }
}

/// How many parameters a [`Dual`] differentiates by: the five of one element's Θ (a group's
/// joint parameters are mapped onto them member by member).
pub const N: usize = 5;

/// A value and its gradient with respect to `N` parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dual {
    pub v: f64,
    pub d: [f64; N],
}

impl Dual {
    /// The `i`-th independent variable at value `v`.
    pub fn var(v: f64, i: usize) -> Dual {
        let mut d = [0.0; N];
        d[i] = 1.0;
        Dual { v, d }
    }

    /// f(self) with f'(self) = `slope`.
    fn chain(self, v: f64, slope: f64) -> Dual {
        Dual {
            v,
            d: self.d.map(|x| x * slope),
        }
    }
}

impl Add for Dual {
    type Output = Dual;
    fn add(self, o: Dual) -> Dual {
        Dual {
            v: self.v + o.v,
            d: std::array::from_fn(|i| self.d[i] + o.d[i]),
        }
    }
}

impl Sub for Dual {
    type Output = Dual;
    fn sub(self, o: Dual) -> Dual {
        Dual {
            v: self.v - o.v,
            d: std::array::from_fn(|i| self.d[i] - o.d[i]),
        }
    }
}

impl Mul for Dual {
    type Output = Dual;
    // The product rule: a derivative of a product is a sum.
    #[allow(clippy::suspicious_arithmetic_impl)]
    fn mul(self, o: Dual) -> Dual {
        Dual {
            v: self.v * o.v,
            d: std::array::from_fn(|i| self.d[i] * o.v + self.v * o.d[i]),
        }
    }
}

impl Div for Dual {
    type Output = Dual;
    // The quotient rule.
    #[allow(clippy::suspicious_arithmetic_impl)]
    fn div(self, o: Dual) -> Dual {
        let q = self.v / o.v;
        Dual {
            v: q,
            d: std::array::from_fn(|i| (self.d[i] - q * o.d[i]) / o.v),
        }
    }
}

impl Neg for Dual {
    type Output = Dual;
    fn neg(self) -> Dual {
        self.chain(-self.v, -1.0)
    }
}

impl Real for Dual {
    fn constant(v: f64) -> Self {
        Dual { v, d: [0.0; N] }
    }
    fn value(self) -> f64 {
        self.v
    }
    fn sqrt(self) -> Self {
        let s = self.v.sqrt();
        // The derivative diverges at 0; a zero-length piece contributes nothing there.
        self.chain(s, if s > 0.0 { 0.5 / s } else { 0.0 })
    }
    fn cos(self) -> Self {
        self.chain(self.v.cos(), -self.v.sin())
    }
    fn sin(self) -> Self {
        self.chain(self.v.sin(), self.v.cos())
    }
    fn acos_clamped(self) -> Self {
        if self.v <= -1.0 || self.v >= 1.0 {
            return Dual::constant(self.v.clamp(-1.0, 1.0).acos());
        }
        self.chain(self.v.acos(), -1.0 / (1.0 - self.v * self.v).sqrt())
    }
    fn asin_clamped(self) -> Self {
        if self.v <= -1.0 || self.v >= 1.0 {
            return Dual::constant(self.v.clamp(-1.0, 1.0).asin());
        }
        self.chain(self.v.asin(), 1.0 / (1.0 - self.v * self.v).sqrt())
    }
    fn hypot(self, o: Self) -> Self {
        let r = self.v.hypot(o.v);
        if r == 0.0 {
            return Dual::constant(0.0);
        }
        Dual {
            v: r,
            d: std::array::from_fn(|i| (self.v * self.d[i] + o.v * o.d[i]) / r),
        }
    }
    fn scale(self, k: f64) -> Self {
        self.chain(self.v * k, k)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small expression with every operation, differentiated by hand.
    #[test]
    fn derivatives_match_the_hand_computed_ones() {
        let x = Dual::var(0.3, 0);
        let y = Dual::var(2.0, 1);
        let f = (x * y).sin() + x.acos_clamped() - (y / x).sqrt() + x.hypot(y).scale(3.0);
        let (xv, yv) = (0.3f64, 2.0f64);
        let r = xv.hypot(yv);
        let dfdx = yv * (xv * yv).cos() - 1.0 / (1.0 - xv * xv).sqrt()
            + 0.5 * (yv / xv).sqrt() / xv
            + 3.0 * xv / r;
        let dfdy = xv * (xv * yv).cos() - 0.5 / (yv * xv).sqrt() + 3.0 * yv / r;
        assert!((f.d[0] - dfdx).abs() < 1e-12, "{} vs {dfdx}", f.d[0]);
        assert!((f.d[1] - dfdy).abs() < 1e-12, "{} vs {dfdy}", f.d[1]);
        assert_eq!(f.d[2..], [0.0; 3]);
    }

    #[test]
    fn clamped_inverse_trig_is_flat_outside_its_domain() {
        assert_eq!(Dual::var(1.5, 0).acos_clamped().d, [0.0; N]);
        assert_eq!(
            Dual::var(-1.0, 0).asin_clamped().v,
            -std::f64::consts::FRAC_PI_2
        );
        assert_eq!(Dual::var(0.0, 0).hypot(Dual::var(0.0, 1)).d, [0.0; N]);
    }
}
