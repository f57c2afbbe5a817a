/* Progress reports and cancellation through the C ABI (idm_mesherNd_set_progress).
 *
 * For 2D and 3D: a full run reports stages in order with `done` never decreasing within a
 * stage; a callback returning nonzero at the first call, at each stage, and in the middle of
 * refinement makes refine return IDM_CANCELLED with a message and no mesh; the same handle
 * then refines to completion, validates, and gives the same mesh as a handle that was never
 * cancelled. Run under ASan and valgrind by scripts/test.sh, which also shows nothing leaks on
 * the cancel path.
 *
 * Exit status 0 when every check passes; each failed check prints its line and reason. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "idmesh.h"

static int g_failures = 0;
static int g_checks = 0;

#define CHECK(cond, ...)                                              \
  do {                                                                \
    ++g_checks;                                                       \
    if (!(cond)) {                                                    \
      ++g_failures;                                                   \
      fprintf(stderr, "FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond); \
      fprintf(stderr, __VA_ARGS__);                                   \
      fprintf(stderr, "\n");                                          \
    }                                                                 \
  } while (0)

#define NUM_STAGES 6
#define ANY_STAGE (-1)

/* What the callback records, and when it asks to stop. */
typedef struct {
  int stop_stage;   /* the stage to stop in (ANY_STAGE: any), or -2 never */
  int stop_at;      /* stop at this call (1-based) within the stop stage */
  int calls[NUM_STAGES];
  int total;
  int last_stage;
  uint64_t last_done;
  int out_of_order; /* a stage before the previous one, or `done` decreasing in a stage */
} recorder;

static void recorder_init(recorder *r, int stop_stage, int stop_at) {
  memset(r, 0, sizeof *r);
  r->stop_stage = stop_stage;
  r->stop_at = stop_at;
  r->last_stage = -1;
}

static int32_t on_progress(idm_stage stage, uint64_t done, uint64_t estimate, void *user) {
  recorder *r = (recorder *)user;
  int s = (int)stage;
  (void)estimate;
  if (s < 0 || s >= NUM_STAGES || s < r->last_stage ||
      (s == r->last_stage && done < r->last_done)) {
    r->out_of_order = 1;
  }
  if (s >= 0 && s < NUM_STAGES) {
    r->calls[s]++;
  }
  r->total++;
  r->last_stage = s;
  r->last_done = done;
  if (r->stop_stage == ANY_STAGE && r->total >= r->stop_at) {
    return 1;
  }
  return (s == r->stop_stage && r->calls[s] >= r->stop_at) ? 1 : 0;
}

static int mentions_cancel(void) {
  return strstr(idm_last_error(), "cancelled") != NULL;
}

/* ------------------------------------------------------------------------------------------ */
/* 2D                                                                                          */

static idm_mesher2d *square_with_hole(double max_area) {
  static const double xy[] = {0, 0, 1, 0, 1, 1, 0, 1, 0.4, 0.4, 0.6, 0.4, 0.6, 0.6, 0.4, 0.6};
  static const uint32_t ab[] = {0, 1, 1, 2, 2, 3, 3, 0, 4, 5, 5, 6, 6, 7, 7, 4};
  static const double hole[] = {0.5, 0.5};
  idm_mesher2d *m = NULL;
  idm_options2d o;
  CHECK(idm_mesher2d_new(&m) == IDM_OK, "new");
  if (m == NULL) {
    exit(1);
  }
  CHECK(idm_mesher2d_add_points(m, xy, 8, NULL) == IDM_OK, "points");
  CHECK(idm_mesher2d_add_segments(m, ab, 8, NULL) == IDM_OK, "segments");
  CHECK(idm_mesher2d_add_holes(m, hole, 1) == IDM_OK, "holes");
  idm_options2d_default(&o);
  o.min_angle = 30.0;
  o.max_area = max_area;
  CHECK(idm_mesher2d_set_options(m, &o) == IDM_OK, "options");
  return m;
}

/* Whether two 2D handles hold the same mesh (same counts and vertex coordinates). */
static int same_mesh2d(const idm_mesher2d *a, const idm_mesher2d *b) {
  size_t na, nb, ta, tb, sa, sb;
  const double *xa = NULL, *xb = NULL;
  if (idm_mesher2d_counts(a, &na, &ta, &sa) != IDM_OK ||
      idm_mesher2d_counts(b, &nb, &tb, &sb) != IDM_OK) {
    return 0;
  }
  if (na != nb || ta != tb || sa != sb) {
    return 0;
  }
  if (idm_mesher2d_vertices(a, &xa, &na) != IDM_OK ||
      idm_mesher2d_vertices(b, &xb, &nb) != IDM_OK) {
    return 0;
  }
  return memcmp(xa, xb, 2 * na * sizeof(double)) == 0;
}

static void test_2d(void) {
  const double area = 1e-4;
  idm_mesher2d *ref = square_with_hole(area);
  idm_mesher2d *m = square_with_hole(area);
  recorder r;
  size_t nv = 0;
  int s;
  CHECK(idm_mesher2d_refine(ref) == IDM_OK, "reference: %s", idm_last_error());

  /* A full run with a callback that never stops: stages in order, the same mesh. */
  recorder_init(&r, -2, 0);
  CHECK(idm_mesher2d_set_progress(m, on_progress, &r) == IDM_OK, "set_progress");
  CHECK(idm_mesher2d_refine(m) == IDM_OK, "watched refine: %s", idm_last_error());
  CHECK(!r.out_of_order, "2D reports out of order");
  CHECK(r.calls[IDM_STAGE_READING] >= 1 && r.calls[IDM_STAGE_DELAUNAY] >= 1 &&
            r.calls[IDM_STAGE_BOUNDARY] >= 1 && r.calls[IDM_STAGE_REFINING] >= 1 &&
            r.calls[IDM_STAGE_OUTPUT] >= 1,
        "2D stages missing: %d %d %d %d %d", r.calls[0], r.calls[1], r.calls[2], r.calls[3],
        r.calls[5]);
  CHECK(r.calls[IDM_STAGE_SLIVERS] == 0, "2D has no sliver stage");
  CHECK(same_mesh2d(m, ref), "watched 2D mesh differs from the reference");

  /* Cancel at the very first call: no mesh, a message, the handle still usable. */
  recorder_init(&r, ANY_STAGE, 1);
  CHECK(idm_mesher2d_refine(m) == IDM_CANCELLED, "cancel at first call");
  CHECK(mentions_cancel(), "message: \"%s\"", idm_last_error());
  CHECK(r.total == 1, "%d calls after a cancel at the first", r.total);
  CHECK(idm_mesher2d_counts(m, &nv, NULL, NULL) == IDM_ERR_NO_MESH, "no mesh after a cancel");

  /* Cancel at each stage 2D goes through; then run to completion on the same handle. */
  for (s = 0; s < NUM_STAGES; s++) {
    if (s == IDM_STAGE_SLIVERS) {
      continue;
    }
    recorder_init(&r, s, 1);
    CHECK(idm_mesher2d_refine(m) == IDM_CANCELLED, "cancel in stage %d", s);
    CHECK(mentions_cancel(), "stage %d message: \"%s\"", s, idm_last_error());
    CHECK(r.last_stage == s, "stage %d: last report in stage %d", s, r.last_stage);
    recorder_init(&r, -2, 0);
    CHECK(idm_mesher2d_refine(m) == IDM_OK, "rerun after stage %d: %s", s, idm_last_error());
    CHECK(idm_mesher2d_validate(m) == IDM_OK, "validate: %s", idm_last_error());
    CHECK(same_mesh2d(m, ref), "rerun after a cancel in stage %d differs", s);
  }

  /* Cancel in the middle of a long refinement (the second report of the stage comes from a
   * refinement step, not its start), then refine the same handle to completion. */
  {
    idm_mesher2d *big = square_with_hole(1e-7);
    idm_options2d o;
    recorder_init(&r, IDM_STAGE_REFINING, 2);
    CHECK(idm_mesher2d_set_progress(big, on_progress, &r) == IDM_OK, "set_progress");
    CHECK(idm_mesher2d_refine(big) == IDM_CANCELLED, "cancel mid-refinement");
    CHECK(r.calls[IDM_STAGE_REFINING] == 2 && r.last_done > 0,
          "mid-refinement: %d refining reports, done %llu", r.calls[IDM_STAGE_REFINING],
          (unsigned long long)r.last_done);
    idm_options2d_default(&o);
    o.min_angle = 30.0;
    o.max_area = area;
    CHECK(idm_mesher2d_set_options(big, &o) == IDM_OK, "options");
    recorder_init(&r, -2, 0);
    CHECK(idm_mesher2d_refine(big) == IDM_OK, "rerun: %s", idm_last_error());
    CHECK(idm_mesher2d_validate(big) == IDM_OK, "validate: %s", idm_last_error());
    CHECK(same_mesh2d(big, ref), "rerun after a mid-refinement cancel differs");
    /* Clearing the callback: nothing more is reported. */
    CHECK(idm_mesher2d_set_progress(big, NULL, NULL) == IDM_OK, "clear");
    recorder_init(&r, ANY_STAGE, 1);
    CHECK(idm_mesher2d_refine(big) == IDM_OK, "refine without a callback");
    CHECK(r.total == 0, "a cleared callback was called %d times", r.total);
    idm_mesher2d_free(big);
  }

  /* Setting a callback keeps the mesh; a NULL handle is refused. */
  CHECK(idm_mesher2d_set_progress(m, NULL, NULL) == IDM_OK, "clear");
  CHECK(idm_mesher2d_counts(m, &nv, NULL, NULL) == IDM_OK && nv > 0, "mesh kept");
  CHECK(idm_mesher2d_set_progress(NULL, on_progress, &r) == IDM_ERR_NULL_POINTER, "NULL m");
  idm_mesher2d_free(m);
  idm_mesher2d_free(ref);
}

/* ------------------------------------------------------------------------------------------ */
/* 3D                                                                                          */

static idm_mesher3d *cube(double max_volume) {
  static const double xyz[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0,
                               0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 1, 1};
  static const uint32_t quads[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                       {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
  static const size_t offsets[] = {0, 4};
  idm_mesher3d *m = NULL;
  idm_options3d o;
  int f;
  CHECK(idm_mesher3d_new(&m) == IDM_OK, "new");
  if (m == NULL) {
    exit(1);
  }
  CHECK(idm_mesher3d_add_points(m, xyz, 8, NULL) == IDM_OK, "points");
  for (f = 0; f < 6; f++) {
    CHECK(idm_mesher3d_add_facet(m, quads[f], offsets, 1, NULL, 0, 1) == IDM_OK, "facet");
  }
  idm_options3d_default(&o);
  o.radius_edge = 1.5;
  o.max_volume = max_volume;
  CHECK(idm_mesher3d_set_options(m, &o) == IDM_OK, "options");
  return m;
}

static int same_mesh3d(const idm_mesher3d *a, const idm_mesher3d *b) {
  size_t na, nb, ta, tb, fa, fb, ea, eb;
  const double *xa = NULL, *xb = NULL;
  if (idm_mesher3d_counts(a, &na, &ta, &fa, &ea) != IDM_OK ||
      idm_mesher3d_counts(b, &nb, &tb, &fb, &eb) != IDM_OK) {
    return 0;
  }
  if (na != nb || ta != tb || fa != fb || ea != eb) {
    return 0;
  }
  if (idm_mesher3d_vertices(a, &xa, &na) != IDM_OK ||
      idm_mesher3d_vertices(b, &xb, &nb) != IDM_OK) {
    return 0;
  }
  return memcmp(xa, xb, 3 * na * sizeof(double)) == 0;
}

static void test_3d(void) {
  const double volume = 2e-3;
  idm_mesher3d *ref = cube(volume);
  idm_mesher3d *m = cube(volume);
  recorder r;
  size_t nv = 0;
  int s;
  CHECK(idm_mesher3d_refine(ref) == IDM_OK, "reference: %s", idm_last_error());

  recorder_init(&r, -2, 0);
  CHECK(idm_mesher3d_set_progress(m, on_progress, &r) == IDM_OK, "set_progress");
  CHECK(idm_mesher3d_refine(m) == IDM_OK, "watched refine: %s", idm_last_error());
  CHECK(!r.out_of_order, "3D reports out of order");
  for (s = 0; s < NUM_STAGES; s++) {
    CHECK(r.calls[s] >= 1, "3D stage %d not reported", s);
  }
  CHECK(same_mesh3d(m, ref), "watched 3D mesh differs from the reference");

  recorder_init(&r, ANY_STAGE, 1);
  CHECK(idm_mesher3d_refine(m) == IDM_CANCELLED, "cancel at first call");
  CHECK(mentions_cancel(), "message: \"%s\"", idm_last_error());
  CHECK(idm_mesher3d_counts(m, &nv, NULL, NULL, NULL) == IDM_ERR_NO_MESH, "no mesh");

  for (s = 0; s < NUM_STAGES; s++) {
    recorder_init(&r, s, 1);
    CHECK(idm_mesher3d_refine(m) == IDM_CANCELLED, "cancel in stage %d", s);
    CHECK(mentions_cancel(), "stage %d message: \"%s\"", s, idm_last_error());
    CHECK(r.last_stage == s, "stage %d: last report in stage %d", s, r.last_stage);
    recorder_init(&r, -2, 0);
    CHECK(idm_mesher3d_refine(m) == IDM_OK, "rerun after stage %d: %s", s, idm_last_error());
    CHECK(idm_mesher3d_validate(m) == IDM_OK, "validate: %s", idm_last_error());
    CHECK(same_mesh3d(m, ref), "rerun after a cancel in stage %d differs", s);
  }

  /* Mid-refinement on a long run, then the same handle to completion. */
  {
    idm_mesher3d *big = cube(1e-7);
    idm_options3d o;
    recorder_init(&r, IDM_STAGE_REFINING, 2);
    CHECK(idm_mesher3d_set_progress(big, on_progress, &r) == IDM_OK, "set_progress");
    CHECK(idm_mesher3d_refine(big) == IDM_CANCELLED, "cancel mid-refinement");
    CHECK(r.calls[IDM_STAGE_REFINING] == 2 && r.last_done > 0,
          "mid-refinement: %d refining reports, done %llu", r.calls[IDM_STAGE_REFINING],
          (unsigned long long)r.last_done);
    idm_options3d_default(&o);
    o.radius_edge = 1.5;
    o.max_volume = volume;
    CHECK(idm_mesher3d_set_options(big, &o) == IDM_OK, "options");
    recorder_init(&r, -2, 0);
    CHECK(idm_mesher3d_refine(big) == IDM_OK, "rerun: %s", idm_last_error());
    CHECK(idm_mesher3d_validate(big) == IDM_OK, "validate: %s", idm_last_error());
    CHECK(same_mesh3d(big, ref), "rerun after a mid-refinement cancel differs");
    idm_mesher3d_free(big);
  }

  /* The point-set Delaunay call reports and cancels too. */
  recorder_init(&r, IDM_STAGE_DELAUNAY, 1);
  CHECK(idm_mesher3d_delaunay(m) == IDM_CANCELLED, "delaunay cancel");
  recorder_init(&r, -2, 0);
  CHECK(idm_mesher3d_delaunay(m) == IDM_OK, "delaunay: %s", idm_last_error());
  CHECK(r.calls[IDM_STAGE_DELAUNAY] >= 1 && !r.out_of_order, "delaunay reports");
  CHECK(idm_mesher3d_set_progress(NULL, on_progress, &r) == IDM_ERR_NULL_POINTER, "NULL m");
  idm_mesher3d_free(m);
  idm_mesher3d_free(ref);
}

int main(void) {
  test_2d();
  test_3d();
  if (g_failures != 0) {
    fprintf(stderr, "%d of %d checks failed\n", g_failures, g_checks);
    return 1;
  }
  printf("test_progress: all %d checks passed\n", g_checks);
  return 0;
}
