// fast_assembly: what FreeFEM's varf, sparse products and interpolation build slowly, assembled in
// C++ from the same P0 fields (built by `make` with ff-c++, loaded by
// include/body/elastic_energy.idp and used there). The laws stay in their .idp files: these
// functions only sum element contributions. Each gives the values of the script-level form it
// replaces, which stays the reference: tests/stiffness_check.edp and tests/fd_volumetric.edp
// compare them.
//
// 1. isotropicStiffnessLower(Th, lambda, mu, K): small-strain isotropic elasticity on P1
//    tetrahedra, lower triangle: the varf vIsotropicStiffness,
//      int lambda div(w) div(v) + 2 mu eps(w) : eps(v),
//    whose FreeFEM assembly took 5.3 s of the 3D Hertz sphere's 60 s at 201k dofs (391k
//    tetrahedra) against 0.9 s here: the gradients of P1 are constant on an element, so each
//    12 x 12 element matrix is a few products, and the pattern is known from the vertices'
//    neighbours. Th a mesh3, lambda and mu one value per element (P0 arrays), K receives the lower
//    triangle (FreeFEM's sym = 1 form) in the numbering of [P1, P1, P1]: dof 3 v + c for vertex v,
//    component c. Entry (a i, b j), vertex a component i against vertex b component j, on an
//    element of volume V whose barycentric coordinates have the gradients g:
//      V (lambda g_a[i] g_b[j] + mu (g_a[j] g_b[i] + delta_ij g_a . g_b)).
// 2. tangentStiffness2D(Th, A, cofactors, nodalVolume, weights, K): a hyperelastic law's tangent on
//    P1 triangles in plane strain (16 arrays A, 4 cofactors) or in the axisymmetric mode (25 and 5:
//    the hoop component F_thth = 1 + u_r / r at the barycentre, 1 / (3 r_c) per radial dof, and the
//    measure 2 pi r_c |T|), int Grad v : A : Grad w (the varf vStiffness with one-point
//    quadrature, exact since A is constant per element): entry (a i, b k) is
//    |T| sum_JL A_(iJ)(kL) g_a[J] g_b[L]. A the 16 P0 arrays of the in-plane component pairs one
//    after the other, pair (iJ, kL) at (4 (2 i + J) + 2 k + L) nt. With weights (one per vertex;
//    an empty array for none) it adds the nodal volumetric penalty's coupling
//    (P C)^T diag(weights) (P C) of include/body/volumetric.idp: row n of P C is the sum over the
//    triangles T of vertex n of |T| / (3 V_n) dJ_T/dU, dJ_T/du_(a,i) = sum_j cof(F_T)_ij g_a[j],
//    cofactors the P0 arrays of cof_11, cof_12, cof_21, cof_22 one after the other. K receives the
//    whole matrix in the numbering of [P1, P1] (dof 2 v + c), its pattern the vertex pairs that
//    share a triangle, or with the coupling a vertex's patch. At 1146 dofs (O-ring plates) the varf
//    took 5 ms a tangent (FreeFEM evaluating the 16-field integrand at each element). The coupling
//    took 43 ms a tangent at 4360 dofs with FreeFEM's products and sum, then 13 ms inserted into
//    the varf's matrix from C++; summed here with the tangent on the patch pattern, the O-ring's
//    solve at 4360 dofs went from 9.6 s to 8.3 s (94 tangents; medians of 3).
// 3. internalForce2D(Th, P, f): the internal forces int P : Grad v on P1 triangles in plane strain
//    (the varf vInternalForce): f[2 a + i] = sum over the triangles of a of |T| sum_J P_iJ g_a[J],
//    P the 4 P0 arrays P_11, P_12, P_21, P_22 one after the other (axisymmetric: 5, with P_thth).
// 4. p1DisplacementGradients(Th, U, G): grad u on each P1 triangle or tetrahedron, u the field of
//    dof vector U ([P1, P1] or [P1, P1, P1]: dof d v + c): G[(3 i + J) nt + k] = du_i/dX_J on
//    element k (the 3 x 3 layout of the deformation gradient; the out-of-plane entries of a
//    triangle are 0). FreeFEM interpolates each component into P0 through its finite-element
//    machinery: 1.8 s for the 9 of the 3D sphere's 391k tetrahedra.
// 5. tangentStiffness3D(Th, A, K): tangentStiffness2D's tangent on P1 tetrahedra, without the
//    coupling: A the 81 P0 arrays of the component pairs (iJ, kL) at (9 (3 i + J) + 3 k + L) nt, K
//    the whole matrix in the numbering of [P1, P1, P1] (dof 3 v + c). The varf vStiffness took
//    0.19 s at 12,825 dofs (FreeFEM evaluating its 81-field integrand at each tetrahedron).
// 6. internalForce3D(Th, P, f): internalForce2D on P1 tetrahedra, P the 9 P0 arrays P_iJ.
// 7. nodalSaddle3D(Th, A, cofactors, nodalVolume, compliance, M, diagonal): the nodal volumetric
//    form's tangent as its saddle point matrix (include/body/volumetric.idp, volumetricSaddle), on
//    P1 tetrahedra: [K_el, R^T; R, -diag(compliance)] with K_el the tangent of 5 and R = Q C, row n
//    sum over the tetrahedra T of vertex n of |T| / 4 dJ_T/dU, dJ_T/du_(b,i) = sum_j cof(F_T)_ij
//    g_b[j] (cofactors the 9 P0 arrays of cof F, compliance V_n / K_n per vertex): 3 nv + nv
//    unknowns, the pressure of vertex n last (3 nv + n), scaled by |R_n| / compliance_n. diagonal
//    receives the diagonal of the tangent it stands for, K_el + R^T diag(1 / compliance) R, on the
//    3 nv displacement dofs (the condensed SQP shifts an indefinite tangent relative to it). At
//    12,825 dofs FreeFEM's varf, sparse products and block matrix took 0.66 s a tangent. M's
//    entries come row by row in increasing columns; an M that already holds them (the last
//    tangent's) is rewritten in place. 5 and 7 keep the last mesh's vertex pattern (tetPattern).
// They return the number of entries stored (1, 2, 5, 7) or of values (3, 4, 6).
#include "ff++.hpp"
#include "AFunction_ext.hpp"
#include <algorithm>
#include <vector>

namespace {

long isotropicStiffnessLower(pmesh3 const &pTh, KN<double> *const &pLambda, KN<double> *const &pMu,
                             Matrice_Creuse<double> *const &pK) {
  ffassert(pTh);
  const Mesh3 &Th = *pTh;
  const KN<double> &lambda = *pLambda, &mu = *pMu;
  const long nv = Th.nv, nt = Th.nt;
  ffassert(lambda.N() == nt && mu.N() == nt);
  // the lower vertex pattern: for vertex a, its neighbours b <= a (itself included), sorted
  std::vector<long> start(nv + 1, 0);
  for (long k = 0; k < nt; k++)
    for (int p = 0; p < 4; p++) {
      long a = Th(Th[k][p]);
      for (int q = 0; q < 4; q++)
        if (Th(Th[k][q]) <= a) start[a + 1]++;
    }
  for (long a = 0; a < nv; a++) start[a + 1] += start[a];
  std::vector<int> neighbour(start[nv]);
  {
    std::vector<long> fill(start.begin(), start.end() - 1);
    for (long k = 0; k < nt; k++)
      for (int p = 0; p < 4; p++) {
        long a = Th(Th[k][p]);
        for (int q = 0; q < 4; q++) {
          long b = Th(Th[k][q]);
          if (b <= a) neighbour[fill[a]++] = int(b);
        }
      }
  }
  // sorted and without repeats, in place; rowStart the compacted rows
  std::vector<long> rowStart(nv + 1, 0);
  long pairs = 0;
  for (long a = 0; a < nv; a++) {
    std::sort(neighbour.begin() + start[a], neighbour.begin() + start[a + 1]);
    long first = pairs;
    for (long m = start[a]; m < start[a + 1]; m++)
      if (m == start[a] || neighbour[m] != neighbour[m - 1]) neighbour[pairs++] = neighbour[m];
    rowStart[a] = first;
  }
  rowStart[nv] = pairs;
  // the 3 x 3 blocks of the vertex pairs, summed over the elements
  std::vector<double> block(9 * pairs, 0.);
  for (long k = 0; k < nt; k++) {
    const Tet &K = Th[k];
    R3 g[4];
    K.Gradlambda(g);
    const double volume = K.mesure(), l = lambda[k] * volume, m = mu[k] * volume;
    for (int p = 0; p < 4; p++) {
      long a = Th(K[p]);
      for (int q = 0; q < 4; q++) {
        long b = Th(K[q]);
        if (b > a) continue;
        long where = std::lower_bound(neighbour.begin() + rowStart[a], neighbour.begin() + rowStart[a + 1], int(b))
                     - neighbour.begin();
        double *B = &block[9 * where];
        const double ga[3] = {g[p].x, g[p].y, g[p].z}, gb[3] = {g[q].x, g[q].y, g[q].z};
        const double dot = ga[0] * gb[0] + ga[1] * gb[1] + ga[2] * gb[2];
        for (int i = 0; i < 3; i++)
          for (int j = 0; j < 3; j++) B[3 * i + j] += l * ga[i] * gb[j] + m * (ga[j] * gb[i] + (i == j ? dot : 0.));
      }
    }
  }
  // the dof-level lower triangle by rows: row 3 a + i holds, for each neighbour b < a, columns
  // 3 b + j for every j, and for b = a the columns 3 a + j, j <= i
  long n = 3 * nv, entries = 0;
  for (long a = 0; a < nv; a++) entries += 9 * (rowStart[a + 1] - rowStart[a]) - 3;
  std::vector<int> rows(entries), columns(entries);
  std::vector<double> values(entries);
  long e = 0;
  for (long a = 0; a < nv; a++)
    for (int i = 0; i < 3; i++)
      for (long w = rowStart[a]; w < rowStart[a + 1]; w++) {
        long b = neighbour[w];
        for (int j = 0; j < 3 && (b < a || j <= i); j++) {
          rows[e] = int(3 * a + i);
          columns[e] = int(3 * b + j);
          values[e] = block[9 * w + 3 * i + j];
          e++;
        }
      }
  ffassert(e == entries);
  HashMatrix<int, double> *K = new HashMatrix<int, double>(int(n), int(n), 0, 1);
  K->set(int(n), int(n), 1, size_t(entries), rows.data(), columns.data(), values.data());
  pK->A.master(K);   // (master frees the matrix held before; init() would only forget it: 16 MB a tangent at 12,825 dofs)
  pK->typemat = 0;
  return entries;
}

// the gradients of a triangle's barycentric coordinates
void barycentricGradients(const Mesh::Triangle &K, double g[3][2]) {
  const R2 A = K[0], B = K[1], C = K[2];
  const double det = (B.x - A.x) * (C.y - A.y) - (C.x - A.x) * (B.y - A.y);
  g[1][0] = (C.y - A.y) / det;  g[1][1] = -(C.x - A.x) / det;
  g[2][0] = -(B.y - A.y) / det;  g[2][1] = (B.x - A.x) / det;
  g[0][0] = -g[1][0] - g[2][0];  g[0][1] = -g[1][1] - g[2][1];
}

// The element's map from its corner dofs to the active components of F (plane strain: F_11, F_12,
// F_21, F_22; axisymmetric also F_thth = 1 + u_r / r, whose derivative at the barycentre is
// 1 / (3 r_c) for the radial dof of every corner), and its measure (|T|, or 2 pi r_c |T|).
struct TriangleMap {
  double g[3][2];
  double weight = 0, hoop = 0;   // the measure, and dF_thth/du_(a,r) (axisymmetric)
  void set(const Mesh::Triangle &K, bool axisymmetric) {
    barycentricGradients(K, g);
    weight = K.area;
    if (axisymmetric) {
      const double rc = (K[0].x + K[1].x + K[2].x) / 3;
      weight *= 2 * M_PI * rc;
      hoop = 1 / (3 * rc);
    }
  }
  // dF_alpha/du_(a,i) for the active component alpha (0..3: 2 I + J; 4: the hoop)
  double operator()(int alpha, int a, int i) const {
    if (alpha == 4) return i == 0 ? hoop : 0.;
    return (alpha / 2 == i) ? g[a][alpha % 2] : 0.;
  }
};

long tangentStiffness2D(pmesh const &pTh, KN<double> *const &pA, KN<double> *const &pCofactors,
                        KN<double> *const &pNodalVolume, KN<double> *const &pWeights, Matrice_Creuse<double> *const &pK) {
  ffassert(pTh);
  const Mesh &Th = *pTh;
  const KN<double> &A = *pA, &cofactors = *pCofactors, &nodalVolume = *pNodalVolume, &weights = *pWeights;
  const long nv = Th.nv, nt = Th.nt;
  const bool axisymmetric = A.N() == 25 * nt;
  const int na = axisymmetric ? 5 : 4;   // active components of F
  ffassert(A.N() == na * na * nt);
  const bool coupled = weights.N() > 0;
  ffassert(!coupled || (cofactors.N() == na * nt && nodalVolume.N() == nv && weights.N() == nv));
  // the triangles of each vertex
  std::vector<long> first(nv + 1, 0);
  for (long k = 0; k < nt; k++)
    for (int p = 0; p < 3; p++) first[Th(Th[k][p]) + 1]++;
  for (long v = 0; v < nv; v++) first[v + 1] += first[v];
  std::vector<long> triangles(first[nv]);
  {
    std::vector<long> fill(first.begin(), first.end() - 1);
    for (long k = 0; k < nt; k++)
      for (int p = 0; p < 3; p++) triangles[fill[Th(Th[k][p])]++] = k;
  }
  // each vertex's patch: the vertices of its triangles (itself included), sorted, without repeats
  std::vector<long> patchStart(nv + 1, 0);
  std::vector<int> patch;
  patch.reserve(7 * nv);
  for (long v = 0; v < nv; v++) {
    size_t from = patch.size();
    for (long m = first[v]; m < first[v + 1]; m++)
      for (int p = 0; p < 3; p++) patch.push_back(int(Th(Th[triangles[m]][p])));
    std::sort(patch.begin() + from, patch.end());
    patch.erase(std::unique(patch.begin() + from, patch.end()), patch.end());
    patchStart[v + 1] = long(patch.size());
  }
  // the vertex pattern: a's patch, and with the coupling every vertex sharing a patch with a
  std::vector<long> start(nv + 1, 0);
  for (long n = 0; n < nv; n++) {
    long size = patchStart[n + 1] - patchStart[n];
    if (coupled) for (long p = patchStart[n]; p < patchStart[n + 1]; p++) start[patch[p] + 1] += size;
    else start[n + 1] += size;
  }
  for (long a = 0; a < nv; a++) start[a + 1] += start[a];
  std::vector<int> neighbour(start[nv]);
  {
    std::vector<long> fill(start.begin(), start.end() - 1);
    for (long n = 0; n < nv; n++)
      for (long p = patchStart[n]; p < patchStart[n + 1]; p++) {
        if (!coupled && patch[p] != n) continue;
        for (long q = patchStart[n]; q < patchStart[n + 1]; q++) neighbour[fill[patch[p]]++] = patch[q];
      }
  }
  std::vector<long> rowStart(nv + 1, 0);
  long pairs = 0;
  for (long a = 0; a < nv; a++) {
    std::sort(neighbour.begin() + start[a], neighbour.begin() + start[a + 1]);
    rowStart[a] = pairs;
    for (long m = start[a]; m < start[a + 1]; m++)
      if (m == start[a] || neighbour[m] != neighbour[m - 1]) neighbour[pairs++] = neighbour[m];
  }
  rowStart[nv] = pairs;
  auto blockOf = [&](long a, long b) {
    return std::lower_bound(neighbour.begin() + rowStart[a], neighbour.begin() + rowStart[a + 1], int(b)) - neighbour.begin();
  };
  // the 2 x 2 blocks of the vertex pairs: the tangent summed over the triangles
  std::vector<double> block(4 * pairs, 0.);
  std::vector<double> derivative(coupled ? 6 * nt : 0);   // |T| / 3 dJ_T/du on T's 6 dofs
  TriangleMap map;
  for (long k = 0; k < nt; k++) {
    const Mesh::Triangle &K = Th[k];
    map.set(K, axisymmetric);
    double a25[25];
    for (int r = 0; r < na * na; r++) a25[r] = map.weight * A[r * nt + k];
    for (int p = 0; p < 3; p++) {
      long a = Th(K[p]);
      for (int q = 0; q < 3; q++) {
        double *B = &block[4 * blockOf(a, Th(K[q]))];
        for (int i = 0; i < 2; i++)
          for (int c = 0; c < 2; c++) {
            double sum = 0;
            for (int alpha = 0; alpha < na; alpha++) {
              const double left = map(alpha, p, i);
              if (left == 0) continue;
              for (int beta = 0; beta < na; beta++) sum += a25[na * alpha + beta] * left * map(beta, q, c);
            }
            B[2 * i + c] += sum;
          }
      }
    }
    if (coupled)
      for (int p = 0; p < 3; p++)
        for (int i = 0; i < 2; i++) {
          double dJ = 0;
          for (int alpha = 0; alpha < na; alpha++) dJ += cofactors[alpha * nt + k] * map(alpha, p, i);
          derivative[6 * k + 2 * p + i] = map.weight / 3 * dJ;
        }
  }
  // the nodal penalty's coupling: row n of P C on n's patch, its weighted outer product
  if (coupled) {
    std::vector<double> row;
    for (long n = 0; n < nv; n++) {
      const long from = patchStart[n], size = patchStart[n + 1] - from;
      row.assign(2 * size, 0.);
      for (long m = first[n]; m < first[n + 1]; m++) {
        long k = triangles[m];
        for (int p = 0; p < 3; p++) {
          long at = std::lower_bound(patch.begin() + from, patch.begin() + from + size, int(Th(Th[k][p]))) - patch.begin() - from;
          for (int i = 0; i < 2; i++) row[2 * at + i] += derivative[6 * k + 2 * p + i] / nodalVolume[n];
        }
      }
      const double w = weights[n];
      for (long p = 0; p < size; p++)
        for (long q = 0; q < size; q++) {
          double *B = &block[4 * blockOf(patch[from + p], patch[from + q])];
          for (int i = 0; i < 2; i++)
            for (int c = 0; c < 2; c++) B[2 * i + c] += w * row[2 * p + i] * row[2 * q + c];
        }
    }
  }
  long n = 2 * nv, entries = 4 * pairs;
  std::vector<int> rows(entries), columns(entries);
  std::vector<double> values(entries);
  long e = 0;
  for (long a = 0; a < nv; a++)
    for (int i = 0; i < 2; i++)
      for (long w = rowStart[a]; w < rowStart[a + 1]; w++)
        for (int c = 0; c < 2; c++) {
          rows[e] = int(2 * a + i);
          columns[e] = int(2 * neighbour[w] + c);
          values[e] = block[4 * w + 2 * i + c];
          e++;
        }
  HashMatrix<int, double> *K = new HashMatrix<int, double>(int(n), int(n), 0, 0);
  K->set(int(n), int(n), 0, size_t(entries), rows.data(), columns.data(), values.data());
  pK->A.master(K);   // (master frees the matrix held before; init() would only forget it: 16 MB a tangent at 12,825 dofs)
  pK->typemat = 0;
  return entries;
}

long internalForce2D(pmesh const &pTh, KN<double> *const &pP, KN<double> *const &pf) {
  ffassert(pTh);
  const Mesh &Th = *pTh;
  const KN<double> &P = *pP;
  const long nv = Th.nv, nt = Th.nt;
  const bool axisymmetric = P.N() == 5 * nt;
  const int na = axisymmetric ? 5 : 4;
  ffassert(P.N() == na * nt);
  KN<double> &f = *pf;
  f.resize(2 * nv);
  f = 0.;
  TriangleMap map;
  for (long k = 0; k < nt; k++) {
    const Mesh::Triangle &K = Th[k];
    map.set(K, axisymmetric);
    for (int a = 0; a < 3; a++) {
      long v = Th(K[a]);
      for (int i = 0; i < 2; i++) {
        double sum = 0;
        for (int alpha = 0; alpha < na; alpha++) sum += P[alpha * nt + k] * map(alpha, a, i);
        f[2 * v + i] += map.weight * sum;
      }
    }
  }
  return 2 * nv;
}

// the gradients of an element's barycentric coordinates, d per corner
void elementGradients(const Mesh::Triangle &K, double g[3][2]) { barycentricGradients(K, g); }
void elementGradients(const Tet &K, double g[4][3]) {
  R3 G[4];
  K.Gradlambda(G);
  for (int a = 0; a < 4; a++) { g[a][0] = G[a].x; g[a][1] = G[a].y; g[a][2] = G[a].z; }
}

// du_i/dX_J on each element of a P1 mesh of dimension d (the 3 x 3 layout, 0 out of plane)
template <class MeshType, int d>
long p1DisplacementGradients(const MeshType *pTh, KN<double> *const &pU, KN<double> *const &pG) {
  ffassert(pTh);
  const MeshType &Th = *pTh;
  const KN<double> &U = *pU;
  const long nt = Th.nt;
  ffassert(U.N() == d * Th.nv);
  KN<double> &G = *pG;
  G.resize(9 * nt);
  G = 0.;
  for (long k = 0; k < nt; k++) {
    const auto &K = Th[k];
    double g[d + 1][d];
    elementGradients(K, g);
    for (int i = 0; i < d; i++)
      for (int J = 0; J < d; J++) {
        double sum = 0;
        for (int a = 0; a <= d; a++) sum += U[d * Th(K[a]) + i] * g[a][J];
        G[(3 * i + J) * nt + k] = sum;
      }
  }
  return 9 * nt;
}
long p1DisplacementGradients2D(pmesh const &pTh, KN<double> *const &pU, KN<double> *const &pG) {
  return p1DisplacementGradients<Mesh, 2>(pTh, pU, pG);
}
long p1DisplacementGradients3D(pmesh3 const &pTh, KN<double> *const &pU, KN<double> *const &pG) {
  return p1DisplacementGradients<Mesh3, 3>(pTh, pU, pG);
}


// The sorted vertex neighbours of every vertex of a tetrahedral mesh (itself included), in
// compressed rows: the vertex pairs that share a tetrahedron.
void tetVertexPattern(const Mesh3 &Th, std::vector<long> &rowStart, std::vector<int> &neighbour) {
  const long nv = Th.nv, nt = Th.nt;
  std::vector<long> start(nv + 1, 0);
  for (long k = 0; k < nt; k++)
    for (int p = 0; p < 4; p++) start[Th(Th[k][p]) + 1] += 4;
  for (long a = 0; a < nv; a++) start[a + 1] += start[a];
  neighbour.assign(start[nv], 0);
  {
    std::vector<long> fill(start.begin(), start.end() - 1);
    for (long k = 0; k < nt; k++)
      for (int p = 0; p < 4; p++)
        for (int q = 0; q < 4; q++) neighbour[fill[Th(Th[k][p])]++] = int(Th(Th[k][q]));
  }
  rowStart.assign(nv + 1, 0);
  long pairs = 0;
  for (long a = 0; a < nv; a++) {
    std::sort(neighbour.begin() + start[a], neighbour.begin() + start[a + 1]);
    rowStart[a] = pairs;
    for (long m = start[a]; m < start[a + 1]; m++)
      if (m == start[a] || neighbour[m] != neighbour[m - 1]) neighbour[pairs++] = neighbour[m];
  }
  rowStart[nv] = pairs;
  neighbour.resize(pairs);
}

// The vertex pattern of the last tetrahedral mesh (the SQP assembles a tangent on one mesh at every
// factorization; at R/32 perf put the pattern's sort at 0.4 % of the run): its rows
// (tetVertexPattern), the place of each tetrahedron's 16 vertex pairs in them (corner p's row,
// corner q's column: place[16 k + 4 p + q]), and for each pair (a, b) the place of (b, a). A
// signature of the connectivity tells a new mesh allocated at the same address.
struct TetPattern {
  const Mesh3 *mesh = nullptr;
  long nv = -1, nt = -1;
  unsigned long long signature = 0;
  std::vector<long> rowStart, place, transposed;
  std::vector<int> neighbour;
};

unsigned long long connectivitySignature(const Mesh3 &Th) {
  unsigned long long h = 1469598103934665603ULL;   // FNV-1a over the corners' vertex numbers
  for (long k = 0; k < Th.nt; k++)
    for (int p = 0; p < 4; p++) {
      h ^= (unsigned long long)Th(Th[k][p]);
      h *= 1099511628211ULL;
    }
  return h;
}

const TetPattern &tetPattern(const Mesh3 &Th) {
  static TetPattern cached;
  const unsigned long long signature = connectivitySignature(Th);
  if (cached.mesh == &Th && cached.nv == Th.nv && cached.nt == Th.nt && cached.signature == signature)
    return cached;
  cached.mesh = &Th;
  cached.nv = Th.nv;
  cached.nt = Th.nt;
  cached.signature = signature;
  tetVertexPattern(Th, cached.rowStart, cached.neighbour);
  const std::vector<long> &rowStart = cached.rowStart;
  const std::vector<int> &neighbour = cached.neighbour;
  auto find = [&](long a, long b) {
    return long(std::lower_bound(neighbour.begin() + rowStart[a], neighbour.begin() + rowStart[a + 1], int(b)) - neighbour.begin());
  };
  cached.place.resize(16 * Th.nt);
  for (long k = 0; k < Th.nt; k++)
    for (int p = 0; p < 4; p++)
      for (int q = 0; q < 4; q++) cached.place[16 * k + 4 * p + q] = find(Th(Th[k][p]), Th(Th[k][q]));
  cached.transposed.resize(neighbour.size());
  for (long a = 0; a < Th.nv; a++)
    for (long w = rowStart[a]; w < rowStart[a + 1]; w++) cached.transposed[w] = find(neighbour[w], a);
  return cached;
}

// The 3 x 3 tangent blocks of the vertex pairs summed over the tetrahedra, from the 81 arrays A.
void tetTangentBlocks(const Mesh3 &Th, const KN<double> &A, const TetPattern &pattern, std::vector<double> &block) {
  const long nt = Th.nt;
  block.assign(9 * pattern.neighbour.size(), 0.);
  for (long k = 0; k < nt; k++) {
    const Tet &K = Th[k];
    double g[4][3];
    elementGradients(K, g);
    const double volume = K.mesure();
    double a81[81];
    for (int r = 0; r < 81; r++) a81[r] = volume * A[r * nt + k];
    for (int p = 0; p < 4; p++) {
      // h[(3 i + k) 3 + L] = sum_J A_(iJ)(kL) g_a[J]: the row half of the product, once per corner
      double h[27];
      for (int i = 0; i < 3; i++)
        for (int c = 0; c < 3; c++)
          for (int L = 0; L < 3; L++) {
            double sum = 0;
            for (int J = 0; J < 3; J++) sum += a81[9 * (3 * i + J) + 3 * c + L] * g[p][J];
            h[(3 * i + c) * 3 + L] = sum;
          }
      for (int q = 0; q < 4; q++) {
        double *B = &block[9 * pattern.place[16 * k + 4 * p + q]];
        for (int i = 0; i < 3; i++)
          for (int c = 0; c < 3; c++)
            B[3 * i + c] += h[(3 * i + c) * 3] * g[q][0] + h[(3 * i + c) * 3 + 1] * g[q][1] + h[(3 * i + c) * 3 + 2] * g[q][2];
      }
    }
  }
}

long tangentStiffness3D(pmesh3 const &pTh, KN<double> *const &pA, Matrice_Creuse<double> *const &pK) {
  ffassert(pTh);
  const Mesh3 &Th = *pTh;
  const KN<double> &A = *pA;
  const long nv = Th.nv;
  ffassert(A.N() == 81 * Th.nt);
  const TetPattern &pattern = tetPattern(Th);
  const std::vector<long> &rowStart = pattern.rowStart;
  const std::vector<int> &neighbour = pattern.neighbour;
  static std::vector<double> block;   // (kept between calls, as nodalSaddle3D's)
  tetTangentBlocks(Th, A, pattern, block);
  long n = 3 * nv, entries = 9 * long(neighbour.size());
  std::vector<int> rows(entries), columns(entries);
  std::vector<double> values(entries);
  long e = 0;
  for (long a = 0; a < nv; a++)
    for (int i = 0; i < 3; i++)
      for (long w = rowStart[a]; w < rowStart[a + 1]; w++)
        for (int c = 0; c < 3; c++) {
          rows[e] = int(3 * a + i);
          columns[e] = int(3 * neighbour[w] + c);
          values[e] = block[9 * w + 3 * i + c];
          e++;
        }
  HashMatrix<int, double> *K = new HashMatrix<int, double>(int(n), int(n), 0, 0);
  K->set(int(n), int(n), 0, size_t(entries), rows.data(), columns.data(), values.data());
  pK->A.master(K);   // (master frees the matrix held before; init() would only forget it: 16 MB a tangent at 12,825 dofs)
  pK->typemat = 0;
  return entries;
}

long internalForce3D(pmesh3 const &pTh, KN<double> *const &pP, KN<double> *const &pf) {
  ffassert(pTh);
  const Mesh3 &Th = *pTh;
  const KN<double> &P = *pP;
  const long nv = Th.nv, nt = Th.nt;
  ffassert(P.N() == 9 * nt);
  KN<double> &f = *pf;
  f.resize(3 * nv);
  f = 0.;
  for (long k = 0; k < nt; k++) {
    const Tet &K = Th[k];
    double g[4][3];
    elementGradients(K, g);
    const double volume = K.mesure();
    for (int a = 0; a < 4; a++) {
      long v = Th(K[a]);
      for (int i = 0; i < 3; i++)
        f[3 * v + i] += volume * (P[(3 * i) * nt + k] * g[a][0] + P[(3 * i + 1) * nt + k] * g[a][1] + P[(3 * i + 2) * nt + k] * g[a][2]);
    }
  }
  return 3 * nv;
}

long nodalSaddle3D(pmesh3 const &pTh, KN<double> *const &pA, KN<double> *const &pCofactors, KN<double> *const &pNodalVolume,
                   KN<double> *const &pCompliance, Matrice_Creuse<double> *const &pM, KN<double> *const &pDiagonal) {
  ffassert(pTh);
  const Mesh3 &Th = *pTh;
  const KN<double> &A = *pA, &cofactors = *pCofactors, &nodalVolume = *pNodalVolume, &compliance = *pCompliance;
  const long nv = Th.nv, nt = Th.nt;
  ffassert(A.N() == 81 * nt && cofactors.N() == 9 * nt && nodalVolume.N() == nv && compliance.N() == nv);
  const TetPattern &pattern = tetPattern(Th);
  const std::vector<long> &rowStart = pattern.rowStart;
  const std::vector<int> &neighbour = pattern.neighbour;
  // kept between calls (one tangent at a time): fresh vectors of this size (100 MB at 395k
  // tetrahedra) had their pages faulted in at every tangent: the call took 0.57-1.3 s there, and
  // 0.53-0.62 s with them kept
  static std::vector<double> block, rcoef;
  tetTangentBlocks(Th, A, pattern, block);
  // R: for the pair (n, b) of the pattern, the 3 entries of row n on vertex b's dofs
  rcoef.assign(3 * neighbour.size(), 0.);
  for (long k = 0; k < nt; k++) {
    const Tet &K = Th[k];
    double g[4][3];
    elementGradients(K, g);
    const double quarter = K.mesure() / 4;
    double cof[3][3];
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) cof[i][j] = cofactors[(3 * i + j) * nt + k];
    for (int p = 0; p < 4; p++)
      for (int q = 0; q < 4; q++) {
        double *r = &rcoef[3 * pattern.place[16 * k + 4 * p + q]];
        for (int i = 0; i < 3; i++) r[i] += quarter * (cof[i][0] * g[q][0] + cof[i][1] * g[q][1] + cof[i][2] * g[q][2]);
      }
  }
  // the pressure unknowns scaled, p_n = s_n q_n, s_n = |R_n| / compliance_n: the scale of
  // include/body/volumetric.idp (saddlePressureScales), which says why
  std::vector<double> scale(nv, 1.);
  for (long n = 0; n < nv; n++) {
    double norm2 = 0;
    for (long w = rowStart[n]; w < rowStart[n + 1]; w++)
      for (int i = 0; i < 3; i++) norm2 += rcoef[3 * w + i] * rcoef[3 * w + i];
    if (norm2 > 0 && compliance[n] > 0) scale[n] = std::sqrt(norm2) / compliance[n];
  }
  KN<double> &diagonal = *pDiagonal;
  diagonal.resize(3 * nv);
  for (long a = 0; a < nv; a++) {
    long self = std::lower_bound(neighbour.begin() + rowStart[a], neighbour.begin() + rowStart[a + 1], int(a)) - neighbour.begin();
    for (int i = 0; i < 3; i++) diagonal[3 * a + i] = block[9 * self + 4 * i];
  }
  for (long n = 0; n < nv; n++)
    for (long w = rowStart[n]; w < rowStart[n + 1]; w++)
      for (int i = 0; i < 3; i++) diagonal[3 * neighbour[w] + i] += rcoef[3 * w + i] * rcoef[3 * w + i] / compliance[n];
  // The entries row by row, each row's columns increasing (the order FreeFEM sorts a matrix into
  // before MUMPS reads it): a matrix already holding this pattern in this order (the last call's)
  // takes the values in place, without a new HashMatrix, its hashing and its sort (at R/32 perf
  // put those at 2.0 % of the run, the tangent's blocks at 3.5 %); any other gets a new one.
  const long pairs = long(neighbour.size()), size = 4 * nv, entries = 15 * pairs + nv;
  HashMatrix<int, double> *held = pM->pHM();
  bool inPlace = held && held->n == size && held->m == size && long(held->nnz) == entries && held->half == 0
                 && held->fortran == 0;
  std::vector<int> rows, columns;
  std::vector<double> fresh;
  double *values = inPlace ? held->aij : nullptr;
  auto emit = [&](long e, long row, long column, double value) {
    if (inPlace && (held->i[e] != row || held->j[e] != column)) {   // another pattern: a new matrix
      inPlace = false;
      rows.resize(entries);
      columns.resize(entries);
      fresh.resize(entries);
      for (long f = 0; f < e; f++) { rows[f] = held->i[f]; columns[f] = held->j[f]; fresh[f] = held->aij[f]; }
      values = fresh.data();
    }
    if (!inPlace && rows.empty()) {
      rows.resize(entries);
      columns.resize(entries);
      fresh.resize(entries);
      values = fresh.data();
    }
    if (!inPlace) { rows[e] = int(row); columns[e] = int(column); }
    values[e] = value;
  };
  long e = 0;
  for (long a = 0; a < nv; a++)
    for (int i = 0; i < 3; i++) {
      const long row = 3 * a + i;
      for (long w = rowStart[a]; w < rowStart[a + 1]; w++)
        for (int c = 0; c < 3; c++) emit(e++, row, 3 * neighbour[w] + c, block[9 * w + 3 * i + c]);
      for (long w = rowStart[a]; w < rowStart[a + 1]; w++) {   // R^T: R's entry (n, a), the pair (n, a)
        const long n = neighbour[w];
        emit(e++, row, 3 * nv + n, scale[n] * rcoef[3 * pattern.transposed[w] + i]);
      }
    }
  for (long n = 0; n < nv; n++) {
    for (long w = rowStart[n]; w < rowStart[n + 1]; w++)
      for (int i = 0; i < 3; i++) emit(e++, 3 * nv + n, 3 * neighbour[w] + i, scale[n] * rcoef[3 * w + i]);
    emit(e++, 3 * nv + n, 3 * nv + n, -compliance[n] * scale[n] * scale[n]);
  }
  ffassert(e == entries);
  if (inPlace) {
    held->re_do_numerics++;   // (what FreeFEM's own in-place changes of values tell its solvers)
    return entries;
  }
  HashMatrix<int, double> *M = new HashMatrix<int, double>(int(size), int(size), 0, 0);
  M->set(int(size), int(size), 0, size_t(entries), rows.data(), columns.data(), fresh.data());
  pM->A.master(M);
  pM->typemat = 0;
  return entries;
}

void init() {
  Global.Add("isotropicStiffnessLower", "(",
             new OneOperator4_<long, pmesh3, KN<double> *, KN<double> *, Matrice_Creuse<double> *>(isotropicStiffnessLower));
  Global.Add("tangentStiffness2D", "(",
             new OneOperator6_<long, pmesh, KN<double> *, KN<double> *, KN<double> *, KN<double> *, Matrice_Creuse<double> *>(
                 tangentStiffness2D));
  Global.Add("internalForce2D", "(", new OneOperator3_<long, pmesh, KN<double> *, KN<double> *>(internalForce2D));
  Global.Add("tangentStiffness3D", "(", new OneOperator3_<long, pmesh3, KN<double> *, Matrice_Creuse<double> *>(tangentStiffness3D));
  Global.Add("internalForce3D", "(", new OneOperator3_<long, pmesh3, KN<double> *, KN<double> *>(internalForce3D));
  Global.Add("nodalSaddle3D", "(",
             new OneOperator7_<long, pmesh3, KN<double> *, KN<double> *, KN<double> *, KN<double> *, Matrice_Creuse<double> *, KN<double> *>(
                 nodalSaddle3D));
  Global.Add("p1DisplacementGradients", "(",
             new OneOperator3_<long, pmesh, KN<double> *, KN<double> *>(p1DisplacementGradients2D));
  Global.Add("p1DisplacementGradients", "(",
             new OneOperator3_<long, pmesh3, KN<double> *, KN<double> *>(p1DisplacementGradients3D));
}

}  // namespace

LOADFUNC(init)
