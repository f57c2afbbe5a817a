/*
 * Meshes a unit box with a cubic cavity (a hole) through the idmesh 3D C API and prints the
 * mesh size and quality. The same input through the Rust API is checked against this output by
 * tests/c_api3d.rs.
 *
 * Build and run from the repository root:
 *   cargo build --release --lib
 *   cc -std=c99 -Wall -Iinclude examples/c/mesh_box3d.c target/release/libidmesh.a \
 *      -pthread -ldl -lm -o mesh_box3d
 *   ./mesh_box3d
 */
#include "idmesh.h"

#include <stdio.h>

/* Prints the failed call and the library's message, and returns 1 from main. */
#define TRY(call)                                                                   \
  do {                                                                              \
    idm_status st_ = (call);                                                        \
    if (st_ != IDM_OK) {                                                            \
      fprintf(stderr, "%s failed (status %d): %s\n", #call, (int)st_, idm_last_error()); \
      idm_mesher3d_free(m);                                                         \
      return 1;                                                                     \
    }                                                                               \
  } while (0)

int main(void) {
  /* Points 0-7: the box [0,1]^3; points 8-15: the cavity [0.4,0.6]^3, in the same order. */
  static const double points[] = {
      0,   0,   0,   1,   0,   0,   1,   1,   0,   0,   1,   0,
      0,   0,   1,   1,   0,   1,   1,   1,   1,   0,   1,   1,
      0.4, 0.4, 0.4, 0.6, 0.4, 0.4, 0.6, 0.6, 0.4, 0.4, 0.6, 0.4,
      0.4, 0.4, 0.6, 0.6, 0.4, 0.6, 0.6, 0.6, 0.6, 0.4, 0.6, 0.6,
  };
  /* The six sides of a cube, as loops of its corner numbers. */
  static const uint32_t sides[6][4] = {
      {0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7},
  };
  /* Each facet is one loop of four points: loop 0 is indices[0..4]. */
  static const size_t one_loop[] = {0, 4};
  static const double cavity_seed[] = {0.5, 0.5, 0.5};
  idm_mesher3d *m = NULL;
  idm_options3d opts;
  idm_stats3d stats;
  size_t nv, nt, nf, ne;
  int side, box;

  TRY(idm_mesher3d_new(&m));
  TRY(idm_mesher3d_add_points(m, points, 16, NULL));
  for (box = 0; box < 2; box++)
    for (side = 0; side < 6; side++) {
      uint32_t loop[4];
      int k;
      for (k = 0; k < 4; k++) loop[k] = sides[side][k] + 8 * (uint32_t)box;
      /* Marker 1 on the outside, 2 on the cavity's walls. */
      TRY(idm_mesher3d_add_facet(m, loop, one_loop, 1, NULL, 0, box + 1));
    }
  TRY(idm_mesher3d_add_hole(m, cavity_seed));
  idm_options3d_default(&opts);
  opts.radius_edge = 2.0;   /* like TetGen's -q2 */
  opts.max_volume = 0.001;  /* like TetGen's -a0.001 */
  TRY(idm_mesher3d_set_options(m, &opts));
  TRY(idm_mesher3d_refine(m));
  TRY(idm_mesher3d_validate(m));

  TRY(idm_mesher3d_counts(m, &nv, &nt, &nf, &ne));
  TRY(idm_mesher3d_stats(m, &stats));
  printf("idmesh %s: %zu vertices, %zu tetrahedra, %zu faces, %zu edges, volume %.6f, "
         "radius-edge %.4f, dihedral %.4f..%.4f degrees\n",
         idm_version(), nv, nt, nf, ne, stats.volume, stats.max_radius_edge, stats.min_dihedral,
         stats.max_dihedral);
  idm_mesher3d_free(m);
  return 0;
}
