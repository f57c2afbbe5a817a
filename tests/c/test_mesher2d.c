/*
 * End-to-end test of the C API, using only include/idmesh.h. Run by tests/c_api.rs:
 *   cc -std=c99 -Wall -Wextra -Werror -pedantic -Iinclude tests/c/test_mesher2d.c \
 *      target/.../libidmesh.a -pthread -ldl -lm
 * Exits non-zero (after printing every failed check) when anything is wrong.
 */
#define _POSIX_C_SOURCE 200809L

#include "idmesh.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int checks = 0;
static int failures = 0;

/* Records one check; on failure prints where and why, plus the library's last message. */
#define CHECK(cond, ...)                                                    \
  do {                                                                      \
    checks++;                                                               \
    if (!(cond)) {                                                          \
      failures++;                                                           \
      fprintf(stderr, "%s:%d: check failed: %s: ", __FILE__, __LINE__, #cond); \
      fprintf(stderr, __VA_ARGS__);                                         \
      fprintf(stderr, " (idm_last_error: \"%s\")\n", idm_last_error());     \
    }                                                                       \
  } while (0)

/* ---- The test domain: a 10x10 square with a 2x2 hole, split by a segment at x = 2. ---- */

#define NUM_POINTS 10
static const double POINTS[2 * NUM_POINTS] = {
    0, 0, 10, 0, 10, 10, 0, 10,  /* 0-3: outer corners */
    4, 4, 6, 4, 6, 6, 4, 6,      /* 4-7: hole corners */
    2, 0, 2, 10,                 /* 8-9: ends of the divider */
};
#define NUM_SEGMENTS 11
static const uint32_t SEGMENTS[2 * NUM_SEGMENTS] = {
    0, 8, 8, 1, 1, 2, 2, 9, 9, 3, 3, 0, /* outer boundary, marker 1 */
    4, 5, 5, 6, 6, 7, 7, 4,             /* hole boundary, marker 2 */
    8, 9,                               /* divider, marker 3 */
};
static const int32_t SEGMENT_MARKERS[NUM_SEGMENTS] = {1, 1, 1, 1, 1, 1, 2, 2, 2, 2, 3};
static const double HOLE[2] = {5, 5};
static const double REGION[2] = {1, 5};
static const double REGION_ATTR = 7.0;
static const double REGION_MAX_AREA = 0.05;
static const double GLOBAL_MAX_AREA = 0.5;
static const double MIN_ANGLE = 25.0;
#define PI 3.14159265358979323846

static int32_t point_markers[NUM_POINTS];

/* A copy of a mesh read through the getters (the borrowed arrays die with the handle). */
typedef struct mesh {
  size_t nv, nt, ns;
  double *xy;
  uint32_t *tri;
} mesh;

static void mesh_release(mesh *m) {
  free(m->xy);
  free(m->tri);
  m->xy = NULL;
  m->tri = NULL;
}

static double tri_area(const double *a, const double *b, const double *c) {
  return 0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
}

static double angle_at(const double *p, const double *q, const double *r) {
  double ux = q[0] - p[0], uy = q[1] - p[1], vx = r[0] - p[0], vy = r[1] - p[1];
  return atan2(fabs(ux * vy - uy * vx), ux * vx + uy * vy) * 180.0 / PI;
}

/* Adds the test domain to a fresh handle; returns the first failing status. */
static idm_status load_domain(idm_mesher2d *m, int with_region) {
  idm_status st;
  double max_area = REGION_MAX_AREA;
  if ((st = idm_mesher2d_add_points(m, POINTS, NUM_POINTS, point_markers)) != IDM_OK) return st;
  if ((st = idm_mesher2d_add_segments(m, SEGMENTS, NUM_SEGMENTS, SEGMENT_MARKERS)) != IDM_OK)
    return st;
  if ((st = idm_mesher2d_add_holes(m, HOLE, 1)) != IDM_OK) return st;
  if (with_region &&
      (st = idm_mesher2d_add_regions(m, REGION, &REGION_ATTR, &max_area, 1)) != IDM_OK)
    return st;
  return IDM_OK;
}

/* Meshes the domain with the region, quality and area bounds, copying the result to *out.
   Used by the main thread and by the worker threads, so it reports by status, not CHECK. */
static idm_status mesh_domain(mesh *out) {
  idm_mesher2d *m = NULL;
  idm_options2d o;
  const double *xy;
  const uint32_t *tri;
  idm_status st = idm_mesher2d_new(&m);
  if (st != IDM_OK) return st;
  idm_options2d_default(&o);
  o.min_angle = MIN_ANGLE;
  o.max_area = GLOBAL_MAX_AREA;
  o.region_max_area = 1;
  o.region_attributes = 1;
  if ((st = load_domain(m, 1)) != IDM_OK || (st = idm_mesher2d_set_options(m, &o)) != IDM_OK ||
      (st = idm_mesher2d_refine(m)) != IDM_OK ||
      (st = idm_mesher2d_vertices(m, &xy, &out->nv)) != IDM_OK ||
      (st = idm_mesher2d_triangles(m, &tri, &out->nt)) != IDM_OK ||
      (st = idm_mesher2d_counts(m, NULL, NULL, &out->ns)) != IDM_OK) {
    idm_mesher2d_free(m);
    return st;
  }
  out->xy = malloc(2 * out->nv * sizeof(double));
  out->tri = malloc(3 * out->nt * sizeof(uint32_t));
  if (out->xy == NULL || out->tri == NULL) {
    idm_mesher2d_free(m);
    return IDM_ERR_INTERNAL;
  }
  memcpy(out->xy, xy, 2 * out->nv * sizeof(double));
  memcpy(out->tri, tri, 3 * out->nt * sizeof(uint32_t));
  idm_mesher2d_free(m);
  return IDM_OK;
}

/* ---- The main meshing test: every output array checked against the input. ---- */

static void test_square_with_hole_and_region(void) {
  idm_mesher2d *m = NULL;
  idm_options2d o;
  size_t nv = 0, nt = 0, ns = 0, n = 0, t, i, boundary_edges = 0, boundary_subsegs = 0;
  const double *xy = NULL, *attr = NULL;
  const uint32_t *tri = NULL, *nbr = NULL, *seg = NULL;
  const int32_t *vmark = NULL, *smark = NULL;
  double total_area = 0, min_angle = 180, length[4] = {0, 0, 0, 0};

  CHECK(idm_mesher2d_new(&m) == IDM_OK && m != NULL, "new");
  CHECK(load_domain(m, 1) == IDM_OK, "load");
  /* Getters before refine. */
  CHECK(idm_mesher2d_vertices(m, &xy, &n) == IDM_ERR_NO_MESH, "vertices before refine");
  CHECK(strlen(idm_last_error()) > 0, "no-mesh message");
  CHECK(xy == NULL && n == 0, "out-parameters written on failure");

  idm_options2d_default(&o);
  CHECK(o.off_centers == 1 && o.max_steiner == -1 && o.min_angle == 0, "defaults");
  o.min_angle = MIN_ANGLE;
  o.max_area = GLOBAL_MAX_AREA;
  o.region_max_area = 1;
  o.region_attributes = 1;
  CHECK(idm_mesher2d_set_options(m, &o) == IDM_OK, "set_options");
  CHECK(idm_mesher2d_refine(m) == IDM_OK, "refine");
  CHECK(idm_last_error()[0] == '\0', "last error not cleared on success");
  CHECK(idm_mesher2d_validate(m) == IDM_OK, "validate");

  CHECK(idm_mesher2d_counts(m, &nv, &nt, &ns) == IDM_OK, "counts");
  CHECK(nv > NUM_POINTS && nt > 0 && ns >= NUM_SEGMENTS, "counts %zu %zu %zu", nv, nt, ns);
  CHECK(idm_mesher2d_vertices(m, &xy, &n) == IDM_OK && n == nv, "vertices");
  CHECK(idm_mesher2d_vertex_markers(m, &vmark, &n) == IDM_OK && n == nv, "vertex markers");
  CHECK(idm_mesher2d_triangles(m, &tri, &n) == IDM_OK && n == nt, "triangles");
  CHECK(idm_mesher2d_neighbors(m, &nbr, &n) == IDM_OK && n == nt, "neighbors");
  CHECK(idm_mesher2d_triangle_attributes(m, &attr, &n) == IDM_OK && n == nt, "attributes");
  CHECK(idm_mesher2d_segments(m, &seg, &smark, &n) == IDM_OK && n == ns, "segments");
  if (failures > 0) {
    idm_mesher2d_free(m);
    return;
  }

  /* Input points come first, unchanged, with their markers. */
  for (i = 0; i < NUM_POINTS; i++) {
    CHECK(xy[2 * i] == POINTS[2 * i] && xy[2 * i + 1] == POINTS[2 * i + 1], "point %zu moved", i);
    CHECK(vmark[i] == point_markers[i], "vertex %zu marker %d", i, vmark[i]);
  }

  for (t = 0; t < nt; t++) {
    const uint32_t *v = tri + 3 * t;
    const double *a, *b, *c;
    double area, cx;
    if (v[0] >= nv || v[1] >= nv || v[2] >= nv) {
      CHECK(0, "triangle %zu has an index out of range", t);
      continue;
    }
    a = xy + 2 * v[0];
    b = xy + 2 * v[1];
    c = xy + 2 * v[2];
    area = tri_area(a, b, c);
    CHECK(area > 0, "triangle %zu is not counter-clockwise (area %g)", t, area);
    total_area += area;
    cx = (a[0] + b[0] + c[0]) / 3;
    if (cx < 2) {
      CHECK(attr[t] == REGION_ATTR, "triangle %zu in the region has attribute %g", t, attr[t]);
      CHECK(area <= REGION_MAX_AREA * (1 + 1e-9), "region triangle %zu area %g", t, area);
    } else {
      CHECK(attr[t] == 0, "triangle %zu outside the region has attribute %g", t, attr[t]);
      CHECK(area <= GLOBAL_MAX_AREA * (1 + 1e-9), "triangle %zu area %g", t, area);
    }
    for (i = 0; i < 3; i++) {
      double ang = angle_at(xy + 2 * v[i], xy + 2 * v[(i + 1) % 3], xy + 2 * v[(i + 2) % 3]);
      if (ang < min_angle) min_angle = ang;
      if (nbr[3 * t + i] == IDM_NONE) {
        boundary_edges++;
      } else {
        uint32_t u = nbr[3 * t + i];
        CHECK(u < nt, "neighbour %u of triangle %zu out of range", u, t);
        if (u < nt)
          CHECK(nbr[3 * u] == t || nbr[3 * u + 1] == t || nbr[3 * u + 2] == t,
                "neighbours %zu -> %u not symmetric", t, u);
      }
    }
  }
  CHECK(fabs(total_area - 96.0) < 1e-9, "total area %.17g, expected 96", total_area);
  CHECK(min_angle >= MIN_ANGLE - 1e-9, "minimum angle %g below %g", min_angle, MIN_ANGLE);

  for (i = 0; i < ns; i++) {
    const double *a = xy + 2 * seg[2 * i], *b = xy + 2 * seg[2 * i + 1];
    CHECK(smark[i] >= 1 && smark[i] <= 3, "subsegment %zu marker %d", i, smark[i]);
    if (smark[i] >= 1 && smark[i] <= 3) length[smark[i]] += hypot(b[0] - a[0], b[1] - a[1]);
    if (smark[i] != 3) boundary_subsegs++;
  }
  CHECK(fabs(length[1] - 40) < 1e-9 && fabs(length[2] - 8) < 1e-9 && fabs(length[3] - 10) < 1e-9,
        "subsegment lengths by marker %g %g %g, expected 40 8 10", length[1], length[2],
        length[3]);
  CHECK(boundary_edges == boundary_subsegs, "%zu boundary edges but %zu boundary subsegments",
        boundary_edges, boundary_subsegs);
  printf("mesh: %zu vertices, %zu triangles, %zu subsegments, min angle %.2f\n", nv, nt, ns,
         min_angle);

  /* Changing the input drops the mesh. */
  CHECK(idm_mesher2d_add_holes(m, HOLE, 1) == IDM_OK, "add_holes");
  CHECK(idm_mesher2d_validate(m) == IDM_ERR_NO_MESH, "mesh kept after an input change");
  idm_mesher2d_free(m);
}

/* ---- Bad input: status and a message naming the item. ---- */

static const double SQUARE[8] = {0, 0, 1, 0, 1, 1, 0, 1};
static const uint32_t SQUARE_SEGMENTS[8] = {0, 1, 1, 2, 2, 3, 3, 0};

static void expect_refine_error(const uint32_t *extra, size_t nextra, idm_status want,
                                const char *needle, const char *what) {
  idm_mesher2d *m = NULL;
  idm_status st;
  CHECK(idm_mesher2d_new(&m) == IDM_OK, "new");
  CHECK(idm_mesher2d_add_points(m, SQUARE, 4, NULL) == IDM_OK, "points");
  CHECK(idm_mesher2d_add_segments(m, SQUARE_SEGMENTS, 4, NULL) == IDM_OK, "segments");
  CHECK(idm_mesher2d_add_segments(m, extra, nextra, NULL) == IDM_OK, "extra segments");
  st = idm_mesher2d_refine(m);
  CHECK(st == want, "%s: status %d, expected %d", what, (int)st, (int)want);
  CHECK(strstr(idm_last_error(), needle) != NULL, "%s: message lacks \"%s\"", what, needle);
  CHECK(idm_mesher2d_validate(m) == IDM_ERR_NO_MESH, "%s: a mesh after a failed refine", what);
  idm_mesher2d_free(m);
}

static void test_bad_input(void) {
  static const uint32_t crossing[4] = {0, 2, 1, 3};
  static const uint32_t out_of_range[2] = {3, 17};
  idm_mesher2d *m = NULL;
  idm_options2d o;

  expect_refine_error(crossing, 2, IDM_ERR_INVALID_INPUT, "segments 4 and 5", "crossing");
  expect_refine_error(out_of_range, 1, IDM_ERR_INVALID_INPUT, "segment 4 refers to point 17",
                      "index out of range");

  CHECK(idm_mesher2d_new(NULL) == IDM_ERR_NULL_POINTER, "new(NULL)");
  CHECK(strstr(idm_last_error(), "out") != NULL, "new(NULL) message");
  CHECK(idm_mesher2d_new(&m) == IDM_OK, "new");
  CHECK(idm_last_error()[0] == '\0', "last error not cleared");
  CHECK(idm_mesher2d_add_points(m, NULL, 4, NULL) == IDM_ERR_NULL_POINTER, "NULL xy");
  CHECK(strstr(idm_last_error(), "xy") != NULL, "NULL xy message");
  CHECK(idm_mesher2d_add_points(m, NULL, 0, NULL) == IDM_OK, "NULL with count 0");
  CHECK(idm_mesher2d_add_points(NULL, SQUARE, 4, NULL) == IDM_ERR_NULL_POINTER, "NULL handle");
  CHECK(idm_mesher2d_add_points(m, SQUARE, (size_t)-1, NULL) == IDM_ERR_INVALID_ARGUMENT,
        "count overflow");
  CHECK(strstr(idm_last_error(), "too large") != NULL, "overflow message");
  CHECK(idm_mesher2d_set_options(m, NULL) == IDM_ERR_NULL_POINTER, "NULL options");
  idm_options2d_default(&o);
  o.min_angle = 80; /* out of range: checked by refine */
  CHECK(idm_mesher2d_add_points(m, SQUARE, 4, NULL) == IDM_OK, "points");
  CHECK(idm_mesher2d_set_options(m, &o) == IDM_OK, "set_options");
  CHECK(idm_mesher2d_refine(m) == IDM_ERR_INVALID_ARGUMENT, "min_angle 80");
  CHECK(strstr(idm_last_error(), "angle") != NULL, "angle message");
  /* The Steiner cap: IDM_INCOMPLETE with a readable, valid mesh. */
  o.min_angle = 30;
  o.max_area = 1e-4;
  o.max_steiner = 5;
  CHECK(idm_mesher2d_set_options(m, &o) == IDM_OK, "set_options");
  CHECK(idm_mesher2d_refine(m) == IDM_INCOMPLETE, "Steiner cap");
  CHECK(strlen(idm_last_error()) > 0, "incomplete message");
  CHECK(idm_mesher2d_validate(m) == IDM_OK, "validate incomplete mesh");
  idm_mesher2d_free(m);
  idm_mesher2d_free(NULL);
}

/* ---- The sizing callback. ---- */

typedef struct sizing_data {
  long calls;
} sizing_data;

/* Too large: area above 0.02 for triangles whose centroid is within 1.5 of (8, 8). */
static int32_t near_corner(void *user, const double *a, const double *b, const double *c,
                           double area) {
  double cx = (a[0] + b[0] + c[0]) / 3 - 8, cy = (a[1] + b[1] + c[1]) / 3 - 8;
  ((sizing_data *)user)->calls++;
  return cx * cx + cy * cy < 1.5 * 1.5 && area > 0.02;
}

static void test_sizing_callback(void) {
  idm_mesher2d *m = NULL;
  sizing_data data = {0}, recheck = {0};
  const double *xy = NULL;
  const uint32_t *tri = NULL;
  size_t nv = 0, nt = 0, t, near = 0, unsized_nt = 0;
  CHECK(idm_mesher2d_new(&m) == IDM_OK, "new");
  CHECK(load_domain(m, 0) == IDM_OK, "load");
  CHECK(idm_mesher2d_refine(m) == IDM_OK, "refine without sizing");
  CHECK(idm_mesher2d_counts(m, NULL, &unsized_nt, NULL) == IDM_OK, "counts");
  CHECK(idm_mesher2d_set_sizing(m, near_corner, &data) == IDM_OK, "set_sizing");
  CHECK(idm_mesher2d_refine(m) == IDM_OK, "refine with sizing");
  CHECK(data.calls > 0, "the sizing callback was never called");
  CHECK(idm_mesher2d_vertices(m, &xy, &nv) == IDM_OK, "vertices");
  CHECK(idm_mesher2d_triangles(m, &tri, &nt) == IDM_OK, "triangles");
  CHECK(nt > unsized_nt, "sizing did not refine: %zu vs %zu triangles", nt, unsized_nt);
  for (t = 0; tri != NULL && t < nt; t++) {
    const double *a = xy + 2 * tri[3 * t], *b = xy + 2 * tri[3 * t + 1],
                 *c = xy + 2 * tri[3 * t + 2];
    double cx = (a[0] + b[0] + c[0]) / 3 - 8, cy = (a[1] + b[1] + c[1]) / 3 - 8;
    near += cx * cx + cy * cy < 1.5 * 1.5;
    CHECK(!near_corner(&recheck, a, b, c, tri_area(a, b, c)), "triangle %zu still too large", t);
  }
  CHECK(near > 20, "only %zu triangles near (8, 8)", near);
  /* NULL clears the callback: back to the unsized mesh. */
  CHECK(idm_mesher2d_set_sizing(m, NULL, NULL) == IDM_OK, "clear sizing");
  CHECK(idm_mesher2d_refine(m) == IDM_OK, "refine after clearing");
  CHECK(idm_mesher2d_counts(m, NULL, &nt, NULL) == IDM_OK && nt == unsized_nt,
        "clearing the sizing callback: %zu triangles, expected %zu", nt, unsized_nt);
  idm_mesher2d_free(m);
}

/* ---- Concurrency: two threads, each with its own handle, give the main thread's result. ---- */

typedef struct worker {
  mesh result;
  idm_status status;
  int error_was_clean;
} worker;

/* Invalid input reaches C with its kind and indices (idm_last_error_item), next to the
   message, and an options struct that never went through idm_options2d_default is refused. */
static void test_error_items(void) {
  static const double square[8] = {0, 0, 1, 0, 1, 1, 0, 1};
  static const uint32_t diagonals[12] = {0, 1, 1, 2, 2, 3, 3, 0, 0, 2, 1, 3};
  static const uint32_t dangling[2] = {1, 9};
  static const double nan_point[2] = {NAN, 0.5};
  idm_mesher2d *m = NULL;
  idm_options2d o;
  int64_t item = 0, part = 0, other = 0;
  CHECK(idm_mesher2d_new(&m) == IDM_OK, "new");
  CHECK(idm_mesher2d_add_points(m, square, 4, NULL) == IDM_OK, "points");
  CHECK(idm_mesher2d_add_segments(m, diagonals, 6, NULL) == IDM_OK, "segments");
  CHECK(idm_mesher2d_refine(m) == IDM_ERR_INVALID_INPUT, "crossing diagonals accepted");
  CHECK(idm_last_error_item(&item, &part, &other) == IDM_INPUT_CROSSING_SEGMENTS,
        "kind of crossing segments");
  CHECK(item == 4 && part == -1 && other == 5, "crossing items %lld %lld %lld", (long long)item,
        (long long)part, (long long)other);
  CHECK(strstr(idm_last_error(), "segments 4 and 5") != NULL, "message kept");
  idm_mesher2d_free(m);

  CHECK(idm_mesher2d_new(&m) == IDM_OK, "new");
  CHECK(idm_mesher2d_add_points(m, square, 4, NULL) == IDM_OK, "points");
  CHECK(idm_mesher2d_add_segments(m, dangling, 1, NULL) == IDM_OK, "segment");
  CHECK(idm_mesher2d_refine(m) == IDM_ERR_INVALID_INPUT, "dangling index accepted");
  CHECK(idm_last_error_item(&item, NULL, &other) == IDM_INPUT_SEGMENT_INDEX_OUT_OF_RANGE,
        "kind of an index out of range");
  CHECK(item == 0 && other == 9, "index items %lld %lld", (long long)item, (long long)other);
  CHECK(idm_mesher2d_add_points(m, nan_point, 1, NULL) == IDM_OK, "NaN point stored");
  CHECK(idm_mesher2d_refine(m) == IDM_ERR_INVALID_INPUT, "NaN accepted");
  CHECK(idm_last_error_item(&item, NULL, NULL) == IDM_INPUT_NON_FINITE_POINT, "kind of NaN");
  CHECK(item == 4, "NaN point %lld", (long long)item);

  memset(&o, 0, sizeof o);
  CHECK(idm_mesher2d_set_options(m, &o) == IDM_ERR_INVALID_ARGUMENT, "struct_size 0 accepted");
  CHECK(strstr(idm_last_error(), "struct_size") != NULL, "struct_size not named");
  CHECK(idm_last_error_item(&item, NULL, NULL) == IDM_INPUT_OK && item == -1,
        "an argument error has no input item");
  idm_options2d_default(&o);
  CHECK(o.struct_size == sizeof o, "struct_size %zu", o.struct_size);
  CHECK(idm_mesher2d_set_options(m, &o) == IDM_OK, "default options refused");
  idm_mesher2d_free(m);
}

static void *worker_main(void *arg) {
  worker *w = arg;
  /* The main thread's pending error message is not visible here. */
  w->error_was_clean = idm_last_error()[0] == '\0';
  w->status = mesh_domain(&w->result);
  return NULL;
}

static void test_threads(void) {
  mesh reference = {0, 0, 0, NULL, NULL};
  worker w[2];
  pthread_t th[2];
  int i, started[2] = {0, 0};
  CHECK(mesh_domain(&reference) == IDM_OK, "reference mesh");
  memset(w, 0, sizeof w);
  /* Leave an error pending on this thread: it must survive the workers' successes. */
  CHECK(idm_mesher2d_refine(NULL) == IDM_ERR_NULL_POINTER, "refine(NULL)");
  for (i = 0; i < 2; i++) {
    started[i] = pthread_create(&th[i], NULL, worker_main, &w[i]) == 0;
    CHECK(started[i], "pthread_create %d", i);
  }
  for (i = 0; i < 2; i++) {
    if (!started[i]) continue;
    pthread_join(th[i], NULL);
    CHECK(w[i].status == IDM_OK, "worker %d status %d", i, (int)w[i].status);
    CHECK(w[i].error_was_clean, "worker %d saw another thread's error", i);
    CHECK(w[i].result.nv == reference.nv && w[i].result.nt == reference.nt,
          "worker %d: %zu vertices / %zu triangles, main thread %zu / %zu", i, w[i].result.nv,
          w[i].result.nt, reference.nv, reference.nt);
    if (w[i].status == IDM_OK && w[i].result.nv == reference.nv &&
        w[i].result.nt == reference.nt) {
      CHECK(memcmp(w[i].result.xy, reference.xy, 2 * reference.nv * sizeof(double)) == 0,
            "worker %d vertices differ", i);
      CHECK(memcmp(w[i].result.tri, reference.tri, 3 * reference.nt * sizeof(uint32_t)) == 0,
            "worker %d triangles differ", i);
    }
    mesh_release(&w[i].result);
  }
  CHECK(strstr(idm_last_error(), "NULL") != NULL, "this thread's error was lost");
  mesh_release(&reference);
}

int main(void) {
  int i;
  const char *v = idm_version();
  for (i = 0; i < NUM_POINTS; i++) point_markers[i] = 100 + i;
  CHECK(v != NULL && strlen(v) > 0, "version");
  CHECK(idm_last_error() != NULL && idm_last_error()[0] == '\0', "initial last error");
  printf("idmesh %s\n", v);
  test_square_with_hole_and_region();
  test_bad_input();
  test_error_items();
  test_sizing_callback();
  test_threads();
  printf("%d checks, %d failed\n", checks, failures);
  return failures == 0 ? 0 : 1;
}
