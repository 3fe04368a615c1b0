// run_control: how a run ends and how long it took, for include/core/errors.idp and output.idp.
//   exitRun(code): ends the process at once with `code`, from anywhere, including inside an IPOPT
//     callback. FreeFEM's exit() throws an exception that IPOPT catches inside its callbacks (the run
//     goes on) and that prints FreeFEM's call stack; the suite's error rule is one line and a
//     documented exit code.
//   clockSeconds(): wall-clock seconds with microseconds (FreeFEM's time() counts whole seconds).
//   peakMemoryMiB(): this process's largest resident memory so far (getrusage's ru_maxrss), MiB.
//   pageFaults(): this process's minor page faults so far (getrusage's ru_minflt): summary.json's
//     timings, and tests/allocator_check.edp's measure of the allocator below.
//   processCount(), processRank(): the run's MPI processes and this one's rank (1 and 0 under
//     FreeFem++; FreeFEM's own mpirank and mpisize are names only FreeFem++-mpi's scripts know).
//   processBarrier(): every process waits for the others (nothing under FreeFem++).
//   Under FreeFem++-mpi every process runs the whole script (include/core/output.idp): the standard
//   output of all but process 0 goes to /dev/null from the moment this plugin loads, so that each
//   progress and error line is printed once (their standard error stays: a crash still shows).
//   launchedProcesses(): the processes mpirun (OpenMPI's OMPI_COMM_WORLD_SIZE) or a PMI launcher
//     (PMI_SIZE) started, 1 without one: FreeFem++ started N times by mpirun sees N here and 1 in
//     processCount() (include/core/run.idp refuses it).
//   The allocator: from the moment this plugin loads, glibc's malloc serves every block from its
//     heap and keeps what is freed for the next (mallopt: M_MMAP_MAX 0, M_TRIM_THRESHOLD -1). By
//     default a block above the mmap threshold (128 KB, rising to at most 32 MB) is a fresh
//     mapping, its pages zeroed and faulted in at first touch and unmapped when freed: every
//     factorization's factors and workspace, every tangent's arrays. The 3D indentation at 200k
//     dofs (issue 43): a factorization 15.1 s -> 12.0 s on average, the run 339.7 s -> 307.3 s,
//     the same peak memory (5.25 GB); at R/16 160k page faults -> 68k.
//   The standard output, from the moment this plugin loads, is line-buffered: each progress line
//     reaches a file or a pipe (`| tee`) as it is printed. FreeFEM's endl does not flush, and
//     stdio buffers a file's or a pipe's output by blocks: a 200k dofs run's step lines showed
//     minutes late, several at once.
//   holdOutput(), releaseOutput(): the standard output between the two goes to an anonymous file
//     in memory and is then printed without IPOPT's line 'Using option file "<path>".' and its
//     blank lines. IPOPT prints it for any options file not named ipopt.opt, before it reads the
//     file's print_level (IpoptApplication::Initialize), and ff-Ipopt passes the file only by that
//     name (include/solve/ipopt_problem.idp). exitRun releases held output first: an error line
//     printed inside an IPOPT callback is not lost.
#include "ff++.hpp"
#include "mpi_bridge.hpp"
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <malloc.h>
#include <sys/mman.h>
#include <string>
#include <sys/resource.h>
#include <sys/time.h>
#include <unistd.h>

namespace {

FILE *heldOutput = 0;   // where the standard output goes while held
int savedOutput = -1;   // the standard output's own descriptor meanwhile

long holdOutput() {
  if (heldOutput) return 0;
  cout.flush();
  fflush(stdout);
  // in memory (memfd), not in /tmp: a full disk there must not swallow an error line
  int memory = memfd_create("held-output", MFD_CLOEXEC);
  heldOutput = (memory >= 0) ? fdopen(memory, "w+") : 0;
  if (!heldOutput) {   // nothing held: the line is printed, nothing else changes
    if (memory >= 0) close(memory);
    return 0;
  }
  savedOutput = dup(1);
  if (savedOutput < 0 || dup2(fileno(heldOutput), 1) < 0) {
    if (savedOutput >= 0) close(savedOutput);
    fclose(heldOutput);
    heldOutput = 0;
    savedOutput = -1;
  }
  return 0;
}

bool isOptionFileLine(const std::string &line) {
  const char *head = "Using option file \"";
  return line.compare(0, strlen(head), head) == 0 && line.size() >= 2
         && line.compare(line.size() - 2, 2, "\".") == 0;
}

long releaseOutput() {
  if (!heldOutput) return 0;
  cout.flush();
  fflush(stdout);
  if (dup2(savedOutput, 1) < 0) {   // the standard output cannot be given back: keep the hold's
    close(savedOutput);
    savedOutput = -1;
    fclose(heldOutput);
    heldOutput = 0;
    return 0;
  }
  close(savedOutput);
  savedOutput = -1;
  std::string text;
  char buffer[65536];
  rewind(heldOutput);
  for (size_t n; (n = fread(buffer, 1, sizeof buffer, heldOutput)) > 0;) text.append(buffer, n);
  fclose(heldOutput);
  heldOutput = 0;
  // the lines, each with its end; IPOPT's is "\nUsing option file \"...\".\n\n"
  std::string kept;
  size_t start = 0;
  bool dropBlank = false;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    end = (end == std::string::npos) ? text.size() : end + 1;
    std::string line = text.substr(start, end - start);
    std::string bare = line.substr(0, line.find('\n'));
    start = end;
    if (isOptionFileLine(bare)) {
      if (kept.size() >= 2 && kept.compare(kept.size() - 2, 2, "\n\n") == 0) kept.pop_back();
      else if (kept == "\n") kept.clear();
      dropBlank = true;
      continue;
    }
    if (dropBlank && bare.empty()) { dropBlank = false; continue; }
    dropBlank = false;
    kept += line;
  }
  if (!kept.empty()) {
    fwrite(kept.data(), 1, kept.size(), stdout);
    fflush(stdout);
  }
  return 0;
}

long exitRun(long code) {
  // under MPI every process fails at the same point: the others leave it to process 0 to print its
  // error line and end the job (mpirun stops all at the first failed exit, and stopped process 0's
  // last lines unprinted when another process was first). They wait for mpirun to stop them, not a
  // fixed while that a loaded machine could outlast, and end by themselves after a minute only if
  // process 0 went on (a failure of theirs alone)
  releaseOutput();
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

double peakMemoryMiB() {
  rusage usage;
  if (getrusage(RUSAGE_SELF, &usage) != 0) return -1;
  return usage.ru_maxrss/1024.;   // (kilobytes on Linux)
}

double pageFaults() {
  rusage usage;
  if (getrusage(RUSAGE_SELF, &usage) != 0) return -1;
  return double(usage.ru_minflt);
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
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, -1);   // (-1: the largest size_t, never trim)
  fflush(stdout);
  setvbuf(stdout, nullptr, _IOLBF, 0);
  mpiBridge();   // under MPI, opened now: a missing bridge is one error line before any work
  if (mpisize > 1 && mpirank > 0) {
    int null = open("/dev/null", O_WRONLY);
    fflush(stdout);
    if (null >= 0) { dup2(null, 1); close(null); }
  }
  Global.Add("exitRun", "(", new OneOperator1<long, long>(exitRun));
  Global.Add("clockSeconds", "(", new OneOperator0<double>(clockSeconds));
  Global.Add("peakMemoryMiB", "(", new OneOperator0<double>(peakMemoryMiB));
  Global.Add("pageFaults", "(", new OneOperator0<double>(pageFaults));
  Global.Add("processCount", "(", new OneOperator0<long>(processCount));
  Global.Add("processRank", "(", new OneOperator0<long>(processRank));
  Global.Add("processBarrier", "(", new OneOperator0<long>(processBarrier));
  Global.Add("launchedProcesses", "(", new OneOperator0<long>(launchedProcesses));
  Global.Add("holdOutput", "(", new OneOperator0<long>(holdOutput));
  Global.Add("releaseOutput", "(", new OneOperator0<long>(releaseOutput));
}

}  // namespace

LOADFUNC(init)
