/* An out-of-tree program built against an installed idmesh (ctests/install/run.sh): meshes a
 * square through Triangle's interface and through idmesh's own, and checks both. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "idmesh.h"
#include "triangle.h"

int main(void) {
  double pts[] = {0, 0, 1, 0, 1, 1, 0, 1};
  int segs[] = {0, 1, 1, 2, 2, 3, 3, 0};
  char sw[] = "pq30a0.01zQ";
  struct triangulateio in, out;
  idm_mesher2d *m = NULL;
  size_t nt = 0;
  memset(&in, 0, sizeof in);
  memset(&out, 0, sizeof out);
  in.numberofpoints = 4;
  in.pointlist = pts;
  in.numberofsegments = 4;
  in.segmentlist = segs;
  triangulate(sw, &in, &out, NULL);
  if (out.numberoftriangles < 100) {
    fprintf(stderr, "triangulate: %d triangles (%s)\n", out.numberoftriangles, idm_last_error());
    return 1;
  }
  if (idm_mesher2d_new(&m) != IDM_OK || idm_mesher2d_add_points(m, pts, 4, NULL) != IDM_OK ||
      idm_mesher2d_refine(m) != IDM_OK || idm_mesher2d_counts(m, NULL, &nt, NULL) != IDM_OK ||
      nt != 2) {
    fprintf(stderr, "idm_mesher2d: %zu triangles (%s)\n", nt, idm_last_error());
    return 1;
  }
  idm_mesher2d_free(m);
  printf("idmesh %s: %d triangles through triangle.h\n", idm_version(), out.numberoftriangles);
  trifree(out.pointlist);
  trifree(out.pointmarkerlist);
  trifree(out.trianglelist);
  trifree(out.segmentlist);
  trifree(out.segmentmarkerlist);
  return 0;
}
