#!/usr/bin/env python3
"""`make run`: the benchmarks, one progress line as each starts and ends, then the results
table (printed and written to results/RESULTS.md).
    run_benchmarks.py               every benchmark in turn, then the table
    run_benchmarks.py --only NAME   one benchmark (the Makefile runs these in parallel)
    run_benchmarks.py --table       the table from the summaries already in results/
    run_benchmarks.py --names       the benchmark names, one line
    run_benchmarks.py --write-list FILE                       the benchmarks as a run list (scripts/run_list.py)
    run_benchmarks.py --list FILE [--index K] [--out DIR]     the list's runs (or its run K: a job array's
        task) each into DIR/<name> (results/ by default), then (without --index) their table
    run_benchmarks.py --table --list FILE [--out DIR]         the table of the list's runs in DIR"""

import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from benchmark_list import BENCHMARKS  # noqa: E402
from freefem import ROOT, read_summary, run_driver, run_ok, share_cores, summary_failure  # noqa: E402
import md_tables  # noqa: E402
import run_list  # noqa: E402
import verdicts  # noqa: E402


def fmt(value, spec):
    return "-" if value is None else format(value, spec)


def run_one(name, script, args, out_root="results", processes=1):
    """Runs one benchmark into <out_root>/<name> (on `processes` MPI processes); True when it ends
    with a summary and exit 0."""
    out_dir = os.path.join(out_root, name)
    print(f"{name}: started ({script} {' '.join(args)})", flush=True)
    code, output, seconds = run_driver(script, args, out_dir, processes=processes)
    with open(os.path.join(ROOT, out_dir, "output.log"), "w") as f:
        f.write(output)
    summary = read_summary(out_dir)
    status = summary["ipopt_status"] if summary else "no summary"
    ok = run_ok(code, summary)
    print(f"{name}: {'ok' if ok else 'FAILED'} ({status}, {seconds:.1f} s)", flush=True)
    if not ok:
        print("    " + "\n    ".join(output.strip().splitlines()[-5:]), flush=True)
    return ok


def table(names=None, out_root="results"):
    """The verdict table (scripts/verdicts.py) of the runs `names` (every benchmark by default) in
    out_root: every checked quantity with its reference, kind, tolerance and PASS/FAIL, written to
    <out_root>/RESULTS.md (the failing rows and the count printed); 1 if any fails or is missing."""
    rows, missing, failed = [], [], 0
    for name in names or [b[0] for b in BENCHMARKS]:
        summary = read_summary(os.path.join(out_root, name))
        if summary is None:
            missing.append(name)
            continue
        if summary_failure(summary):
            failed += 1
            rows.append((name, "run", "-", "-", "-", "-", "-", "FAIL: " + summary_failure(summary)))
        stored = stored_reference(name)
        for quantity, r in summary["results"].items():
            reference, error, tolerance, verdict = verdicts.verdict(name, quantity, r, stored)
            if verdict == "info":
                continue
            failed += verdict != "PASS"
            rows.append((name, quantity, fmt(r["computed"], ".10g"), fmt(reference, ".10g"),
                         verdicts.check(name, quantity).kind, tolerance, fmt(error, ".2e"), verdict))
    header = ("benchmark", "quantity", "computed", "reference", "reference kind", "tolerance", "error", "verdict")
    text = md_tables.table(header, rows)
    line = f"{len(rows) - failed} PASS, {failed} FAIL" + (f"; missing or failed runs: {', '.join(missing)}" if missing else "")
    # the terminal gets the failures and the count; the whole table is results/RESULTS.md (and the report)
    failing = [r for r in rows if r[-1] != "PASS"]
    if failing:
        print("\n" + md_tables.table(header, failing))
    print(f"\n{line}\nthe verdict table: {out_root}/RESULTS.md")
    md_tables.write(os.path.join(ROOT, out_root, "RESULTS.md"), "Results", text + "\n\n" + line)
    return 1 if missing or failed else 0


def stored_reference(name):
    """Mesh-converged references kept in benchmarks/reference/<name>.json."""
    path = os.path.join(ROOT, "benchmarks", "reference", name + ".json")
    return {q: v["value"] for q, v in json.load(open(path))["reference"].items()} if os.path.exists(path) else {}


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--names", action="store_true")
    parser.add_argument("--table", action="store_true")
    parser.add_argument("--only")
    parser.add_argument("--write-list")
    parser.add_argument("--list")
    parser.add_argument("--index", type=int)
    parser.add_argument("--out", default="results")
    args = parser.parse_args(argv)
    if args.names:
        print(" ".join(name for name, _, _ in BENCHMARKS))
        return 0
    if args.write_list:
        run_list.write(args.write_list, [{"name": n, "script": s, "args": a} for n, s, a in BENCHMARKS])
        return 0
    if args.list:
        runs, chosen = run_list.load(args.list, args.index)
        if args.table:
            return table([r["name"] for r in runs], args.out)
        ok = all([run_one(r["name"], r["script"], r.get("args", []), args.out, r.get("processes", 1)) for r in chosen])
        if args.index is not None:   # one task of a job array: the table once all have run (--table)
            return 0 if ok else 1
        return max(table([r["name"] for r in runs], args.out), 0 if ok else 1)
    if args.table:
        return table()
    if args.only:
        entry = [b for b in BENCHMARKS if b[0] == args.only]
        if not entry:
            print(f"error: no benchmark named {args.only}")
            return 2
        return 0 if run_one(*entry[0]) else 1
    ok = all([run_one(*b) for b in BENCHMARKS])
    return max(table(), 0 if ok else 1)


if __name__ == "__main__":
    share_cores()
    sys.exit(main(sys.argv[1:]))
