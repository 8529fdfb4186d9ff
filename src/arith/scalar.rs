//! The number trait the models are written against.
//!
//! A [`Scalar<R>`] is anything the vector fields, forces and Lyapunov functions can be evaluated
//! on, with parameters of type `R`: the coefficient field itself (f64, intervals), truncated
//! Taylor series of it, dual numbers, and the recording type of the rigorous engine's tape.
//! Each model is written once, generic over `T: Scalar<R>`.

use super::real::Exponent;
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
    /// (|self|^(q−1)·self, |self|^q): the same values as `spow` and `apow`, computed together
    /// where that is cheaper (one power for `f64`).
    fn spow_apow(&self, q: &R) -> (Self, Self) {
        (self.spow(q), self.apow(q))
    }
    /// (|self|^(q−1)·self, |self|^(q−1)) for q > 1.
    fn spow_base(&self, q: &R) -> (Self, Self) {
        (self.spow(q), self.apow(&(q.clone() - R::one())))
    }
    /// `spow` with a prepared [`Exponent`] (the models' right-hand sides): the value of
    /// `spow(q.value())`, except for `f64`, which reads q's tables (a few ulps).
    fn spow_prepared(&self, q: &Exponent<R>) -> Self {
        self.spow(q.value())
    }
    /// `spow_apow` with a prepared [`Exponent`] (as [`Scalar::spow_prepared`]).
    fn spow_apow_prepared(&self, q: &Exponent<R>) -> (Self, Self) {
        self.spow_apow(q.value())
    }
    /// `spow_base` with a prepared [`Exponent`] (as [`Scalar::spow_prepared`]).
    fn spow_base_prepared(&self, q: &Exponent<R>) -> (Self, Self) {
        self.spow_base(q.value())
    }
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
    #[inline]
    fn spow_apow(&self, q: &R) -> (Self, Self) {
        Real::spow_apow(self, q)
    }
    #[inline]
    fn spow_base(&self, q: &R) -> (Self, Self) {
        Real::spow_base(self, q)
    }
    #[inline(always)]
    fn spow_prepared(&self, q: &Exponent<R>) -> Self {
        Real::spow_prepared(self, q)
    }
    #[inline(always)]
    fn spow_apow_prepared(&self, q: &Exponent<R>) -> (Self, Self) {
        Real::spow_apow_prepared(self, q)
    }
    #[inline(always)]
    fn spow_base_prepared(&self, q: &Exponent<R>) -> (Self, Self) {
        Real::spow_base_prepared(self, q)
    }
}
