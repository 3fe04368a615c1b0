"""Running a FreeFem++ driver from the repository root and reading its summary."""

import json
import os
import subprocess
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


# an MPI run, as docs/scaling.md shows it: mpirun with FreeFem++-mpi (FreeFEM's ff-mpirun splices its
# arguments into a shell command with eval); --allow-run-as-root for the root of a fresh machine,
# --oversubscribe for more processes than cores
MPIRUN = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np"]


def share_cores():
    """Runs side by side (make's -j JOBS, pytest's -n workers) share the cores (called by the tests
    and the main job's runner; the timing scripts set their threads themselves): each FreeFEM's BLAS
    and MUMPS threads get cores / runs of them, unless the caller set OMP_NUM_THREADS. Left at their
    default, two runs' threads spun against each other: make test took 1,066 s with 13 of its 33
    CPU-minutes in the kernel (indentation.edp alone: 6.5 s of system time on 2 threads, 1.3 s on
    one, the same wall time)."""
    runs = os.environ.get("PYTEST_XDIST_WORKER_COUNT") or os.environ.get("JOBS") or "1"
    threads = max(1, (os.cpu_count() or 1) // max(1, int(runs) if runs.isdigit() else 1))
    for name in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS"):
        os.environ.setdefault(name, str(threads))


def run_driver(script, args, out_dir, timeout=1800, cwd=ROOT, processes=1):
    """Run `FreeFem++ script args [-out out_dir]` (with processes > 1: `mpirun -np processes
    FreeFem++-mpi ...`); return (exit code, output, seconds)."""
    program = ["FreeFem++"] if processes == 1 else MPIRUN + [str(processes), "FreeFem++-mpi"]
    command = program + ["-nw", script] + list(args) + (["-out", out_dir] if out_dir else [])
    start = time.time()
    proc = subprocess.run(command, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          text=True, timeout=timeout)
    return proc.returncode, proc.stdout, time.time() - start


def summary_failure(summary):
    """Why a run's summary says it did not succeed ("" when it did): a failed solve (incomplete) or a
    completed run whose own checks failed (checks_failed, exit code 4)."""
    if summary is None:
        return "no summary"
    if not summary.get("complete", False):
        return summary.get("failure") or "incomplete"
    if summary.get("checks_failed"):
        return "checks failed: " + ", ".join(summary["checks_failed"])
    return ""


def run_ok(code, summary):
    """A benchmark run succeeded: exit code 0 (never 3, a failed solve, or 4, failed checks) and a
    summary that says so."""
    return code == 0 and summary_failure(summary) == ""


def read_summary(out_dir):
    path = os.path.join(out_dir if os.path.isabs(out_dir) else os.path.join(ROOT, out_dir), "summary.json")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return json.load(f)
