#!/usr/bin/env python3
"""`make run`: the benchmarks, one progress line as each starts and ends, then the results
table (printed and written to results/RESULTS.md).
    run_benchmarks.py               every benchmark in turn, then the table
    run_benchmarks.py --only NAME   one benchmark (the Makefile runs these in parallel)
    run_benchmarks.py --table       the table from the summaries already in results/
    run_benchmarks.py --names       the benchmark names, one line"""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchmarks import BENCHMARKS  # noqa: E402
from freefem import ROOT, read_summary, run_driver  # noqa: E402
import markdown  # noqa: E402


def fmt(value, spec):
    return "-" if value is None else format(value, spec)


def run_one(name, script, args):
    """Runs one benchmark into results/<name>; True when it ends with a summary and exit 0."""
    out_dir = os.path.join("results", name)
    print(f"{name}: started ({script} {' '.join(args)})", flush=True)
    code, output, seconds = run_driver(script, args, out_dir)
    with open(os.path.join(ROOT, out_dir, "output.log"), "w") as f:
        f.write(output)
    summary = read_summary(out_dir)
    status = summary["ipopt_status"] if summary else "no summary"
    ok = code == 0 and summary is not None
    print(f"{name}: {'ok' if ok else 'FAILED'} ({status}, {seconds:.1f} s)", flush=True)
    if not ok:
        print("    " + "\n    ".join(output.strip().splitlines()[-5:]), flush=True)
    return ok


def table():
    rows, missing = [], []
    for name, _, _ in BENCHMARKS:
        summary = read_summary(os.path.join("results", name))
        if summary is None:
            missing.append(name)
            continue
        for quantity, r in summary["results"].items():
            rows.append((name, quantity, r["computed"], r["reference"], r["rel_error"],
                         summary["ndof"], summary["ipopt_iterations"], summary["wall_time_s"]))
    header = ("benchmark", "quantity", "computed", "reference", "rel. error", "DOFs", "IPOPT it.", "time (s)")
    text = markdown.table(header, [(b, q, fmt(c, ".10g"), fmt(r, ".10g"), fmt(e, ".2e"), n, it, f"{t:.2f}")
                                   for b, q, c, r, e, n, it, t in rows])
    print("\n" + text)
    markdown.write(os.path.join(ROOT, "results", "RESULTS.md"), "Results", text)
    if missing:
        print(f"\nmissing or failed: {', '.join(missing)}")
    return 1 if missing else 0


def main(argv):
    if argv[:1] == ["--names"]:
        print(" ".join(name for name, _, _ in BENCHMARKS))
        return 0
    if argv[:1] == ["--table"]:
        return table()
    if argv[:1] == ["--only"]:
        entry = [b for b in BENCHMARKS if b[0] == argv[1]]
        if not entry:
            print(f"error: no benchmark named {argv[1]}")
            return 2
        return 0 if run_one(*entry[0]) else 1
    ok = all([run_one(*b) for b in BENCHMARKS])
    return max(table(), 0 if ok else 1)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
