// Bad input through idmesh's TetGen interface: each failure is thrown as TetGen's int code
// with a message in idm_last_error(), nothing leaks (run under ASan/UBSan by
// IDMESH_SANITIZE=address,undefined scripts/ctest.sh), and the host goes on to mesh the next
// input. Also: a C++ exception thrown by the user's tetunsuitable reaches the caller.
#include <tetgen.h>
#include <idmesh.h>

#include <cstdio>
#include <stdexcept>
#include <string>

static int failures = 0;
static void check(bool ok, const std::string &what) {
  if (!ok) {
    fprintf(stderr, "FAIL: %s\n", what.c_str());
    failures++;
  }
}

// A unit tetrahedron as a PLC; `extra` more points, and the facets' first vertex shifted by
// `bad` (an index out of range when nonzero).
static void tetra(tetgenio &in, int bad) {
  in.firstnumber = 1;
  in.numberofpoints = 4;
  in.pointlist = new REAL[12]{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const int f[4][3] = {{1, 2, 3}, {1, 2, 4}, {1, 3, 4}, {2, 3, 4}};
  in.numberoffacets = 4;
  in.facetlist = new tetgenio::facet[4];
  for (int i = 0; i < 4; i++) {
    tetgenio::facet *fa = &in.facetlist[i];
    tetgenio::init(fa);
    fa->numberofpolygons = 1;
    fa->polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&fa->polygonlist[0]);
    fa->polygonlist[0].numberofvertices = 3;
    fa->polygonlist[0].vertexlist = new int[3]{f[i][0] + (i == 0 ? bad : 0), f[i][1], f[i][2]};
  }
}

// Expects tetrahedralize to throw `code` with a message containing `word`.
static void expect_throw(tetgenio &in, const char *switches, int code, const char *word) {
  tetgenio out;
  std::string sw = switches;
  try {
    tetrahedralize(&sw[0], &in, &out);
    check(false, std::string("no throw for ") + word);
  } catch (int c) {
    std::string msg = idm_last_error();
    check(c == code, "code " + std::to_string(c) + " instead of " + std::to_string(code) +
                         " (" + msg + ")");
    check(msg.find(word) != std::string::npos, "message '" + msg + "' lacks '" + word + "'");
    printf("thrown %d: %s\n", c, msg.c_str());
  }
}

static bool throwing_sizing(REAL *, REAL *, REAL *, REAL *, REAL *, REAL) {
  throw std::runtime_error("from tetunsuitable");
}

int main() {
  {
    tetgenio in;
    tetra(in, 9);  // facet vertex 10 of 4
    expect_throw(in, "pQ", 10, "facet");
  }
  {
    tetgenio in;
    tetra(in, 0);
    expect_throw(in, "pqrQ", 10, "-r");
    expect_throw(in, "pq1.4/20/170Q", 10, "dihedral");
  }
  {
    // A triangle piercing the tetrahedron's face: self-intersecting input, code 3.
    tetgenio in;
    tetra(in, 0);
    REAL *p = new REAL[21]{0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0.2, 0.2, -1, 0.2, 0.2, 2, 0.2, 2, 0.5};
    delete[] in.pointlist;
    in.pointlist = p;
    in.numberofpoints = 7;
    tetgenio::facet *old = in.facetlist;
    in.facetlist = new tetgenio::facet[5];
    for (int i = 0; i < 4; i++) in.facetlist[i] = old[i];
    delete[] old;
    tetgenio::facet *fa = &in.facetlist[4];
    tetgenio::init(fa);
    fa->numberofpolygons = 1;
    fa->polygonlist = new tetgenio::polygon[1];
    fa->polygonlist[0].numberofvertices = 3;
    fa->polygonlist[0].vertexlist = new int[3]{5, 6, 7};
    in.numberoffacets = 5;
    expect_throw(in, "pQ", 3, "");
  }
  {
    tetgenio in;
    tetra(in, 0);
    // An anisotropic metric (6 values per point) is refused by name.
    in.numberofpointmtrs = 6;
    in.pointmtrlist = new REAL[24]();
    expect_throw(in, "pmQ", 10, "isotropic");
  }
  {
    tetgenio in, out;
    tetra(in, 0);
    in.tetunsuitable = throwing_sizing;
    char sw[] = "pqQ";
    try {
      tetrahedralize(sw, &in, &out);
      check(false, "the exception of tetunsuitable was lost");
    } catch (const std::runtime_error &e) {
      check(std::string(e.what()) == "from tetunsuitable", "wrong exception");
    }
  }
  // The host goes on: the next input meshes, with a working sizing test of its own.
  for (int firstnumber = 0; firstnumber < 2; firstnumber++) {
    tetgenio in, out;
    tetra(in, 0);
    if (firstnumber == 0)
      for (int i = 0; i < 4; i++)
        for (int k = 0; k < 3; k++) in.facetlist[i].polygonlist[0].vertexlist[k] -= 1;
    in.firstnumber = firstnumber;
    char sw[] = "pq1.414a0.001nneQ";
    try {
      tetrahedralize(sw, &in, &out);
      check(out.numberoftetrahedra > 50 && out.firstnumber == firstnumber,
            "the next input meshes, numbered as its input");
      check(out.point2tetlist != NULL && out.face2tetlist == out.adjtetlist &&
                out.tet2edgelist != NULL && out.numberofedges > 0,
            "TetGen 1.6's connectivity lists are filled");
      printf("meshed: %d tetrahedra from firstnumber %d\n", out.numberoftetrahedra, firstnumber);
    } catch (int code) {
      check(false, "valid input threw " + std::to_string(code) + ": " + idm_last_error());
    }
  }
  return failures ? 1 : 0;
}
