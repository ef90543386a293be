//! Where a target error falls among measured errors, and the steps or times there, by linear
//! interpolation of logarithms (errors and times of a run follow powers of N).

/// The position of `target` among decreasing `errors`: (i, s) with
/// ln target = (1 − s) ln e_i + s ln e_{i+1}, 0 ≤ s ≤ 1.
pub(super) fn bracket(errors: &[f64], target: f64) -> Option<(usize, f64)> {
    let t = target.ln();
    errors.windows(2).enumerate().find_map(|(i, w)| {
        let (a, b) = (w[0].ln(), w[1].ln());
        (a > b && a >= t && t >= b).then(|| (i, (a - t) / (a - b)))
    })
}

/// exp((1 − s) ln a + s ln b).
pub(super) fn between(a: f64, b: f64, s: f64) -> f64 {
    (a.ln() + s * (b.ln() - a.ln())).exp()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bracket_and_interpolation_recover_a_power_law() {
        // e = 100 N⁻², so e = 10⁻² at N = 100 exactly, between the tabulated N = 50 and 200.
        let n = [25.0, 50.0, 200.0, 400.0];
        let errors: Vec<f64> = n.iter().map(|n: &f64| 100.0 / (n * n)).collect();
        let (i, s) = bracket(&errors, 1e-2).unwrap();
        assert_eq!(i, 1);
        assert!((s - 0.5).abs() < 1e-12);
        assert!((between(n[i], n[i + 1], s) - 100.0).abs() < 1e-9);
        // Time proportional to N: 3 µs per step gives 0.3 ms at N = 100.
        assert!((between(3e-6 * 50.0, 3e-6 * 200.0, s) - 3e-4).abs() < 1e-15);
        assert_eq!(bracket(&errors, 1.0), None);
        assert_eq!(bracket(&errors, 1e-4), None);
    }
}
