"""Run lists: the runs of the benchmark runner or of the sweep written to a file, so that a cluster's
job array (or GNU parallel over ssh) runs them one per task and each result lands in a folder of its
own (docs/scaling.md shows the one-liners).

A list is JSON Lines: one run per line, {"name": ..., "script": ..., "args": [...]} and whatever
else its program keeps there (the sweep: "size"; either: "processes", run under mpirun). A name is
the run's folder under the output folder: letters, digits, '_', '-' and '.', not starting with '-'
or '.'; a script is a driver of the suite (benchmarks/*.edp)."""

import json
import re
import sys

NAME = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.-]*$")


class ListError(Exception):
    """A list that cannot be used: the message names the file and line."""


def write(path, runs):
    with open(path, "w") as f:
        for run in runs:
            f.write(json.dumps(run) + "\n")


def read(path):
    """The runs of the list at path, each checked; ListError when one is unusable."""
    try:
        lines = open(path).read().splitlines()
    except OSError as e:
        raise ListError(f"cannot read run list {path}: {e.strerror}")
    runs, names = [], set()
    for number, line in enumerate(lines, 1):
        if not line.strip():
            continue
        where = f"run list {path}, line {number}"
        try:
            run = json.loads(line)
        except ValueError:
            raise ListError(f"{where}: not a JSON object")
        if not isinstance(run, dict):
            raise ListError(f"{where}: not a JSON object")
        name, script, args = run.get("name"), run.get("script"), run.get("args", [])
        if not isinstance(name, str) or not NAME.match(name):
            raise ListError(f"{where}: name must be letters, digits, '_', '-' or '.', not starting with '-' or '.'")
        if name in names:
            raise ListError(f"{where}: name {name} appears twice")
        if not isinstance(script, str) or not re.match(r"^benchmarks/[A-Za-z0-9_]+\.edp$", script):
            raise ListError(f"{where}: script must be a driver benchmarks/<name>.edp")
        if not isinstance(args, list) or not all(isinstance(a, str) for a in args):
            raise ListError(f"{where}: args must be a list of strings")
        processes = run.get("processes", 1)
        if not isinstance(processes, int) or isinstance(processes, bool) or not 1 <= processes <= 4096:
            raise ListError(f"{where}: processes must be an integer from 1 to 4096")
        names.add(name)
        runs.append(run)
    return runs


def load(path, index, required=()):
    """The runs of the list and those to run now (all, or the one at index), each with the keys
    `required` too; an unusable list is one error line and exit code 2."""
    try:
        runs = read(path)
        missing = [k for k in required if any(k not in run for run in runs)]
        if missing:
            raise ListError(f"run list {path}: every run needs {', '.join(missing)}")
        return runs, select(runs, index)
    except ListError as e:
        print(f"error: {e}")
        sys.exit(2)


def select(runs, index):
    """All the runs (index None) or the one at index (a job array's task number)."""
    if index is None:
        return runs
    if not 0 <= index < len(runs):
        raise ListError(f"--index {index} is not a run of the list (0 to {len(runs) - 1})")
    return [runs[index]]
