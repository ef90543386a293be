//! Composition methods: a step of size h taken as s sub-steps γ₁h, …, γₛh of a symmetric basic
//! method of order 2 (Hairer, Lubich & Wanner, *Geometric Numerical Integration*, 2nd ed., §II.4 and
//! §V.3). With Σγᵢ = 1 and symmetric coefficients (γᵢ = γₛ₊₁₋ᵢ) the composed map is symmetric, and
//! its order is that of the coefficient set. Each sub-step is a step of the same scheme, so the
//! composed map is symplectic, conserves the momentum map exactly, and the reduced composed map is the
//! reduction of the unreduced one.
//!
//! The basic methods that are symmetric are the midpoint and trapezoid rules, in both variants: the
//! left and right rules are each other's adjoints, and a composition of either alone has order 1.
//!
//! Coefficient sets:
//!
//! | name | order | stages | source |
//! |---|---|---|---|
//! | `triple-jump` | 4, 6, 8 | 3, 9, 27 | Yoshida 1990, Suzuki 1990; HLW II.4, eq. (4.4), applied recursively |
//! | `suzuki` | 4 | 5 | Suzuki 1990; HLW II.4, eq. (4.5) |
//! | `kahan-li` | 6 | 9 | Kahan & Li 1997, s9odr6a; HLW V.3, eq. (3.11) |
//! | `kahan-li` | 8 | 17 | Kahan & Li 1997, s17odr8a; HLW V.3, eq. (3.12) |

use std::fmt;

/// How a step is composed of sub-steps of the basic method (of order 2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Composition {
    /// One sub-step: the basic method itself, order 2.
    #[default]
    Basic,
    /// The triple jump γ₁ = γ₃ = 1/(2 − 2^{1/(p+1)}), γ₂ = 1 − 2γ₁, raising order p to p + 2, applied
    /// recursively to reach `order` (4, 6 or 8: 3, 9 or 27 sub-steps).
    TripleJump {
        /// 4, 6 or 8.
        order: u8,
    },
    /// Suzuki's 5-stage fourth-order set: γ₁ = γ₂ = γ₄ = γ₅ = 1/(4 − 4^{1/3}), γ₃ = 1 − 4γ₁.
    Suzuki5,
    /// Kahan and Li's optimised 9-stage sixth-order set.
    KahanLi9,
    /// Kahan and Li's optimised 17-stage eighth-order set.
    KahanLi17,
}

/// Kahan & Li (1997), s9odr6a, as printed in HLW V.3, eq. (3.11): γ₁ … γ₅ (γ₆ … γ₉ mirror them).
#[allow(clippy::excessive_precision)] // the digits as published
const KAHAN_LI_9: [f64; 5] = [
    0.392_161_444_007_314_139_279_250_56,
    0.332_599_136_789_359_438_599_748_64,
    -0.706_246_172_557_639_359_809_964_82,
    0.082_213_596_293_550_800_231_490_45,
    0.798_543_990_934_829_963_398_950_35,
];

/// Kahan & Li (1997), s17odr8a, as printed in HLW V.3, eq. (3.12): γ₁ … γ₉ (γ₁₀ … γ₁₇ mirror them).
#[allow(clippy::excessive_precision)] // the digits as published
const KAHAN_LI_17: [f64; 9] = [
    0.130_202_483_088_890_080_878_817_63,
    0.561_162_981_775_108_384_561_964_41,
    -0.389_474_962_644_847_286_408_078_60,
    0.158_841_906_555_155_600_896_210_75,
    -0.395_903_894_133_237_577_336_231_54,
    0.184_539_640_978_315_707_091_832_54,
    0.258_374_387_686_322_047_293_979_11,
    0.295_011_723_609_310_298_870_966_24,
    -0.605_508_533_830_034_511_698_921_08,
];

/// The orders a composition reaches.
pub const ORDERS: [u8; 4] = [2, 4, 6, 8];

impl Composition {
    /// The recommended set of an order: the basic method for 2, Suzuki's 5 stages for 4, Kahan–Li's
    /// 9 stages for 6 and 17 stages for 8 (the optimised sets have smaller error constants than the
    /// triple jumps of the same order). `None` for another order.
    pub fn for_order(order: u8) -> Option<Self> {
        match order {
            2 => Some(Self::Basic),
            4 => Some(Self::Suzuki5),
            6 => Some(Self::KahanLi9),
            8 => Some(Self::KahanLi17),
            _ => None,
        }
    }

    /// The set named `name` (`triple-jump`, `suzuki`, `kahan-li`, or `basic` for order 2) of order
    /// `order`; an error naming the sets that exist when there is none.
    pub fn named(name: &str, order: u8) -> Result<Self, String> {
        let found = match (name, order) {
            ("basic", 2) => Some(Self::Basic),
            ("triple-jump", 4 | 6 | 8) => Some(Self::TripleJump { order }),
            ("suzuki", 4) => Some(Self::Suzuki5),
            ("kahan-li", 6) => Some(Self::KahanLi9),
            ("kahan-li", 8) => Some(Self::KahanLi17),
            _ => None,
        };
        found.ok_or_else(|| {
            let sets = match order {
                2 => "`basic`",
                4 => "`suzuki` (the default) or `triple-jump`",
                6 | 8 => "`kahan-li` (the default) or `triple-jump`",
                _ => return format!("there is no composition of order {order} (orders are 2, 4, 6 and 8)"),
            };
            format!("there is no composition `{name}` of order {order}; order {order} has {sets}")
        })
    }

    /// The set the method keys `order` and `composition` select: the recommended set of the order
    /// when no name is given, the named set of the order, or for a name without order the set's only
    /// order (`suzuki`: 4; `basic`: 2). An error says what is missing or which sets exist.
    pub fn select(order: Option<u8>, name: Option<&str>) -> Result<Self, String> {
        match (name, order) {
            (None, order) => {
                let order = order.unwrap_or(2);
                Self::for_order(order).ok_or_else(|| format!("there is no method of order {order} (orders are 2, 4, 6 and 8)"))
            }
            (Some(name), Some(order)) => Self::named(name, order),
            (Some("suzuki"), None) => Ok(Self::Suzuki5),
            (Some("basic"), None) => Ok(Self::Basic),
            (Some(name @ ("kahan-li" | "triple-jump")), None) => Err(format!(
                "the composition `{name}` has several orders: give the order too (`kahan-li`: 6 or 8; `triple-jump`: 4, 6 or 8)"
            )),
            (Some(other), None) => Err(format!(
                "unknown composition `{other}`: the compositions are `suzuki` (order 4), `kahan-li` (orders 6, 8) and \
                 `triple-jump` (orders 4, 6, 8)"
            )),
        }
    }

    /// The order of the composed method.
    pub fn order(self) -> u8 {
        match self {
            Self::Basic => 2,
            Self::TripleJump { order } => order,
            Self::Suzuki5 => 4,
            Self::KahanLi9 => 6,
            Self::KahanLi17 => 8,
        }
    }

    /// The set's name in specs.
    pub fn name(self) -> &'static str {
        match self {
            Self::Basic => "basic",
            Self::TripleJump { .. } => "triple-jump",
            Self::Suzuki5 => "suzuki",
            Self::KahanLi9 | Self::KahanLi17 => "kahan-li",
        }
    }

    /// Whether a step is one step of the basic method.
    pub fn is_basic(self) -> bool {
        self == Self::Basic
    }

    /// The sub-step fractions γ₁, …, γₛ (Σγᵢ = 1, γᵢ = γₛ₊₁₋ᵢ), in the order they are taken.
    pub fn coefficients(self) -> Vec<f64> {
        match self {
            Self::Basic => vec![1.0],
            Self::TripleJump { order } => triple_jump(order),
            Self::Suzuki5 => {
                let g = 1.0 / (4.0 - 4f64.cbrt());
                vec![g, g, 1.0 - 4.0 * g, g, g]
            }
            Self::KahanLi9 => mirrored(&KAHAN_LI_9),
            Self::KahanLi17 => mirrored(&KAHAN_LI_17),
        }
    }
}

impl fmt::Display for Composition {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} (order {}, {} stages)", self.name(), self.order(), self.coefficients().len())
    }
}

/// The recursive triple jump reaching `order`: each level composes the previous method with
/// γ₁ = γ₃ = 1/(2 − 2^{1/(p+1)}) and γ₂ = −2^{1/(p+1)}/(2 − 2^{1/(p+1)}) for its order p.
fn triple_jump(order: u8) -> Vec<f64> {
    let mut gammas = vec![1.0];
    let mut p = 2;
    while p < order {
        let root = 2f64.powf(1.0 / f64::from(p + 1));
        let outer = 1.0 / (2.0 - root);
        let inner = -root / (2.0 - root);
        gammas = [outer, inner, outer].iter().flat_map(|&c| gammas.iter().map(move |g| c * g)).collect();
        p += 2;
    }
    gammas
}

/// γ₁, …, γₘ followed by γₘ₋₁, …, γ₁.
fn mirrored(half: &[f64]) -> Vec<f64> {
    half.iter().chain(half.iter().rev().skip(1)).copied().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALL: [Composition; 7] = [
        Composition::Basic,
        Composition::TripleJump { order: 4 },
        Composition::TripleJump { order: 6 },
        Composition::TripleJump { order: 8 },
        Composition::Suzuki5,
        Composition::KahanLi9,
        Composition::KahanLi17,
    ];

    /// Every set is consistent (Σγ = 1) and symmetric, with the number of stages of its table.
    #[test]
    fn coefficient_sets_sum_to_one_and_are_symmetric() {
        for (c, stages) in ALL.iter().zip([1, 3, 9, 27, 5, 9, 17]) {
            let g = c.coefficients();
            assert_eq!(g.len(), stages, "{c}");
            assert!((g.iter().sum::<f64>() - 1.0).abs() < 1e-14, "{c}: Σγ = {}", g.iter().sum::<f64>());
            assert!(g.iter().zip(g.iter().rev()).all(|(a, b)| a == b), "{c} is not symmetric");
        }
    }

    /// Necessary order conditions of a symmetric composition of a symmetric method of order 2 (HLW
    /// V.3.2): Σγᵢ^p = 0 for every odd p below the order (the other conditions are held by the observed
    /// orders of the integration tests).
    #[test]
    fn odd_power_sums_vanish_to_the_order() {
        for c in ALL {
            let g = c.coefficients();
            for power in (3..c.order()).step_by(2) {
                let sum = g.iter().map(|x| x.powi(i32::from(power))).sum::<f64>();
                let scale = g.iter().map(|x| x.abs().powi(i32::from(power))).sum::<f64>();
                assert!(sum.abs() < 1e-14 * scale, "{c}: Σγ^{power} = {sum:e} (Σ|γ|^{power} = {scale})");
            }
        }
    }

    /// Names and orders select the sets; unknown pairs name what exists.
    #[test]
    fn named_sets_and_refusals() {
        assert_eq!(Composition::named("kahan-li", 8), Ok(Composition::KahanLi17));
        assert_eq!(Composition::named("triple-jump", 6), Ok(Composition::TripleJump { order: 6 }));
        let refused = Composition::named("suzuki", 6).unwrap_err();
        assert!(refused.contains("`kahan-li`") && refused.contains("`triple-jump`"), "{refused}");
        assert!(Composition::named("suzuki", 5).unwrap_err().contains("orders are 2, 4, 6 and 8"));
        for order in ORDERS {
            assert_eq!(Composition::for_order(order).unwrap().order(), order);
            assert_eq!(Composition::select(Some(order), None), Ok(Composition::for_order(order).unwrap()));
        }
        assert_eq!(Composition::select(None, None), Ok(Composition::Basic));
        assert_eq!(Composition::select(None, Some("suzuki")), Ok(Composition::Suzuki5));
        assert!(Composition::select(None, Some("kahan-li")).unwrap_err().contains("give the order"));
        assert!(Composition::select(None, Some("yoshida")).unwrap_err().contains("unknown composition `yoshida`"));
        assert!(Composition::select(Some(3), None).unwrap_err().contains("order 3"));
    }
}
