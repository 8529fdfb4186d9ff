//! The tape with its chains of linear operations fused into one form each
//! ([`crate::engines::taylor::linear`]), and the value of a form, rounded as the tape says.

use super::merges::lin_merges;
use super::shortcuts::NO_SIGN;
use super::{Rounding, Tape};
use crate::arith::{Dot, Real};
use crate::engines::taylor::linear::fuse;
use std::borrow::Borrow;

impl<R: Real, const N: usize> Tape<R, N> {
    /// The same function with its chains of linear operations fused into one form each
    /// ([`crate::engines::taylor::linear`]), rounded as `rounding` says: fewer operations per
    /// Taylor order. Measured on an order-16 jet of SHC DSS over varying boxes (interleaved, one
    /// thread): 6.6 µs as recorded, 6.0 µs fused with [`Rounding::Each`], 5.6 µs with
    /// [`Rounding::Once`]; on duals of order 3, 4.1 → 3.6 µs with `Once`. Which tape the engine
    /// rounds how: [`crate::engines::taylor::step::Tapes::of`].
    ///
    /// A tape that is fused already is only given the new rounding.
    pub fn fused(&self, rounding: Rounding) -> Self {
        if !self.lins.is_empty() {
            let mut t = self.clone();
            t.rounding = rounding;
            return t;
        }
        let mut consts = self.consts.clone();
        let f = fuse(&self.ops, &mut consts, &self.tconst, &self.outputs);
        let keep = |i: usize| f.map[i].is_some();
        let mut t = Self {
            ops: f.ops,
            consts,
            outputs: self
                .outputs
                .iter()
                .map(|&o| f.map[o].expect("an output is computed"))
                .collect(),
            switching: self.switching.clone(),
            kinks: self.kinks.clone(),
            log_lead: (0..self.ops.len())
                .filter(|&i| keep(i))
                .map(|i| self.log_lead[i].map(|l| f.map[l].expect("a power is computed")))
                .collect(),
            integral_of: (0..self.ops.len())
                .filter(|&i| keep(i))
                .map(|i| self.integral_of[i].map(|m| f.map[m].expect("a product is computed")))
                .collect(),
            sign_copy_of: (0..self.ops.len())
                .filter(|&i| keep(i))
                .map(|i| {
                    let (m, g) = self.sign_copy_of[i]?;
                    let node = |n: usize| {
                        if n == NO_SIGN {
                            Some(NO_SIGN)
                        } else {
                            f.map[n]
                        }
                    };
                    Some((f.map[m]?, [node(g[0])?, node(g[1])?]))
                })
                .collect(),
            tconst: (0..self.ops.len())
                .filter(|&i| keep(i))
                .map(|i| self.tconst[i])
                .collect(),
            lin_merges: Vec::new(),
            mergeable: (0..self.ops.len())
                .filter(|&i| keep(i))
                .map(|i| self.mergeable[i])
                .collect(),
            params: self.params.clone(),
            lins: f.lins,
            rounding,
            extra_needed: std::sync::OnceLock::new(),
            second_order: self.second_order,
        };
        t.lin_merges = lin_merges(&t.lins, &t.sign_copy_of, &t.mergeable);
        t
    }

    /// The value of the fused form `l` from its leaves' values `v`: c₀ + Σ cⱼ·v(nⱼ) as one sum
    /// of products (`shift`: with c₀, at order 0; a coefficient of order ≥ 1 is Σ cⱼ·v(nⱼ)).
    #[inline]
    pub(super) fn lin_value<'a>(&self, l: usize, v: impl Fn(usize) -> &'a R, shift: bool) -> R
    where
        R: 'a,
    {
        let terms = self.lins[l]
            .terms
            .iter()
            .map(|&(c, n)| (&self.consts[c], n));
        self.form_sum(l, terms, v, shift)
    }

    /// c₀ + Σ cⱼ·v(nⱼ) over the (constant, leaf) `terms` of form `l` (`shift`: with its c₀),
    /// rounded as the tape says ([`Rounding`]): each product and sum in turn, or one sum of
    /// products.
    #[inline]
    pub(super) fn form_sum<'a, C: Borrow<R>>(
        &self,
        l: usize,
        terms: impl Iterator<Item = (C, usize)>,
        v: impl Fn(usize) -> &'a R,
        shift: bool,
    ) -> R
    where
        R: 'a,
    {
        let lin = &self.lins[l];
        if self.rounding == Rounding::Each {
            let mut acc: Option<R> = None;
            for (c, n) in terms {
                let p = v(n).mul_constant(c.borrow());
                acc = Some(match acc {
                    Some(a) => a + p,
                    None => p,
                });
            }
            let acc = acc.unwrap_or_else(R::zero);
            return match lin.shift {
                Some(c) if shift => acc + self.consts[c].clone(),
                _ => acc,
            };
        }
        let mut d = <R::Dot as Dot<R>>::new();
        for (c, n) in terms {
            d.add_scaled(c.borrow(), v(n));
        }
        if shift && let Some(c) = lin.shift {
            d.add_scaled(&self.consts[c], &R::one());
        }
        d.sum()
    }
}
