/*
 * Meshes a unit square with a square hole through the idmesh C API and prints the mesh size
 * and its smallest angle. The Rust twin is examples/mesh_square.rs.
 *
 * Build and run from the repository root:
 *   cargo build --release --lib
 *   cc -std=c99 -Wall -Iinclude examples/mesh_square.c target/release/libidmesh.a \
 *      -pthread -ldl -lm -o mesh_square
 *   ./mesh_square
 */
#include "idmesh.h"

#include <math.h>
#include <stdio.h>

/* Prints the failed call and the library's message, and returns 1 from main. */
#define TRY(call)                                                                   \
  do {                                                                              \
    idm_status st_ = (call);                                                        \
    if (st_ != IDM_OK) {                                                            \
      fprintf(stderr, "%s failed (status %d): %s\n", #call, (int)st_, idm_last_error()); \
      idm_mesher2d_free(m);                                                         \
      return 1;                                                                     \
    }                                                                               \
  } while (0)

static double angle_at(const double *p, const double *q, const double *r) {
  double ux = q[0] - p[0], uy = q[1] - p[1], vx = r[0] - p[0], vy = r[1] - p[1];
  return atan2(fabs(ux * vy - uy * vx), ux * vx + uy * vy) * 180.0 / 3.14159265358979323846;
}

int main(void) {
  /* Outer square (points 0-3, segment marker 1) and hole (points 4-7, marker 2). */
  static const double points[] = {0, 0, 1, 0, 1, 1, 0, 1, 0.4, 0.4, 0.6, 0.4, 0.6, 0.6, 0.4, 0.6};
  static const uint32_t segments[] = {0, 1, 1, 2, 2, 3, 3, 0, 4, 5, 5, 6, 6, 7, 7, 4};
  static const int32_t markers[] = {1, 1, 1, 1, 2, 2, 2, 2};
  static const double hole[] = {0.5, 0.5};
  idm_mesher2d *m = NULL;
  idm_options2d opts;
  const double *xy;
  const uint32_t *tri;
  size_t nv, nt, ns, t;
  int i;
  double min_angle = 180;

  TRY(idm_mesher2d_new(&m));
  TRY(idm_mesher2d_add_points(m, points, 8, NULL));
  TRY(idm_mesher2d_add_segments(m, segments, 8, markers));
  TRY(idm_mesher2d_add_holes(m, hole, 1));
  idm_options2d_default(&opts);
  opts.min_angle = 30;   /* like Triangle's -q30 */
  opts.max_area = 0.002; /* like Triangle's -a0.002 */
  TRY(idm_mesher2d_set_options(m, &opts));
  TRY(idm_mesher2d_refine(m));

  /* The arrays are borrowed from the handle: read them before idm_mesher2d_free. */
  TRY(idm_mesher2d_counts(m, &nv, &nt, &ns));
  TRY(idm_mesher2d_vertices(m, &xy, &nv));
  TRY(idm_mesher2d_triangles(m, &tri, &nt));
  for (t = 0; t < nt; t++)
    for (i = 0; i < 3; i++) {
      double a = angle_at(xy + 2 * tri[3 * t + i], xy + 2 * tri[3 * t + (i + 1) % 3],
                          xy + 2 * tri[3 * t + (i + 2) % 3]);
      if (a < min_angle) min_angle = a;
    }
  printf("idmesh %s: %zu vertices, %zu triangles, %zu subsegments, min angle %.2f degrees\n",
         idm_version(), nv, nt, ns, min_angle);
  idm_mesher2d_free(m);
  return 0;
}
