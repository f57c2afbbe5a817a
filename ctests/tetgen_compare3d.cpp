// Compares idmesh's 3D mesher (through the C API) with TetGen 1.5 (Debian libtet1.5-dev,
// tetrahedralize() with -DTETLIBRARY) on the same PLCs and switches. Both results must be
// valid and cover the same volume; the ratios of tet counts, of the largest radius-edge ratio
// and of the smallest dihedral angle are printed and the count ratio is checked.
#include <tetgen.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

extern "C" {
#include "idmesh.h"
}

namespace {

struct Plc {
    std::string name;
    std::vector<double> xyz;
    std::vector<std::vector<unsigned>> facets;  // one loop each
    std::vector<double> holes;
    double volume;  // the exact volume of the domain
};

void add_box(Plc &p, double x0, double y0, double z0, double x1, double y1, double z1) {
    unsigned o = static_cast<unsigned>(p.xyz.size() / 3);
    for (int i = 0; i < 8; ++i) {
        p.xyz.push_back(i & 1 ? x1 : x0);
        p.xyz.push_back(i & 2 ? y1 : y0);
        p.xyz.push_back(i & 4 ? z1 : z0);
    }
    const unsigned q[6][4] = {{0, 1, 3, 2}, {4, 5, 7, 6}, {0, 1, 5, 4},
                              {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 3, 7, 5}};
    for (const auto &f : q) p.facets.push_back({o + f[0], o + f[1], o + f[2], o + f[3]});
}

double tet_volume(const double *a, const double *b, const double *c, const double *d) {
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; ++k) {
        u[k] = b[k] - a[k];
        v[k] = c[k] - a[k];
        w[k] = d[k] - a[k];
    }
    return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
            u[2] * (v[0] * w[1] - v[1] * w[0])) /
           6.0;
}

struct Stats {
    size_t tets = 0;
    double volume = 0, max_re = 0, min_dih = 180, max_vol = 0;
    bool positive = true;
};

// Radius-edge ratio and smallest dihedral angle of one tet (floating point).
void quality(const double *p[4], double &re, double &mindih) {
    double a[3][3];
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) a[i][k] = p[i + 1][k] - p[0][k];
    double n01 = a[1][1] * a[2][2] - a[1][2] * a[2][1], n02 = a[1][2] * a[2][0] - a[1][0] * a[2][2],
           n03 = a[1][0] * a[2][1] - a[1][1] * a[2][0];
    double det = a[0][0] * n01 + a[0][1] * n02 + a[0][2] * n03;
    double l[3];
    for (int i = 0; i < 3; ++i) l[i] = a[i][0] * a[i][0] + a[i][1] * a[i][1] + a[i][2] * a[i][2];
    double c[3] = {0, 0, 0};
    double cr[3][3] = {{a[1][1] * a[2][2] - a[1][2] * a[2][1], a[1][2] * a[2][0] - a[1][0] * a[2][2],
                        a[1][0] * a[2][1] - a[1][1] * a[2][0]},
                       {a[2][1] * a[0][2] - a[2][2] * a[0][1], a[2][2] * a[0][0] - a[2][0] * a[0][2],
                        a[2][0] * a[0][1] - a[2][1] * a[0][0]},
                       {a[0][1] * a[1][2] - a[0][2] * a[1][1], a[0][2] * a[1][0] - a[0][0] * a[1][2],
                        a[0][0] * a[1][1] - a[0][1] * a[1][0]}};
    for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) c[k] += l[i] * cr[i][k] / (2 * det);
    double r = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    double e2 = 1e300;
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
            double s = 0;
            for (int k = 0; k < 3; ++k) s += (p[i][k] - p[j][k]) * (p[i][k] - p[j][k]);
            e2 = std::min(e2, s);
        }
    re = r / std::sqrt(e2);
    // Face normals (outward); dihedral = pi - angle between normals.
    double nrm[4][3];
    for (int f = 0; f < 4; ++f) {
        int idx[3], m = 0;
        for (int i = 0; i < 4; ++i)
            if (i != f) idx[m++] = i;
        double u[3], v[3];
        for (int k = 0; k < 3; ++k) {
            u[k] = p[idx[1]][k] - p[idx[0]][k];
            v[k] = p[idx[2]][k] - p[idx[0]][k];
        }
        double nn[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
        double side = 0;
        for (int k = 0; k < 3; ++k) side += nn[k] * (p[f][k] - p[idx[0]][k]);
        double len = std::sqrt(nn[0] * nn[0] + nn[1] * nn[1] + nn[2] * nn[2]);
        for (int k = 0; k < 3; ++k) nrm[f][k] = (side > 0 ? -nn[k] : nn[k]) / len;
    }
    mindih = 180;
    for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
            double d = -(nrm[i][0] * nrm[j][0] + nrm[i][1] * nrm[j][1] + nrm[i][2] * nrm[j][2]);
            d = std::max(-1.0, std::min(1.0, d));
            mindih = std::min(mindih, std::acos(d) * 180.0 / M_PI);
        }
}

Stats stats_of(const double *xyz, const unsigned *tets, size_t n, int base) {
    Stats s;
    s.tets = n;
    for (size_t t = 0; t < n; ++t) {
        const double *p[4];
        for (int i = 0; i < 4; ++i) p[i] = xyz + 3 * (tets[4 * t + i] - base);
        double v = tet_volume(p[0], p[1], p[2], p[3]);
        if (!(v > 0)) s.positive = false;
        s.volume += v;
        s.max_vol = std::max(s.max_vol, v);
        double re, dih;
        quality(p, re, dih);
        s.max_re = std::max(s.max_re, re);
        s.min_dih = std::min(s.min_dih, dih);
    }
    return s;
}

bool run_idmesh(const Plc &p, double ratio, double maxvol, Stats &out) {
    idm_mesher3d *m = nullptr;
    if (idm_mesher3d_new(&m) != IDM_OK) return false;
    bool ok = idm_mesher3d_add_points(m, p.xyz.data(), p.xyz.size() / 3, nullptr) == IDM_OK;
    for (const auto &f : p.facets) {
        size_t off[2] = {0, f.size()};
        std::vector<uint32_t> idx(f.begin(), f.end());
        ok = ok && idm_mesher3d_add_facet(m, idx.data(), off, 1, nullptr, 0, 1) == IDM_OK;
    }
    for (size_t h = 0; h < p.holes.size() / 3; ++h)
        ok = ok && idm_mesher3d_add_hole(m, &p.holes[3 * h]) == IDM_OK;
    idm_options3d o;
    idm_options3d_default(&o);
    o.radius_edge = ratio;
    o.max_volume = maxvol;
    ok = ok && idm_mesher3d_set_options(m, &o) == IDM_OK;
    ok = ok && idm_mesher3d_refine(m) == IDM_OK;
    ok = ok && idm_mesher3d_validate(m) == IDM_OK;
    if (!ok) {
        std::printf("  idmesh failed: %s\n", idm_last_error());
        idm_mesher3d_free(m);
        return false;
    }
    const double *xyz = nullptr;
    const uint32_t *tets = nullptr;
    size_t nv = 0, nt = 0;
    idm_mesher3d_vertices(m, &xyz, &nv);
    idm_mesher3d_tets(m, &tets, &nt);
    std::vector<unsigned> t(tets, tets + 4 * nt);
    out = stats_of(xyz, t.data(), nt, 0);
    idm_mesher3d_free(m);
    return true;
}

bool run_tetgen(const Plc &p, const std::string &switches, Stats &out) {
    tetgenio in, res;
    in.firstnumber = 0;
    in.numberofpoints = static_cast<int>(p.xyz.size() / 3);
    in.pointlist = new REAL[p.xyz.size()];
    std::copy(p.xyz.begin(), p.xyz.end(), in.pointlist);
    in.numberoffacets = static_cast<int>(p.facets.size());
    in.facetlist = new tetgenio::facet[in.numberoffacets];
    in.facetmarkerlist = new int[in.numberoffacets];
    for (int i = 0; i < in.numberoffacets; ++i) {
        tetgenio::facet &f = in.facetlist[i];
        tetgenio::init(&f);
        f.numberofpolygons = 1;
        f.polygonlist = new tetgenio::polygon[1];
        tetgenio::init(&f.polygonlist[0]);
        f.polygonlist[0].numberofvertices = static_cast<int>(p.facets[i].size());
        f.polygonlist[0].vertexlist = new int[p.facets[i].size()];
        for (size_t k = 0; k < p.facets[i].size(); ++k)
            f.polygonlist[0].vertexlist[k] = static_cast<int>(p.facets[i][k]);
        in.facetmarkerlist[i] = 1;
    }
    in.numberofholes = static_cast<int>(p.holes.size() / 3);
    if (in.numberofholes) {
        in.holelist = new REAL[p.holes.size()];
        std::copy(p.holes.begin(), p.holes.end(), in.holelist);
    }
    std::vector<char> sw(switches.begin(), switches.end());
    sw.push_back('\0');
    try {
        tetrahedralize(sw.data(), &in, &res);
    } catch (...) {
        std::printf("  tetgen threw\n");
        return false;
    }
    std::vector<unsigned> t(res.tetrahedronlist, res.tetrahedronlist + 4 * res.numberoftetrahedra);
    out = stats_of(res.pointlist, t.data(), res.numberoftetrahedra, res.firstnumber);
    return true;
}

}  // namespace

int main() {
    std::vector<Plc> cases;
    {
        Plc p{"unit cube", {}, {}, {}, 1.0};
        add_box(p, 0, 0, 0, 1, 1, 1);
        cases.push_back(p);
    }
    {
        Plc p{"box with a box-shaped hole", {}, {}, {}, 64.0 - 1.0 * 2.0 * 1.5};
        add_box(p, 0, 0, 0, 4, 4, 4);
        add_box(p, 1, 1, 1, 2, 3, 2.5);
        p.holes = {1.5, 2.0, 2.0};
        cases.push_back(p);
    }
    {
        Plc p{"flat slab 8 x 8 x 1", {}, {}, {}, 64.0};
        add_box(p, 0, 0, 0, 8, 8, 1);
        cases.push_back(p);
    }
    struct Run {
        double ratio, vol_fraction;
    };
    const Run runs[] = {{2.0, 0.0}, {1.414, 0.001}};
    int failures = 0;
    std::printf("%-28s %-14s %9s %9s %7s %8s %8s %8s %8s\n", "case", "switches", "tets idm", "tetgen",
                "ratio", "re idm", "re tg", "dih idm", "dih tg");
    for (const auto &c : cases) {
        for (const auto &r : runs) {
            double maxvol = r.vol_fraction * c.volume;
            char sw[64];
            if (maxvol > 0)
                std::snprintf(sw, sizeof sw, "pq%.3fa%.6fQ", r.ratio, maxvol);
            else
                std::snprintf(sw, sizeof sw, "pq%.3fQ", r.ratio);
            Stats a, b;
            bool ok_a = run_idmesh(c, r.ratio, maxvol, a);
            bool ok_b = run_tetgen(c, sw, b);
            if (!ok_a || !ok_b) {
                std::printf("%-28s %-14s FAILED (idmesh %d, tetgen %d)\n", c.name.c_str(), sw, ok_a, ok_b);
                ++failures;
                continue;
            }
            double ratio = static_cast<double>(a.tets) / static_cast<double>(b.tets);
            std::printf("%-28s %-14s %9zu %9zu %7.3f %8.3f %8.3f %8.2f %8.2f\n", c.name.c_str(), sw, a.tets,
                        b.tets, ratio, a.max_re, b.max_re, a.min_dih, b.min_dih);
            bool good = a.positive && std::fabs(a.volume - c.volume) <= 1e-9 * c.volume &&
                        std::fabs(b.volume - c.volume) <= 1e-6 * c.volume &&
                        a.max_re <= r.ratio * (1 + 1e-9) &&
                        (maxvol <= 0 || a.max_vol <= maxvol * (1 + 1e-9));
            // Element counts: at most 1.3x TetGen's, as the issue asks, once refinement is
            // real (tiny meshes without a volume bound are dominated by the boundary).
            if (maxvol > 0 && ratio > 1.3) good = false;
            if (!good) {
                std::printf("  check failed: volume %.12g (tetgen %.12g, exact %.12g), max radius-edge %.4f, "
                            "largest tet %.6g (bound %.6g)\n",
                            a.volume, b.volume, c.volume, a.max_re, a.max_vol, maxvol);
                ++failures;
            }
        }
    }
    std::printf("%s\n", failures ? "FAILED" : "all comparisons passed");
    return failures ? 1 : 0;
}
