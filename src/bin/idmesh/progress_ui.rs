//! The command line's progress bar and Ctrl-C handling, both on top of the library's progress
//! callback ([`idmesh::progress`]).
//!
//! * The bar goes to standard error, only when it is a terminal and without `-Q` (nor `-V`,
//!   whose progress lines it would garble), and only once a run has lasted [`SHOW_AFTER`]:
//!   short runs print nothing extra. It is removed before the output files are written.
//! * SIGINT sets a flag that the progress callback turns into a cancel, so the mesher stops
//!   through its ordinary error path; the command then exits with status 130
//!   ([`EXIT_INTERRUPTED`]) and leaves no output file behind (files are written only after a
//!   successful run; a Ctrl-C while they are being written removes them). A second SIGINT
//!   ends the process at once.

use std::io::IsTerminal;
use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, OnceLock};
use std::time::{Duration, Instant, SystemTime};

use idmesh::progress::{ProgressFn, Stage};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// How long a run goes before the bar appears.
pub const SHOW_AFTER: Duration = Duration::from_secs(1);

/// The exit status after Ctrl-C (128 + SIGINT, as shells report it).
pub const EXIT_INTERRUPTED: u8 = 130;

/// Set by the SIGINT handler.
fn flag() -> &'static Arc<AtomicBool> {
    static FLAG: OnceLock<Arc<AtomicBool>> = OnceLock::new();
    FLAG.get_or_init(|| Arc::new(AtomicBool::new(false)))
}

/// Installs the SIGINT handler: the first Ctrl-C sets the flag (the run stops at its next
/// progress check), a second one exits at once with [`EXIT_INTERRUPTED`].
pub fn catch_interrupt() -> Result<(), String> {
    let f = flag();
    // The conditional shutdown is registered first so that it sees the flag before this
    // signal sets it: it fires only on the second Ctrl-C.
    signal_hook::flag::register_conditional_shutdown(
        signal_hook::consts::SIGINT,
        EXIT_INTERRUPTED as i32,
        f.clone(),
    )
    .and_then(|_| signal_hook::flag::register(signal_hook::consts::SIGINT, f.clone()))
    .map(|_| ())
    .map_err(|e| format!("cannot install the Ctrl-C handler: {e}"))
}

/// Whether Ctrl-C was pressed.
pub fn interrupted() -> bool {
    flag().load(Ordering::Relaxed)
}

/// Fails with a message when Ctrl-C was pressed (for the steps outside the mesher).
pub fn check_interrupt() -> Result<(), String> {
    if interrupted() {
        Err("interrupted".into())
    } else {
        Ok(())
    }
}

/// The progress display of one command run.
pub struct Progress {
    bar: Arc<Mutex<Option<ProgressBar>>>,
    show: bool,
    start: Instant,
}

impl Progress {
    /// A display for a run; `quiet` (`-Q` or `-V`) or a standard error that is not a terminal
    /// shows nothing, but Ctrl-C still cancels through [`Progress::callback`].
    pub fn new(quiet: bool) -> Progress {
        Progress {
            bar: Arc::new(Mutex::new(None)),
            show: !quiet && std::io::stderr().is_terminal(),
            start: Instant::now(),
        }
    }

    /// The callback for the mesher: updates the bar, and cancels once Ctrl-C was pressed.
    pub fn callback(&self) -> ProgressFn {
        let (bar, show, start) = (self.bar.clone(), self.show, self.start);
        Arc::new(move |stage, done, estimate| {
            if interrupted() {
                return ControlFlow::Break(());
            }
            update(&bar, show, start, stage, done, estimate);
            ControlFlow::Continue(())
        })
    }

    /// Removes the bar (before the command prints its results).
    pub fn finish(&self) {
        if let Some(b) = lock(&self.bar).take() {
            b.finish_and_clear();
        }
    }
}

impl Drop for Progress {
    fn drop(&mut self) {
        self.finish();
    }
}

fn lock(bar: &Mutex<Option<ProgressBar>>) -> std::sync::MutexGuard<'_, Option<ProgressBar>> {
    bar.lock().unwrap_or_else(|e| e.into_inner())
}

/// Moves the bar to `stage`, `done` of `estimate` (a spinner when the estimate is unknown),
/// creating it once the run has lasted [`SHOW_AFTER`].
fn update(
    bar: &Mutex<Option<ProgressBar>>,
    show: bool,
    start: Instant,
    stage: Stage,
    done: u64,
    estimate: u64,
) {
    if !show || start.elapsed() < SHOW_AFTER {
        return;
    }
    let mut bar = lock(bar);
    let b = bar.get_or_insert_with(|| {
        let b = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr_with_hz(10));
        b.set_style(
            ProgressStyle::with_template("{elapsed:>4} {msg:<20} {wide_bar} {pos}/{len}")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        b
    });
    b.set_message(stage.name());
    b.set_length(estimate.max(done));
    b.set_position(done);
}

/// The output files `stem.EXT` (for every output extension) as they were before writing:
/// after a Ctrl-C during writing, [`Outputs::remove_written`] removes those the run created
/// or changed, so no partial file is left.
pub struct Outputs(Vec<(String, Option<SystemTime>)>);

impl Outputs {
    /// Notes the state of the possible outputs of `stem`.
    pub fn before_writing(stem: &str) -> Outputs {
        let exts = [
            "node", "ele", "face", "edge", "neigh", "poly", "vtk", "vtu", "msh", "mesh",
        ];
        Outputs(
            exts.iter()
                .map(|ext| {
                    let name = format!("{stem}.{ext}");
                    let t = modified(&name);
                    (name, t)
                })
                .collect(),
        )
    }

    /// Removes the files written (created or changed) since [`Outputs::before_writing`].
    pub fn remove_written(&self) {
        for (name, before) in &self.0 {
            let now = modified(name);
            if now.is_some() && now != *before {
                let _ = std::fs::remove_file(name);
            }
        }
    }
}

fn modified(name: &str) -> Option<SystemTime> {
    std::fs::metadata(name).and_then(|m| m.modified()).ok()
}
