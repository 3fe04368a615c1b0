#!/usr/bin/env python3
"""Names a driver declares that hide another: FreeFEM's own (a built-in function, keyword or global,
as `dumptable` lists them with the suite's plugins loaded) or the suite's (docs/reserved_names.md).
A driver shares one namespace with both, and a clash shows up, if at all, as an error inside an
include file (`int floor` at the top of a driver made FreeFEM's floor() an int, and the error named
line 335 of a solver file). Prints one `warning:` line per clash, naming the driver's line; exit 1
when there is one, 2 when the file cannot be read, else 0.
    make check-driver F=my_problem.edp
    scripts/check_driver.py benchmarks/hertz_plane.edp"""

import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import reserved_names  # noqa: E402

ROOT = reserved_names.ROOT
# a declaration as the drivers write them: a type (with [int] or [string] index types), then names
TYPE = r"(?:real|int|bool|string|complex|matrix|mesh|mesh3|meshS|meshL|ifstream|ofstream|border|func\s+\w+(?:\[int\])?|fespace|macro|varf|problem|solve|Vh\w*)"
DECLARED = re.compile(r"^\s*(" + TYPE + r")(?:\[[^\]]*\])*\s+(.*)")


def freefem_names():
    """FreeFEM's keywords and global identifiers with the suite's plugins loaded (dumptable)."""
    plugins = set()
    for folder, _, files in os.walk(os.path.join(ROOT, "include")):
        for name in files:
            if name.endswith(".idp"):
                plugins.update(re.findall(r'^\s*load\s+"([^"]+)"', open(os.path.join(folder, name)).read(), re.M))
    with tempfile.TemporaryDirectory() as work:
        script = os.path.join(work, "names.edp")
        with open(script, "w") as f:
            f.write("".join(f'load "{p}"\n' for p in sorted(plugins)) + "dumptable(cout);\n")
        proc = subprocess.run(["FreeFem++", "-nw", script], cwd=ROOT, stdout=subprocess.PIPE,
                              stderr=subprocess.STDOUT, text=True, timeout=120)
    text = proc.stdout
    keywords = text.split(" the keywords", 1)[-1].split(" the types", 1)[0]
    names = set(re.findall(r"^\s{6}(\w+) \d+ ", keywords, re.M))
    names |= set(re.findall(r"^  - (\w+),", text, re.M))
    return names


def declarations(path):
    """(line number, name, at the top level) for every name the driver declares."""
    found = []
    depth = 0
    for number, line in enumerate(open(path, encoding="utf-8", errors="replace"), 1):
        code = line.split("//", 1)[0]
        m = DECLARED.match(code)
        if m:
            kind, rest = m.group(1), m.group(2)
            if kind.startswith(("func", "macro", "fespace", "varf", "problem", "solve")):
                name = re.match(r"(\w+)", rest)
                parts = [name.group(1)] if name else []
            else:
                parts = [m.group(1) for m in (re.match(r"\s*(?:vectorField\()?(\w+)", p)
                                              for p in reserved_names.split_top(rest.rstrip("; \n"))) if m]
            for name in parts:
                found.append((number, name, depth == 0))
        if not code.lstrip().startswith("macro"):
            depth += code.count("{") - code.count("}")
    return found


def main(argv):
    if len(argv) != 1:
        print("usage: scripts/check_driver.py <driver.edp>", file=sys.stderr)
        return 2
    path = argv[0]
    if not os.path.isfile(path):
        print(f"error: the driver {path!r} is not a readable file")
        return 2
    builtin = freefem_names()
    suite = reserved_names.reserved()
    clashes = 0
    for number, name, top in declarations(path):
        where = "" if top else " (inside a block: the suite's macros used there see it)"
        if name in suite:
            print(f"warning: {path}:{number}: '{name}' hides the suite's {name} (include/{suite[name]}){where}")
            clashes += 1
        elif name in builtin:
            print(f"warning: {path}:{number}: '{name}' hides FreeFEM's built-in {name}{where}")
            clashes += 1
    if clashes == 0:
        print(f"{path}: no name hides FreeFEM's or the suite's")
    return 1 if clashes else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
