//! Timing of contenders side by side in one process: each contender is a closure running one whole
//! computation of a known number of steps; a batch repeats it a calibrated number of times, and
//! every round runs one batch of each contender, in an order rotated from round to round.
//!
//! Times per step and the ratios between contenders are formed round by round, so that a change of
//! the machine's load between rounds moves numerator and denominator of a ratio together. Each is
//! summarised by its median over the rounds with the interquartile range and the extremes
//! ([`Spread`]).

use std::hint::black_box;
use std::time::{Duration, Instant};

use serde::Serialize;

/// The result a contender's closure returns: `Err` stops the benchmark with that report.
pub type Outcome = Result<(), miette::Report>;

/// Upper bound on the repetitions of one batch.
const MAX_REPS: usize = 10_000_000;

/// How long batches take and how many rounds run.
#[derive(Debug, Clone, Copy)]
pub struct Schedule {
    /// Rounds R.
    pub rounds: usize,
    /// Target duration of one batch.
    pub batch: Duration,
}

/// One computation to time: `run` performs `steps` steps (one whole integration, say).
pub struct Contender<'a> {
    /// Name in tables and in the JSON output.
    pub name: String,
    /// Steps per call of `run`.
    pub steps: usize,
    /// Mean Newton iterations and Jacobian evaluations per step, for engine runs.
    pub newton: Option<Newton>,
    run: Box<dyn FnMut() -> Outcome + 'a>,
}

impl<'a> Contender<'a> {
    /// A contender doing `steps` steps per call of `run`.
    pub fn new(name: impl Into<String>, steps: usize, run: impl FnMut() -> Outcome + 'a) -> Self {
        Self { name: name.into(), steps, newton: None, run: Box::new(run) }
    }

    /// Records the Newton work per step of the computation.
    pub fn with_newton(mut self, newton: Newton) -> Self {
        self.newton = Some(newton);
        self
    }

    /// Seconds taken by `reps` calls.
    fn batch(&mut self, reps: usize) -> Result<f64, miette::Report> {
        let started = Instant::now();
        for _ in 0..reps {
            black_box((self.run)())?;
        }
        Ok(started.elapsed().as_secs_f64())
    }

    /// The number of calls that take about `target`: doubles (at most tenfold at a time) until a
    /// batch takes a quarter of the target, then scales. The calls made here also warm up caches
    /// and branch predictors.
    fn calibrate(&mut self, target: Duration) -> Result<usize, miette::Report> {
        let target = target.as_secs_f64();
        let mut reps = 1;
        loop {
            let seconds = self.batch(reps)?;
            if seconds >= target / 4.0 || reps >= MAX_REPS {
                let scaled = (reps as f64 * target / seconds.max(1e-9)).round();
                return Ok((scaled as usize).clamp(1, MAX_REPS));
            }
            let factor = (target / 4.0 / seconds.max(1e-9)).ceil().clamp(2.0, 10.0) as usize;
            reps = (reps * factor).min(MAX_REPS);
        }
    }
}

/// The mean Newton work per step of an engine run.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Newton {
    /// Corrections per step.
    pub iterations: f64,
    /// Jacobian evaluations per step.
    pub jacobians: f64,
}

/// Median, quartiles and extremes of a sample.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Spread {
    /// Median.
    pub median: f64,
    /// First quartile.
    pub q1: f64,
    /// Third quartile.
    pub q3: f64,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
}

impl Spread {
    /// The spread of a non-empty sample; `None` for an empty one.
    pub fn of(values: &[f64]) -> Option<Self> {
        let mut sorted = values.to_vec();
        sorted.sort_by(f64::total_cmp);
        Some(Self {
            median: quantile(&sorted, 0.5)?,
            q1: quantile(&sorted, 0.25)?,
            q3: quantile(&sorted, 0.75)?,
            min: *sorted.first()?,
            max: *sorted.last()?,
        })
    }
}

/// The p-quantile of a sorted sample, interpolating linearly between order statistics: position
/// p·(n − 1) counted from 0 (the default of R and NumPy). `None` for an empty sample.
pub fn quantile(sorted: &[f64], p: f64) -> Option<f64> {
    let last = sorted.len().checked_sub(1)?;
    let position = p.clamp(0.0, 1.0) * last as f64;
    let below = position.floor() as usize;
    let above = (below + 1).min(last);
    let fraction = position - below as f64;
    Some(sorted[below] + fraction * (sorted[above] - sorted[below]))
}

/// The timings of one contender.
#[derive(Debug, Clone, Serialize)]
pub struct Timing {
    /// Its name.
    pub name: String,
    /// Steps per call.
    pub steps: usize,
    /// Calls per batch.
    pub reps: usize,
    /// Newton work per step, for engine runs.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub newton: Option<Newton>,
    /// Nanoseconds per step over the rounds.
    pub ns_per_step: Spread,
    /// Nanoseconds per step in each round.
    pub rounds: Vec<f64>,
}

/// A target a measured value is compared with.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Target {
    /// The value should be at most this.
    AtMost(f64),
    /// The value should be at least this.
    AtLeast(f64),
}

impl Target {
    /// Whether `value` meets the target.
    pub fn met(self, value: f64) -> bool {
        match self {
            Target::AtMost(bound) => value <= bound,
            Target::AtLeast(bound) => value >= bound,
        }
    }

    /// `≤ 5`, `≥ 1.75`.
    pub fn text(self) -> String {
        match self {
            Target::AtMost(bound) => format!("≤ {bound}"),
            Target::AtLeast(bound) => format!("≥ {bound}"),
        }
    }
}

/// A ratio of the per-step times of two contenders, formed in every round.
#[derive(Debug, Clone, Serialize)]
pub struct Ratio {
    /// `numerator / denominator`.
    pub name: String,
    /// The contender in the numerator.
    pub numerator: String,
    /// The contender in the denominator.
    pub denominator: String,
    /// Its spread over the rounds.
    pub spread: Spread,
    /// The ratio in each round.
    pub rounds: Vec<f64>,
    /// The target, if there is one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub target: Option<Target>,
    /// Whether the median meets the target.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub target_met: Option<bool>,
}

/// The contenders of one comparison, timed side by side, and the ratios asked for.
#[derive(Debug, Clone, Serialize)]
pub struct Comparison {
    /// What is compared.
    pub title: String,
    /// Per contender, in the order given.
    pub timings: Vec<Timing>,
    /// The ratios, in the order asked for.
    pub ratios: Vec<Ratio>,
}

impl Comparison {
    /// The timing of the contender called `name`.
    pub fn timing(&self, name: &str) -> Option<&Timing> {
        self.timings.iter().find(|t| t.name == name)
    }
}

/// A ratio to form: numerator, denominator (contender names), target.
pub struct Pair<'n> {
    /// Contender in the numerator.
    pub numerator: &'n str,
    /// Contender in the denominator.
    pub denominator: &'n str,
    /// Target of the ratio, if any.
    pub target: Option<Target>,
}

impl<'n> Pair<'n> {
    /// `numerator / denominator` without a target.
    pub fn new(numerator: &'n str, denominator: &'n str) -> Self {
        Self { numerator, denominator, target: None }
    }

    /// With a target for the median.
    pub fn target(mut self, target: Target) -> Self {
        self.target = Some(target);
        self
    }
}

/// Times `contenders` side by side: calibrates each, then runs `schedule.rounds` rounds, round r
/// starting with contender r mod n; forms the per-round ratios of `pairs`.
pub fn compare(
    title: impl Into<String>,
    schedule: Schedule,
    mut contenders: Vec<Contender<'_>>,
    pairs: &[Pair<'_>],
) -> Result<Comparison, miette::Report> {
    let n = contenders.len();
    let rounds = schedule.rounds.max(1);
    let mut reps = Vec::with_capacity(n);
    for contender in &mut contenders {
        reps.push(contender.calibrate(schedule.batch)?);
    }
    let mut per_step = vec![Vec::with_capacity(rounds); n];
    for round in 0..rounds {
        for j in 0..n {
            let i = (round + j) % n;
            let seconds = contenders[i].batch(reps[i])?;
            per_step[i].push(seconds * 1e9 / (reps[i] * contenders[i].steps.max(1)) as f64);
        }
    }
    let empty = || miette::miette!("no rounds were timed");
    let timings = contenders
        .iter()
        .zip(&reps)
        .zip(per_step)
        .map(|((c, &reps), rounds)| {
            Ok(Timing {
                name: c.name.clone(),
                steps: c.steps,
                reps,
                newton: c.newton,
                ns_per_step: Spread::of(&rounds).ok_or_else(empty)?,
                rounds,
            })
        })
        .collect::<Result<Vec<_>, miette::Report>>()?;
    let mut ratios = vec![];
    for pair in pairs {
        let find = |name: &str| {
            timings.iter().find(|t| t.name == name).ok_or_else(|| miette::miette!("no contender `{name}` to compare"))
        };
        let (a, b) = (find(pair.numerator)?, find(pair.denominator)?);
        let rounds: Vec<f64> = a.rounds.iter().zip(&b.rounds).map(|(x, y)| x / y).collect();
        ratios.push(ratio(pair, rounds)?);
    }
    Ok(Comparison { title: title.into(), timings, ratios })
}

/// A ratio from its values in each round.
pub fn ratio(pair: &Pair<'_>, rounds: Vec<f64>) -> Result<Ratio, miette::Report> {
    let spread = Spread::of(&rounds).ok_or_else(|| miette::miette!("no rounds were timed"))?;
    Ok(Ratio {
        name: format!("{} / {}", pair.numerator, pair.denominator),
        numerator: pair.numerator.to_owned(),
        denominator: pair.denominator.to_owned(),
        spread,
        rounds,
        target: pair.target,
        target_met: pair.target.map(|t| t.met(spread.median)),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_and_quartiles_of_odd_and_even_samples() {
        // 1 2 3 4 5: positions 1, 2, 3 of 0..4.
        let s = Spread::of(&[5.0, 1.0, 4.0, 2.0, 3.0]).unwrap();
        assert_eq!((s.min, s.q1, s.median, s.q3, s.max), (1.0, 2.0, 3.0, 4.0, 5.0));
        // 1 2 3 4: median (2 + 3)/2; q1 at position 0.75 → 1 + 0.75·1; q3 at 2.25 → 3 + 0.25·1.
        let s = Spread::of(&[4.0, 3.0, 2.0, 1.0]).unwrap();
        assert_eq!((s.q1, s.median, s.q3), (1.75, 2.5, 3.25));
        // 10 20 40 80 160 320: median at 2.5 → 60; q1 at 1.25 → 20 + 0.25·20 = 25; q3 at 3.75 → 80 + 0.75·80 = 140.
        let s = Spread::of(&[320.0, 10.0, 160.0, 20.0, 80.0, 40.0]).unwrap();
        assert_eq!((s.q1, s.median, s.q3), (25.0, 60.0, 140.0));
    }

    #[test]
    fn one_value_and_no_value() {
        let s = Spread::of(&[7.0]).unwrap();
        assert_eq!((s.min, s.q1, s.median, s.q3, s.max), (7.0, 7.0, 7.0, 7.0, 7.0));
        assert!(Spread::of(&[]).is_none());
        assert_eq!(quantile(&[], 0.5), None);
    }

    #[test]
    fn quantile_end_points_and_interpolation() {
        let sorted = [0.0, 10.0, 30.0];
        assert_eq!(quantile(&sorted, 0.0), Some(0.0));
        assert_eq!(quantile(&sorted, 1.0), Some(30.0));
        // Position 0.9·2 = 1.8: 10 + 0.8·20.
        assert_eq!(quantile(&sorted, 0.9), Some(26.0));
    }

    #[test]
    fn rounds_rotate_and_ratios_are_formed_per_round() {
        use std::cell::RefCell;
        let order = RefCell::new(vec![]);
        let contenders = ["a", "b", "c"]
            .map(|name| {
                let order = &order;
                Contender::new(name, 1, move || {
                    order.borrow_mut().push(name);
                    Ok(())
                })
            })
            .into_iter()
            .collect();
        let schedule = Schedule { rounds: 3, batch: Duration::from_micros(1) };
        let comparison = compare("t", schedule, contenders, &[Pair::new("a", "b")]).unwrap();
        // After calibration, each round runs one batch of each, starting one further along.
        let calls = order.borrow();
        let firsts: Vec<&str> = comparison.timings.iter().map(|t| t.name.as_str()).collect();
        assert_eq!(firsts, ["a", "b", "c"]);
        let reps: Vec<usize> = comparison.timings.iter().map(|t| t.reps).collect();
        let timed = reps.iter().sum::<usize>() * 3;
        let tail: Vec<&str> = calls[calls.len() - timed..].to_vec();
        let mut expected = vec![];
        for round in 0..3 {
            for j in 0..3 {
                let i = (round + j) % 3;
                expected.extend((0..reps[i]).map(|_| ["a", "b", "c"][i]));
            }
        }
        assert_eq!(tail, expected);
        let ratio = &comparison.ratios[0];
        for (r, (a, b)) in
            ratio.rounds.iter().zip(comparison.timings[0].rounds.iter().zip(&comparison.timings[1].rounds))
        {
            assert_eq!(*r, a / b);
        }
    }

    #[test]
    fn targets() {
        assert!(Target::AtMost(5.0).met(5.0) && !Target::AtMost(5.0).met(5.1));
        assert!(Target::AtLeast(1.75).met(2.0) && !Target::AtLeast(1.75).met(1.0));
        assert_eq!(Target::AtLeast(1.75).text(), "≥ 1.75");
    }

    #[test]
    fn a_failing_contender_stops_the_comparison() {
        let contenders = vec![Contender::new("bad", 1, || Err(miette::miette!("the run failed")))];
        let schedule = Schedule { rounds: 2, batch: Duration::from_micros(1) };
        let error = compare("t", schedule, contenders, &[]).unwrap_err();
        assert!(error.to_string().contains("the run failed"));
    }
}
