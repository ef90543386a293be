//! A progress bar on stderr for long runs: steps done, rate and time left.
//!
//! It appears only when stderr is a terminal, the command was not asked to be quiet, and the work
//! has already taken [`DELAY`]: short runs and runs whose stderr goes to a file or a pipe print
//! nothing. It is driven from the integrator's row callback with the step index of each reported
//! row; indicatif limits how often the bar is redrawn.

use std::io::IsTerminal;
use std::time::{Duration, Instant};

use indicatif::{HumanCount, HumanDuration, ProgressBar, ProgressDrawTarget, ProgressState, ProgressStyle};

/// How long a piece of work runs before its bar appears.
pub const DELAY: Duration = Duration::from_secs(1);

/// Progress over a known total number of steps, possibly made of several runs in sequence.
pub struct Progress {
    enabled: bool,
    total: u64,
    started: Instant,
    /// Steps of the runs already finished (set by [`Progress::stage`]).
    offset: u64,
    label: String,
    bar: Option<ProgressBar>,
}

impl Progress {
    /// Progress over `total` steps; shown only if `quiet` is false and stderr is a terminal.
    pub fn new(total: u64, quiet: bool) -> Self {
        Self::with(total, !quiet && std::io::stderr().is_terminal())
    }

    fn with(total: u64, enabled: bool) -> Self {
        Self { enabled, total, started: Instant::now(), offset: 0, label: String::new(), bar: None }
    }

    /// Starts the next run of a sequence: `done` steps of the total are behind, and the bar is
    /// labelled `label` from now on.
    pub fn stage(&mut self, done: u64, label: &str) {
        self.offset = done;
        label.clone_into(&mut self.label);
        if let Some(bar) = &self.bar {
            bar.set_message(self.label.clone());
            bar.set_position(done);
        }
    }

    /// Reports that the current run has reached step `step`.
    pub fn update(&mut self, step: usize) {
        if !self.enabled {
            return;
        }
        let position = self.offset + step as u64;
        match &self.bar {
            Some(bar) => bar.set_position(position),
            None if self.started.elapsed() >= DELAY => self.bar = Some(self.create(position)),
            None => {}
        }
    }

    fn create(&self, position: u64) -> ProgressBar {
        // Rate and time left over the whole work so far: steady, unlike an estimate from the latest
        // updates, and right from the first draw although the bar appears only after DELAY.
        let rate = |state: &ProgressState| state.pos() as f64 / state.elapsed().as_secs_f64().max(1e-9);
        let style = ProgressStyle::with_template(
            "{msg} [{elapsed_precise}] {wide_bar} {human_pos}/{human_len} steps ({rate} steps/s, {left} left)",
        )
        .expect("the template is valid")
        .with_key("rate", move |state: &ProgressState, w: &mut dyn std::fmt::Write| {
            let _ = write!(w, "{}", HumanCount(rate(state).round() as u64));
        })
        .with_key("left", move |state: &ProgressState, w: &mut dyn std::fmt::Write| {
            let remaining = state.len().unwrap_or(0).saturating_sub(state.pos()) as f64 / rate(state).max(1e-9);
            let _ = write!(w, "{:#}", HumanDuration(Duration::from_secs_f64(remaining.min(1e7))));
        });
        ProgressBar::with_draw_target(Some(self.total), ProgressDrawTarget::stderr())
            .with_style(style)
            .with_message(self.label.clone())
            .with_elapsed(self.started.elapsed())
            .with_position(position)
    }

    /// Removes the bar from the terminal, if it was shown.
    pub fn finish(&mut self) {
        if let Some(bar) = self.bar.take() {
            bar.finish_and_clear();
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.finish();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_hidden_progress_never_creates_a_bar() {
        let mut progress = Progress::with(0, false);
        progress.started -= 2 * DELAY;
        progress.update(10);
        assert!(progress.bar.is_none());
    }

    #[test]
    fn an_enabled_progress_waits_for_the_delay_then_tracks_the_offset() {
        let mut progress = Progress::with(100, true);
        progress.update(10);
        assert!(progress.bar.is_none(), "the bar appeared before the delay");
        progress.started -= 2 * DELAY;
        progress.stage(40, "second run");
        progress.update(5);
        let bar = progress.bar.as_ref().expect("the bar appears after the delay");
        assert_eq!(bar.position(), 45);
        assert_eq!(bar.message(), "second run");
        progress.finish();
        assert!(progress.bar.is_none());
    }
}
