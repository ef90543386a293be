//! The test of a rigid system's declared symmetry: ℓ(g R, Ω, s, ṡ) = ℓ(R, Ω, s, ṡ) for rotations g of
//! the declared group, at attitudes and velocities spread around the initial data.

use super::so3::{self, Matrix3};
use super::system::{RigidSystem, Symmetry};
use crate::{Error, Hypothesis};

/// The largest relative change of ℓ under the declared rotations that passes.
pub const INVARIANCE_TOLERANCE: f64 = 1e-9;

/// Sample points of the test.
const SAMPLES: usize = 24;

/// A reproducible sequence of numbers in [−1, 1) (SplitMix64).
struct Draws(u64);

impl Draws {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    fn vector(&mut self, size: f64) -> [f64; 3] {
        [0; 3].map(|_| size * self.next())
    }
}

/// The largest relative change of ℓ over the samples under rotations of `symmetry`; refuses with
/// [`Error::NotInvariantUnderRotations`] above [`INVARIANCE_TOLERANCE`], and with [`Error::Undecided`]
/// when ℓ is finite at fewer than half the samples. Nothing to test for [`Symmetry::None`].
pub fn test_symmetry<S: RigidSystem>(
    system: &S,
    r0: &Matrix3<f64>,
    omega0: &[f64; 3],
    s0: &[f64],
    v0: &[f64],
) -> Result<f64, Error> {
    let symmetry = system.symmetry();
    if symmetry == Symmetry::None {
        return Ok(0.0);
    }
    let mut draws = Draws(0x5EED_0FD1_AC00);
    let speed = omega0.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    let (mut worst, mut scale, mut finite) = (0.0f64, 0.0f64, 0);
    for _ in 0..SAMPLES {
        // Attitudes anywhere on SO(3) (Cayley vectors up to length 4: angles up to 2.2 rad from R0).
        let r = so3::mul(r0, &so3::cayley(&draws.vector(4.0)));
        let omega: [f64; 3] = [0, 1, 2].map(|i| omega0[i] + speed * draws.next());
        let s: Vec<f64> = s0.iter().map(|&x| x + 0.5 * draws.next()).collect();
        let v: Vec<f64> = v0.iter().map(|&x| x + (1.0 + x.abs()) * draws.next()).collect();
        let g = match symmetry {
            Symmetry::Vertical => so3::cayley(&[0.0, 0.0, 4.0 * draws.next()]),
            _ => so3::cayley(&draws.vector(4.0)),
        };
        let l = system.lagrangian(&r, &omega, &s, &v);
        let moved = system.lagrangian(&so3::mul(&g, &r), &omega, &s, &v);
        if !(l.is_finite() && moved.is_finite()) {
            continue;
        }
        finite += 1;
        worst = worst.max((moved - l).abs());
        scale = scale.max(l.abs()).max(moved.abs());
    }
    if finite < SAMPLES / 2 {
        return Err(Error::Undecided {
            hypothesis: Hypothesis::Invariance,
            coordinate: symmetry.name().into(),
            samples: finite,
            wanted: SAMPLES,
        });
    }
    let deviation = if scale > 0.0 { worst / scale } else { worst };
    if deviation > INVARIANCE_TOLERANCE {
        return Err(Error::NotInvariantUnderRotations {
            symmetry: symmetry.name(),
            deviation,
            tolerance: INVARIANCE_TOLERANCE,
        });
    }
    Ok(deviation)
}
