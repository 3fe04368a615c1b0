#!/usr/bin/env python3
"""`make run`: every benchmark, one progress line each, then the results table
(printed and written to results/RESULTS.md)."""

import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchmarks import BENCHMARKS  # noqa: E402
from freefem import ROOT, read_summary, run_driver  # noqa: E402


def fmt(value, spec):
    return "-" if value is None else format(value, spec)


def main():
    rows, failed = [], []
    for index, (name, script, args) in enumerate(BENCHMARKS, 1):
        out_dir = os.path.join("results", name)
        print(f"[{index}/{len(BENCHMARKS)}] {name}: running {script} {' '.join(args)}", flush=True)
        code, output, seconds = run_driver(script, args, out_dir)
        summary = read_summary(out_dir)
        status = summary["ipopt_status"] if summary else "no summary"
        ok = code == 0 and summary is not None
        print(f"[{index}/{len(BENCHMARKS)}] {name}: {'ok' if ok else 'FAILED'} ({status}, {seconds:.1f} s)", flush=True)
        if not ok:
            failed.append(name)
            print("    " + "\n    ".join(output.strip().splitlines()[-5:]))
            continue
        for quantity, r in summary["results"].items():
            rows.append((name, quantity, r["computed"], r["reference"], r["rel_error"],
                         summary["ndof"], summary["ipopt_iterations"], summary["wall_time_s"]))

    header = ("benchmark", "quantity", "computed", "reference", "rel. error", "DOFs", "IPOPT it.", "time (s)")
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for b, q, c, r, e, n, it, t in rows:
        lines.append(f"| {b} | {q} | {fmt(c, '.10g')} | {fmt(r, '.10g')} | {fmt(e, '.2e')} | {n} | {it} | {t:.2f} |")
    table = "\n".join(lines)
    print()
    print(table)
    os.makedirs(os.path.join(ROOT, "results"), exist_ok=True)
    with open(os.path.join(ROOT, "results", "RESULTS.md"), "w") as f:
        f.write("# Results\n\n" + table + "\n")
    if failed:
        print(f"\nfailed: {', '.join(failed)}")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
