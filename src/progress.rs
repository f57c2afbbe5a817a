//! Progress reports and cancellation of a meshing run.
//!
//! A run reports to a [`ProgressFn`] (set in [`crate::Options::progress`] or
//! [`crate::Options3::progress`], or given to [`observe`]): the [`Stage`] it is in, how much of
//! the stage is done and an estimate of the stage's total. The callback's answer decides
//! whether the run goes on; a run told to stop returns [`Error::Cancelled`] as soon as it next
//! looks, with everything it built dropped.
//!
//! How it stays cheap: the meshers' loops call `tick` once per step, which only counts down
//! a thread-local counter; every [`CHECK_EVERY`] steps it reads the clock, and only when
//! [`MIN_INTERVAL`] has passed since the last report does it call the callback. So the
//! callback runs a bounded number of times per second (at most one per `MIN_INTERVAL`, plus
//! one at the start of each stage, of which a run has a handful), and a request to stop is
//! seen within about `MIN_INTERVAL` plus the time of `CHECK_EVERY` steps.
//!
//! The callback of the run in progress lives in thread-local storage for the duration of the
//! run ([`observe`] installs it and restores the previous one on the way out, also on a
//! panic), so the hooks in the meshers' loops are one line each and need no extra parameter.

use std::cell::{Cell, RefCell};
use std::fmt;
use std::ops::ControlFlow;
use std::sync::Arc;
use std::time::{Duration, Instant};

use crate::error::Error;

/// The stages of a meshing run, in the order a run goes through them (a run may skip some:
/// without quality bounds there is no refinement; without facets no boundary recovery).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Stage {
    /// Reading and checking the input (the command line reads its files in this stage).
    Reading,
    /// Inserting the input points into the Delaunay triangulation / tetrahedralization.
    /// `done` counts the points inserted, the estimate is the number of input points.
    Delaunay,
    /// Recovering the boundary: input segments (and facets, in 3D) become unions of mesh
    /// edges (faces), split where needed; then the exterior and holes are carved away.
    /// `done` counts the Steiner points added so far.
    Boundary,
    /// Quality and size refinement. `done` counts the Steiner points added so far, the
    /// estimate is `done` plus the work queued (it grows and shrinks as refinement goes).
    Refining,
    /// Removing slivers (3D): the flat tetrahedra refinement leaves behind; with mesh
    /// optimisation (TetGen's `-O`) also the flips and smoothing after the output mesh is built
    /// (`done` counts the bad tetrahedra of the pass treated so far).
    Slivers,
    /// Building the output mesh (and, on the command line, writing its files).
    Output,
}

impl Stage {
    /// Every stage, in run order.
    pub const ALL: [Stage; 6] = [
        Stage::Reading,
        Stage::Delaunay,
        Stage::Boundary,
        Stage::Refining,
        Stage::Slivers,
        Stage::Output,
    ];

    /// A short lower-case name ("reading", "Delaunay", ...), as a progress display shows it.
    pub fn name(self) -> &'static str {
        match self {
            Stage::Reading => "reading",
            Stage::Delaunay => "Delaunay",
            Stage::Boundary => "recovering boundary",
            Stage::Refining => "refining",
            Stage::Slivers => "removing slivers",
            Stage::Output => "output",
        }
    }
}

impl fmt::Display for Stage {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A progress callback: called with the stage, the work done in it and an estimate of the
/// stage's total (0 when unknown; `done` never decreases within a stage, the estimate may
/// change). Return [`ControlFlow::Continue`] to go on, [`ControlFlow::Break`] to cancel the
/// run, which then returns [`Error::Cancelled`].
///
/// It is called from the meshing thread only, at most about once per [`MIN_INTERVAL`] plus
/// once at the start of each stage; it should return quickly (the run waits for it).
pub type ProgressFn = Arc<dyn Fn(Stage, u64, u64) -> ControlFlow<()> + Send + Sync>;

/// The shortest time between two reports within a stage.
pub const MIN_INTERVAL: Duration = Duration::from_millis(20);

/// How many steps `tick` lets pass between two looks at the clock.
pub const CHECK_EVERY: u32 = 32;

/// The callback of the run in progress on this thread, and where it stands.
struct Active {
    f: ProgressFn,
    stage: Option<Stage>,
    last: Instant,
    /// Set when the callback asked to stop (the stage it was in): every later tick fails.
    cancelled: Option<Stage>,
    /// The `done` last reported in the current stage: a later report never goes below it
    /// (a stage may run several loops that each count from their own start).
    done: u64,
}

thread_local! {
    /// Steps left before [`tick`] looks at the clock (1 once cancelled, so every tick fails
    /// fast; `u32::MAX` when no callback is installed).
    static COUNTDOWN: Cell<u32> = const { Cell::new(u32::MAX) };
    static ACTIVE: RefCell<Option<Active>> = const { RefCell::new(None) };
}

/// Runs `body` (a call of the meshers) with `f` receiving its progress reports, and returns
/// its result; [`Error::Cancelled`] when `f` asked to stop. With `f` `None` nothing is reported
/// (even when an outer `observe` on this thread has a callback: a mesher called from inside a
/// progress callback does not report to it).
///
/// [`crate::triangulate`] and [`crate::tetrahedralize`] call this with the options' callback;
/// use it directly to observe [`crate::delaunay3d`].
pub fn observe<T>(
    f: Option<&ProgressFn>,
    body: impl FnOnce() -> Result<T, Error>,
) -> Result<T, Error> {
    /// Puts back the previous state when the run ends, also on a panic.
    struct Restore(Option<Option<Active>>, u32);
    impl Drop for Restore {
        fn drop(&mut self) {
            let previous = self.0.take().flatten();
            let _ = ACTIVE.try_with(|a| *a.borrow_mut() = previous);
            let _ = COUNTDOWN.try_with(|c| c.set(self.1));
        }
    }
    let active = f.map(|f| Active {
        f: f.clone(),
        stage: None,
        last: Instant::now(),
        cancelled: None,
        done: 0,
    });
    let countdown = if active.is_some() {
        CHECK_EVERY
    } else {
        u32::MAX
    };
    let restore = Restore(
        Some(ACTIVE.with(|a| a.replace(active))),
        COUNTDOWN.with(|c| c.replace(countdown)),
    );
    let result = body();
    // A cancel is the outcome even if some caller on the way out turned it into another error.
    let cancelled = ACTIVE.with(|a| a.borrow().as_ref().and_then(|a| a.cancelled));
    drop(restore);
    match cancelled {
        Some(stage) => Err(Error::Cancelled(stage)),
        None => result,
    }
}

/// One step of a loop in `stage`'s work: cheap (a thread-local countdown) on all but one in
/// [`CHECK_EVERY`] calls; then reports `work()` = (done, estimate) when [`MIN_INTERVAL`] has
/// passed. Fails with [`Error::Cancelled`] once the callback asked to stop.
#[inline]
pub(crate) fn tick(work: impl FnOnce() -> (u64, u64)) -> Result<(), Error> {
    let left = COUNTDOWN.with(|c| {
        let n = c.get().wrapping_sub(1);
        c.set(n);
        n
    });
    if left != 0 {
        return Ok(());
    }
    look(None, work)
}

/// Enters `stage` and reports it at once with `work()` = (done, estimate). A stage earlier
/// than the current one is ignored (stages only go forward: the 3D run's repeated refinement
/// rounds stay in one stage), as is the current one.
pub(crate) fn stage(stage: Stage, work: impl FnOnce() -> (u64, u64)) -> Result<(), Error> {
    look(Some(stage), work)
}

/// The slow path of [`tick`] and [`stage`]: resets the countdown, reads the clock, and calls
/// the callback when due (always when entering a new stage).
#[cold]
#[inline(never)]
fn look(enter: Option<Stage>, work: impl FnOnce() -> (u64, u64)) -> Result<(), Error> {
    let call = ACTIVE.with(|a| {
        let mut a = a.borrow_mut();
        let Some(a) = a.as_mut() else {
            COUNTDOWN.with(|c| c.set(u32::MAX));
            return Ok(None);
        };
        if let Some(s) = a.cancelled {
            COUNTDOWN.with(|c| c.set(1));
            return Err(Error::Cancelled(s));
        }
        COUNTDOWN.with(|c| c.set(CHECK_EVERY));
        let now = Instant::now();
        let due = match enter {
            Some(s) if a.stage.map_or(true, |cur| s > cur) => {
                a.stage = Some(s);
                true
            }
            Some(_) => false,
            None => a.stage.is_some() && now.duration_since(a.last) >= MIN_INTERVAL,
        };
        if !due {
            return Ok(None);
        }
        a.last = now;
        Ok(a.stage.map(|s| (a.f.clone(), s)))
    })?;
    let Some((f, s)) = call else {
        return Ok(());
    };
    let (done, estimate) = work();
    let entered = enter.is_some();
    let done = ACTIVE.with(|a| match a.borrow_mut().as_mut() {
        Some(a) if !entered => {
            a.done = a.done.max(done);
            a.done
        }
        Some(a) => {
            a.done = done;
            done
        }
        None => done,
    });
    let estimate = estimate.max(done);
    // No borrow is held while user code runs: it may itself mesh (see `observe`).
    if f(s, done, estimate).is_break() {
        ACTIVE.with(|a| {
            if let Some(a) = a.borrow_mut().as_mut() {
                a.cancelled = Some(s);
            }
        });
        COUNTDOWN.with(|c| c.set(1));
        return Err(Error::Cancelled(s));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;

    type Log = Arc<Mutex<Vec<(Stage, u64, u64)>>>;

    fn recorder() -> (ProgressFn, Log) {
        let log = Arc::new(Mutex::new(Vec::new()));
        let l = log.clone();
        let f: ProgressFn = Arc::new(move |s, d, e| {
            l.lock().unwrap().push((s, d, e));
            ControlFlow::Continue(())
        });
        (f, log)
    }

    #[test]
    fn stages_are_reported_at_once_and_only_forward() {
        let (f, log) = recorder();
        observe(Some(&f), || {
            stage(Stage::Delaunay, || (0, 10))?;
            stage(Stage::Reading, || (0, 0))?;
            stage(Stage::Delaunay, || (5, 10))?;
            stage(Stage::Output, || (0, 1))
        })
        .unwrap();
        let got = log.lock().unwrap().clone();
        assert_eq!(got, [(Stage::Delaunay, 0, 10), (Stage::Output, 0, 1)]);
    }

    #[test]
    fn ticks_are_throttled_by_time() {
        let (f, log) = recorder();
        let start = Instant::now();
        observe(Some(&f), || {
            stage(Stage::Refining, || (0, 0))?;
            let mut i = 0u64;
            while start.elapsed() < Duration::from_millis(200) {
                i += 1;
                tick(|| (i, 0))?;
            }
            Ok(())
        })
        .unwrap();
        let n = log.lock().unwrap().len();
        // One report per MIN_INTERVAL at most (plus the stage's own), and some at all.
        assert!((2..=1 + 200 / 20 + 1).contains(&n), "{n} reports");
    }

    #[test]
    fn a_break_cancels_and_every_later_tick_fails() {
        let f: ProgressFn = Arc::new(|s, _, _| {
            if s == Stage::Boundary {
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        });
        let mut after = 0;
        let r: Result<(), Error> = observe(Some(&f), || {
            stage(Stage::Delaunay, || (0, 0))?;
            // A caller that swallows the error still cannot make the run succeed.
            let _ = stage(Stage::Boundary, || (0, 0));
            for _ in 0..10 {
                if tick(|| (0, 0)).is_err() {
                    after += 1;
                }
            }
            Ok(())
        });
        assert_eq!(r, Err(Error::Cancelled(Stage::Boundary)));
        assert_eq!(after, 10);
        // The state is restored: no callback outside the run.
        assert_eq!(stage(Stage::Boundary, || (0, 0)), Ok(()));
        assert_eq!(COUNTDOWN.with(|c| c.get()), u32::MAX);
    }

    #[test]
    fn nested_runs_without_a_callback_do_not_report_to_the_outer_one() {
        let (f, log) = recorder();
        observe(Some(&f), || {
            stage(Stage::Reading, || (0, 0))?;
            observe(None, || stage(Stage::Output, || (0, 0)))?;
            stage(Stage::Delaunay, || (0, 0))
        })
        .unwrap();
        let stages: Vec<Stage> = log.lock().unwrap().iter().map(|e| e.0).collect();
        assert_eq!(stages, [Stage::Reading, Stage::Delaunay]);
    }
}
