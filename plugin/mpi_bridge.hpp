// mpi_bridge.hpp: plugin/mpi_bridge.so opened in its own symbol scope (that file says why), for
// the suite's plugins under FreeFem++-mpi. Needs FreeFEM's mpisize (1 under FreeFem++).
//   mpiBridge(): the bridge's calls when the run has more than one process, else null (the
//     sequential build never opens it); a bridge that cannot be opened under MPI is one error line
//     and exit code 2.
#ifndef MPI_BRIDGE_HPP
#define MPI_BRIDGE_HPP
#include <dlfcn.h>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unistd.h>

extern long mpisize, mpirank;   // FreeFEM's: the processes of this run and this one's rank

struct MpiBridge {
  int (*mumps)(void *id);
  int (*mumpsSingle)(void *id);
  void (*broadcast)(double *data, long n);
  void (*gather)(double value, double *all);
  void (*barrier)();
  int (*processes)();
};

inline void mpiBridgeAnchor() {}   // an address in this plugin, to find its folder

inline const MpiBridge *mpiBridge() {
  static MpiBridge bridge;
  static bool opened = false;
  if (mpisize <= 1) return nullptr;
  if (opened) return &bridge;
  Dl_info self;
  std::string path = "mpi_bridge.so";
  if (dladdr((void *)&mpiBridgeAnchor, &self) && self.dli_fname) {
    std::string plugin = self.dli_fname;
    size_t slash = plugin.rfind('/');
    if (slash != std::string::npos) path = plugin.substr(0, slash + 1) + path;
  }
  void *library = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL | RTLD_DEEPBIND);
  const char *missing = library ? nullptr : dlerror();
  if (library) {
    bridge.mumps = (int (*)(void *))dlsym(library, "mpiBridgeMumps");
    bridge.mumpsSingle = (int (*)(void *))dlsym(library, "mpiBridgeMumpsSingle");
    bridge.broadcast = (void (*)(double *, long))dlsym(library, "mpiBridgeBroadcast");
    bridge.gather = (void (*)(double, double *))dlsym(library, "mpiBridgeGather");
    bridge.barrier = (void (*)())dlsym(library, "mpiBridgeBarrier");
    bridge.processes = (int (*)())dlsym(library, "mpiBridgeProcesses");
    if (!bridge.mumps || !bridge.mumpsSingle || !bridge.broadcast || !bridge.gather || !bridge.barrier || !bridge.processes) missing = "a call is missing";
  }
  if (missing) {
    if (mpirank == 0) fprintf(stdout, "error: the MPI run cannot open %s (%s): run `make` to build it\n", path.c_str(), missing);
    fflush(stdout);
    _exit(2);
  }
  opened = true;
  return &bridge;
}
#endif
