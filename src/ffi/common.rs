//! The machinery every C entry point shares, written once for both dimensions: the status
//! enum, the panic guard, the thread-local last error, pointer and count checks, the handle
//! lifecycle (`_new`/`_free`), lending output arrays, counts, validation, running a mesher,
//! the stage enum and the sizing- and progress-callback wrappers, and the options header.
//!
//! The per-dimension files ([`super::mesh2d`], [`super::mesh3d`]) declare the `extern "C"`
//! functions (cbindgen reads declarations, not macro expansions) and forward each body here,
//! through the `Handle` trait that says what differs: the input, the options and the mesh.

use std::cell::RefCell;
use std::ffi::{c_char, c_void, CString};
use std::mem::size_of;
use std::panic::{catch_unwind, AssertUnwindSafe};

use crate::error::{panic_message, Error};
use crate::progress::{ProgressFn, Stage};
use crate::NONE;

/// The "no index" value of the index arrays (a missing neighbour): `UINT32_MAX`.
pub const IDM_NONE: u32 = u32::MAX;

/// The result of every status-returning call. The values are fixed (ABI).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum idm_status {
    /// Success.
    IDM_OK = 0,
    /// Refinement stopped at the Steiner point cap (`max_steiner`); the mesh is valid,
    /// conforming and readable, but does not meet every quality or size bound.
    IDM_INCOMPLETE = 1,
    /// A required pointer argument was NULL (the message names it).
    IDM_ERR_NULL_POINTER = 2,
    /// A bad count or option value (the message says which).
    IDM_ERR_INVALID_ARGUMENT = 3,
    /// The input is invalid (the message names the offending item; `idm_last_error_item`
    /// gives its kind and index).
    IDM_ERR_INVALID_INPUT = 4,
    /// A getter was called with no mesh: before a successful refine, or after the input or
    /// options changed.
    IDM_ERR_NO_MESH = 5,
    /// A requested feature is not implemented.
    IDM_ERR_UNSUPPORTED = 6,
    /// A caught panic or a failed internal invariant: a bug in idmesh, please report it.
    IDM_ERR_INTERNAL = 7,
    /// The progress callback asked to stop (see `idm_progress_fn`): there is no mesh, the
    /// input and options are kept, and the handle can be refined again or freed.
    IDM_CANCELLED = 8,
}

/// The stage a run is in, as the progress callback receives it (see `idm_progress_fn`). A run
/// goes through them in this order, possibly skipping some. The values are fixed (ABI).
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum idm_stage {
    /// Checking the input.
    IDM_STAGE_READING = 0,
    /// Inserting the input points (`done` counts them, `estimate` is their number).
    IDM_STAGE_DELAUNAY = 1,
    /// Recovering segments and facets and carving holes (`done`: Steiner points so far).
    IDM_STAGE_BOUNDARY = 2,
    /// Quality and size refinement (`done`: Steiner points so far; `estimate`: `done` plus
    /// the work queued, which changes as refinement goes).
    IDM_STAGE_REFINING = 3,
    /// Removing slivers (3D).
    IDM_STAGE_SLIVERS = 4,
    /// Building the output mesh.
    IDM_STAGE_OUTPUT = 5,
}

impl From<Stage> for idm_stage {
    fn from(s: Stage) -> Self {
        match s {
            Stage::Reading => idm_stage::IDM_STAGE_READING,
            Stage::Delaunay => idm_stage::IDM_STAGE_DELAUNAY,
            Stage::Boundary => idm_stage::IDM_STAGE_BOUNDARY,
            Stage::Refining => idm_stage::IDM_STAGE_REFINING,
            Stage::Slivers => idm_stage::IDM_STAGE_SLIVERS,
            Stage::Output => idm_stage::IDM_STAGE_OUTPUT,
        }
    }
}

/// A progress callback: called during `idm_mesher2d_refine`, `idm_mesher3d_refine` and
/// `idm_mesher3d_delaunay` with the stage, the work done in it (never decreasing within a
/// stage) and an estimate of the stage's total (0 when unknown; it may change), and the
/// `user` pointer given to `idm_mesherNd_set_progress`. Return 0 to go on, nonzero to cancel:
/// the call then returns `IDM_CANCELLED` promptly (within a few tens of milliseconds).
///
/// It is called at the start of each stage and then at most about 50 times per second, from
/// the thread that called refine; it should return quickly. It must return normally: no C++
/// exception may leave it and it must not `longjmp` out (the library's frames would be
/// skipped and their memory leaked or corrupted); it must not call back into the same handle.
pub type idm_progress_fn = Option<
    unsafe extern "C" fn(stage: idm_stage, done: u64, estimate: u64, user: *mut c_void) -> i32,
>;

/// A failed (or incomplete) call: the status to return, the message for `idm_last_error` and,
/// for invalid input, the error itself (for `idm_last_error_item`).
pub(crate) struct Failure {
    status: idm_status,
    message: String,
    input: Option<crate::error::InputError>,
}

impl Failure {
    pub(crate) fn new(status: idm_status, message: impl Into<String>) -> Self {
        Failure {
            status,
            message: message.into(),
            input: None,
        }
    }

    pub(crate) fn null(what: &str) -> Self {
        Failure::new(
            idm_status::IDM_ERR_NULL_POINTER,
            format!("argument `{what}` is NULL"),
        )
    }

    pub(crate) fn invalid(message: impl Into<String>) -> Self {
        Failure::new(idm_status::IDM_ERR_INVALID_ARGUMENT, message)
    }
}

impl From<Error> for Failure {
    fn from(e: Error) -> Self {
        let status = match &e {
            Error::Input(_) => idm_status::IDM_ERR_INVALID_INPUT,
            Error::InvalidOption(_) => idm_status::IDM_ERR_INVALID_ARGUMENT,
            Error::Unsupported(_) => idm_status::IDM_ERR_UNSUPPORTED,
            Error::Internal(_) => idm_status::IDM_ERR_INTERNAL,
            Error::Cancelled(_) => idm_status::IDM_CANCELLED,
        };
        let mut f = Failure::new(status, e.to_string());
        if let Error::Input(input) = e {
            f.input = Some(input);
        }
        f
    }
}

pub(crate) type CallResult = Result<(), Failure>;

/// This thread's last failure: its message, and the input error behind it when there is one.
#[derive(Default)]
pub(crate) struct LastError {
    pub(crate) message: CString,
    pub(crate) input: Option<crate::error::InputError>,
}

thread_local! {
    /// The last failure on this thread; empty after a success.
    pub(crate) static LAST_ERROR: RefCell<LastError> = RefCell::new(LastError::default());
}

/// Stores `f` as this thread's last error. Interior NULs (impossible in our own messages, but
/// a panic payload could carry one) are escaped so the text is never cut short.
fn set_last_error(f: Failure) {
    let message = CString::new(f.message.replace('\0', "\\0")).unwrap_or_default();
    // `try_with` fails only during thread teardown, when nobody can read the message anyway.
    let _ = LAST_ERROR.try_with(|e| {
        *e.borrow_mut() = LastError {
            message,
            input: f.input,
        }
    });
}

/// Clears this thread's last error, without reallocating when it is already empty so that a
/// pointer from `idm_last_error` stays valid across a run of successful calls.
fn clear_last_error() {
    let _ = LAST_ERROR.try_with(|e| {
        let mut e = e.borrow_mut();
        if !e.message.as_bytes().is_empty() {
            e.message = CString::default();
        }
        e.input = None;
    });
}

/// Runs the body of a status-returning entry point: catches panics, maps the result to a
/// status and records or clears the thread's last error.
pub(crate) fn guard(body: impl FnOnce() -> CallResult) -> idm_status {
    let outcome = catch_unwind(AssertUnwindSafe(body)).unwrap_or_else(|payload| {
        let what = panic_message(payload.as_ref());
        Err(Failure::from(Error::Internal(format!("panic: {what}"))))
    });
    match outcome {
        Ok(()) => {
            clear_last_error();
            idm_status::IDM_OK
        }
        Err(f) => {
            let status = f.status;
            set_last_error(f);
            status
        }
    }
}

/// The message of the last failed `idm_` call on this thread, or "" when the last
/// status-returning call succeeded. Never NULL. The string is owned by the library and stays
/// valid until the next `idm_` call on this thread.
#[no_mangle]
pub extern "C" fn idm_last_error() -> *const c_char {
    static EMPTY: &[u8] = b"\0";
    LAST_ERROR
        .try_with(|e| e.borrow().message.as_ptr())
        .unwrap_or(EMPTY.as_ptr().cast())
}

/// The library version ("major.minor.patch"), a static string.
#[no_mangle]
pub extern "C" fn idm_version() -> *const c_char {
    concat!(env!("CARGO_PKG_VERSION"), "\0").as_ptr().cast()
}

/// `count * k`, or an error naming `what` when it overflows.
pub(crate) fn scaled(count: usize, k: usize, what: &str) -> Result<usize, Failure> {
    count
        .checked_mul(k)
        .ok_or_else(|| Failure::invalid(format!("`{what}` = {count} is too large")))
}

/// Borrows `len` elements at `ptr` as a slice after checking what can be checked: NULL (allowed
/// only when `len` is 0), alignment, and that the byte length fits `isize`.
///
/// # Safety
/// When the checks pass, `ptr` must point to `len` readable elements that stay unchanged during
/// the call (the caller's contract, documented in the header).
pub(crate) unsafe fn input_slice<'a, T>(
    ptr: *const T,
    len: usize,
    what: &str,
) -> Result<&'a [T], Failure> {
    if len == 0 {
        return Ok(&[]);
    }
    if ptr.is_null() {
        return Err(Failure::new(
            idm_status::IDM_ERR_NULL_POINTER,
            format!("argument `{what}` is NULL but {len} values were requested from it"),
        ));
    }
    if !ptr.is_aligned() {
        return Err(Failure::invalid(format!(
            "argument `{what}` is not suitably aligned"
        )));
    }
    match len.checked_mul(size_of::<T>()) {
        Some(bytes) if bytes <= isize::MAX as usize => {}
        _ => {
            return Err(Failure::invalid(format!(
                "argument `{what}`: {len} values is too large"
            )))
        }
    }
    // SAFETY: non-null, aligned, size in range; readability is the caller's contract.
    Ok(unsafe { std::slice::from_raw_parts(ptr, len) })
}

/// Like [`input_slice`] for a nullable array: NULL gives `None`.
///
/// # Safety
/// As [`input_slice`].
pub(crate) unsafe fn optional_slice<'a, T>(
    ptr: *const T,
    len: usize,
    what: &str,
) -> Result<Option<&'a [T]>, Failure> {
    if ptr.is_null() {
        Ok(None)
    } else {
        // SAFETY: forwarded contract.
        unsafe { input_slice(ptr, len, what) }.map(Some)
    }
}

/// Checks an out-parameter pointer: non-NULL and aligned.
pub(crate) fn check_out<T>(ptr: *mut T, what: &str) -> CallResult {
    if ptr.is_null() {
        Err(Failure::null(what))
    } else if !ptr.is_aligned() {
        Err(Failure::invalid(format!(
            "argument `{what}` is not suitably aligned"
        )))
    } else {
        Ok(())
    }
}

/// Checks an optional out-parameter: NULL (not wanted) or aligned.
fn check_optional_out<T>(ptr: *mut T, what: &str) -> CallResult {
    if ptr.is_null() {
        Ok(())
    } else {
        check_out(ptr, what)
    }
}

/// Writes through an optional out-parameter already checked by [`check_out`] (NULL: skipped).
///
/// # Safety
/// `ptr` must be NULL or valid for a write of `T`.
pub(crate) unsafe fn write_out<T>(ptr: *mut T, value: T) {
    if !ptr.is_null() {
        // SAFETY: the caller's contract.
        unsafe { ptr.write(value) };
    }
}

/// Pointer to the first element of an output array, or NULL when it is empty (an empty `Vec`'s
/// dangling pointer must not reach C code).
pub(crate) fn array_ptr<T, U>(v: &[T]) -> *const U {
    if v.is_empty() {
        std::ptr::null()
    } else {
        v.as_ptr().cast()
    }
}

/// Grows `v` by `extra` elements, reporting allocation failure instead of aborting.
pub(crate) fn reserve<T>(v: &mut Vec<T>, extra: usize, what: &str) -> CallResult {
    v.try_reserve(extra)
        .map_err(|_| Failure::invalid(format!("out of memory adding {extra} {what}")))
}

/// Rejects a count that would push the number of items past what `uint32_t` indices address.
pub(crate) fn check_index_room(have: usize, extra: usize, what: &str) -> CallResult {
    match have.checked_add(extra) {
        Some(total) if total < NONE as usize => Ok(()),
        _ => Err(Failure::invalid(format!(
            "adding {extra} {what} to {have} exceeds the uint32_t index range"
        ))),
    }
}

/// Appends the items of `flat` (K values each) to `items` and their markers to `markers`
/// (`default` for each when the caller gave none), after the index-range and memory checks;
/// nothing is appended when a check fails.
fn append_marked<T: Copy, const K: usize>(
    items: &mut Vec<[T; K]>,
    markers: &mut Vec<i32>,
    flat: &[T],
    given: Option<&[i32]>,
    default: i32,
    what: &str,
) -> CallResult {
    let count = flat.len() / K;
    check_index_room(items.len(), count, what)?;
    reserve(items, count, what)?;
    reserve(markers, count, "markers")?;
    items.extend(flat.chunks_exact(K).map(|c| std::array::from_fn(|i| c[i])));
    match given {
        Some(mk) => markers.extend_from_slice(mk),
        None => markers.resize(items.len(), default),
    }
    Ok(())
}

/// Picks an item list of a handle and its parallel marker list.
pub(crate) type MarkedLists<H, T, const K: usize> = fn(&mut H) -> (&mut Vec<[T; K]>, &mut Vec<i32>);

/// The body of the `_add_points` / `_add_segments` calls: appends `count` items of K values
/// read at `flat` (the argument named `names[0]`), with their markers (NULL: `default` for
/// each), to the lists `lists` picks (`names[1]` names the items in messages).
///
/// # Safety
/// `m` a live handle; `flat` and (when not NULL) `markers` hold the stated number of values.
pub(crate) unsafe fn add_marked<H: Handle, T: Copy, const K: usize>(
    m: *mut H,
    flat: *const T,
    count: usize,
    markers: *const i32,
    default: i32,
    names: [&str; 2],
    lists: MarkedLists<H, T, K>,
) -> idm_status {
    // SAFETY (all blocks here): the caller's contract, checked as far as possible.
    unsafe {
        change(m, |m| {
            let flat = input_slice(flat, scaled(count, K, "count")?, names[0])?;
            let given = optional_slice(markers, count, "markers")?;
            let (items, item_markers) = lists(m);
            append_marked(items, item_markers, flat, given, default, names[1])
        })
    }
}

/// What the shared entry-point bodies need to know about a mesher handle.
pub(crate) trait Handle: Sized {
    /// The output mesh.
    type Mesh;
    /// The calls that make a mesh, as the "no mesh" message names them.
    const MAKERS: &'static str;
    /// A handle with no input, the default options and no mesh.
    fn empty() -> Self;
    /// The mesh slot: `None` until a successful run, and again after any change.
    fn mesh_slot(&mut self) -> &mut Option<Self::Mesh>;
    /// The mesh, if any.
    fn mesh(&self) -> Option<&Self::Mesh>;
    /// Whether `mesh` meets every bound, and how many Steiner points it has.
    fn progress(mesh: &Self::Mesh) -> (bool, usize);
    /// Checks the mesh's invariants exactly; the message names the first violation.
    fn check(&self, mesh: &Self::Mesh) -> Result<(), String>;
}

/// Implements [`Handle`] for a handle struct with the fields `$input` (the input, of a
/// `Default` type), `opts` (the options) and `mesh` (`Option` of the mesh, which has
/// `complete` and `steiner_points`); `$check` validates `$mesh` for handle `$h`.
macro_rules! impl_handle {
    ($handle:ident { $input:ident, $makers:expr }, $mesh_ty:ty, |$h:ident, $mesh:ident| $check:expr) => {
        impl Handle for $handle {
            type Mesh = $mesh_ty;
            const MAKERS: &'static str = $makers;

            fn empty() -> Self {
                $handle {
                    $input: Default::default(),
                    opts: Default::default(),
                    mesh: None,
                }
            }

            fn mesh_slot(&mut self) -> &mut Option<$mesh_ty> {
                &mut self.mesh
            }

            fn mesh(&self) -> Option<&$mesh_ty> {
                self.mesh.as_ref()
            }

            fn progress(mesh: &$mesh_ty) -> (bool, usize) {
                (mesh.complete, mesh.steiner_points)
            }

            fn check(&self, $mesh: &$mesh_ty) -> Result<(), String> {
                let $h = self;
                $check
            }
        }
    };
}
pub(crate) use impl_handle;

/// Borrows the handle mutably.
///
/// # Safety
/// `m` must be NULL or a live handle not used elsewhere meanwhile.
pub(crate) unsafe fn handle_mut<'a, H: 'a>(m: *mut H) -> Result<&'a mut H, Failure> {
    // SAFETY: the caller's contract.
    unsafe { m.as_mut() }.ok_or_else(|| Failure::null("m"))
}

/// Borrows the handle and its mesh, or reports that there is none.
///
/// # Safety
/// As [`handle_mut`].
pub(crate) unsafe fn mesh_of<'a, H: Handle + 'a>(m: *const H) -> Result<&'a H::Mesh, Failure> {
    // SAFETY: the caller's contract.
    let m = unsafe { m.as_ref() }.ok_or_else(|| Failure::null("m"))?;
    m.mesh().ok_or_else(|| {
        Failure::new(
            idm_status::IDM_ERR_NO_MESH,
            format!(
                "no mesh: call {} first (the mesh is dropped when that call fails or the input \
                 or options change)",
                H::MAKERS
            ),
        )
    })
}

/// Creates an empty handle in `*out`.
///
/// # Safety
/// `out` must be NULL (an error) or valid for writing a pointer.
pub(crate) unsafe fn new_handle<H: Handle>(out: *mut *mut H) -> idm_status {
    guard(|| {
        check_out(out, "out")?;
        // SAFETY: checked above.
        unsafe { out.write(Box::into_raw(Box::new(H::empty()))) };
        Ok(())
    })
}

/// Destroys a handle. NULL is a no-op.
///
/// # Safety
/// `m` must be NULL or a handle from `new_handle` not freed before and not in use.
pub(crate) unsafe fn free_handle<H>(m: *mut H) {
    if m.is_null() {
        return;
    }
    // Dropping the handle runs no user code except the release of the sizing closure (a plain
    // Arc); the guard keeps a panic there from unwinding into C all the same. The status is
    // dropped because `_free` returns nothing.
    let _ = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: the caller's contract.
        drop(unsafe { Box::from_raw(m) });
    }));
}

/// The body of an input call: borrows the handle, runs `change` on it and drops the mesh when
/// the change succeeded (a failed change must leave the handle as it was).
///
/// # Safety
/// As [`handle_mut`].
pub(crate) unsafe fn change<H: Handle>(
    m: *mut H,
    change: impl FnOnce(&mut H) -> CallResult,
) -> idm_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let m = unsafe { handle_mut(m) }?;
        change(m)?;
        *m.mesh_slot() = None;
        Ok(())
    })
}

/// Runs a mesher on the handle's input, replacing any previous mesh. With `bounded`, a mesh
/// that stopped at the Steiner cap is kept but reported as `IDM_INCOMPLETE`.
///
/// # Safety
/// As [`handle_mut`].
pub(crate) unsafe fn run<H: Handle>(
    m: *mut H,
    bounded: bool,
    mesher: impl FnOnce(&H) -> Result<H::Mesh, Error>,
) -> idm_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let m = unsafe { handle_mut(m) }?;
        // Dropped first so that a failure (or a panic caught by the guard) leaves no stale mesh.
        *m.mesh_slot() = None;
        let mesh = mesher(m)?;
        let (complete, steiner) = H::progress(&mesh);
        *m.mesh_slot() = Some(mesh);
        if complete || !bounded {
            Ok(())
        } else {
            Err(Failure::new(
                idm_status::IDM_INCOMPLETE,
                format!(
                    "refinement stopped at the Steiner point cap after {steiner} Steiner \
                     points: the mesh is valid but does not meet every bound"
                ),
            ))
        }
    })
}

/// The body of every array getter: checks the handle and the out-pointers, then lends the
/// array chosen by `field` (NULL when empty), its parallel marker array when `markers` is not
/// NULL (getters without markers pass NULL and an empty slice), and the element count.
///
/// # Safety
/// As for the getters: `m` a live handle, `out` and `count` valid for a write, `markers` NULL
/// or valid for a write.
pub(crate) unsafe fn lend<H: Handle, T, U>(
    m: *const H,
    out: *mut *const U,
    markers: *mut *const i32,
    count: *mut usize,
    what: &str,
    field: impl FnOnce(&H::Mesh) -> (&[T], &[i32]),
) -> idm_status {
    guard(|| {
        // SAFETY (all blocks here): the caller's contract, checked as far as possible.
        let mesh = unsafe { mesh_of(m) }?;
        check_out(out, what)?;
        check_optional_out(markers, "markers")?;
        check_out(count, "count")?;
        let (v, mk) = field(mesh);
        unsafe {
            out.write(array_ptr(v));
            write_out(markers, array_ptr(mk));
            count.write(v.len());
        }
        Ok(())
    })
}

/// [`lend`] for an array without markers.
///
/// # Safety
/// As [`lend`].
pub(crate) unsafe fn lend_plain<H: Handle, T, U>(
    m: *const H,
    out: *mut *const U,
    count: *mut usize,
    what: &str,
    field: impl FnOnce(&H::Mesh) -> &[T],
) -> idm_status {
    // SAFETY: the caller's contract, forwarded.
    unsafe {
        lend(m, out, std::ptr::null_mut(), count, what, |mesh| {
            (field(mesh), &[])
        })
    }
}

/// The body of the `_counts` getters: each out-pointer (NULL when not wanted) gets the size
/// `sizes` gives at its position.
///
/// # Safety
/// `m` a live handle; each out-pointer NULL or valid for a write.
pub(crate) unsafe fn counts<H: Handle, const N: usize>(
    m: *const H,
    outs: [(*mut usize, &str); N],
    sizes: impl FnOnce(&H::Mesh) -> [usize; N],
) -> idm_status {
    guard(|| {
        // SAFETY (all blocks here): the caller's contract, checked as far as possible.
        let mesh = unsafe { mesh_of(m) }?;
        for (p, what) in outs {
            check_optional_out(p, what)?;
        }
        for ((p, _), n) in outs.into_iter().zip(sizes(mesh)) {
            unsafe { write_out(p, n) };
        }
        Ok(())
    })
}

/// The body of the `_validate` calls: `IDM_OK`, or `IDM_ERR_INTERNAL` naming the violation.
///
/// # Safety
/// `m` a live handle.
pub(crate) unsafe fn validate<H: Handle>(m: *const H) -> idm_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let mesh = unsafe { mesh_of(m) }?;
        // SAFETY: `mesh_of` has just checked the pointer.
        let h = unsafe { &*m };
        h.check(mesh).map_err(|msg| {
            Failure::new(
                idm_status::IDM_ERR_INTERNAL,
                format!("mesh validation failed: {msg}"),
            )
        })
    })
}

/// A C callback of type `F` (a sizing test or a progress callback) with its user pointer;
/// each dimension calls a sizing `f` with its own arguments.
#[derive(Clone, Copy)]
pub(crate) struct CCallback<F> {
    pub(crate) f: F,
    pub(crate) user: *mut c_void,
}

// SAFETY: the raw `user` pointer is what makes this type neither Send nor Sync. The mesher calls
// the function only inside `idm_mesherNd_refine` (or `_delaunay`), from the thread that called
// it, and keeps no copy after the handle is freed. Whether `user` (and the callback) may be used
// from the thread that calls refine is the caller's contract, stated in the header at
// `idm_sizingNd_fn`, `idm_progress_fn` and their setters; Rust cannot check it.
unsafe impl<F: Send> Send for CCallback<F> {}
// SAFETY: as for Send: concurrent use would require the caller to refine one handle from two
// threads at once, which the header forbids.
unsafe impl<F: Sync> Sync for CCallback<F> {}

/// The C function of `idm_progress_fn`.
type ProgressFnC = unsafe extern "C" fn(idm_stage, u64, u64, *mut c_void) -> i32;

impl CCallback<ProgressFnC> {
    /// Calls the C progress function: whether to go on. A method so that the closure captures
    /// the whole `Send + Sync` struct, not its bare raw pointer.
    fn go_on(&self, stage: Stage, done: u64, estimate: u64) -> bool {
        // SAFETY: the function pointer and `user` are the caller's contract (see
        // `idm_progress_fn` and `idm_mesherNd_set_progress`).
        unsafe { (self.f)(stage.into(), done, estimate, self.user) == 0 }
    }
}

/// The body of the `_set_progress` calls: wraps the C callback (NULL clears it) and hands it to
/// `install`. The mesh is kept: a callback does not change what refine makes.
///
/// # Safety
/// `m` a live handle; `f` NULL or a function with the `idm_progress_fn` contract.
pub(crate) unsafe fn set_progress<H: Handle>(
    m: *mut H,
    f: idm_progress_fn,
    user: *mut c_void,
    install: impl FnOnce(&mut H, Option<ProgressFn>),
) -> idm_status {
    guard(|| {
        // SAFETY: the caller's contract.
        let m = unsafe { handle_mut(m) }?;
        let progress = f.map(|f| {
            let c = CCallback { f, user };
            std::sync::Arc::new(move |s, done, estimate| {
                if c.go_on(s, done, estimate) {
                    std::ops::ControlFlow::Continue(())
                } else {
                    std::ops::ControlFlow::Break(())
                }
            }) as ProgressFn
        });
        install(m, progress);
        Ok(())
    })
}

/// A bound of the C options as the Rust options hold it: `<= 0` means none.
pub(crate) fn positive(x: f64) -> Option<f64> {
    (x > 0.0).then_some(x)
}

/// The Steiner cap as C holds it: `-1` for none.
pub(crate) fn steiner_cap_to_c(cap: Option<u64>) -> i64 {
    cap.map_or(-1, |n| i64::try_from(n).unwrap_or(i64::MAX))
}

/// Rejects NaN in the named real options.
pub(crate) fn reject_nan(values: &[(&str, f64)]) -> CallResult {
    match values.iter().find(|(_, x)| x.is_nan()) {
        Some((name, _)) => Err(Failure::invalid(format!("option {name} is NaN"))),
        None => Ok(()),
    }
}

/// An options struct that can grow: its first field is `size_t struct_size`, the size of the
/// struct as the caller was compiled, so that a library and a caller built against different
/// versions of the header agree on how many bytes are theirs.
///
/// * A caller's struct smaller than [`Self::BASELINE`] (the size in 0.2.0, the first version
///   with `struct_size`) is refused: it is not an options struct of any version.
/// * A smaller struct than this library's (a caller built against an older header) is read
///   up to its size; the newer fields keep their defaults.
/// * A larger struct (a caller built against a newer header) is accepted when every byte
///   beyond the fields this library knows is zero (the newer fields are unset), and refused
///   with `IDM_ERR_UNSUPPORTED` otherwise: a request this library cannot honour is never
///   silently dropped.
///
/// # Safety
/// Implementors are `#[repr(C)]`, start with a `usize` `struct_size`, and every bit pattern of
/// their fields is valid (integers and floats only).
pub(crate) unsafe trait SizedOptions: Copy {
    /// The struct's size in the first version that had `struct_size`.
    const BASELINE: usize;
    /// The C name, for messages.
    const NAME: &'static str;
    /// The defaults, with `struct_size` set to this library's size.
    fn defaults() -> Self;
}

/// Fills the caller's options struct of `size` bytes at `out` with the defaults: the bytes this
/// library knows get the default values (and `struct_size` gets `size`); bytes beyond them, a
/// newer header's fields, are zeroed. NULL, a misaligned pointer or a size smaller than any
/// version's struct leave `out` untouched (the `_default` functions return nothing).
///
/// # Safety
/// `out` must be NULL or valid for writing `size` bytes.
pub(crate) unsafe fn init_options<T: SizedOptions>(out: *mut T, size: usize) {
    if out.is_null() || !out.is_aligned() || size < T::BASELINE || size > isize::MAX as usize {
        return;
    }
    let mut value = T::defaults();
    // SAFETY: `T` starts with its `usize` size field (the trait's contract).
    unsafe { (&mut value as *mut T).cast::<usize>().write(size) };
    let known = size.min(size_of::<T>());
    // SAFETY: `out` is valid for `size` bytes (the caller's contract) and `value` for
    // `size_of::<T>()`; the two do not overlap.
    unsafe {
        let dst = out.cast::<u8>();
        std::ptr::copy_nonoverlapping((&value as *const T).cast::<u8>(), dst, known);
        std::ptr::write_bytes(dst.add(known), 0, size - known);
    }
}

/// Reads the caller's options struct at `ptr` by the rules of [`SizedOptions`].
///
/// # Safety
/// `ptr` must be NULL (an error) or point to a struct of at least `struct_size` readable bytes
/// whose `struct_size` field is initialised.
pub(crate) unsafe fn read_options<T: SizedOptions>(ptr: *const T) -> Result<T, Failure> {
    if ptr.is_null() {
        return Err(Failure::null("opts"));
    }
    if !ptr.is_aligned() {
        return Err(Failure::invalid("argument `opts` is not suitably aligned"));
    }
    // SAFETY: non-null and aligned; the size field is the caller's contract.
    let size = unsafe { ptr.cast::<usize>().read() };
    if size < T::BASELINE || size > isize::MAX as usize {
        return Err(Failure::invalid(format!(
            "opts.struct_size is {size}, not the size of an {} (this library's is {}): fill \
             the struct with {}_default first",
            T::NAME,
            size_of::<T>(),
            T::NAME
        )));
    }
    let known = size.min(size_of::<T>());
    // SAFETY: `size` bytes are readable (the caller's contract).
    let bytes = unsafe { std::slice::from_raw_parts(ptr.cast::<u8>(), size) };
    if let Some(k) = bytes[known..].iter().position(|&b| b != 0) {
        return Err(Failure::new(
            idm_status::IDM_ERR_UNSUPPORTED,
            format!(
                "opts sets a field this library version ({}) does not know (byte {} of a \
                 {size}-byte {}; this library's is {} bytes)",
                env!("CARGO_PKG_VERSION"),
                known + k,
                T::NAME,
                size_of::<T>()
            ),
        ));
    }
    let mut value = T::defaults();
    // SAFETY: `known` bytes of both are valid and every bit pattern is a valid `T` field value
    // (the trait's contract); they do not overlap.
    unsafe {
        std::ptr::copy_nonoverlapping(bytes.as_ptr(), (&mut value as *mut T).cast::<u8>(), known)
    };
    Ok(value)
}

/// Helpers of the per-dimension tests.
#[cfg(test)]
pub(crate) mod testing {
    use super::{free_handle, idm_last_error, idm_status, new_handle, Handle};
    use std::ffi::CStr;

    /// The current thread's last error as a Rust string.
    pub(crate) fn last_error() -> String {
        // SAFETY: idm_last_error never returns NULL and the string lives until the next call.
        unsafe { CStr::from_ptr(idm_last_error()) }
            .to_str()
            .unwrap()
            .to_string()
    }

    /// A fresh handle made by `_new`, freed by `_free` on drop so a failing assertion does not
    /// leak it.
    pub(crate) struct TestHandle<H: Handle>(pub(crate) *mut H);

    impl<H: Handle> TestHandle<H> {
        pub(crate) fn new() -> Self {
            let mut m: *mut H = std::ptr::null_mut();
            assert_eq!(unsafe { new_handle(&mut m) }, idm_status::IDM_OK);
            assert!(!m.is_null());
            TestHandle(m)
        }

        pub(crate) fn get(&self) -> &H {
            unsafe { &*self.0 }
        }

        pub(crate) fn get_mut(&mut self) -> &mut H {
            unsafe { &mut *self.0 }
        }
    }

    impl<H: Handle> Drop for TestHandle<H> {
        fn drop(&mut self) {
            unsafe { free_handle(self.0) };
        }
    }
}
