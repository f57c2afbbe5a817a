//! The 3D C API under random call sequences and arguments (NULL pointers and bad lengths
//! included): every call returns a status, a successful refine's mesh validates, an internal
//! error never hides a panic, and the handle is always freed (the leak checker sees the rest).
#![no_main]
use arbitrary::Arbitrary;
use idmesh::ffi::common::{idm_last_error, idm_status};
use idmesh::ffi::mesh3d::*;
use libfuzzer_sys::fuzz_target;
use std::ptr::{null, null_mut};

mod common;

#[derive(Arbitrary, Debug)]
enum Call {
    Points {
        xyz: Vec<f64>,
        claim: u8,
        null_xyz: bool,
    },
    Segments {
        ab: Vec<u32>,
        claim: u8,
    },
    Facet {
        idx: Vec<u8>,
        loops: u8,
    },
    Cube {
        scale: i8,
        shift: i8,
    },
    Hole {
        xyz: [f64; 3],
    },
    Options {
        ratio: f64,
        volume: f64,
        keep_surface: bool,
        steiner: i16,
    },
    Refine,
    Delaunay,
    Read {
        null_count: bool,
    },
    Validate,
    Renew,
}

fn last_error() -> String {
    // SAFETY: the library's string is NUL-terminated and lives until the next call.
    unsafe { std::ffi::CStr::from_ptr(idm_last_error()) }
        .to_string_lossy()
        .into_owned()
}

fn checked(s: idm_status) -> idm_status {
    if s == idm_status::IDM_ERR_INTERNAL {
        let e = last_error();
        assert!(!e.contains("caught a panic"), "{e}");
    }
    s
}

fuzz_target!(|calls: Vec<Call>| {
    if calls.len() > 24 {
        return;
    }
    let mut m: *mut idm_mesher3d = null_mut();
    // SAFETY (all blocks): `m` is a live handle from `_new`; every array passed holds at least
    // the count passed unless the call is meant to be refused (a NULL pointer).
    assert_eq!(unsafe { idm_mesher3d_new(&mut m) }, idm_status::IDM_OK);
    for call in calls {
        match call {
            Call::Points {
                xyz,
                claim,
                null_xyz,
            } => {
                let n = (claim as usize).min(xyz.len() / 3);
                let p = if null_xyz { null() } else { xyz.as_ptr() };
                checked(unsafe { idm_mesher3d_add_points(m, p, n, null()) });
            }
            Call::Segments { ab, claim } => {
                let n = (claim as usize).min(ab.len() / 2);
                checked(unsafe { idm_mesher3d_add_segments(m, ab.as_ptr(), n, null()) });
            }
            Call::Facet { idx, loops } => {
                let idx: Vec<u32> = idx.iter().map(|&i| i as u32 % 32).collect();
                let k = (loops as usize % 3).min(idx.len());
                let mut offsets: Vec<usize> = (0..=k).map(|j| j * idx.len() / k.max(1)).collect();
                if k == 0 {
                    offsets = vec![0];
                }
                checked(unsafe {
                    idm_mesher3d_add_facet(m, idx.as_ptr(), offsets.as_ptr(), k, null(), 0, 1)
                });
            }
            Call::Cube { scale, shift } => {
                let (s, t) = (10f64.powi(scale as i32 % 40), 10f64.powi(shift as i32 % 8));
                let xyz: Vec<f64> = (0..8)
                    .flat_map(|k| [k & 1, (k >> 1) & 1, (k >> 2) & 1].map(|b| b as f64 * s + t))
                    .collect();
                checked(unsafe { idm_mesher3d_add_points(m, xyz.as_ptr(), 8, null()) });
                let mut base = 0usize;
                checked(unsafe {
                    idm_mesher3d_counts(m, &mut base, null_mut(), null_mut(), null_mut())
                });
                for q in [
                    [0, 1, 3, 2],
                    [4, 5, 7, 6],
                    [0, 1, 5, 4],
                    [2, 3, 7, 6],
                    [0, 2, 6, 4],
                    [1, 3, 7, 5],
                ] {
                    let q = q.map(|v: u32| v);
                    let offsets = [0usize, 4];
                    checked(unsafe {
                        idm_mesher3d_add_facet(m, q.as_ptr(), offsets.as_ptr(), 1, null(), 0, 2)
                    });
                }
            }
            Call::Hole { xyz } => {
                checked(unsafe { idm_mesher3d_add_hole(m, xyz.as_ptr()) });
            }
            Call::Options {
                ratio,
                volume,
                keep_surface,
                steiner,
            } => {
                let mut o = std::mem::MaybeUninit::<idm_options3d>::uninit();
                unsafe { idm_options3d_default(o.as_mut_ptr()) };
                let mut o = unsafe { o.assume_init() };
                o.radius_edge = ratio;
                o.max_volume = volume;
                o.keep_surface = keep_surface as i32;
                // The meshing targets' budget: a tiny volume bound on the cube with the cap
                // at 400k took 79 s under the fuzzer's instrumentation (not a hang, but past
                // libFuzzer's 20 s timeout), and at 20,000 replaying the corpus took 97 s;
                // the smoke run looks for crashes, not size.
                o.max_steiner =
                    ((steiner as i64).abs().max(1) * 16).min(common::FUZZ_BUDGET as i64);
                checked(unsafe { idm_mesher3d_set_options(m, &o) });
            }
            Call::Refine => {
                if checked(unsafe { idm_mesher3d_refine(m) }) == idm_status::IDM_OK {
                    assert_eq!(
                        unsafe { idm_mesher3d_validate(m) },
                        idm_status::IDM_OK,
                        "{}",
                        last_error()
                    );
                }
            }
            Call::Delaunay => {
                if checked(unsafe { idm_mesher3d_delaunay(m) }) == idm_status::IDM_OK {
                    assert_eq!(
                        unsafe { idm_mesher3d_validate(m) },
                        idm_status::IDM_OK,
                        "{}",
                        last_error()
                    );
                }
            }
            Call::Read { null_count } => {
                let (mut p, mut n) = (null::<u32>(), 0usize);
                let np = if null_count {
                    null_mut()
                } else {
                    &mut n as *mut usize
                };
                if checked(unsafe { idm_mesher3d_tets(m, &mut p, np) }) == idm_status::IDM_OK
                    && n > 0
                {
                    // SAFETY: lent by the library: n tets of four indices.
                    let tets = unsafe { std::slice::from_raw_parts(p, 4 * n) };
                    std::hint::black_box(tets.iter().max());
                }
            }
            Call::Validate => {
                checked(unsafe { idm_mesher3d_validate(m) });
            }
            Call::Renew => {
                unsafe { idm_mesher3d_free(m) };
                assert_eq!(unsafe { idm_mesher3d_new(&mut m) }, idm_status::IDM_OK);
            }
        }
    }
    unsafe { idm_mesher3d_free(m) };
});
