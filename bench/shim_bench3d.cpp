// The TetGen compatibility layer's overhead: one process meshes the unit cube with radius-edge
// 1.414 and a volume bound, either through idmesh's own C API (MODE capi: idm_mesher3d_*,
// output copied into the caller's arrays, as a C caller does) or through compat/tetgen
// (MODE shim: tetgenio + tetrahedralize("pq1.414a<V>Q"), which fills tetgenio's arrays).
// It prints one JSON line: {"mode": ..., "seconds": ..., "tets": ..., "points": ...}, the time
// being the wall clock from the input's construction to the output in the caller's arrays.
//
// Usage: shim_bench3d capi|shim VOLUME
#include <tetgen.h>

#include <idmesh.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

static const int kQuads[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                 {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};

static double corner(int i, int k) { return (i >> k) & 1; }

static int run_capi(double volume, size_t *tets, size_t *points) {
  idm_mesher3d *m = nullptr;
  if (idm_mesher3d_new(&m) != IDM_OK) return 1;
  double xyz[24];
  for (int i = 0; i < 8; i++)
    for (int k = 0; k < 3; k++) xyz[3 * i + k] = corner(i, k);
  idm_mesher3d_add_points(m, xyz, 8, nullptr);
  for (int f = 0; f < 6; f++) {
    uint32_t q[4];
    for (int k = 0; k < 4; k++) q[k] = (uint32_t)kQuads[f][k];
    size_t off[2] = {0, 4};
    idm_mesher3d_add_facet(m, q, off, 1, nullptr, 0, f + 1);
  }
  idm_options3d o;
  idm_options3d_default(&o);
  o.radius_edge = 1.414;
  o.max_volume = volume;
  idm_mesher3d_set_options(m, &o);
  if (idm_mesher3d_refine(m) != IDM_OK) {
    fprintf(stderr, "%s\n", idm_last_error());
    return 1;
  }
  const double *v;
  const int32_t *vm, *fm, *em;
  const uint32_t *t, *f, *e;
  size_t nv, nt, nf, ne;
  idm_mesher3d_vertices(m, &v, &nv);
  idm_mesher3d_vertex_markers(m, &vm, &nv);
  idm_mesher3d_tets(m, &t, &nt);
  idm_mesher3d_faces(m, &f, &fm, &nf);
  idm_mesher3d_edges(m, &e, &em, &ne);
  // The caller's own arrays, as tetgenio's are filled.
  std::vector<double> pts(v, v + 3 * nv);
  std::vector<int> marks(vm, vm + nv), tl(t, t + 4 * nt), fl(f, f + 3 * nf), fmk(fm, fm + nf);
  *tets = tl.size() / 4;
  *points = pts.size() / 3;
  idm_mesher3d_free(m);
  return 0;
}

static int run_shim(double volume, size_t *tets, size_t *points) {
  tetgenio in, out;
  in.firstnumber = 0;
  in.numberofpoints = 8;
  in.pointlist = new REAL[24];
  for (int i = 0; i < 8; i++)
    for (int k = 0; k < 3; k++) in.pointlist[3 * i + k] = corner(i, k);
  in.numberoffacets = 6;
  in.facetlist = new tetgenio::facet[6];
  in.facetmarkerlist = new int[6];
  for (int f = 0; f < 6; f++) {
    tetgenio::facet *fa = &in.facetlist[f];
    tetgenio::init(fa);
    fa->numberofpolygons = 1;
    fa->polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&fa->polygonlist[0]);
    fa->polygonlist[0].numberofvertices = 4;
    fa->polygonlist[0].vertexlist = new int[4];
    for (int k = 0; k < 4; k++) fa->polygonlist[0].vertexlist[k] = kQuads[f][k];
    in.facetmarkerlist[f] = f + 1;
  }
  char sw[64];
  snprintf(sw, sizeof sw, "pq1.414a%.17gQ", volume);
  try {
    tetrahedralize(sw, &in, &out);
  } catch (int code) {
    fprintf(stderr, "tetrahedralize threw %d: %s\n", code, idm_last_error());
    return 1;
  }
  *tets = (size_t)out.numberoftetrahedra;
  *points = (size_t)out.numberofpoints;
  return 0;
}

int main(int argc, char **argv) {
  if (argc != 3 || (strcmp(argv[1], "capi") != 0 && strcmp(argv[1], "shim") != 0)) {
    fprintf(stderr, "usage: shim_bench3d capi|shim VOLUME\n");
    return 2;
  }
  double volume = atof(argv[2]);
  size_t tets = 0, points = 0;
  auto t0 = std::chrono::steady_clock::now();
  int rc = strcmp(argv[1], "capi") == 0 ? run_capi(volume, &tets, &points)
                                        : run_shim(volume, &tets, &points);
  double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (rc != 0) return rc;
  printf("{\"mode\": \"%s\", \"seconds\": %.6f, \"tets\": %zu, \"points\": %zu}\n", argv[1], s,
         tets, points);
  return 0;
}
