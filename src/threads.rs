//! How many threads a run may use, and two ways to use them: contiguous chunks of a range,
//! each on its own scoped thread, or blocks of it dealt to the threads as they become free;
//! results come back in range order either way (so a run's outcome never depends on the
//! thread count or on which thread finishes first).
//!
//! The count comes from the environment variable `IDMESH_THREADS` (a positive integer), and
//! defaults to all the cores the process may use. A host that runs one process per core (MPI)
//! sets `IDMESH_THREADS=1`.

use crate::error::Error;
use std::ops::Range;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// The environment variable that sets the thread count.
pub const THREADS_VAR: &str = "IDMESH_THREADS";

/// The thread count: `IDMESH_THREADS` when set, else the cores available (1 if unknown). An
/// unreadable value is an error naming it.
pub fn count() -> Result<usize, Error> {
    from_value(std::env::var(THREADS_VAR))
}

/// The thread count of a run whose options ask for `asked` (`None`: [`count`]). Zero is an
/// error.
pub fn resolve(asked: Option<usize>) -> Result<usize, Error> {
    match asked {
        None => count(),
        Some(0) => Err(Error::InvalidOption(
            "threads must be at least 1 (leave it unset for IDMESH_THREADS or all cores)".into(),
        )),
        Some(n) => Ok(n),
    }
}

fn from_value(v: Result<String, std::env::VarError>) -> Result<usize, Error> {
    let all = || {
        std::thread::available_parallelism()
            .map(|n| n.get())
            .unwrap_or(1)
    };
    let bad = |s: &str| {
        Error::InvalidOption(format!(
            "{THREADS_VAR}={s}: expected a positive number of threads"
        ))
    };
    match v {
        Err(std::env::VarError::NotPresent) => Ok(all()),
        Err(std::env::VarError::NotUnicode(s)) => Err(bad(&s.to_string_lossy())),
        Ok(s) if s.trim().is_empty() => Ok(all()),
        Ok(s) => match s.trim().parse::<usize>() {
            Ok(n) if n >= 1 => Ok(n),
            _ => Err(bad(&s)),
        },
    }
}

/// Splits `0..n` into at most `threads` contiguous chunks of at least `min_chunk` items and
/// runs `work(chunk, stop)` on each, the first on the calling thread (the one whose progress
/// callback and cancel are live) and the others on scoped threads. `stop` is raised when the
/// first chunk's work returns `Err` (a cancel or a fault found early), so that the others can
/// give up; they poll it. Results come back in chunk order. A panic on any thread is passed
/// on to the caller once all have finished.
pub(crate) fn chunks<R: Send, E: Send>(
    n: usize,
    threads: usize,
    min_chunk: usize,
    work: impl Fn(Range<usize>, &AtomicBool) -> Result<R, E> + Sync,
) -> Vec<Result<R, E>> {
    let k = threads.clamp(1, n.div_ceil(min_chunk.max(1)).max(1));
    let bounds: Vec<Range<usize>> = (0..k).map(|i| i * n / k..(i + 1) * n / k).collect();
    let stop = AtomicBool::new(false);
    if k == 1 {
        return vec![work(0..n, &stop)];
    }
    std::thread::scope(|s| {
        let others: Vec<_> = bounds[1..]
            .iter()
            .map(|r| {
                let (r, work, stop) = (r.clone(), &work, &stop);
                s.spawn(move || work(r, stop))
            })
            .collect();
        let first = work(bounds[0].clone(), &stop);
        if first.is_err() {
            stop.store(true, Ordering::Relaxed);
        }
        let mut out = vec![first];
        out.extend(join_all(others));
        out
    })
}

/// The results of `handles` in order, once all have finished; a panic on any of them is
/// passed on then.
fn join_all<T>(handles: Vec<std::thread::ScopedJoinHandle<'_, T>>) -> Vec<T> {
    let mut out = Vec::with_capacity(handles.len());
    let mut panic = None;
    for h in handles {
        match h.join() {
            Ok(r) => out.push(r),
            Err(p) => panic = Some(p),
        }
    }
    if let Some(p) = panic {
        std::panic::resume_unwind(p);
    }
    out
}

/// Splits `0..n` into blocks of `block` items (at least one block), deals them to `threads`
/// threads as each becomes free, the calling thread among them, and returns the blocks'
/// results in block order up to the first that failed (all of them when none did).
///
/// Where [`chunks`] gives each thread one part (for work that keeps per-part state), this
/// balances: the parts of a mesh's element table can differ in cost severalfold (slots
/// reused across the insertion rounds scatter the elements of some ranges in memory, and a
/// pass over them is bound by the random reads), and an even split then leaves one thread
/// idle for most of the run.
///
/// A failed block stops the blocks after it (not yet started, or polling
/// [`Block::stopped`]); every block before it runs to its end, so the first failure in
/// block order is the same for any thread count. A panic on any thread is passed on once
/// all have finished.
pub(crate) fn blocks<R: Send, E: Send>(
    n: usize,
    threads: usize,
    block: usize,
    work: impl Fn(Range<usize>, &Block) -> Result<R, E> + Sync,
) -> Vec<Result<R, E>> {
    let block = block.max(1);
    let count = n.div_ceil(block).max(1);
    let next = AtomicUsize::new(0);
    let failed = AtomicUsize::new(usize::MAX);
    let run = |on_caller: bool| {
        let mut out = Vec::new();
        loop {
            let index = next.fetch_add(1, Ordering::Relaxed);
            if index >= count || index > failed.load(Ordering::Relaxed) {
                return out;
            }
            let b = Block {
                index,
                on_caller,
                failed: &failed,
            };
            let r = work(index * block..((index + 1) * block).min(n), &b);
            if r.is_err() {
                failed.fetch_min(index, Ordering::Relaxed);
            }
            out.push((index, r));
        }
    };
    let k = threads.clamp(1, count);
    let mut all = if k == 1 {
        run(true)
    } else {
        std::thread::scope(|s| {
            let others: Vec<_> = (1..k).map(|_| s.spawn(|| run(false))).collect();
            let mut all = run(true);
            all.extend(join_all(others).into_iter().flatten());
            all
        })
    };
    all.sort_unstable_by_key(|(index, _)| *index);
    let end = all
        .iter()
        .position(|(_, r)| r.is_err())
        .map_or(all.len(), |i| i + 1);
    all.truncate(end);
    all.into_iter().map(|(_, r)| r).collect()
}

/// One block of [`blocks`]: whether it runs on the calling thread (the one whose progress
/// callback and cancel are live), and whether an earlier block has failed.
pub(crate) struct Block<'a> {
    index: usize,
    /// Runs on the calling thread.
    pub on_caller: bool,
    failed: &'a AtomicUsize,
}

impl Block<'_> {
    /// Whether an earlier block has failed, read only at every 4096th item `i`: the rest of
    /// this one is then not needed.
    #[inline]
    pub fn stopped(&self, i: usize) -> bool {
        i % 4096 == 0 && self.failed.load(Ordering::Relaxed) < self.index
    }
}

/// Whether `stop` has been raised, read only at every 4096th item `i` (the polling of
/// [`chunks`]' work).
#[inline]
pub(crate) fn stopped(i: usize, stop: &AtomicBool) -> bool {
    i % 4096 == 0 && stop.load(Ordering::Relaxed)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_cover_the_range_in_order_and_the_first_failure_wins_for_any_thread_count() {
        for n in [0, 1, 7, 64, 1000] {
            for threads in [1, 2, 3, 8] {
                let parts = blocks(n, threads, 10, |r, _| Ok::<_, ()>(r));
                let flat: Vec<usize> = parts.into_iter().flat_map(|p| p.unwrap()).collect();
                assert_eq!(flat, (0..n).collect::<Vec<_>>(), "n {n}, threads {threads}");
            }
        }
        // Items 333 and 777 fail: the parts end with the block of 333, and every block before
        // it ran to its end, whatever the thread count and whichever thread saw 777 first.
        for threads in [1, 2, 3, 8] {
            let parts = blocks(1000, threads, 10, |r, b| {
                let mut sum = 0;
                for i in r {
                    if !b.on_caller && b.stopped(i) {
                        break;
                    }
                    if i == 333 || i == 777 {
                        return Err(i);
                    }
                    sum += i;
                }
                Ok(sum)
            });
            assert_eq!(parts.len(), 34, "threads {threads}");
            assert_eq!(parts[33], Err(333));
            for (k, p) in parts[..33].iter().enumerate() {
                assert_eq!(*p, Ok((10 * k..10 * k + 10).sum::<usize>()));
            }
        }
    }

    #[test]
    fn the_count_is_the_variable_or_all_cores_and_bad_values_are_named() {
        use std::env::VarError;
        let all = from_value(Err(VarError::NotPresent)).unwrap();
        assert!(all >= 1);
        assert_eq!(from_value(Ok(String::new())).unwrap(), all);
        assert_eq!(from_value(Ok(" 3 ".into())).unwrap(), 3);
        for bad in ["0", "-2", "two", "1.5"] {
            match from_value(Ok(bad.into())) {
                Err(Error::InvalidOption(m)) => assert!(m.contains(&format!("={bad}")), "{m}"),
                other => panic!("{bad}: {other:?}"),
            }
        }
    }

    #[test]
    fn an_explicit_count_wins_and_zero_is_refused() {
        assert_eq!(resolve(Some(3)).unwrap(), 3);
        assert!(matches!(resolve(Some(0)), Err(Error::InvalidOption(_))));
    }

    #[test]
    fn chunks_cover_the_range_in_order_for_any_thread_count() {
        for threads in [1, 2, 3, 7, 64] {
            let out = chunks(1000, threads, 10, |r, _| Ok::<_, ()>(r));
            assert!(out.len() <= threads.min(100));
            let mut next = 0;
            for r in out {
                let r = r.unwrap();
                assert_eq!(r.start, next);
                next = r.end;
            }
            assert_eq!(next, 1000);
        }
        // Small ranges stay on one thread.
        assert_eq!(chunks(5, 8, 10, |r, _| Ok::<_, ()>(r)).len(), 1);
        assert_eq!(chunks(0, 8, 10, |r, _| Ok::<_, ()>(r)).len(), 1);
    }

    #[test]
    fn an_error_in_the_first_chunk_stops_the_others() {
        let out = chunks(1 << 20, 2, 1, |r, stop| {
            if r.start == 0 {
                return Err(());
            }
            // Wait (boundedly) for the stop the first chunk's error raises.
            for i in 0..1_000_000_000usize {
                if stopped(i * 4096, stop) {
                    return Ok(true);
                }
                std::hint::spin_loop();
            }
            Ok(false)
        });
        assert_eq!(out.len(), 2);
        assert!(out[0].is_err());
        assert_eq!(out[1], Ok(true));
    }

    #[test]
    fn a_panic_on_a_worker_reaches_the_caller() {
        let r = std::panic::catch_unwind(|| {
            chunks(100, 2, 1, |r, _| {
                if r.start > 0 {
                    panic!("worker");
                }
                Ok::<_, ()>(())
            })
        });
        assert!(r.is_err());
    }
}
