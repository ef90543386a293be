//! Axis ranges and tick labels that stay short and distinct.
//!
//! A tick label shows as many digits as the spacing of the ticks needs and no more: `0`, `2.5`,
//! `-0.04`, and `3e-7` / `1.25e6` once the numbers are very small or very large.

/// The range an axis shows for data in `[lo, hi]`: a little wider than the data, never empty.
pub fn padded(lo: f64, hi: f64, fraction: f64) -> (f64, f64) {
    if !(lo.is_finite() && hi.is_finite()) {
        return (-1.0, 1.0);
    }
    let span = hi - lo;
    let magnitude = lo.abs().max(hi.abs());
    if span <= magnitude * 1e-12 {
        // A constant: centre it in a range that still has readable ticks.
        let half = if magnitude > 0.0 { magnitude * 1e-3 } else { 1.0 };
        return (lo - half, hi + half);
    }
    (lo - fraction * span, hi + fraction * span)
}

/// An offset worth subtracting from data in `[lo, hi]` so that the ticks do not all start with
/// the same long run of digits: `Some(c)` when the spread is tiny compared with the values.
/// `c` is rounded to the digit just above the spread, so that it reads short.
pub fn offset(lo: f64, hi: f64) -> Option<f64> {
    let centre = 0.5 * (lo + hi);
    let span = hi - lo;
    if !(centre.is_finite() && span.is_finite()) || centre == 0.0 || span > 1e-3 * centre.abs() {
        return None;
    }
    if span == 0.0 {
        return Some(centre);
    }
    let unit = 10f64.powf(span.log10().ceil());
    Some((centre / unit).round() * unit)
}

/// Ticks at the multiples of a step of 1, 2, 2.5 or 5 × 10^k in `[lo, hi]`: the most that do not
/// exceed `max`, and the minor ticks between them (a fifth of the step).
pub fn nice(lo: f64, hi: f64, max: usize) -> (Vec<f64>, Vec<f64>) {
    let span = hi - lo;
    if !(span.is_finite() && span > 0.0) || max < 2 {
        return (vec![lo], vec![]);
    }
    let mut power = 10f64.powf((span / max as f64).log10().floor());
    loop {
        for mantissa in [1.0, 2.0, 2.5, 5.0] {
            let step = mantissa * power;
            let (first, last) = ((lo / step).ceil(), (hi / step).floor());
            if last - first + 1.0 <= max as f64 {
                let major: Vec<f64> = (first as i64..=last as i64).map(|k| k as f64 * step).collect();
                let minor_step = step / 5.0;
                let (a, b) = ((lo / minor_step).ceil() as i64, (hi / minor_step).floor() as i64);
                let minor = (a..=b).map(|k| k as f64 * minor_step).collect();
                return (major, minor);
            }
        }
        power *= 10.0;
    }
}

/// Ticks of a logarithmic axis over `[lo, hi]` (0 < lo < hi): 1, 2 and 5 × 10^k when at most `max`
/// of them fit, else the powers of ten (every other, every third, … as needed); minor ticks at the
/// other multiples of each power of ten.
pub fn logarithmic(lo: f64, hi: f64, max: usize) -> (Vec<f64>, Vec<f64>) {
    if !(lo > 0.0 && hi > lo && hi.is_finite()) {
        return (vec![], vec![]);
    }
    let (first, last) = (lo.log10().floor() as i32 - 1, hi.log10().ceil() as i32);
    let within = |v: &f64| *v >= lo * (1.0 - 1e-12) && *v <= hi * (1.0 + 1e-12);
    let multiples = |mantissas: &[f64], every: i32| -> Vec<f64> {
        (first..=last)
            .filter(|d| d.rem_euclid(every) == 0)
            .flat_map(|d| mantissas.iter().map(move |m| m * 10f64.powi(d)))
            .filter(within)
            .collect()
    };
    let minor = multiples(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0], 1);
    for mantissas in [&[1.0, 2.0, 5.0][..], &[1.0, 3.0][..]] {
        let major = multiples(mantissas, 1);
        if major.len() <= max && major.len() >= 2 {
            return (major, minor);
        }
    }
    let every = (1..).find(|&e| multiples(&[1.0], e).len() <= max.max(1)).unwrap_or(1);
    (multiples(&[1.0], every), minor)
}

/// Formats tick values of an axis covering `[lo, hi]` with about `count` ticks.
#[derive(Debug, Clone, Copy)]
pub struct TickFormat {
    /// Decimals after the point (fixed) or of the mantissa (scientific).
    decimals: usize,
    scientific: bool,
}

impl TickFormat {
    /// The shortest format that writes every one of `ticks` exactly (to a millionth of their spacing).
    pub fn for_ticks(ticks: &[f64]) -> Self {
        let magnitude = ticks.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let step = ticks.windows(2).map(|w| (w[1] - w[0]).abs()).filter(|d| *d > 0.0).fold(f64::INFINITY, f64::min);
        if !(magnitude.is_finite() && magnitude > 0.0 && step.is_finite()) {
            return Self { decimals: 1, scientific: false };
        }
        let magnitude_exponent = magnitude.log10().floor();
        let step_exponent = step.log10().floor();
        let scientific = !(-3.0..5.0).contains(&magnitude_exponent);
        let first = if scientific {
            (magnitude_exponent - step_exponent).clamp(0.0, 12.0) as usize
        } else {
            (-step_exponent).clamp(0.0, 12.0) as usize
        };
        let exact = |format: &Self| {
            ticks.iter().all(|&v| format.format(v).parse::<f64>().is_ok_and(|back| (back - v).abs() <= 1e-6 * step))
        };
        (first..first + 3)
            .map(|decimals| Self { decimals, scientific })
            .find(exact)
            .unwrap_or(Self { decimals: first + 3, scientific })
    }

    /// The format for a logarithmic axis: powers of ten and their multiples, in few digits.
    pub fn logarithmic() -> Self {
        Self { decimals: usize::MAX, scientific: false }
    }

    /// The label of the tick at `value`.
    pub fn format(&self, value: f64) -> String {
        if self.decimals == usize::MAX {
            return short(value);
        }
        let text = if self.scientific {
            if value == 0.0 {
                "0".to_owned()
            } else {
                format!("{value:.*e}", self.decimals)
            }
        } else {
            format!("{value:.*}", self.decimals)
        };
        // Ticks on either side of 0 may round to "-0.00".
        if text.starts_with('-') && text[1..].chars().all(|c| c == '0' || c == '.') {
            text[1..].to_owned()
        } else {
            text
        }
    }
}

/// A short label for a single number: up to three significant digits, scientific when far from 1.
pub fn short(value: f64) -> String {
    if value == 0.0 || !value.is_finite() {
        return format!("{value}");
    }
    let exponent = value.abs().log10().floor();
    if (-3.0..5.0).contains(&exponent) {
        let decimals = (2.0 - exponent).max(0.0) as usize;
        let text = format!("{value:.decimals$}");
        if text.contains('.') {
            text.trim_end_matches('0').trim_end_matches('.').to_owned()
        } else {
            text
        }
    } else {
        let text = format!("{value:.2e}");
        let (mantissa, exponent) = text.split_once('e').expect("scientific notation has an exponent");
        let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
        format!("{mantissa}e{exponent}")
    }
}

/// A number written with as few digits as represent it to 12 significant digits (axis offsets).
pub fn short_exact(value: f64) -> String {
    if value == 0.0 || !value.is_finite() {
        return format!("{value}");
    }
    let close = |text: &str| text.parse::<f64>().is_ok_and(|back| (back - value).abs() <= 1e-12 * value.abs());
    let exponent = value.abs().log10().floor();
    if (-3.0..12.0).contains(&exponent) {
        (0..=15).map(|d| format!("{value:.d$}")).find(|t| close(t)).unwrap_or_else(|| format!("{value}"))
    } else {
        (0..=12).map(|d| format!("{value:.d$e}")).find(|t| close(t)).unwrap_or_else(|| format!("{value:e}"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_ticks_show_the_digits_their_spacing_needs() {
        let f = TickFormat::for_ticks(&[0.0, 5.0, 10.0, 15.0, 20.0]);
        assert_eq!([f.format(0.0), f.format(5.0), f.format(20.0)], ["0", "5", "20"]);
        let f = TickFormat::for_ticks(&[-0.04, -0.02, 0.0, 0.02, 0.04]);
        assert_eq!([f.format(-0.04), f.format(0.0), f.format(0.02)], ["-0.04", "0.00", "0.02"]);
        let f = TickFormat::for_ticks(&[0.0, 2.5, 5.0, 7.5]);
        assert_eq!([f.format(0.0), f.format(7.5)], ["0.0", "7.5"]);
        let f = TickFormat::for_ticks(&[-3e-7, -2e-7, 0.0, 4e-7]);
        assert_eq!([f.format(-3e-7), f.format(0.0), f.format(4e-7)], ["-3e-7", "0", "4e-7"]);
        let f = TickFormat::for_ticks(&[1.0e6, 1.25e6, 1.5e6]);
        assert_eq!([f.format(1.0e6), f.format(1.25e6)], ["1.00e6", "1.25e6"]);
        let (ticks, _) = nice(0.0, 100.0, 6);
        let f = TickFormat::for_ticks(&ticks);
        assert_eq!(f.format(40.0), "40");
    }

    #[test]
    fn nice_ticks_cover_the_range_to_its_ends() {
        // A range where a tick sits just below the upper end, as 3.0 in [2.2058, 3.1774].
        let (ticks, minor) = nice(2.2058, 3.1774, 6);
        let f = TickFormat::for_ticks(&ticks);
        let labels: Vec<String> = ticks.iter().map(|&t| f.format(t)).collect();
        assert_eq!(labels, ["2.4", "2.6", "2.8", "3.0"]);
        assert!(minor.len() > ticks.len());
        let (ticks, _) = nice(-3.2e-7, 5.1e-7, 6);
        assert_eq!(ticks, [-2e-7, 0.0, 2e-7, 4e-7]);
        let (ticks, _) = nice(0.0, 20.0, 10);
        assert_eq!(ticks, [0.0, 2.5, 5.0, 7.5, 10.0, 12.5, 15.0, 17.5, 20.0]);
        let (ticks, _) = nice(0.0, 20.0, 8);
        assert_eq!(ticks, [0.0, 5.0, 10.0, 15.0, 20.0]);
        assert_eq!(nice(1.0, 1.0, 6).0, [1.0]);
    }

    #[test]
    fn logarithmic_ticks_take_multiples_or_powers_of_ten() {
        let (major, minor) = logarithmic(0.08, 2.5, 8);
        assert_eq!(major.iter().map(|&v| short(v)).collect::<Vec<_>>(), ["0.1", "0.2", "0.5", "1", "2"]);
        assert!(minor.len() > major.len());
        let (major, _) = logarithmic(0.0104, 40.0, 6);
        assert_eq!(major.iter().map(|&v| short(v)).collect::<Vec<_>>(), ["0.1", "1", "10"]);
        let (major, _) = logarithmic(0.05, 40.0, 8);
        assert_eq!(major.iter().map(|&v| short(v)).collect::<Vec<_>>(), ["0.1", "0.3", "1", "3", "10", "30"]);
        let (major, _) = logarithmic(1e-12, 1.0, 6);
        assert!(major.len() <= 6 && major.contains(&1.0), "{major:?}");
    }

    #[test]
    fn negative_zero_is_written_as_zero() {
        let f = TickFormat::for_ticks(&[-1.0, -0.5, 0.0, 0.5]);
        assert_eq!(f.format(-1e-17), "0.0");
    }

    #[test]
    fn short_labels_have_three_significant_digits() {
        assert_eq!(short(0.2), "0.2");
        assert_eq!(short(1.6781), "1.68");
        assert_eq!(short(0.0125), "0.0125");
        assert_eq!(short(2e-5), "2e-5");
        assert_eq!(short(100.0), "100");
    }

    #[test]
    fn offsets_are_written_short_but_exact() {
        assert_eq!(short_exact(1234.5679 + 1e-13), "1234.5679");
        assert_eq!(short_exact(-20.0), "-20");
        assert_eq!(short_exact(1.5e-7), "1.5e-7");
    }

    #[test]
    fn ranges_are_padded_and_never_empty() {
        assert_eq!(padded(0.0, 10.0, 0.05), (-0.5, 10.5));
        assert_eq!(padded(0.0, 0.0, 0.05), (-1.0, 1.0));
        let (lo, hi) = padded(2.0, 2.0, 0.05);
        assert!(lo < 2.0 && hi > 2.0);
    }

    #[test]
    fn an_offset_is_taken_only_for_a_tiny_spread() {
        assert_eq!(offset(0.0, 1.0), None);
        assert_eq!(offset(-1.0, 1.0), None);
        let c = offset(1234.56789, 1234.56791).unwrap();
        assert!((c - 1234.5679).abs() < 1e-9, "{c}");
    }
}
