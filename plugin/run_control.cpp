// run_control: how a run ends and how long it took, for include/core/errors.idp and output.idp.
//   exitRun(code): ends the process at once with `code`, from anywhere, including inside an IPOPT
//     callback. FreeFEM's exit() throws an exception that IPOPT catches inside its callbacks (the run
//     goes on) and that prints FreeFEM's call stack; the suite's error rule is one line and a
//     documented exit code.
//   clockSeconds(): wall-clock seconds with microseconds (FreeFEM's time() counts whole seconds).
#include "ff++.hpp"
#include <cstdio>
#include <sys/time.h>
#include <unistd.h>

namespace {

long exitRun(long code) {
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

void init() {
  Global.Add("exitRun", "(", new OneOperator1<long, long>(exitRun));
  Global.Add("clockSeconds", "(", new OneOperator0<double>(clockSeconds));
}

}  // namespace

LOADFUNC(init)
