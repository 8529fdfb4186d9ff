//! A product and its sign copy in one fused form taken as one term (c + s·c′)·P: the pairs
//! ([`lin_merges`]) and a form's value with them.

use super::Tape;
use crate::arith::Real;
use crate::engines::taylor::linear::Lin;
use std::borrow::Cow;

impl<R: Real, const N: usize> Tape<R, N> {
    /// The same tape with every fused form's terms summed one by one (no [`lin_merges`]).
    #[cfg(test)]
    pub(crate) fn without_merges(&self) -> Self {
        let mut t = self.clone();
        t.lin_merges = vec![Vec::new(); t.lins.len()];
        t
    }

    /// How many term pairs the fused forms merge ([`lin_merges`]).
    #[cfg(test)]
    pub(crate) fn merges(&self) -> usize {
        self.lin_merges.iter().map(Vec::len).sum()
    }

    /// [`Tape::lin_value`] of a form with sign-copy pairs ([`lin_merges`]), in a jet whose
    /// copies' signs are `sign` (set at order 0): each pair (j, j′) is the one term
    /// (c_j + s·c_j′)·x_{n_j}, s = ±1 the sign with which x_{n_j′} = s·x_{n_j}, and the
    /// constants' sum is enclosed in the type's arithmetic. For the true values
    /// c_j·x + c_j′·(s·x) = (c_j + s·c_j′)·x, so the term encloses the pair's sum; what it
    /// spares is the dependency: with β ≈ −γ (every Table 1 set: |β + γ| ≈ 0.01 against
    /// |β| ≈ 0.4–1.4) the two terms nearly cancel, and an interval sum of them is about
    /// (|β| + |γ|)/|β + γ| ≈ 100 times wider than their value's range — a width that the
    /// recurrences compound order by order over a wide box.
    pub(super) fn merged_lin_value<'a>(
        &self,
        l: usize,
        v: impl Fn(usize) -> &'a R,
        shift: bool,
        sign: &[i8],
    ) -> R
    where
        R: 'a,
    {
        let lin = &self.lins[l];
        let merges = &self.lin_merges[l];
        // (constant, leaf) of each term left: a pair's first term with the summed constant
        let terms = lin.terms.iter().enumerate().filter_map(|(j, &(c, n))| {
            if merges.iter().any(|&(_, b)| b == j) {
                return None;
            }
            let c = &self.consts[c];
            Some(match merges.iter().find(|&&(a, _)| a == j) {
                Some(&(_, b)) => {
                    let (cb, m) = lin.terms[b];
                    let cb = self.consts[cb].clone();
                    let merged = if sign[m] < 0 {
                        c.clone() - cb
                    } else {
                        c.clone() + cb
                    };
                    (Cow::Owned(merged), n)
                }
                None => (Cow::Borrowed(c), n),
            })
        });
        self.form_sum(l, terms, v, shift)
    }
}

/// Per fused form: the pairs (j, j′) of its terms whose leaves are a product and a sign copy of it
/// ([`super::shortcuts::sign_copies`]: x_{n_j′} = ±x_{n_j} in every jet), each term in at most one
/// pair.
pub(super) fn lin_merges(
    lins: &[Lin],
    sign_copy_of: &[Option<(usize, [usize; 2])>],
    mergeable: &[bool],
) -> Vec<Vec<(usize, usize)>> {
    lins.iter()
        .map(|lin| {
            let mut pairs: Vec<(usize, usize)> = Vec::new();
            for (b, &(_, m)) in lin.terms.iter().enumerate() {
                let Some((base, _)) = sign_copy_of.get(m).copied().flatten() else {
                    continue;
                };
                if !mergeable.get(m).copied().unwrap_or(false) {
                    continue;
                }
                let used = |j: usize| pairs.iter().any(|&(x, y)| x == j || y == j);
                if let Some(a) = (0..lin.terms.len())
                    .find(|&a| a != b && lin.terms[a].1 == base && !used(a) && !used(b))
                {
                    pairs.push((a, b));
                }
            }
            pairs
        })
        .collect()
}
