//! The pieces a line is drawn in: one piece per stretch of finite points, and for an angle written
//! wrapped to (−π, π] a new piece where it wraps.
//!
//! A wrapped angle that moves by δ between two samples, |δ| < π, is written either δ apart (no wrap)
//! or δ ∓ 2π apart (a wrap), so consecutive values more than π apart mark a wrap. Joining them would
//! draw a vertical line across the panel that the angle never travelled; instead the piece before
//! the wrap is continued to the boundary ±π it crosses and the next piece starts at the opposite
//! boundary, at the time the crossing is interpolated at.

use std::f64::consts::{PI, TAU};

/// The pieces of the line through `points`, in order. Non-finite points are skipped; with `wrapped`,
/// the values are angles in (−π, π] and the line is broken where they wrap.
pub fn segments(points: &[(f64, f64)], wrapped: bool) -> Vec<Vec<(f64, f64)>> {
    let mut pieces: Vec<Vec<(f64, f64)>> = vec![];
    let mut current: Vec<(f64, f64)> = vec![];
    for &(t, y) in points.iter().filter(|(t, y)| t.is_finite() && y.is_finite()) {
        if let Some(&(t0, y0)) = current.last() {
            if wrapped && (y - y0).abs() > PI {
                // The value continued past the boundary: y0 + δ with |δ| < π.
                let continued = if y < y0 { y + TAU } else { y - TAU };
                let boundary = if continued > y0 { PI } else { -PI };
                let fraction = ((boundary - y0) / (continued - y0)).clamp(0.0, 1.0);
                let crossing = t0 + fraction * (t - t0);
                current.push((crossing, boundary));
                pieces.push(std::mem::take(&mut current));
                current.push((crossing, -boundary));
            }
        }
        current.push((t, y));
    }
    if !current.is_empty() {
        pieces.push(current);
    }
    pieces
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_without_wraps_is_one_piece() {
        let points = vec![(0.0, 3.0), (1.0, 3.1), (2.0, 3.0)];
        assert_eq!(segments(&points, true), vec![points.clone()]);
        assert_eq!(segments(&points, false), vec![points]);
    }

    #[test]
    fn an_increasing_angle_is_broken_at_pi_and_continues_from_minus_pi() {
        // 3.0 → 3.0 + 0.4 = 3.4, written 3.4 − 2π; it crosses π at a fraction (π − 3)/0.4 of the step.
        let after = 3.4 - TAU;
        let pieces = segments(&[(0.0, 3.0), (1.0, after)], true);
        assert_eq!(pieces.len(), 2);
        let crossing = (PI - 3.0) / 0.4;
        assert_eq!(pieces[0][0], (0.0, 3.0));
        assert!((pieces[0][1].0 - crossing).abs() < 1e-12 && pieces[0][1].1 == PI);
        assert!((pieces[1][0].0 - crossing).abs() < 1e-12 && pieces[1][0].1 == -PI);
        assert_eq!(pieces[1][1], (1.0, after));
    }

    #[test]
    fn a_decreasing_angle_is_broken_at_minus_pi() {
        let pieces = segments(&[(0.0, -3.0), (1.0, 3.0)], true);
        assert_eq!(pieces.len(), 2);
        assert_eq!(pieces[0].last().unwrap().1, -PI);
        assert_eq!(pieces[1][0].1, PI);
        assert!(pieces.iter().flatten().all(|p| p.1.abs() <= PI));
    }

    #[test]
    fn real_values_are_never_broken_and_non_finite_points_are_skipped() {
        let points = [(0.0, -3.0), (1.0, f64::NAN), (2.0, 3.0)];
        assert_eq!(segments(&points, false), vec![vec![(0.0, -3.0), (2.0, 3.0)]]);
        assert!(segments(&[], true).is_empty());
    }
}
