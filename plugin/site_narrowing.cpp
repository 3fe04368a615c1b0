//ff-c++-LIBRARY-dep: blas
// site_narrowing: friction's reduced problem narrowed to the dofs its rows hold
// (include/solve/site_narrowing.idp). Built by `make` with ff-c++ against Debian's LAPACK and
// BLAS; loaded by include/solve/site_narrowing.idp.
//
// With friction every component of every contact candidate is a condensed dof (a candidate may
// become a friction site), and IPOPT factorizes the dense condensed Hessian S at each iteration.
// A candidate with no friction bound (not in contact, or not yet) holds only its contact row's
// dof: its tangential dofs D are free, and are eliminated from S exactly by a second, dense Schur
// complement on the kept dofs K:
//   S_K = S_KK - S_KD S_DD^-1 S_DK,  r_K = r_K - S_KD S_DD^-1 r_D,  x_D = S_DD^-1 (r_D - S_DK x_K).
// S_DD is the stiffness of the free tangential dofs with every other contact dof held: positive
// definite (the platen's own dofs are held by the rows, so kept).
//
// narrowSchur(S, keep, drop, SK): LU of S_DD (LAPACK dgetrf), W = S_DD^-1 S_DK and
// V^T = S_DD^-T S_KD^T kept for the vectors, SK receives S_K. Returns dgetrf's info (0, or > 0
// when S_DD is singular: nothing kept), -1 for bad indices.
// narrowVector(v, vK): vK = v_K - V v_D, after narrowSchur.
// widenVector(v, xK, x): x on every dof, x_K = xK and x_D = S_DD^-1 v_D - W xK, after narrowSchur.
#include "ff++.hpp"
#include "AFunction_ext.hpp"
#include <vector>

extern "C" {
void dgetrf_(const int *m, const int *n, double *a, const int *lda, int *ipiv, int *info);
void dgetrs_(const char *trans, const int *n, const int *nrhs, const double *a, const int *lda, const int *ipiv,
             double *b, const int *ldb, int *info);
void dgemm_(const char *ta, const char *tb, const int *m, const int *n, const int *k, const double *alpha,
            const double *a, const int *lda, const double *b, const int *ldb, const double *beta, double *c,
            const int *ldc);
}

namespace {
// the last narrowing's: the kept and dropped dofs, S_DD's LU, W (|D| x |K|) and V^T (|D| x |K|)
std::vector<long> keptDofs, droppedDofs;
std::vector<double> dropLu, dropToKept, keptFromDrop;
std::vector<int> dropPivots;
bool ready = false;
}  // namespace

static long narrowSchur(KNM<double> *const &pS, KN<long> *const &pKeep, KN<long> *const &pDrop,
                        KNM<double> *const &pSK) {
  const KNM<double> &S = *pS;
  const KN<long> &keep = *pKeep, &drop = *pDrop;
  ready = false;
  int n = int(S.N()), nk = int(keep.N()), nd = int(drop.N());
  if (S.M() != n || nk + nd != n) return -1;
  for (int i = 0; i < nk; i++) if (keep[i] < 0 || keep[i] >= n) return -1;
  for (int i = 0; i < nd; i++) if (drop[i] < 0 || drop[i] >= n) return -1;
  keptDofs.assign(keep.operator long *(), keep.operator long *() + nk);
  droppedDofs.assign(drop.operator long *(), drop.operator long *() + nd);
  // column-major blocks: S_DD (nd x nd), S_DK (nd x nk), S_KD^T (nd x nk), S_KK (nk x nk)
  dropLu.assign(size_t(nd)*nd, 0.);
  dropToKept.assign(size_t(nd)*nk, 0.);
  keptFromDrop.assign(size_t(nd)*nk, 0.);
  for (int j = 0; j < nd; j++)
    for (int i = 0; i < nd; i++) dropLu[size_t(j)*nd + i] = S(drop[i], drop[j]);
  for (int j = 0; j < nk; j++)
    for (int i = 0; i < nd; i++) {
      dropToKept[size_t(j)*nd + i] = S(drop[i], keep[j]);
      keptFromDrop[size_t(j)*nd + i] = S(keep[j], drop[i]);
    }
  dropPivots.assign(std::max(nd, 1), 0);
  int info = 0;
  if (nd > 0) dgetrf_(&nd, &nd, dropLu.data(), &nd, dropPivots.data(), &info);
  if (info != 0) return info;
  if (nd > 0 && nk > 0) {
    dgetrs_("N", &nd, &nk, dropLu.data(), &nd, dropPivots.data(), dropToKept.data(), &nd, &info);
    if (info != 0) return -1;
    // (S_KD S_DD^-1)^T = S_DD^-T S_KD^T
    std::vector<double> kd = keptFromDrop;
    dgetrs_("T", &nd, &nk, dropLu.data(), &nd, dropPivots.data(), keptFromDrop.data(), &nd, &info);
    if (info != 0) return -1;
    // S_K = S_KK - S_KD W: S_KD = kd^T
    std::vector<double> product(size_t(nk)*nk, 0.);
    const double one = 1, zero = 0;
    dgemm_("T", "N", &nk, &nk, &nd, &one, kd.data(), &nd, dropToKept.data(), &nd, &zero, product.data(), &nk);
    pSK->resize(nk, nk);
    for (int j = 0; j < nk; j++)
      for (int i = 0; i < nk; i++) (*pSK)(i, j) = S(keep[i], keep[j]) - product[size_t(j)*nk + i];
  } else {
    pSK->resize(nk, nk);
    for (int j = 0; j < nk; j++)
      for (int i = 0; i < nk; i++) (*pSK)(i, j) = S(keep[i], keep[j]);
  }
  ready = true;
  return 0;
}

static long narrowVector(KN<double> *const &pv, KN<double> *const &pvK) {
  if (!ready) return -1;
  const KN<double> &v = *pv;
  int nk = int(keptDofs.size()), nd = int(droppedDofs.size());
  if (v.N() != nk + nd) return -1;
  pvK->resize(nk);
  for (int i = 0; i < nk; i++) {
    double value = v[keptDofs[i]];
    const double *column = keptFromDrop.data() + size_t(i)*nd;
    for (int d = 0; d < nd; d++) value -= column[d]*v[droppedDofs[d]];
    (*pvK)[i] = value;
  }
  return 0;
}

static long widenVector(KN<double> *const &pv, KN<double> *const &pxK, KN<double> *const &px) {
  if (!ready) return -1;
  const KN<double> &v = *pv, &xK = *pxK;
  int nk = int(keptDofs.size()), nd = int(droppedDofs.size());
  if (v.N() != nk + nd || xK.N() != nk) return -1;
  std::vector<double> xD(std::max(nd, 1), 0.);
  for (int d = 0; d < nd; d++) xD[d] = v[droppedDofs[d]];
  int info = 0;
  const int unit = 1;
  if (nd > 0) dgetrs_("N", &nd, &unit, dropLu.data(), &nd, dropPivots.data(), xD.data(), &nd, &info);
  if (info != 0) return -1;
  for (int j = 0; j < nk; j++) {
    const double *column = dropToKept.data() + size_t(j)*nd;
    for (int d = 0; d < nd; d++) xD[d] -= column[d]*xK[j];
  }
  px->resize(nk + nd);
  for (int i = 0; i < nk; i++) (*px)[keptDofs[i]] = xK[i];
  for (int d = 0; d < nd; d++) (*px)[droppedDofs[d]] = xD[d];
  return 0;
}

static void init() {
  Global.Add("narrowSchur", "(",
             new OneOperator4_<long, KNM<double> *, KN<long> *, KN<long> *, KNM<double> *>(narrowSchur));
  Global.Add("narrowVector", "(", new OneOperator2_<long, KN<double> *, KN<double> *>(narrowVector));
  Global.Add("widenVector", "(",
             new OneOperator3_<long, KN<double> *, KN<double> *, KN<double> *>(widenVector));
}

LOADFUNC(init)
