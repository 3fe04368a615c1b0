// contact_runtime: what the suite's FreeFEM scripts cannot do for themselves, built by `make`
// with ff-c++ (Debian package libfreefem++-dev) and loaded from freefem++.pref.
//
// 1. Headless runs. The graphical FreeFem++ opens a pipe to ffglut when it starts, even for a
//    script that never plots. Without a display ffglut exits at once, and FreeFem++'s last write to
//    the dead pipe (its plot header, flushed at exit) kills it with SIGPIPE: exit 141 and the
//    buffered output lost, whenever the output goes to a file or a pipe. With neither DISPLAY nor
//    WAYLAND_DISPLAY set, this plugin closes that pipe at load time, before the script is compiled,
//    and leaves FreeFem++ as -nw would. With a display it does nothing.
// 2. exitRun(code): ends the process at once with `code`, from anywhere, including inside an IPOPT
//    callback. FreeFEM's exit() throws an exception that IPOPT catches inside its callbacks (the run
//    goes on) and that prints FreeFEM's call stack; the suite's error rule is one line and a
//    documented exit code.
// 3. clockSeconds(): wall-clock seconds with microseconds (FreeFEM's time() counts whole seconds).
// 4. boundarySegmentCrossings(xyz, corners, pair) (2D), boundaryTriangleCrossings (3D): how many pairs of boundary elements (segments in
//    2D, triangles in 3D) that share no vertex cross each other, for the fold guard
//    (include/body/injectivity.idp). In FreeFEM's interpreter the same search took 15 s for the
//    1762 boundary triangles of the coarse 3D Hertz mesh, longer than the solve; here it is a
//    sweep over the elements sorted by their lowest x, with bounding boxes, in milliseconds.
//    xyz: the vertices' x, then their y, then their z; corners: 2 or 3 vertex numbers per element; pair receives the
//    first crossing pair found.
#include "ff++.hpp"
#include <elf.h>
#include <link.h>
#include <sys/mman.h>
#include <ctime>
#include <cstring>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <sys/time.h>
#include <unistd.h>
#include <algorithm>
#include <vector>

extern FILE *ThePlotStream;
extern bool NoGraphicWindow;

static bool hasDisplay() {
  const char *x11 = getenv("DISPLAY"), *wayland = getenv("WAYLAND_DISPLAY");
  return (x11 && *x11) || (wayland && *wayland);
}

static void closePlotPipeWithoutDisplay() {
  if (hasDisplay() || !ThePlotStream) return;
  void (*previous)(int) = signal(SIGPIPE, SIG_IGN);   // ffglut may have exited already
  pclose(ThePlotStream);
  signal(SIGPIPE, previous);
  ThePlotStream = 0;
  NoGraphicWindow = true;
}

// FreeFEM's interpreter reads clock() twice per statement (ListOfInst, for its -cpu option),
// and glibc's clock() is a system call that sums the CPU time of every thread of the process: 650 ns a
// call here, about a fifth of the O-ring's run. The FreeFem++ program's entry for clock() in its
// global offset table is pointed at a reading of the monotonic clock (30 ns, no system call), in
// the same units: clock() in a FreeFEM script then measures elapsed time, not processor time.
// CONTACT_CPU_CLOCK=1 in the environment leaves clock() as it is.
static clock_t monotonicClock() {
  timespec now;
  clock_gettime(CLOCK_MONOTONIC, &now);
  return clock_t(now.tv_sec) * CLOCKS_PER_SEC + clock_t(now.tv_nsec / (1000000000 / CLOCKS_PER_SEC));
}

static int redirectClock(dl_phdr_info *info, size_t, void *) {
  if (info->dlpi_name && info->dlpi_name[0]) return 0;   // the program itself comes first, unnamed
  const ElfW(Dyn) *dynamic = 0;
  for (int k = 0; k < info->dlpi_phnum; k++)
    if (info->dlpi_phdr[k].p_type == PT_DYNAMIC) dynamic = (const ElfW(Dyn) *)(info->dlpi_addr + info->dlpi_phdr[k].p_vaddr);
  if (!dynamic) return 1;
  ElfW(Addr) symbols = 0, strings = 0, relocations[2] = {0, 0};
  size_t sizes[2] = {0, 0};
  for (const ElfW(Dyn) *d = dynamic; d->d_tag != DT_NULL; d++) {
    if (d->d_tag == DT_SYMTAB) symbols = d->d_un.d_ptr;
    if (d->d_tag == DT_STRTAB) strings = d->d_un.d_ptr;
    if (d->d_tag == DT_JMPREL) relocations[0] = d->d_un.d_ptr;
    if (d->d_tag == DT_PLTRELSZ) sizes[0] = d->d_un.d_val;
    if (d->d_tag == DT_RELA) relocations[1] = d->d_un.d_ptr;
    if (d->d_tag == DT_RELASZ) sizes[1] = d->d_un.d_val;
  }
  // the dynamic loader has made these addresses absolute; a table that was not is an offset
  auto absolute = [&](ElfW(Addr) a) { return a < info->dlpi_addr ? a + info->dlpi_addr : a; };
  if (!symbols || !strings) return 1;
  const ElfW(Sym) *symbolTable = (const ElfW(Sym) *)absolute(symbols);
  const char *stringTable = (const char *)absolute(strings);
  long page = sysconf(_SC_PAGESIZE);
  for (int t = 0; t < 2; t++) {
    if (!relocations[t]) continue;
    const ElfW(Rela) *r = (const ElfW(Rela) *)absolute(relocations[t]);
    for (size_t k = 0; k < sizes[t] / sizeof(ElfW(Rela)); k++) {
      unsigned type = ELF64_R_TYPE(r[k].r_info);
      if (type != R_X86_64_JUMP_SLOT && type != R_X86_64_GLOB_DAT) continue;
      if (std::strcmp(stringTable + symbolTable[ELF64_R_SYM(r[k].r_info)].st_name, "clock") != 0) continue;
      void **slot = (void **)(info->dlpi_addr + r[k].r_offset);
      void *start = (void *)((uintptr_t)slot & ~(uintptr_t)(page - 1));
      if (mprotect(start, page, PROT_READ | PROT_WRITE) != 0) continue;   // left as it is
      *slot = (void *)&monotonicClock;
      mprotect(start, page, PROT_READ);   // read-only again (RELRO)
    }
  }
  return 1;
}

static long exitRun(long code) {
  cout.flush();
  cerr.flush();
  fflush(stdout);
  fflush(stderr);
  _exit(int(code));
  return code;
}

static double clockSeconds() {
  timeval now;
  gettimeofday(&now, 0);
  return now.tv_sec + 1e-6*now.tv_usec;
}

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
}

static long boundaryCrossings(KN<double> *const &xyz, KN<long> *const &corners, long d, KN<long> *const &pair) {
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

static long boundaryCrossings2(KN<double> *const &xyz, KN<long> *const &corners, KN<long> *const &pair) {
  return boundaryCrossings(xyz, corners, 2, pair);
}
static long boundaryCrossings3(KN<double> *const &xyz, KN<long> *const &corners, KN<long> *const &pair) {
  return boundaryCrossings(xyz, corners, 3, pair);
}

static void init() {
  closePlotPipeWithoutDisplay();
#if defined(__x86_64__)
  const char *keep = getenv("CONTACT_CPU_CLOCK");
  if (!(keep && *keep && std::strcmp(keep, "0") != 0)) dl_iterate_phdr(redirectClock, 0);
#endif
  Global.Add("exitRun", "(", new OneOperator1<long, long>(exitRun));
  Global.Add("clockSeconds", "(", new OneOperator0<double>(clockSeconds));
  Global.Add("boundarySegmentCrossings", "(", new OneOperator3_<long, KN<double> *, KN<long> *, KN<long> *>(boundaryCrossings2));
  Global.Add("boundaryTriangleCrossings", "(", new OneOperator3_<long, KN<double> *, KN<long> *, KN<long> *>(boundaryCrossings3));
}

LOADFUNC(init)
