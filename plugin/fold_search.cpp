// fold_search: the fold guard's search (include/body/injectivity.idp).
//   boundarySegmentCrossings(xyz, corners, pair) (2D), boundaryTriangleCrossings (3D): how many pairs
//   of boundary elements (segments in 2D, triangles in 3D) that share no vertex cross each other.
//   xyz: the vertices' x, then their y, then their z; corners: 2 or 3 vertex numbers per element;
//   pair receives the first crossing pair found. A sweep over the elements sorted by their lowest x,
//   with bounding boxes: milliseconds, where FreeFEM's interpreter took 15 s for the 1762 boundary
//   triangles of the coarse 3D Hertz mesh.
#include "ff++.hpp"
#include <algorithm>
#include <vector>

namespace {

struct Crossings {
  const double *px, *py, *pz;   // vertex coordinates
  double orient2(long a, long b, long c) const {
    return (px[b] - px[a])*(py[c] - py[a]) - (py[b] - py[a])*(px[c] - px[a]);
  }
  double orient3(long a, long b, long c, long d) const {
    double bx = px[b] - px[a], by = py[b] - py[a], bz = pz[b] - pz[a];
    double cx = px[c] - px[a], cy = py[c] - py[a], cz = pz[c] - pz[a];
    double dx = px[d] - px[a], dy = py[d] - py[a], dz = pz[d] - pz[a];
    return bx*(cy*dz - cz*dy) - by*(cx*dz - cz*dx) + bz*(cx*dy - cy*dx);
  }
  // the segment q0 q1 passes through the triangle t: its ends strictly on either side of the
  // triangle's plane, and the crossing point inside the triangle or on its edges (a symmetric
  // fold can cross exactly along an edge)
  bool segmentTriangle(long q0, long q1, const long *t) const {
    double s0 = orient3(t[0], t[1], t[2], q0), s1 = orient3(t[0], t[1], t[2], q1);
    if (!(s0*s1 < 0)) return false;
    double a = orient3(q0, q1, t[0], t[1]), b = orient3(q0, q1, t[1], t[2]), c = orient3(q0, q1, t[2], t[0]);
    return (a >= 0 && b >= 0 && c >= 0) || (a <= 0 && b <= 0 && c <= 0);
  }
  // two segments (2D) meet, at a point of either (collinear overlaps aside), or two triangles
  // (3D) cut each other
  bool cross(const long *e, const long *f, long d) const {
    if (d == 2) {
      double o1 = orient2(e[0], e[1], f[0]), o2 = orient2(e[0], e[1], f[1]);
      double o3 = orient2(f[0], f[1], e[0]), o4 = orient2(f[0], f[1], e[1]);
      if (o1 == 0 && o2 == 0) return false;
      return o1*o2 <= 0 && o3*o4 <= 0;
    }
    for (int k = 0; k < 3; k++)
      if (segmentTriangle(e[k], e[(k + 1) % 3], f) || segmentTriangle(f[k], f[(k + 1) % 3], e)) return true;
    return false;
  }
};

long boundaryCrossings(KN<double> *const &xyz, KN<long> *const &corners, long d, KN<long> *const &pair) {
  long nb = corners->N()/d;
  long nv = xyz->N()/3;
  Crossings geometry;
  geometry.px = &(*xyz)[0];
  geometry.py = geometry.px + nv;
  geometry.pz = geometry.py + nv;
  const double *coordinate[3] = {geometry.px, geometry.py, geometry.pz};
  const long *c = &(*corners)[0];
  std::vector<double> low(3*nb), high(3*nb);
  std::vector<long> order(nb);
  for (long e = 0; e < nb; e++) {
    order[e] = e;
    for (int i = 0; i < 3; i++) {
      low[3*e + i] = 1e300; high[3*e + i] = -1e300;
      for (long j = 0; j < d; j++) {
        double v = coordinate[i][c[d*e + j]];
        low[3*e + i] = std::min(low[3*e + i], v); high[3*e + i] = std::max(high[3*e + i], v);
      }
    }
  }
  std::sort(order.begin(), order.end(), [&](long a, long b) { return low[3*a] < low[3*b]; });
  long count = 0;
  for (long i = 0; i < nb; i++) {
    long e = order[i];
    for (long j = i + 1; j < nb && low[3*order[j]] <= high[3*e]; j++) {
      long f = order[j];
      if (low[3*f + 1] > high[3*e + 1] || low[3*e + 1] > high[3*f + 1]) continue;
      if (low[3*f + 2] > high[3*e + 2] || low[3*e + 2] > high[3*f + 2]) continue;
      bool shared = false;
      for (long a = 0; a < d; a++) for (long b = 0; b < d; b++) if (c[d*e + a] == c[d*f + b]) shared = true;
      if (shared || !geometry.cross(c + d*e, c + d*f, d)) continue;
      if (count == 0 && pair->N() >= 2) { (*pair)[0] = e; (*pair)[1] = f; }
      count++;
    }
  }
  return count;
}

long boundaryCrossings2(KN<double> *const &xyz, KN<long> *const &corners, KN<long> *const &pair) {
  return boundaryCrossings(xyz, corners, 2, pair);
}
long boundaryCrossings3(KN<double> *const &xyz, KN<long> *const &corners, KN<long> *const &pair) {
  return boundaryCrossings(xyz, corners, 3, pair);
}

void init() {
  Global.Add("boundarySegmentCrossings", "(", new OneOperator3_<long, KN<double> *, KN<long> *, KN<long> *>(boundaryCrossings2));
  Global.Add("boundaryTriangleCrossings", "(", new OneOperator3_<long, KN<double> *, KN<long> *, KN<long> *>(boundaryCrossings3));
}

}  // namespace

LOADFUNC(init)
