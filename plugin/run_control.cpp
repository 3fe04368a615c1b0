// run_control: how a run ends and how long it took, for include/core/errors.idp and output.idp.
//   exitRun(code): ends the process at once with `code`, from anywhere, including inside an IPOPT
//     callback. FreeFEM's exit() throws an exception that IPOPT catches inside its callbacks (the run
//     goes on) and that prints FreeFEM's call stack; the suite's error rule is one line and a
//     documented exit code.
//   clockSeconds(): wall-clock seconds with microseconds (FreeFEM's time() counts whole seconds).
//   processCount(), processRank(): the run's MPI processes and this one's rank (1 and 0 under
//     FreeFem++; FreeFEM's own mpirank and mpisize are names only FreeFem++-mpi's scripts know).
//   processBarrier(): every process waits for the others (nothing under FreeFem++).
//   Under FreeFem++-mpi every process runs the whole script (include/core/output.idp): the standard
//   output of all but process 0 goes to /dev/null from the moment this plugin loads, so that each
//   progress and error line is printed once (their standard error stays: a crash still shows).
//   launchedProcesses(): the processes mpirun (OpenMPI's OMPI_COMM_WORLD_SIZE) or a PMI launcher
//     (PMI_SIZE) started, 1 without one: FreeFem++ started N times by mpirun sees N here and 1 in
//     processCount() (include/core/run.idp refuses it).
#include "ff++.hpp"
#include "mpi_bridge.hpp"
#include <cstdio>
#include <cstdlib>
#include <fcntl.h>
#include <sys/time.h>
#include <unistd.h>

namespace {

long exitRun(long code) {
  // under MPI every process fails at the same point: the others leave it to process 0 to print its
  // error line and end the job (mpirun stops all at the first failed exit, and stopped process 0's
  // last lines unprinted when another process was first). They wait for mpirun to stop them, not a
  // fixed while that a loaded machine could outlast, and end by themselves after a minute only if
  // process 0 went on (a failure of theirs alone)
  if (code != 0 && mpisize > 1 && mpirank > 0) sleep(60);
  cout.flush();
  cerr.flush();
  fflush(stdout);
  fflush(stderr);
  _exit(int(code));
  return code;
}

double clockSeconds() {
  timeval now;
  gettimeofday(&now, 0);
  return now.tv_sec + 1e-6*now.tv_usec;
}

long processCount() { return mpisize > 1 ? mpisize : 1; }   // (0 under FreeFem++)
long processRank() { return mpirank; }
long processBarrier() {
  if (const MpiBridge *bridge = mpiBridge()) bridge->barrier();
  return 0;
}

long launchedProcesses() {
  for (const char *name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"}) {
    const char *value = getenv(name);
    if (value && atol(value) > 0) return atol(value);
  }
  return 1;
}

void init() {
  mpiBridge();   // under MPI, opened now: a missing bridge is one error line before any work
  if (mpisize > 1 && mpirank > 0) {
    int null = open("/dev/null", O_WRONLY);
    fflush(stdout);
    if (null >= 0) { dup2(null, 1); close(null); }
  }
  Global.Add("exitRun", "(", new OneOperator1<long, long>(exitRun));
  Global.Add("clockSeconds", "(", new OneOperator0<double>(clockSeconds));
  Global.Add("processCount", "(", new OneOperator0<long>(processCount));
  Global.Add("processRank", "(", new OneOperator0<long>(processRank));
  Global.Add("processBarrier", "(", new OneOperator0<long>(processBarrier));
  Global.Add("launchedProcesses", "(", new OneOperator0<long>(launchedProcesses));
}

}  // namespace

LOADFUNC(init)
