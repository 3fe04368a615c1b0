//ff-c++-LIBRARY-dep: metis mumps_seq
//ff-c++-LIBRARY-extra: -lsmumps_seq
// schur_condensation: the elastic problem condensed onto the contact dofs, by MUMPS's own Schur
// complement (ICNTL(19)) and its reduction/expansion of right-hand sides (ICNTL(26)). Built by
// `make` with ff-c++ against Debian's sequential MUMPS (libmumps-seq-dev) and METIS (libmetis-dev);
// used by include/solve/condensed_solve.idp.
//
// Why a plugin: FreeFEM's SchurComplement (plugin Schur-Complement) solves one right-hand side per
// Schur column, which at 941k dofs costs 0.54 s a column, 722 columns for the Hertz plane; MUMPS
// computes the Schur block as the last front of the one factorization, at the cost of a dense
// update, and FreeFEM's scripts cannot reach its control parameters.
//
// For a quadratic energy 1/2 U'K U - b'U and contact rows that involve only the dofs c:
//   S = K_cc - K_ci K_ii^-1 K_ic  (dense, c x c), reduced right-hand side g = b_c - K_ci K_ii^-1 b_i,
//   and, given U_c, the rest U_i = K_ii^-1 (b_i - K_ic U_c).
// One condensation is held at a time (a load-stepped run re-uses it for every step).
//
//   schurFactor(K, fixedMask, schurDofs, S): factorizes K with the dofs where fixedMask != 0 removed
//     (identity rows: the caller puts their values in the right-hand side) and the dofs schurDofs
//     kept as the Schur block, which it returns dense in S. Returns MUMPS's INFOG(1) (0: success).
//     Called again with the same pattern (a tangent at a new state), it keeps MUMPS's analysis.
//     An empty schurDofs is a plain factorization (a problem without contact rows).
//   schurIndefinite(yes): the next factorizations are LDL^T with pivoting (MUMPS SYM = 2) from the
//     start, for a matrix known to be indefinite (the nodal form's saddle point matrix); else
//     Cholesky first (SYM = 1), LDL^T when it fails.
//   schurVariableNodes(nodes): the mesh vertex (graph node) of every unknown, for the ordering (the
//     saddle point matrix's pressure and displacements at one vertex are one node: 2.9x the
//     penalty form's factor entries when METIS saw them apart); empty: grouped automatically.
//   schurReduce(b, g): g = the reduced right-hand side of b.
//   schurExpand(b, Uc, U): U = the whole solution for the right-hand side b with U(schurDofs) = Uc.
//   schurStatistics(stats): the last factorization's ordering, analysis and factorization times (s),
//     entries in the factors, flops, and its negative pivots (MUMPS INFOG(12): the negative
//     eigenvalues of the factorized matrix without its Schur block, by Sylvester's law of inertia).
//   schurRelease(): frees MUMPS's factors.
//   schurSinglePrecision(yes): the next factorizations in single precision (MUMPS's smumps), for a
//     caller that only uses them as a model whose steps it checks (the SQP: docs/performance.md);
//     returns `yes` (under MPI the bridge's smumps). Its matrix, Schur block and solves are
//     rounded to float inside the plugin; the caller sees doubles. A single precision
//     factorization that fails, or a matrix float cannot hold, is done in double.
//   schurIsSinglePrecision(): whether the live factors are single precision.
//   schurProcessShares(entries, flops): the last factorization's entries in the factors held by each
//     process and the flops of its elimination there (MUMPS's INFO(27) and RINFO(3), one per process
//     in rank order; under FreeFem++ one of each, INFOG(29) and RINFOG(3)).
//
// Under FreeFem++-mpi with more than one process every process makes the same calls with the same
// (replicated) matrix: the MPI MUMPS of plugin/mpi_bridge.so (opened in its own symbol scope, away
// from IPOPT's sequential MUMPS) factorizes it across the processes, each handing it only its share
// of the entries (ICNTL(18) = 3, a contiguous slice of the lower triangle); process 0 computes the
// pivot order and receives the Schur block and the solutions (centralized), which it broadcasts, so
// that every process holds the same S, g and U and goes on identically.
#include "ff++.hpp"
#include "AFunction_ext.hpp"
#include <dmumps_c.h>
#include <smumps_c.h>
#include "mpi_bridge.hpp"
#include <metis.h>
#include <sys/time.h>
#include <algorithm>
#include <cmath>
#include <vector>

namespace {
const int useCommWorld = -987654;   // MUMPS's sequential communicator stand-in

struct Condensation {
  DMUMPS_STRUC_C id;
  // single precision (schurSinglePrecision): the factorization in half the time and the solves in
  // two thirds (3D indentation at R/32, 1.1e8 entries: 3.4-3.8 s against 6.4-6.6 s, 0.098 s
  // against 0.155 s a reduction and expansion), the Schur block to 8e-7 and a solution to 3e-6
  // (relative, against double's)
  SMUMPS_STRUC_C sid;
  bool single = false;        // the live instance is sid
  bool wantSingle = false;    // the next factorizations' precision, as asked
  std::vector<float> valuesSingle, schurSingle, rhsSingle, reducedSingle;
  bool alive = false;
  std::vector<int> rows, columns, schurList, pivotOrder;
  std::vector<double> values, schur, rhs, reduced;
  long n = 0, nSchur = 0;
  double analysisTime = 0;
  double statistics[6] = {0, 0, 0, 0, 0, 0};   // ordering s, analysis s, factorization s, factor entries, flops, negative pivots
  bool indefinite = false;   // LDL^T with pivoting from the start
  std::vector<int> variableNodes;   // the caller's grouping of the variables into graph nodes
  const MpiBridge *bridge = nullptr;   // the MPI MUMPS when the run has several processes
  std::vector<double> processEntries, processFlops;  // INFO(27), RINFO(3) of every process after the last factorization

  bool host() const { return mpirank == 0; }
  // f on the live MUMPS instance (double or single: the same fields)
  template <class F> void live(F f) { if (single) f(sid); else f(id); }
  void call() {
    if (single && bridge) bridge->mumpsSingle(&sid);
    else if (single) smumps_c(&sid);
    else if (bridge) bridge->mumps(&id);
    else dmumps_c(&id);
  }
  // process 0's values of v to every process
  void share(std::vector<double> &v) {
    if (bridge) bridge->broadcast(v.data(), long(v.size()));
  }
  void release() {
    if (!alive) return;
    live([](auto &m) { m.job = -2; });
    call();
    alive = false;
  }
  void quiet() {
    live([](auto &m) { m.icntl[0] = -1; m.icntl[1] = -1; m.icntl[2] = -1; m.icntl[3] = 0; });
  }
  // job 3 with ICNTL(26) = phase (1 reduce, 2 expand) on the right-hand side b
  int solvePhase(const KN<double> &b, int phase) {
    for (long k = 0; k < n; k++) rhs[k] = b[k];
    if (single) {
      // b's Schur entries (the contact dofs': their reactions, large against the residual near
      // the solution) enter the reduced right-hand side alone, b_c - H_ci H_ii^-1 b_i: added
      // below in double, not rounded (rounded, a Newton step's residual stalled at 5e-11 against
      // a target of 1.3e-11, 3D indentation at R/16) and not used by the expansion
      for (long k = 0; k < n; k++) rhsSingle[k] = float(b[k]);
      for (int v : schurList) rhsSingle[v - 1] = 0.f;
      for (long k = 0; k < nSchur; k++) reducedSingle[k] = float(reduced[k]);
      sid.rhs = rhsSingle.data(); sid.redrhs = reducedSingle.data();
    } else {
      id.rhs = rhs.data(); id.redrhs = reduced.data();
    }
    int info = 0;
    live([&](auto &m) {
      m.nrhs = 1;
      m.lrhs = int(n);
      m.lredrhs = int(nSchur);
      m.icntl[25] = phase;
      m.job = 3;
      call();
      m.icntl[25] = 0;
      info = m.infog[0];
    });
    if (single) {
      if (phase == 1) for (long k = 0; k < nSchur; k++) reduced[k] = reducedSingle[k] + b[schurList[k] - 1];
      else for (long k = 0; k < n; k++) rhs[k] = rhsSingle[k];
    }
    if (phase == 1) share(reduced); else share(rhs);   // centralized on process 0
    return info;
  }
};
Condensation condensation;

double clockNow() {
  timeval now;
  gettimeofday(&now, 0);
  return now.tv_sec + 1e-6*now.tv_usec;
}

// The pivot order for MUMPS (PERM_IN, 1-based positions): METIS's nested dissection of the
// matrix graph, then the Schur variables last. With a Schur block requested, MUMPS's own choice
// (ICNTL(7) = 7) fell back to AMD: 26.1M entries in the factors at 242k dofs, 19.8M with METIS.
// METIS orders the nodes: consecutive variables with the same neighbours (a vector field's
// components at one node) are one vertex of its graph.
void nestedDissectionOrder(Condensation &c, const std::vector<int> &rows, const std::vector<int> &columns) {
  long n = c.n;
  // the symmetric pattern with its diagonal (closed neighbourhoods) in compressed rows, each row
  // sorted and without repeats (built by counting: a vector per row took ~2 s at 949k dofs)
  std::vector<long> start(n + 1, 0);
  for (size_t k = 0; k < rows.size(); k++) {
    int i = rows[k] - 1, j = columns[k] - 1;
    if (i != j) { start[i + 1]++; start[j + 1]++; }
  }
  for (long i = 0; i < n; i++) start[i + 1] += start[i] + 1;   // + the diagonal
  std::vector<int> column(start[n]);
  std::vector<long> fill(start.begin(), start.end() - 1);
  for (long i = 0; i < n; i++) column[fill[i]++] = int(i);
  for (size_t k = 0; k < rows.size(); k++) {
    int i = rows[k] - 1, j = columns[k] - 1;
    if (i != j) { column[fill[i]++] = j; column[fill[j]++] = i; }
  }
  std::vector<long> rowFirst(n + 1, 0);   // after sorting and removing repeats, in place
  long kept = 0;
  for (long i = 0; i < n; i++) {
    std::sort(column.begin() + start[i], column.begin() + start[i + 1]);
    long end = std::unique(column.begin() + start[i], column.begin() + start[i + 1]) - column.begin();
    rowFirst[i] = kept;
    for (long k = start[i]; k < end; k++) column[kept++] = column[k];
  }
  rowFirst[n] = kept;
  auto sameRow = [&](long i, long j) {
    return rowFirst[i + 1] - rowFirst[i] == rowFirst[j + 1] - rowFirst[j]
           && std::equal(column.begin() + rowFirst[i], column.begin() + rowFirst[i + 1], column.begin() + rowFirst[j]);
  };
  // variable -> node: the caller's grouping (schurVariableNodes), else consecutive variables with
  // the same row (a vector field's components at one node)
  std::vector<int> node(n);
  long nodes = 0;
  if ((long)c.variableNodes.size() == n) {
    for (long i = 0; i < n; i++) { node[i] = c.variableNodes[i]; nodes = std::max(nodes, long(node[i]) + 1); }
  } else {
    for (long i = 0; i < n; i++) node[i] = (i > 0 && sameRow(i, i - 1)) ? node[i - 1] : int(nodes++);
  }
  std::vector<long> memberStart(nodes + 1, 0);   // node -> its variables, in compressed rows
  for (long i = 0; i < n; i++) memberStart[node[i] + 1]++;
  for (long v = 0; v < nodes; v++) memberStart[v + 1] += memberStart[v];
  std::vector<long> member(n), memberFill(memberStart.begin(), memberStart.end() - 1);
  for (long i = 0; i < n; i++) member[memberFill[node[i]]++] = i;
  std::vector<idx_t> xadj(nodes + 1, 0), adjncy;
  adjncy.reserve(kept/2);
  std::vector<long> seen(nodes, -1);
  for (long v = 0; v < nodes; v++) {
    for (long m = memberStart[v]; m < memberStart[v + 1]; m++) {
      long i = member[m];
      for (long k = rowFirst[i]; k < rowFirst[i + 1]; k++) {
        int w = node[column[k]];
        if (w != v && seen[w] != v) { seen[w] = v; adjncy.push_back(w); }
      }
    }
    xadj[v + 1] = adjncy.size();
  }
  std::vector<int>().swap(column);
  idx_t vertices = idx_t(nodes);
  std::vector<idx_t> permutation(nodes), inverse(nodes);
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  // one refinement iteration per level instead of 10: the same fill (9.14e7 against 9.19e7 entries at
  // 949k dofs), METIS 2.3 s against 2.6-3.2 s
  options[METIS_OPTION_NITER] = 1;
  METIS_NodeND(&vertices, xadj.data(), adjncy.data(), 0, options, permutation.data(), inverse.data());
  std::vector<char> inSchur(n, 0);
  for (int v : c.schurList) inSchur[v - 1] = 1;
  c.pivotOrder.assign(n, 0);
  int position = 0;
  for (long k = 0; k < nodes; k++)
    for (long m = memberStart[permutation[k]]; m < memberStart[permutation[k] + 1]; m++)
      if (!inSchur[member[m]]) c.pivotOrder[member[m]] = ++position;
  for (int v : c.schurList) c.pivotOrder[v - 1] = ++position;
}
}

// MUMPS's analysis and factorization of c's matrix with the Schur block, symmetric type sym;
// returns INFOG(1). On failure MUMPS's instance is released.
// The values (and the Schur block's storage) handed to the live instance: single precision's
// rounded copies, or the doubles themselves.
static void pointValues(Condensation &c) {
  if (c.single) {
    c.valuesSingle.assign(c.values.begin(), c.values.end());
    c.schurSingle.assign(c.nSchur*c.nSchur, 0.f);
    if (c.bridge) c.sid.a_loc = c.valuesSingle.data(); else c.sid.a = c.valuesSingle.data();
    c.sid.schur = c.schurSingle.data();
  } else {
    if (c.bridge) c.id.a_loc = c.values.data(); else c.id.a = c.values.data();
    c.id.schur = c.schur.data();
  }
}

// Every process's verdict, the same on all: true when `mine` is true on every process (one process:
// mine).
static bool onEveryProcess(const Condensation &c, bool mine) {
  if (!c.bridge) return mine;
  std::vector<double> all(mpisize);
  c.bridge->gather(mine ? 1. : 0., all.data());
  return std::all_of(all.begin(), all.end(), [](double v) { return v == 1.; });
}

// Single precision as asked, where it can hold the matrix: its largest entry (over every
// process's slice under MPI) within 1e-30..1e30 (float's normal range is 1e-38..3e38: a matrix at
// another scale, unscaled SI units, is factorized in double). Entries far below the largest are
// round-off (2e-31 in the 3D indentation's first tangent at R/8) that float may flush to 0; a row
// that needed them fails the factorization or the SQP's checks, which fall back to double.
static bool singleFits(const Condensation &c) {
  if (!c.wantSingle) return false;
  double largest = 0;
  bool finite = true;
  for (double v : c.values) {
    if (!std::isfinite(v)) finite = false;
    else largest = std::max(largest, std::fabs(v));
  }
  if (c.bridge) {   // the largest of all, and -1 where a process holds a non-finite entry
    std::vector<double> all(mpisize);
    c.bridge->gather(finite ? largest : -1., all.data());
    for (double v : all) {
      if (v < 0) finite = false;
      largest = std::max(largest, v);
    }
  }
  return finite && largest >= 1e-30 && largest <= 1e30;
}

static int factorWith(Condensation &c, int sym) {
  c.release();
  c.single = singleFits(c);
  int info = 0;
  c.live([&](auto &id) {
    id.comm_fortran = useCommWorld;   // MPI_COMM_WORLD for the MPI MUMPS
    id.par = 1;                       // process 0 works too
    id.sym = sym;
    id.job = -1;
    c.call();
    c.alive = true;
    c.quiet();
    id.n = int(c.n);
    if (c.bridge) {              // ICNTL(18) = 3: each process its own slice of the entries
      id.icntl[17] = 3;
      id.nnz_loc = (MUMPS_INT8)c.values.size();
      id.irn_loc = c.rows.data(); id.jcn_loc = c.columns.data();
    } else {
      id.nnz = (MUMPS_INT8)c.values.size();
      id.irn = c.rows.data(); id.jcn = c.columns.data();
    }
    if (c.nSchur > 0) {
      id.icntl[18] = 1;          // ICNTL(19): the Schur complement, centralized
      id.size_schur = int(c.nSchur);
      id.listvar_schur = c.schurList.data();
    }
    pointValues(c);
    id.perm_in = c.pivotOrder.data();
    id.icntl[6] = 1;             // ICNTL(7): the pivot order given in PERM_IN
    double t0 = clockNow();
    id.job = 1;                  // analysis
    c.call();
    c.analysisTime = clockNow() - t0;
    if (id.infog[0] >= 0) {
      id.job = 2;                // factorization
      c.call();
    }
    info = id.infog[0];
  });
  if (info < 0) c.release();
  return info;
}

// The lower triangle of K's entries first..last-1 on the free dofs (1-based), and with
// withFixed 1 on each fixed dof's diagonal; the values too unless `values` is null (the pattern only).
static void lowerTriangle(const MatriceMorse<double> &K, const KN<double> &fixed, size_t first, size_t last, bool withFixed,
                          std::vector<int> &rows, std::vector<int> &columns, std::vector<double> *values) {
  size_t room = (last - first)/2 + (withFixed ? K.n : 0);
  rows.reserve(room); columns.reserve(room);
  if (values) values->reserve(room);
  for (size_t k = first; k < last; k++) {
    long i = K.i[k], j = K.j[k];
    if (fixed[i] != 0 || fixed[j] != 0) continue;
    if (!K.half && j > i) continue;
    if (K.half && j > i) std::swap(i, j);
    rows.push_back(int(i + 1)); columns.push_back(int(j + 1));
    if (values) values->push_back(K.aij[k]);
  }
  if (withFixed)
    for (long i = 0; i < K.n; i++)
      if (fixed[i] != 0) {
        rows.push_back(int(i + 1)); columns.push_back(int(i + 1));
        if (values) values->push_back(1.);
      }
}

static long schurFactor(Matrice_Creuse<double> *const &pK, KN<double> *const &pFixed, KN<long> *const &pSchur,
                        KNM<double> *const &pS) {
  MatriceCreuse<double> *generic = pK->A;
  MatriceMorse<double> *K = dynamic_cast<MatriceMorse<double> *>(generic);
  ffassert(K && K->n == K->m);
  const KN<double> &fixed = *pFixed;
  const KN<long> &schurDofs = *pSchur;
  long n = K->n, nSchur = schurDofs.N();
  ffassert(fixed.N() == n && nSchur >= 0 && nSchur < n);
  Condensation &c = condensation;
  c.bridge = mpiBridge();
  // this process's entries: all of them, or under MPI its slice of K's entries (process 0's with
  // the fixed dofs' diagonal)
  long processes = c.bridge ? mpisize : 1;
  size_t first = size_t(double(K->nnz)*mpirank/processes), last = size_t(double(K->nnz)*(mpirank + 1)/processes);
  std::vector<int> rows, columns, schurList(nSchur);
  std::vector<double> values;
  lowerTriangle(*K, fixed, first, last, c.host(), rows, columns, &values);
  for (long s = 0; s < nSchur; s++) {
    ffassert(schurDofs[s] >= 0 && schurDofs[s] < n && fixed[schurDofs[s]] == 0);
    schurList[s] = int(schurDofs[s] + 1);
  }
  double t0 = clockNow(), t1 = t0;
  int info = -1;
  // the same pattern as the last factorization (a tangent at a new state): new values, MUMPS's
  // analysis kept (O-ring plates, 1146 dofs: 11 ms -> ms per condensation)
  int liveSym = c.single ? c.sid.sym : c.id.sym;
  bool samePattern = c.alive && c.n == n && c.nSchur == nSchur && schurList == c.schurList && rows == c.rows
                     && columns == c.columns && !(c.indefinite && liveSym == 1);
  c.values.swap(values);
  bool samePrecision = c.single == singleFits(c);
  if (samePattern && samePrecision) {
    c.analysisTime = 0;
    pointValues(c);
    c.live([&](auto &id) { id.job = 2; c.call(); info = id.infog[0]; });
  }
  if (info < 0) {
    c.release();
    c.n = n; c.nSchur = nSchur;
    c.rows.swap(rows); c.columns.swap(columns); c.schurList.swap(schurList);
    c.schur.assign(nSchur*nSchur, 0.);
    c.rhs.assign(n, 0.);
    c.reduced.assign(nSchur, 0.);
    // (same pattern, new values that need LDL^T: same order); under MPI process 0 orders the whole
    // pattern, the others pass no order (MUMPS reads PERM_IN on process 0 only)
    if (!samePattern && !c.bridge) nestedDissectionOrder(c, c.rows, c.columns);
    if (!samePattern && c.bridge && c.host()) {
      std::vector<int> allRows, allColumns;   // the whole pattern, no values: freed once ordered
      lowerTriangle(*K, fixed, 0, K->nnz, true, allRows, allColumns, nullptr);
      nestedDissectionOrder(c, allRows, allColumns);
    }
    t1 = clockNow();
    // Cholesky (sym = 1) when K_ii is positive definite: 5.5 s against 8.7 s for LDL^T with pivoting
    // (sym = 2) on the 67k-dof 3D sphere; LDL^T when it is not (a body left free by its rows)
    info = c.indefinite ? -1 : factorWith(c, 1);
    if (info < 0) info = factorWith(c, 2);
  }
  // single precision that failed, or whose Schur block overflowed: double (under MPI the block is
  // process 0's, and every process follows its verdict)
  bool finite = true;
  if (info >= 0 && c.single) {   // (its lower triangle: the rest is MUMPS's workspace)
    for (long i = 0; i < nSchur; i++)
      for (long j = 0; j <= i; j++) finite = finite && std::isfinite(c.schurSingle[i*nSchur + j]);
    finite = onEveryProcess(c, finite);
  }
  if (c.single && (info < 0 || !finite)) {
    c.wantSingle = false;
    info = c.indefinite ? -1 : factorWith(c, 1);
    if (info < 0) info = factorWith(c, 2);
    c.wantSingle = true;
  }
  double t3 = clockNow();
  c.statistics[0] = t1 - t0; c.statistics[1] = c.analysisTime; c.statistics[2] = t3 - t1 - c.analysisTime;
  c.live([&](auto &id) {
    c.statistics[3] = double(id.infog[28]);   // INFOG(29): entries in the factors
    c.statistics[4] = id.rinfog[2];          // RINFOG(3): flops of the elimination
    c.statistics[5] = double(id.infog[11]);  // INFOG(12): negative pivots
    c.processEntries.assign(processes, double(id.infog[28]));
    c.processFlops.assign(processes, id.rinfog[2]);
    if (c.bridge) {   // INFO(27), RINFO(3): this process's
      c.bridge->gather(double(id.info[26]), c.processEntries.data());
      c.bridge->gather(id.rinfo[2], c.processFlops.data());
    }
  });
  if (info < 0) return info;
  if (c.single) {
    c.schur.assign(c.schurSingle.begin(), c.schurSingle.end());
    c.rhsSingle.assign(n, 0.f);
    c.reducedSingle.assign(nSchur, 0.f);
  }
  c.share(c.schur);   // centralized on process 0
  // a symmetric matrix's Schur block comes back as its lower triangle by rows (ICNTL(19) = 1);
  // the other holds MUMPS's workspace, not zeros
  KNM<double> &S = *pS;
  S.resize(nSchur, nSchur);
  for (long i = 0; i < nSchur; i++)
    for (long j = 0; j <= i; j++) S(i, j) = S(j, i) = c.schur[i*nSchur + j];
  return info;   // > 0: a warning
}

static long schurReduce(KN<double> *const &pb, KN<double> *const &pg) {
  Condensation &c = condensation;
  ffassert(c.alive && pb->N() == c.n);
  pg->resize(c.nSchur);
  if (c.nSchur == 0) return 0;
  int info = c.solvePhase(*pb, 1);
  if (info < 0) return info;
  for (long s = 0; s < c.nSchur; s++) (*pg)[s] = c.reduced[s];
  return 0;
}

static long schurExpand(KN<double> *const &pb, KN<double> *const &pUc, KN<double> *const &pU) {
  Condensation &c = condensation;
  ffassert(c.alive && pb->N() == c.n && pUc->N() == c.nSchur);
  for (long s = 0; s < c.nSchur; s++) c.reduced[s] = (*pUc)[s];
  int info = c.solvePhase(*pb, c.nSchur > 0 ? 2 : 0);
  if (info < 0) return info;
  pU->resize(c.n);
  for (long k = 0; k < c.n; k++) (*pU)[k] = c.rhs[k];
  for (long s = 0; s < c.nSchur; s++) (*pU)[c.schurList[s] - 1] = (*pUc)[s];
  return 0;
}

// [ordering s, analysis s, factorization s, entries in the factors, flops, negative pivots] of the
// last schurFactor
static long schurStatistics(KN<double> *const &pStatistics) {
  pStatistics->resize(6);
  for (int k = 0; k < 6; k++) (*pStatistics)[k] = condensation.statistics[k];
  return 0;
}

static long schurProcessShares(KN<double> *const &pEntries, KN<double> *const &pFlops) {
  const Condensation &c = condensation;
  long n = long(c.processEntries.size());
  pEntries->resize(n);
  pFlops->resize(n);
  for (long k = 0; k < n; k++) { (*pEntries)[k] = c.processEntries[k]; (*pFlops)[k] = c.processFlops[k]; }
  return 0;
}

static long schurIndefinite(const bool &yes) {
  condensation.indefinite = yes;
  return 0;
}

// The graph node of every variable for the nested dissection (empty: grouped automatically).
static long schurVariableNodes(KN<long> *const &pNodes) {
  const KN<long> &nodes = *pNodes;
  condensation.variableNodes.assign(nodes.N(), 0);
  for (long i = 0; i < nodes.N(); i++) {
    ffassert(nodes[i] >= 0);
    condensation.variableNodes[i] = int(nodes[i]);
  }
  return 0;
}

static long schurRelease() {
  condensation.release();
  return 0;
}

static bool schurSinglePrecision(const bool &yes) {
  condensation.wantSingle = yes;
  return condensation.wantSingle;
}

static bool schurIsSinglePrecision() {
  return condensation.alive && condensation.single;
}

static void init() {
  Global.Add("schurFactor", "(", new OneOperator4_<long, Matrice_Creuse<double> *, KN<double> *, KN<long> *, KNM<double> *>(schurFactor));
  Global.Add("schurReduce", "(", new OneOperator2_<long, KN<double> *, KN<double> *>(schurReduce));
  Global.Add("schurExpand", "(", new OneOperator3_<long, KN<double> *, KN<double> *, KN<double> *>(schurExpand));
  Global.Add("schurStatistics", "(", new OneOperator1_<long, KN<double> *>(schurStatistics));
  Global.Add("schurProcessShares", "(", new OneOperator2_<long, KN<double> *, KN<double> *>(schurProcessShares));
  Global.Add("schurIndefinite", "(", new OneOperator1_<long, bool>(schurIndefinite));
  Global.Add("schurVariableNodes", "(", new OneOperator1_<long, KN<long> *>(schurVariableNodes));
  Global.Add("schurRelease", "(", new OneOperator0<long>(schurRelease));
  Global.Add("schurSinglePrecision", "(", new OneOperator1_<bool, bool>(schurSinglePrecision));
  Global.Add("schurIsSinglePrecision", "(", new OneOperator0<bool>(schurIsSinglePrecision));
}

LOADFUNC(init)
