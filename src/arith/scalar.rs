//! The number trait the models are written against.
//!
//! A [`Scalar<R>`] is anything the vector fields, forces and Lyapunov functions can be evaluated
//! on, with parameters of type `R`: the coefficient field itself (f64, intervals), truncated
//! Taylor series of it, dual numbers, and the recording type of the rigorous engine's tape.
//! Each model is written once, generic over `T: Scalar<R>`.

use super::real::Real;
use std::fmt::Debug;
use std::ops::{Add, Div, Mul, Neg, Sub};

pub trait Scalar<R: Real>:
    Clone
    + Debug
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// self·c for a parameter c.
    fn scale(&self, c: &R) -> Self;
    /// self + c for a parameter c.
    fn shift(&self, c: &R) -> Self;
    /// |self|.
    fn abs(&self) -> Self;
    /// The signed power |self|^(q−1)·self.
    fn spow(&self, q: &R) -> Self;
    /// |self|^q.
    fn apow(&self, q: &R) -> Self;
}

impl<R: Real> Scalar<R> for R {
    #[inline]
    fn scale(&self, c: &R) -> Self {
        self.clone() * c.clone()
    }
    #[inline]
    fn shift(&self, c: &R) -> Self {
        self.clone() + c.clone()
    }
    #[inline]
    fn abs(&self) -> Self {
        Real::abs(self)
    }
    #[inline]
    fn spow(&self, q: &R) -> Self {
        Real::spow(self, q)
    }
    #[inline]
    fn apow(&self, q: &R) -> Self {
        Real::apow(self, q)
    }
}
