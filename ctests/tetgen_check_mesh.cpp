// Checks a mesh written in TetGen's files against its input, independently of who wrote it:
//   tetgen_check_mesh INPUT STEM [MAX_VOLUME]
//   tetgen_check_mesh --fails INPUT SWITCHES
//     exit 0 when idmesh's own tetrahedralize(SWITCHES) on INPUT throws too (printing the code),
//     so that a run on libtet.so.1.5 can be checked to fail exactly when idmesh itself fails.
// reads INPUT (any file tetgenio::load_plc reads) and STEM.node/.ele/.face, and checks that
// every tetrahedron is positively oriented, no face has more than two tetrahedra, every face
// with one tetrahedron is listed in STEM.face, every input point is kept at its index, no
// tetrahedron exceeds MAX_VOLUME, and the total volume equals that of idmesh's own mesh of
// INPUT (computed here through idmesh's TetGen interface).
#include <tetgen.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

int failures = 0;
void check(bool ok, const std::string &what) {
  if (!ok) {
    fprintf(stderr, "FAIL: %s\n", what.c_str());
    failures++;
  }
}

// The data lines of a TetGen file (comments and blank lines dropped).
std::vector<std::vector<double>> rows(const std::string &path) {
  std::ifstream f(path);
  std::vector<std::vector<double>> out;
  std::string line;
  while (std::getline(f, line)) {
    line = line.substr(0, line.find('#'));
    std::istringstream s(line);
    std::vector<double> r;
    double x;
    while (s >> x) r.push_back(x);
    if (!r.empty()) out.push_back(r);
  }
  return out;
}

double tet_volume(const double *a, const double *b, const double *c, const double *d) {
  double u[3], v[3], w[3];
  for (int k = 0; k < 3; k++) {
    u[k] = b[k] - a[k];
    v[k] = c[k] - a[k];
    w[k] = d[k] - a[k];
  }
  return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
          u[2] * (v[0] * w[1] - v[1] * w[0])) /
         6.0;
}

}  // namespace

int main(int argc, char **argv) {
  if (argc == 4 && std::string(argv[1]) == "--fails") {
    tetgenio in, out;
    if (!in.load_plc(argv[2], tetgenbehavior::POLY)) return 0;
    std::string sw = std::string(argv[3]) + "Q";
    try {
      tetrahedralize(&sw[0], &in, &out);
    } catch (int code) {
      printf("idmesh fails on %s with code %d too\n", argv[2], code);
      return 0;
    }
    return 1;
  }
  if (argc < 3) {
    fprintf(stderr, "usage: tetgen_check_mesh INPUT STEM [MAX_VOLUME]\n");
    return 2;
  }
  std::string stem = argv[2];
  double max_volume = argc > 3 ? atof(argv[3]) : 0.0;
  auto node = rows(stem + ".node"), ele = rows(stem + ".ele"), face = rows(stem + ".face");
  if (node.empty() || ele.empty() || face.empty()) {
    fprintf(stderr, "FAIL: %s.node/.ele/.face missing or empty\n", stem.c_str());
    return 1;
  }
  int np = (int)node[0][0], nt = (int)ele[0][0], nf = (int)face[0][0];
  check((int)node.size() == np + 1 && (int)ele.size() == nt + 1 && (int)face.size() == nf + 1,
        "item counts match the headers");
  int base = (int)node[1][0];
  std::vector<double> xyz(3 * np);
  for (int i = 0; i < np; i++)
    for (int k = 0; k < 3; k++) xyz[3 * i + k] = node[i + 1][k + 1];

  tetgenio in;
  if (!in.load_plc(argv[1], tetgenbehavior::POLY)) return 1;
  check(np >= in.numberofpoints, "the output keeps every input point");
  for (int i = 0; i < in.numberofpoints && i < np; i++)
    for (int k = 0; k < 3; k++)
      if (xyz[3 * i + k] != in.pointlist[3 * i + k]) {
        check(false, "input point " + std::to_string(i) + " moved or renumbered");
        i = in.numberofpoints;
        break;
      }

  double volume = 0;
  std::map<std::array<int, 3>, int> face_count;
  for (int t = 0; t < nt; t++) {
    int v[4];
    for (int k = 0; k < 4; k++) v[k] = (int)ele[t + 1][k + 1] - base;
    double vol = tet_volume(&xyz[3 * v[0]], &xyz[3 * v[1]], &xyz[3 * v[2]], &xyz[3 * v[3]]);
    if (!(vol > 0)) check(false, "tetrahedron " + std::to_string(t) + " is not positive");
    if (max_volume > 0 && vol > max_volume * (1 + 1e-12))
      check(false, "tetrahedron " + std::to_string(t) + " exceeds the volume bound");
    volume += vol;
    const int fc[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
    for (auto &f : fc) {
      std::array<int, 3> key = {v[f[0]], v[f[1]], v[f[2]]};
      std::sort(key.begin(), key.end());
      face_count[key]++;
    }
  }
  std::map<std::array<int, 3>, int> listed;
  for (int i = 0; i < nf; i++) {
    std::array<int, 3> key = {(int)face[i + 1][1] - base, (int)face[i + 1][2] - base,
                              (int)face[i + 1][3] - base};
    std::sort(key.begin(), key.end());
    listed[key] = 1;
  }
  for (auto &fc : face_count) {
    if (fc.second > 2) check(false, "a face has more than two tetrahedra");
    if (fc.second == 1 && !listed.count(fc.first)) {
      check(false, "a boundary face is missing from the .face file");
      break;
    }
  }

  // The same domain as idmesh's own mesh of the input.
  tetgenio ref;
  char sw[] = "pQ";
  try {
    tetrahedralize(sw, &in, &ref);
  } catch (int code) {
    fprintf(stderr, "FAIL: idmesh could not mesh %s (code %d)\n", argv[1], code);
    return 1;
  }
  double ref_volume = 0;
  for (int t = 0; t < ref.numberoftetrahedra; t++) {
    const int *v = &ref.tetrahedronlist[4 * t];
    int b = ref.firstnumber;
    ref_volume += tet_volume(&ref.pointlist[3 * (v[0] - b)], &ref.pointlist[3 * (v[1] - b)],
                             &ref.pointlist[3 * (v[2] - b)], &ref.pointlist[3 * (v[3] - b)]);
  }
  check(std::fabs(volume - ref_volume) <= 1e-9 * ref_volume,
        "total volume " + std::to_string(volume) + " equals idmesh's " + std::to_string(ref_volume));
  if (failures) return 1;
  printf("%s: %d points, %d tetrahedra, %d faces, volume %.12g: OK\n", stem.c_str(), np, nt, nf,
         volume);
  return 0;
}
