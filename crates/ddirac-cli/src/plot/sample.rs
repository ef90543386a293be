//! Thinning long series for drawing, in one pass and bounded memory.
//!
//! A figure a few thousand pixels wide cannot show more than a few thousand points per curve, and
//! an SVG with millions of points is unusable. [`Envelope`] keeps, for each of a bounded number of
//! consecutive buckets of rows, the smallest and the largest value (in time order), so that short
//! spikes — such as the energy spikes of a passage near a pole — stay visible. [`Stride`] keeps every
//! k-th point (and the last), for paths in a plane, where min/max per bucket has no meaning.

/// Buckets per series: about the width of a figure in pixels.
pub const BUCKETS: usize = 1500;

/// Rows per bucket so that `rows` rows make at most [`BUCKETS`] buckets.
pub fn stride(rows: usize) -> usize {
    rows.div_ceil(BUCKETS).max(1)
}

/// The min/max envelope of a series, bucket by bucket.
#[derive(Debug, Clone)]
pub struct Envelope {
    stride: usize,
    seen: usize,
    bucket: Option<((f64, f64), (f64, f64))>,
    points: Vec<(f64, f64)>,
}

impl Envelope {
    /// An envelope for a series of `rows` rows.
    pub fn new(rows: usize) -> Self {
        Self { stride: stride(rows), seen: 0, bucket: None, points: vec![] }
    }

    /// Adds the next row; a missing or non-finite value counts as a row but draws nothing.
    pub fn push(&mut self, t: f64, value: Option<f64>) {
        if self.seen.is_multiple_of(self.stride) {
            self.flush();
        }
        self.seen += 1;
        let Some(v) = value.filter(|v| v.is_finite() && t.is_finite()) else { return };
        self.bucket = Some(match self.bucket {
            None => ((t, v), (t, v)),
            Some((lo, hi)) => (if v < lo.1 { (t, v) } else { lo }, if v > hi.1 { (t, v) } else { hi }),
        });
    }

    fn flush(&mut self) {
        if let Some((lo, hi)) = self.bucket.take() {
            let (a, b) = if lo.0 <= hi.0 { (lo, hi) } else { (hi, lo) };
            self.points.push(a);
            if b != a {
                self.points.push(b);
            }
        }
    }

    /// The points to draw.
    pub fn finish(mut self) -> Vec<(f64, f64)> {
        self.flush();
        self.points
    }
}

/// Every k-th point of a path, and its last point.
#[derive(Debug, Clone)]
pub struct Stride<P = (f64, f64)> {
    stride: usize,
    seen: usize,
    last: Option<P>,
    points: Vec<P>,
}

impl<P> Stride<P> {
    /// A thinning of a path of `rows` points to about 2 × [`BUCKETS`] points.
    pub fn new(rows: usize) -> Self {
        Self { stride: rows.div_ceil(2 * BUCKETS).max(1), seen: 0, last: None, points: vec![] }
    }

    /// Adds the next point.
    pub fn push(&mut self, point: P) {
        if self.seen.is_multiple_of(self.stride) {
            self.points.push(point);
            self.last = None;
        } else {
            self.last = Some(point);
        }
        self.seen += 1;
    }

    /// The points to draw.
    pub fn finish(mut self) -> Vec<P> {
        self.points.extend(self.last);
        self.points
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn short_series_are_kept_whole() {
        let mut e = Envelope::new(5);
        for k in 0..5 {
            e.push(k as f64, Some((k * k) as f64));
        }
        assert_eq!(e.finish(), vec![(0.0, 0.0), (1.0, 1.0), (2.0, 4.0), (3.0, 9.0), (4.0, 16.0)]);
    }

    #[test]
    fn a_long_series_keeps_its_spike_and_its_bounds() {
        let rows = 1_000_000;
        let mut e = Envelope::new(rows);
        for k in 0..rows {
            let v = if k == 777_777 { 5.0 } else { (k as f64 * 1e-3).sin() };
            e.push(k as f64, Some(v));
        }
        let points = e.finish();
        assert!(points.len() <= 2 * BUCKETS, "{} points", points.len());
        assert!(points.contains(&(777_777.0, 5.0)), "the spike was lost");
        assert!(points.windows(2).all(|w| w[0].0 < w[1].0), "points out of time order");
        let min = points.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
        assert!(min < -0.999_999);
    }

    #[test]
    fn missing_values_draw_nothing() {
        let mut e = Envelope::new(3);
        e.push(0.0, Some(1.0));
        e.push(1.0, None);
        e.push(2.0, Some(f64::NAN));
        assert_eq!(e.finish(), vec![(0.0, 1.0)]);
    }

    #[test]
    fn a_thinned_path_keeps_its_ends() {
        let rows = 10_001;
        let mut s = Stride::new(rows);
        for k in 0..rows {
            s.push((k as f64, 0.0));
        }
        let points = s.finish();
        assert!(points.len() <= 2 * BUCKETS + 1);
        assert_eq!(points.first(), Some(&(0.0, 0.0)));
        assert_eq!(points.last(), Some(&(10_000.0, 0.0)));
    }
}
