//! One discrete Lagrangian on the whole configuration manifold, glued from an atlas's charts (paper §6).
//!
//! Each chart c has its own discrete Lagrangian L_d^c, the rule applied to L ∘ Tφ_c in c's
//! coordinates. Where two charts overlap these are different functions of the same two points, whose
//! methods conserve different modified energies: a run that moved from one chart to the other at a
//! step moved the level of its modified energy by O(h³) at each switch, by an amount that depends on
//! where the steps happen to fall, and its error was irregular in h (BENCHMARKS.md, "The atlas's
//! error in h"). Glued by a partition of unity {w_c},
//!
//! ```text
//! L_d(x0, x1) = Σ_c ½ (w_c(x0) + w_c(x1)) · L_d^c(ψ_c x0, ψ_c x1),
//! ```
//!
//! they are one discrete Lagrangian on Q × Q: consistent to the rule's order (each L_d^c is, and the
//! weights sum to one), symmetric where the rule is (midpoint, trapezoid; the composition of order 4
//! keeps its order, while the error of orders 6 and 8 holds high derivatives of the weights, which
//! change over a few steps, and at the steps those orders are used for is far from its asymptotic
//! size, also with smoother weights: BENCHMARKS.md, "The double spherical pendulum's race after
//! gluing"; those orders switch charts at a step instead, [`crate::atlas::glues`]), and the same function in whichever chart it is evaluated. A run's map is then one
//! symplectic map whatever chart a step is solved in, and a chart switch (the cotangent lift) changes
//! the coordinates and nothing else.
//!
//! The partition comes from the charts' measures ([`crate::System::chart_quality`]): σ rises from 0 at
//! measure [`BLEND_FROM`] to 1 at [`BLEND_TO`] ([`rise`], four times continuously differentiable), and the
//! charts take priority in their order, the main chart first: w_c ∝ σ_c Π_{j<c} (1 − σ_j) over the
//! charts whose domain holds the point, normalized by their sum (1 − Π_j (1 − σ_j)). Where the main
//! chart's measure is at least `BLEND_TO` it alone counts (a system whose charts give no measure stays
//! in its main chart); where one chart alone counts at both ends of a step, L_d is that chart's, and a
//! run takes the step with the chart's own scheme (compiled, reduced where it has group coordinates).
//! Only steps with an end where charts overlap evaluate the glued function, with dual numbers. The glued
//! discrete Lagrangian itself is that of [`crate::atlas::InChart`] in a glued run, in [`crate::atlas`].

use crate::Scalar;

/// The measure of a chart below which it has no weight (0.3: 17.5° from a pole of spherical
/// coordinates, whose measure is |sin θ|).
pub const BLEND_FROM: f64 = 0.3;

/// The measure of a chart from which it has full weight before the charts after it (0.9: 64° from a
/// pole). Overlaps this wide are crossed in many steps, so that the weights vary slowly on the scale of
/// a step and the error stays regular in h for the compositions too.
pub const BLEND_TO: f64 = 0.9;

/// σ(measure): 0 up to [`BLEND_FROM`], 1 from [`BLEND_TO`], and in between the polynomial of degree 9
/// in t = (measure − BLEND_FROM)/(BLEND_TO − BLEND_FROM) whose first four derivatives vanish at both
/// ends, t⁵(126 − 420t + 540t² − 315t³ + 70t⁴).
///
/// Measured on a spherical pendulum going over the top (BENCHMARKS.md, "The atlas's error in h"): a
/// step with fewer continuous derivatives (10t³ − 15t⁴ + 6t⁵) keeps the basic method's error regular
/// in h but not that of the compositions of order 4, whose error terms hold higher derivatives of the
/// weights; exp(−1/t)/(exp(−1/t) + exp(−1/(1 − t))), infinitely differentiable, has larger
/// derivatives and is less regular at the steps tried.
///
/// ```
/// use ddirac::blend::{rise, BLEND_FROM, BLEND_TO};
/// assert_eq!(rise(BLEND_FROM), 0.0);
/// assert_eq!(rise(BLEND_TO), 1.0);
/// assert!((rise(0.5 * (BLEND_FROM + BLEND_TO)) - 0.5).abs() < 1e-15);
/// ```
pub fn rise<D: Scalar>(measure: D) -> D {
    let t = (measure - BLEND_FROM) * (BLEND_TO - BLEND_FROM).recip();
    if t.re() <= 0.0 {
        D::zero()
    } else if t.re() >= 1.0 {
        D::one()
    } else {
        let t2 = t * t;
        t2 * t2 * t * ((((t * 70.0 - 315.0) * t + 540.0) * t - 420.0) * t + 126.0)
    }
}

/// The weights w_c ∝ σ_c Π_{j<c} (1 − σ_j) of the charts given with their σ in order, those that are
/// not zero, normalized by their sum. (The sum is 1 − Π_c (1 − σ_c), but written so it would round to
/// zero where every σ is below the rounding of 1, and a lone chart's weight would be infinite.)
pub(crate) fn partition<D: Scalar>(rises: impl Iterator<Item = (usize, D)>) -> Vec<(usize, D)> {
    let mut rest = D::one();
    let mut total = D::zero();
    let mut raw = Vec::new();
    for (chart, sigma) in rises {
        if rest.re() == 0.0 {
            break;
        }
        if sigma.re() > 0.0 {
            let weight = rest * sigma;
            total += weight;
            raw.push((chart, weight));
            rest *= -sigma + 1.0;
        }
    }
    raw.into_iter().map(|(chart, w)| (chart, w / total)).collect()
}

/// The chart that alone has weight in [`partition`] of the same σ, if one does, without allocating:
/// the one chart with σ > 0 up to the first whose σ is one.
pub(crate) fn sole(rises: impl Iterator<Item = (usize, f64)>) -> Option<usize> {
    let mut found = None;
    for (chart, sigma) in rises {
        if sigma <= 0.0 {
            continue;
        }
        if found.is_some() {
            return None;
        }
        found = Some(chart);
        if sigma >= 1.0 {
            break;
        }
    }
    found
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// `sole` names a chart exactly where `partition` gives one chart all the weight.
        #[test]
        fn sole_agrees_with_the_partition(sigmas in prop::collection::vec(
            prop_oneof![Just(0.0), Just(1.0), 0.0..1.0f64], 0..6)) {
            let rises = || sigmas.iter().copied().enumerate();
            let weights = partition(rises());
            let expected = match weights.as_slice() {
                [(chart, _)] => Some(*chart),
                _ => None,
            };
            prop_assert_eq!(sole(rises()), expected);
        }

        /// The weights are finite, positive and sum to one, however small the σ (down to the
        /// smallest normal numbers, where 1 − Π (1 − σ) rounds to zero).
        #[test]
        fn the_weights_sum_to_one_for_any_rises(sigmas in prop::collection::vec(
            prop_oneof![Just(0.0), Just(1.0), 0.0..1.0f64, (-300.0..-1.0f64).prop_map(|e| 10f64.powf(e))], 1..6)) {
            let weights = partition(sigmas.iter().copied().enumerate());
            if sigmas.iter().any(|&s| s > 0.0) {
                let total: f64 = weights.iter().map(|(_, w)| w).sum();
                prop_assert!((total - 1.0).abs() < 1e-14, "{sigmas:?} → {weights:?}");
                prop_assert!(weights.iter().all(|(_, w)| w.is_finite() && *w > 0.0), "{sigmas:?} → {weights:?}");
            } else {
                prop_assert!(weights.is_empty());
            }
        }
    }

    /// A chart alone, its σ below the rounding of 1 (its measure 2.3e-5 above 0.3, where σ rises from 0):
    /// its weight is 1, not 1e-20 / (1 − (1 − 1e-20)) = 1e-20 / 0.
    #[test]
    fn a_lone_chart_of_tiny_rise_has_weight_one() {
        assert_eq!(partition([(2, 1e-20)].into_iter()), vec![(2, 1.0)]);
        // Two such charts share the weight as their raw weights 1e-20 and (1 − 1e-20) 3e-20 do.
        let shared = partition([(0, 1e-20), (1, 3e-20)].into_iter());
        assert_eq!(shared.len(), 2);
        assert!((shared[0].1 - 0.25).abs() < 1e-15 && (shared[1].1 - 0.75).abs() < 1e-15, "{shared:?}");
    }
}
