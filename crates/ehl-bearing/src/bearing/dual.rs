//! Forward-mode dual numbers with four derivative components, used for exact Jacobians of the
//! per-ball equilibrium with respect to the ball centre (X1, X2) and the inner groove centre (A1, A2).

use std::ops::{Add, Div, Mul, Neg, Sub};

/// A value and its gradient with respect to four seeded variables.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct D4 {
    pub v: f64,
    pub d: [f64; 4],
}

impl D4 {
    pub fn cst(v: f64) -> Self {
        D4 { v, d: [0.0; 4] }
    }
    pub fn var(v: f64, i: usize) -> Self {
        let mut d = [0.0; 4];
        d[i] = 1.0;
        D4 { v, d }
    }
    /// Apply a scalar function with value `f` and derivative `df` at `self.v`.
    pub fn chain(self, f: f64, df: f64) -> Self {
        D4 {
            v: f,
            d: self.d.map(|x| df * x),
        }
    }
    pub fn sqrt(self) -> Self {
        let s = self.v.sqrt();
        self.chain(s, 0.5 / s)
    }
}

impl Add for D4 {
    type Output = D4;
    fn add(self, o: D4) -> D4 {
        let mut d = self.d;
        for (a, b) in d.iter_mut().zip(o.d) {
            *a += b;
        }
        D4 { v: self.v + o.v, d }
    }
}
impl Sub for D4 {
    type Output = D4;
    fn sub(self, o: D4) -> D4 {
        let mut d = self.d;
        for (a, b) in d.iter_mut().zip(o.d) {
            *a -= b;
        }
        D4 { v: self.v - o.v, d }
    }
}
impl Mul for D4 {
    type Output = D4;
    fn mul(self, o: D4) -> D4 {
        let mut d = [0.0; 4];
        for (k, x) in d.iter_mut().enumerate() {
            *x = self.d[k] * o.v + self.v * o.d[k];
        }
        D4 { v: self.v * o.v, d }
    }
}
impl Div for D4 {
    type Output = D4;
    fn div(self, o: D4) -> D4 {
        let inv = 1.0 / o.v;
        let q = self.v * inv;
        let mut d = [0.0; 4];
        for (k, x) in d.iter_mut().enumerate() {
            *x = (self.d[k] - q * o.d[k]) * inv;
        }
        D4 { v: q, d }
    }
}
impl Neg for D4 {
    type Output = D4;
    fn neg(self) -> D4 {
        D4 {
            v: -self.v,
            d: self.d.map(|x| -x),
        }
    }
}
impl Add<f64> for D4 {
    type Output = D4;
    fn add(self, o: f64) -> D4 {
        D4 {
            v: self.v + o,
            ..self
        }
    }
}
impl Sub<f64> for D4 {
    type Output = D4;
    fn sub(self, o: f64) -> D4 {
        D4 {
            v: self.v - o,
            ..self
        }
    }
}
impl Mul<f64> for D4 {
    type Output = D4;
    fn mul(self, o: f64) -> D4 {
        D4 {
            v: self.v * o,
            d: self.d.map(|x| x * o),
        }
    }
}
impl Mul<D4> for f64 {
    type Output = D4;
    fn mul(self, o: D4) -> D4 {
        o * self
    }
}
impl Div<f64> for D4 {
    type Output = D4;
    fn div(self, o: f64) -> D4 {
        self * (1.0 / o)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn derivatives_match_finite_differences() {
        // f(x, y) = sqrt(x² + y²)/(x·y) + 3x
        let f = |x: D4, y: D4| (x * x + y * y).sqrt() / (x * y) + 3.0 * x;
        let (x0, y0) = (0.7, 1.3);
        let r = f(D4::var(x0, 0), D4::var(y0, 1));
        let h = 1e-6;
        let fx =
            (f(D4::cst(x0 + h), D4::cst(y0)).v - f(D4::cst(x0 - h), D4::cst(y0)).v) / (2.0 * h);
        let fy =
            (f(D4::cst(x0), D4::cst(y0 + h)).v - f(D4::cst(x0), D4::cst(y0 - h)).v) / (2.0 * h);
        assert!((r.d[0] - fx).abs() < 1e-8 && (r.d[1] - fy).abs() < 1e-8);
        assert_eq!(r.d[2], 0.0);
    }
}
