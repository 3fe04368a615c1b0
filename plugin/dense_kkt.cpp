//ff-c++-LIBRARY-dep: blas
// dense_kkt: the KKT systems of a contact set on the dense Schur block S, by LAPACK: the friction
// polish's (include/solve/friction_polish.idp) by a dense LU of the whole system, the frictionless
// reduced problem's (include/solve/reduced_problem.idp) on S's Cholesky factor where S is positive
// definite, the Krylov step's preconditioner (include/solve/krylov_step.idp) on LU factors the
// script keeps. Built by `make` with ff-c++ against Debian's LAPACK; loaded by those three files.
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

// Two steps of iterative refinement of z = [x; m] for [S B; C 0] z = [f; d] (B null: C^T), each
// correction from `solve` on the same factors (in place on the residual, n + nc entries; false when
// it fails), as UMFPACK takes by default (without them the rigid sphere's Coulomb check read
// 5.3e-14 against UMFPACK's 4.5e-17). Then x and m receive z. Returns false when a correction
// failed (x and m untouched).
template <class Solve>
static bool refineInto(const KNM<double> &S, MatriceMorse<double> *C, MatriceMorse<double> *B, const KN<double> &f,
                       const KN<double> &d, std::vector<double> &z, Solve solve, KN<double> *px, KN<double> *pm) {
  const int n = int(S.N()), nc = int(C->n);
  std::vector<double> residual(n + nc);
  for (int step = 0; step < 2; step++) {   // r = b - K z from S, B (or C^T) and C
    for (int r = 0; r < n; r++) residual[r] = f[r];
    for (int a = 0; a < nc; a++) residual[n + a] = d[a];
    for (int j = 0; j < n; j++) {
      double xj = z[j];
      for (int i = 0; i < n; i++) residual[i] -= S(i, j)*xj;
    }
    if (B) for (size_t e = 0; e < size_t(B->nnz); e++) residual[B->i[e]] -= B->aij[e]*z[n + B->j[e]];
    else for (size_t e = 0; e < size_t(C->nnz); e++) residual[C->j[e]] -= C->aij[e]*z[n + C->i[e]];
    for (size_t e = 0; e < size_t(C->nnz); e++) residual[n + C->i[e]] -= C->aij[e]*z[C->j[e]];
    if (!solve(residual)) return false;
    for (int r = 0; r < n + nc; r++) z[r] += residual[r];
  }
  px->resize(n);
  pm->resize(nc);
  for (int r = 0; r < n; r++) (*px)[r] = z[r];
  for (int a = 0; a < nc; a++) (*pm)[a] = z[n + a];
  return true;
}

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
  auto solve = [&](std::vector<double> &r) {
    dgetrs_("N", &size, &unit, A.data(), &size, pivots.data(), r.data(), &size, &info);
    return info == 0;
  };
  return refineInto(S, C, B, *pf, *pd, rhs, solve, px, pm) ? 0 : -1;
}

// The reduced problem's KKT systems on a positive definite S (include/solve/reduced_problem.idp):
// S = L L^T factorized once per Schur block, and each contact set's system solved on that factor by
// the range-space method: with W = L^-1 C^T and M = W^T W (na x na), M m = W^T L^-1 f - d and
// x = L^-T (L^-1 f - W m): n^2 na flops a set, not (n + na)^3. For n = 982 and 100 rows (the 3D
// indentation at R/32), one thread: 0.003 s a set and 0.007 s for the factor, against 0.019 s for
// the LU of the whole system (denseKktSolve).
//
// denseCholesky(S): factorizes S, a real[int,int] (n x n, symmetric), and keeps L; returns dpotrf's
// info: 0, or > 0 when S is not positive definite (nothing kept).
// denseCholeskyKktSolve(S, C, f, d, x, m): the system [S C^T; C 0] [x; m] = [f; d] on the kept
// factor of this S (C sparse, nc x n), refined twice on S and C. Returns 0; > 0 when the rows are
// dependent (M singular); -1 when no factor of S's size is kept or the sizes differ.
extern "C" {
void dpotrf_(const char *uplo, const int *n, double *a, const int *lda, int *info);
void dpotrs_(const char *uplo, const int *n, const int *nrhs, const double *a, const int *lda, double *b,
             const int *ldb, int *info);
void dtrsm_(const char *side, const char *uplo, const char *transa, const char *diag, const int *m, const int *n,
            const double *alpha, const double *a, const int *lda, double *b, const int *ldb);
void dsyrk_(const char *uplo, const char *trans, const int *n, const int *k, const double *alpha, const double *a,
            const int *lda, const double *beta, double *c, const int *ldc);
void dtrsv_(const char *uplo, const char *trans, const char *diag, const int *n, const double *a, const int *lda,
            double *x, const int *incx);
void dgemv_(const char *trans, const int *m, const int *n, const double *alpha, const double *a, const int *lda,
            const double *x, const int *incx, const double *beta, double *y, const int *incy);
}

namespace {
std::vector<double> choleskyFactor;   // L, column-major (its upper part zero)
int choleskyOrder = -1;               // n of the kept factor; -1: none
}  // namespace

static long denseCholesky(KNM<double> *const &pS) {
  const KNM<double> &S = *pS;
  int n = int(S.N()), info = 0;
  choleskyOrder = -1;
  if (S.M() != n) return -1;
  choleskyFactor.assign(size_t(n)*n, 0.);
  for (int j = 0; j < n; j++)
    for (int i = j; i < n; i++) choleskyFactor[size_t(j)*n + i] = S(i, j);
  if (n > 0) dpotrf_("L", &n, choleskyFactor.data(), &n, &info);
  if (info == 0) choleskyOrder = n;
  return info;
}

static long denseCholeskyKktSolve(KNM<double> *const &pS, Matrice_Creuse<double> *const &pC, KN<double> *const &pf,
                                  KN<double> *const &pd, KN<double> *const &px, KN<double> *const &pm) {
  const KNM<double> &S = *pS;
  MatriceMorse<double> *C = morse(pC);
  int n = int(S.N()), nc = int(C->n), info = 0;
  if (n != choleskyOrder || S.M() != n || C->m != n || pf->N() != n || pd->N() != nc) return -1;
  ffassert(!C->half);
  const double *L = choleskyFactor.data();
  const double one = 1., zero = 0., minusOne = -1.;
  const int unit = 1;
  // W = L^-1 C^T (n x nc) and M = W^T W (its lower triangle), factorized
  std::vector<double> W(size_t(n)*nc, 0.), M(size_t(nc)*nc, 0.);
  for (size_t e = 0; e < size_t(C->nnz); e++) W[size_t(C->i[e])*n + C->j[e]] += C->aij[e];
  if (nc > 0) {
    dtrsm_("L", "L", "N", "N", &n, &nc, &one, L, &n, W.data(), &n);
    dsyrk_("L", "T", &nc, &n, &one, W.data(), &n, &zero, M.data(), &nc);
    dpotrf_("L", &nc, M.data(), &nc, &info);
    if (info != 0) return info;
  }
  // one solve of [S C^T; C 0] [x; m] = r on the factors, in place (x first, then m)
  auto solve = [&](std::vector<double> &r) {
    double *rf = r.data(), *rd = r.data() + n;
    dtrsv_("L", "N", "N", &n, L, &n, rf, &unit);                                         // z = L^-1 f
    if (nc > 0) {
      dgemv_("T", &n, &nc, &one, W.data(), &n, rf, &unit, &minusOne, rd, &unit);   // W^T z - d
      dpotrs_("L", &nc, &unit, M.data(), &nc, rd, &nc, &info);                     // m
      dgemv_("N", &n, &nc, &minusOne, W.data(), &n, rd, &unit, &one, rf, &unit);   // z - W m
    }
    dtrsv_("L", "T", "N", &n, L, &n, rf, &unit);                                         // x
    return info == 0;
  };
  std::vector<double> z(n + nc);
  for (int r = 0; r < n; r++) z[r] = (*pf)[r];
  for (int a = 0; a < nc; a++) z[n + a] = (*pd)[a];
  solve(z);
  refineInto(S, C, nullptr, *pf, *pd, z, solve, px, pm);
  return 0;
}

// The Krylov step's preconditioner (include/solve/krylov_step.idp) solves one contact set's KKT
// system [alpha S, C^T; C, 0] once per GMRES iteration, S the factorization's Schur block: LU
// factors of it kept by the script, so that each solve is two triangular sweeps. FreeFEM's sparse
// solver on that system (S dense) took 53 ms a solve at R/32 (n = 982), as long as MUMPS's
// reduction on the whole body's factors.
//
// denseKktFactor(S, C, alpha, K, pivots): K (resized to n + nc) receives the LU factors of
// [alpha S, C^T; C, 0] (C sparse, nc x n) and pivots their row interchanges. Returns dgetrf's
// info: 0, or > 0 when the system is singular; -1 when the sizes differ.
// denseLuSolve(K, pivots, b): b <- the solution of K's system for b, in place. Returns dgetrs's
// info (0), or -1 when the sizes differ.
extern "C" {
void dgetrf_(const int *m, const int *n, double *a, const int *lda, int *ipiv, int *info);
}

static long denseKktFactor(KNM<double> *const &pS, Matrice_Creuse<double> *const &pC, const double &alpha,
                           KNM<double> *const &pK, KN<long> *const &pPivots) {
  const KNM<double> &S = *pS;
  MatriceMorse<double> *C = morse(pC);
  int n = int(S.N()), nc = int(C->n), size = n + nc, info = 0;
  if (S.M() != n || C->m != n) return -1;
  ffassert(!C->half);
  std::vector<double> A(size_t(size)*size, 0.);   // column-major
  for (int j = 0; j < n; j++)
    for (int i = 0; i < n; i++) A[size_t(j)*size + i] = alpha*S(i, j);
  for (size_t e = 0; e < size_t(C->nnz); e++) {
    A[size_t(C->j[e])*size + n + C->i[e]] += C->aij[e];   // C
    A[size_t(n + C->i[e])*size + C->j[e]] += C->aij[e];   // C^T
  }
  std::vector<int> pivots(size);
  if (size > 0) dgetrf_(&size, &size, A.data(), &size, pivots.data(), &info);
  pK->resize(size, size);
  KNM<double> &K = *pK;
  for (int j = 0; j < size; j++)
    for (int i = 0; i < size; i++) K(i, j) = A[size_t(j)*size + i];
  pPivots->resize(size);
  for (int i = 0; i < size; i++) (*pPivots)[i] = pivots[i];
  return info;
}

static long denseLuSolve(KNM<double> *const &pK, KN<long> *const &pPivots, KN<double> *const &pb) {
  const KNM<double> &K = *pK;
  int size = int(K.N()), info = 0;
  const int unit = 1;
  if (K.M() != size || pPivots->N() != size || pb->N() != size) return -1;
  // K's own storage when it is column-major and contiguous (as denseKktFactor leaves it), else a copy
  const double *factors = size > 0 ? &K(0, 0) : nullptr;
  std::vector<double> copy;
  if (size > 0 && !(K.step == 1 && K.shapei.step == 1 && K.shapej.step == size)) {
    copy.resize(size_t(size)*size);
    for (int j = 0; j < size; j++)
      for (int i = 0; i < size; i++) copy[size_t(j)*size + i] = K(i, j);
    factors = copy.data();
  }
  std::vector<double> b(size);
  std::vector<int> pivots(size);
  for (int i = 0; i < size; i++) pivots[i] = int((*pPivots)[i]);
  for (int i = 0; i < size; i++) b[i] = (*pb)[i];
  if (size > 0) dgetrs_("N", &size, &unit, factors, &size, pivots.data(), b.data(), &size, &info);
  for (int i = 0; i < size; i++) (*pb)[i] = b[i];
  return info;
}

static void init() {
  Global.Add("denseKktSolve", "(",
             new OneOperator7_<long, KNM<double> *, Matrice_Creuse<double> *, Matrice_Creuse<double> *, KN<double> *,
                               KN<double> *, KN<double> *, KN<double> *>(denseKktSolve));
  Global.Add("denseCholesky", "(", new OneOperator1_<long, KNM<double> *>(denseCholesky));
  Global.Add("denseCholeskyKktSolve", "(",
             new OneOperator6_<long, KNM<double> *, Matrice_Creuse<double> *, KN<double> *, KN<double> *,
                               KN<double> *, KN<double> *>(denseCholeskyKktSolve));
  Global.Add("denseKktFactor", "(",
             new OneOperator5_<long, KNM<double> *, Matrice_Creuse<double> *, double, KNM<double> *, KN<long> *>(
                 denseKktFactor));
  Global.Add("denseLuSolve", "(",
             new OneOperator3_<long, KNM<double> *, KN<long> *, KN<double> *>(denseLuSolve));
}

LOADFUNC(init)
