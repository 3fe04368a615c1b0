//ff-c++-LIBRARY-dep: blas
// dense_kkt: the friction polish's KKT systems (include/solve/friction_polish.idp) by LAPACK's dense
// LU. Built by `make` with ff-c++ against Debian's LAPACK; loaded by
// include/solve/friction_polish.idp.
//
// The polish solves [S B; C 0] [x; m] = [f; d] once per pass: S the condensed Hessian on the n
// contact dofs (dense: schurDense), C the active set's rows (sparse, a few entries a row), B its
// transpose (with Coulomb's coupling columns the system is unsymmetric). UMFPACK, given the whole
// matrix as a sparse one, took 0.9 s for n = 1,382 and 677 rows on the rigid sphere
// (mindlin_sphere.edp -setup rigid), two or three passes a step; the matrix is dense in its S
// block, and LAPACK's blocked LU (dgesv) factorizes it in a fraction of that. (S itself is often
// singular: a platen under a dead load is held by the contact rows alone, so S's own inverse is
// not a way.)
//
// denseKktSolve(S, C, B, f, d, x, m): S a real[int,int] (n x n), C (nc x n) and B (n x nc) sparse
// matrices, f (n) and d (nc); x and m receive the solution, refined twice. Returns dgesv's info: 0,
// or > 0 when the system is singular (x and m untouched); -1 when the sizes differ.
#include "ff++.hpp"
#include "AFunction_ext.hpp"
#include <vector>

extern "C" {
void dgesv_(const int *n, const int *nrhs, double *a, const int *lda, int *ipiv, double *b, const int *ldb,
            int *info);
void dgetrs_(const char *trans, const int *n, const int *nrhs, const double *a, const int *lda, const int *ipiv,
             double *b, const int *ldb, int *info);
}

namespace {
MatriceMorse<double> *morse(Matrice_Creuse<double> *const &p) {
  MatriceCreuse<double> *generic = p->A;
  MatriceMorse<double> *A = dynamic_cast<MatriceMorse<double> *>(generic);
  ffassert(A);
  return A;
}
}  // namespace

static long denseKktSolve(KNM<double> *const &pS, Matrice_Creuse<double> *const &pC,
                          Matrice_Creuse<double> *const &pB, KN<double> *const &pf, KN<double> *const &pd,
                          KN<double> *const &px, KN<double> *const &pm) {
  const KNM<double> &S = *pS;
  MatriceMorse<double> *C = morse(pC), *B = morse(pB);
  int n = int(S.N()), nc = int(C->n), size = n + nc;
  if (S.M() != n || C->m != n || B->n != n || B->m != nc || pf->N() != n || pd->N() != nc) return -1;
  ffassert(!C->half && !B->half);
  // the whole matrix, column-major
  std::vector<double> A(size_t(size)*size, 0.), rhs(size);
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) A[size_t(j)*size + i] = S(i, j);
  for (size_t e = 0; e < size_t(B->nnz); e++) A[size_t(n + B->j[e])*size + B->i[e]] += B->aij[e];
  for (size_t e = 0; e < size_t(C->nnz); e++) A[size_t(C->j[e])*size + n + C->i[e]] += C->aij[e];
  for (int r = 0; r < n; r++) rhs[r] = (*pf)[r];
  for (int a = 0; a < nc; a++) rhs[n + a] = (*pd)[a];
  std::vector<int> pivots(size);
  const int unit = 1;
  int info = 0;
  if (size > 0) dgesv_(&size, &unit, A.data(), &size, pivots.data(), rhs.data(), &size, &info);
  if (info != 0) return info;
  // two steps of iterative refinement on the same factors, as UMFPACK takes by default (without
  // them the rigid sphere's Coulomb check read 5.3e-14 against UMFPACK's 4.5e-17): r = b - K x
  // from S, B and C
  std::vector<double> residual(size);
  for (int step = 0; step < 2; step++) {
    for (int r = 0; r < n; r++) residual[r] = (*pf)[r];
    for (int a = 0; a < nc; a++) residual[n + a] = (*pd)[a];
    for (int j = 0; j < n; j++) {
      double xj = rhs[j];
      for (int i = 0; i < n; i++) residual[i] -= S(i, j)*xj;
    }
    for (size_t e = 0; e < size_t(B->nnz); e++) residual[B->i[e]] -= B->aij[e]*rhs[n + B->j[e]];
    for (size_t e = 0; e < size_t(C->nnz); e++) residual[n + C->i[e]] -= C->aij[e]*rhs[C->j[e]];
    dgetrs_("N", &size, &unit, A.data(), &size, pivots.data(), residual.data(), &size, &info);
    if (info != 0) return -1;
    for (int r = 0; r < size; r++) rhs[r] += residual[r];
  }
  px->resize(n);
  pm->resize(nc);
  for (int r = 0; r < n; r++) (*px)[r] = rhs[r];
  for (int a = 0; a < nc; a++) (*pm)[a] = rhs[n + a];
  return 0;
}

static void init() {
  Global.Add("denseKktSolve", "(",
             new OneOperator7_<long, KNM<double> *, Matrice_Creuse<double> *, Matrice_Creuse<double> *, KN<double> *,
                               KN<double> *, KN<double> *, KN<double> *>(denseKktSolve));
}

LOADFUNC(init)
