// tetgenio's file loaders and line helpers through idmesh's TetGen interface: load_vtk reads a
// legacy VTK surface that then meshes to its volume (and a bad file fails naming the line);
// load_edge fills edgelist/edgemarkerlist, and tetrahedralize takes those edges as segments;
// load_pbc is refused; readline, findnextfield, readnumberline and findnextnumber walk a file
// as TetGen's do, and load_node_call reads the points after a header the caller parsed. Files are written to the current directory (ctest's build directory).
#include <tetgen.h>
#include <idmesh.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

static int failures = 0;
static void check(bool ok, const std::string &what) {
  if (!ok) {
    fprintf(stderr, "FAIL: %s\n", what.c_str());
    failures++;
  }
}

static void write_file(const char *name, const char *text) {
  FILE *f = fopen(name, "w");
  if (f == NULL) {
    check(false, std::string("cannot write ") + name);
    return;
  }
  fputs(text, f);
  fclose(f);
}

static double volume(const tetgenio &out) {
  double v = 0;
  for (int t = 0; t < out.numberoftetrahedra; t++) {
    const REAL *p[4];
    for (int k = 0; k < 4; k++)
      p[k] = &out.pointlist[3 * (out.tetrahedronlist[4 * t + k] - out.firstnumber)];
    double a[3], b[3], c[3];
    for (int k = 0; k < 3; k++) {
      a[k] = p[1][k] - p[0][k];
      b[k] = p[2][k] - p[0][k];
      c[k] = p[3][k] - p[0][k];
    }
    v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
          a[2] * (b[0] * c[1] - b[1] * c[0])) / 6.0;
  }
  return std::fabs(v);
}

// The unit cube as POLYDATA quads, with a marker per face.
static const char *CUBE_VTK =
    "# vtk DataFile Version 3.0\n"
    "unit cube\n"
    "ASCII\n"
    "DATASET POLYDATA\n"
    "POINTS 8 double\n"
    "0 0 0 1 0 0 1 1 0 0 1 0\n"
    "0 0 1 1 0 1 1 1 1 0 1 1\n"
    "POLYGONS 6 30\n"
    "4 0 3 2 1\n"
    "4 4 5 6 7\n"
    "4 0 1 5 4\n"
    "4 1 2 6 5\n"
    "4 2 3 7 6\n"
    "4 3 0 4 7\n"
    "CELL_DATA 6\n"
    "SCALARS marker int 1\n"
    "LOOKUP_TABLE default\n"
    "1 2 3 4 5 6\n";

static void vtk() {
  write_file("loaders_cube.vtk", CUBE_VTK);
  tetgenio in, out;
  char name[] = "loaders_cube";
  check(in.load_vtk(name), "load_vtk");
  check(in.numberofpoints == 8 && in.numberoffacets == 6 && in.firstnumber == 0,
        "load_vtk: 8 points, 6 facets, 0-based");
  check(in.facetmarkerlist != NULL && in.facetmarkerlist[5] == 6, "load_vtk: facet markers");
  char sw[] = "pq1.414a0.01Q";
  try {
    tetrahedralize(sw, &in, &out);
    check(std::fabs(volume(out) - 1.0) < 1e-12, "the VTK cube meshes to volume 1");
    check(out.numberoftetrahedra > 100, "a0.01 refines the cube");
  } catch (int c) {
    check(false, "tetrahedralize threw " + std::to_string(c) + ": " + idm_last_error());
  }
  // load_plc picks the reader by extension, and by object VTK.
  tetgenio by_ext, by_object;
  char with_ext[] = "loaders_cube.vtk";
  check(by_ext.load_plc(with_ext, tetgenbehavior::POLY) && by_ext.numberoffacets == 6,
        "load_plc on a .vtk name");
  check(by_object.load_plc(name, tetgenbehavior::VTK) && by_object.numberoffacets == 6,
        "load_plc with object VTK");
  // A bad corner: the load fails and the message names the file and line 10.
  std::string bad = CUBE_VTK;
  bad.replace(bad.find("4 4 5 6 7"), 9, "4 4 5 6 9");
  write_file("loaders_bad.vtk", bad.c_str());
  tetgenio b;
  char bad_name[] = "loaders_bad.vtk";
  check(!b.load_vtk(bad_name), "a bad VTK file fails");
  std::string msg = idm_last_error();
  check(msg.find("loaders_bad.vtk:10") != std::string::npos, "the message names the line: " + msg);
}

// A cube (1-based .poly) with an interior edge between two inner points, in a .edge file.
static void edges() {
  write_file("loaders_edge.poly",
             "10 3 0 0\n"
             "1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n5 0 0 1\n6 1 0 1\n7 1 1 1\n8 0 1 1\n"
             "9 0.25 0.25 0.25\n10 0.75 0.75 0.75\n"
             "6 0\n"
             "1\n4 1 4 3 2\n1\n4 5 6 7 8\n1\n4 1 2 6 5\n"
             "1\n4 2 3 7 6\n1\n4 3 4 8 7\n1\n4 4 1 5 8\n"
             "0\n0\n");
  write_file("loaders_edge.edge", "1 1\n1 9 10 7\n");
  tetgenio in, out;
  char name[] = "loaders_edge";
  check(in.load_poly(name), "load_poly");
  check(in.load_edge(name), std::string("load_edge: ") + idm_last_error());
  check(in.numberofedges == 1 && in.edgelist != NULL && in.edgelist[0] == 9 &&
            in.edgelist[1] == 10 && in.edgemarkerlist != NULL && in.edgemarkerlist[0] == 7,
        "load_edge fills edgelist and edgemarkerlist as in the file");
  char sw[] = "peQ";
  try {
    tetrahedralize(sw, &in, &out);
    // The segment is in the mesh: every output edge with marker 7 lies on it, and together
    // they cover its length.
    double length = 0;
    for (int e = 0; e < out.numberofedges; e++) {
      if (out.edgemarkerlist[e] != 7) continue;
      const REAL *a = &out.pointlist[3 * (out.edgelist[2 * e] - 1)];
      const REAL *c = &out.pointlist[3 * (out.edgelist[2 * e + 1] - 1)];
      check(a[0] == a[1] && a[1] == a[2] && c[0] == c[1] && c[1] == c[2],
            "an edge marked 7 off the diagonal segment");
      length += std::fabs(c[0] - a[0]) * std::sqrt(3.0);
    }
    check(std::fabs(length - 0.5 * std::sqrt(3.0)) < 1e-12,
          "the marked edges cover the segment: length " + std::to_string(length));
  } catch (int c) {
    check(false, "tetrahedralize with edges threw " + std::to_string(c) + ": " + idm_last_error());
  }
  write_file("loaders_bad.edge", "1 0\n1 9 11\n");
  char bad[] = "loaders_bad";
  tetgenio b;
  b.numberofpoints = 10;
  b.firstnumber = 1;
  check(!b.load_edge(bad), "an edge to a missing point fails");
  std::string msg = idm_last_error();
  check(msg.find("loaders_bad.edge:2") != std::string::npos, "the message names the line: " + msg);
  tetgenio p;
  char pbc[] = "loaders_edge";
  check(!p.load_pbc(pbc), "load_pbc is refused");
}

static void line_helpers() {
  write_file("loaders_lines.txt", "\n   \t\n# a comment\n  12, 3.5;x  -4 # tail\n\nword only\n7\n");
  FILE *f = fopen("loaders_lines.txt", "r");
  if (f == NULL) return check(false, "cannot read loaders_lines.txt");
  tetgenio io;
  char buf[INPUTLINESIZE];
  int line = 0;
  char *s = io.readline(buf, f, &line);
  check(s != NULL && std::string(s, 11) == "# a comment" && line == 3,
        "readline skips blank lines, not comments (line " + std::to_string(line) + ")");
  s = io.readline(buf, f, &line);
  check(s != NULL && s[0] == '1' && line == 4, "readline: first non-blank character");
  s = io.findnextfield(s);
  check(std::string(s, 3) == "3.5", "findnextfield skips the field and ', '");
  s = io.findnextfield(s);
  check(s[0] == 'x', "findnextfield stops after ';'");
  rewind(f);
  s = io.readnumberline(buf, f, NULL);
  check(s != NULL && s[0] == '1' && s[1] == '2', "readnumberline skips lines without numbers");
  s = io.findnextnumber(s);
  check(std::string(s, 3) == "3.5", "findnextnumber: 3.5");
  s = io.findnextnumber(s);
  check(s[0] == '-' && s[1] == '4', "findnextnumber skips non-numbers: -4");
  s = io.findnextnumber(s);
  check(*s == '\0', "findnextnumber ends at a comment");
  s = io.readnumberline(buf, f, NULL);
  check(s != NULL && s[0] == '7', "readnumberline skips 'word only'");
  check(io.readnumberline(buf, f, NULL) == NULL && io.readline(buf, f, NULL) == NULL,
        "NULL at the end of the file");
  fclose(f);
}

// load_node_call: the caller reads the header line itself (with TetGen's helpers), then the
// points come from the open file.
static void node_call() {
  write_file("loaders_points.node",
             "# header next\n3 3 1 1\n1 0 0 0 7.5 4\n\n2 1 0 0 8.5 5 # comment\n3 0 1 0 9.5 6\n");
  write_file("loaders_short.node", "3 3 0 0\n1 0 0 0\n2 1 0\n3 0 1 0\n");
  for (int bad = 0; bad < 2; bad++) {
    FILE *f = fopen(bad ? "loaders_short.node" : "loaders_points.node", "r");
    if (f == NULL) return check(false, "cannot read the .node file");
    tetgenio io;
    char buf[INPUTLINESIZE];
    char name[] = "loaders_points.node";
    char *s = io.readnumberline(buf, f, name);
    io.numberofpoints = (int)strtol(s, &s, 0);
    s = io.findnextnumber(s);
    io.mesh_dim = (int)strtol(s, &s, 0);
    s = io.findnextnumber(s);
    io.numberofpointattributes = (int)strtol(s, &s, 0);
    s = io.findnextnumber(s);
    int markers = (int)strtol(s, &s, 0);
    bool ok = io.load_node_call(f, markers, 0, name);
    fclose(f);
    if (bad) {
      check(!ok, "load_node_call fails on a point without z");
      continue;
    }
    check(ok, std::string("load_node_call: ") + idm_last_error());
    check(io.numberofpoints == 3 && io.firstnumber == 1 && io.pointlist[3] == 1.0 &&
              io.pointlist[7] == 1.0,
          "load_node_call: 3 points, 1-based, coordinates");
    check(io.numberofpointattributes == 1 && io.pointattributelist != NULL &&
              io.pointattributelist[2] == 9.5,
          "load_node_call: attributes");
    check(io.pointmarkerlist != NULL && io.pointmarkerlist[1] == 5, "load_node_call: markers");
  }
}

int main() {
  node_call();
  vtk();
  edges();
  line_helpers();
  if (failures) fprintf(stderr, "%d checks failed\n", failures);
  return failures ? 1 : 0;
}
