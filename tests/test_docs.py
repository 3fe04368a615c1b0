"""The documentation against the suite: the numbers the pages mark are recomputed, every relative link
points to a file, and the README stays short.

A key number in README.md or docs/**/*.md is followed by a marker naming the run that gives it:
    0.0340725<!-- check: benchmarks/cube.edp -material mooney -> w -->
The test runs `FreeFem++ -nw benchmarks/cube.edp -material mooney -out <tmp>` once per distinct
command, and compares the number as written with summary.json: `w` is results.w.computed,
`w.reference` and `w.rel_error` pick those fields, and a name that is not a result (`ndof`) is a
top-level key. The number must match to the precision written: half a unit of its last digit
(0.0340725: 5e-8; 1.2e-05: 5e-7; 18565: 0.5). Markers go on results of runs that take a few seconds."""

import glob
import shlex

import pytest

from helpers import *  # noqa: F401,F403 (check, out, run_driver, read_summary, ROOT, TMP and the shared helpers)

MARKER = re.compile(r"<!-- check:(.*?)-->")
NUMBER_MARKER = re.compile(r"(-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?)<!-- check: (\S.*?) -> (\S+) -->")
LINK = re.compile(r"\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
README_MAX_LINES = 200


def doc_files():
    return [os.path.join(ROOT, "README.md")] + sorted(glob.glob(os.path.join(ROOT, "docs", "**", "*.md"), recursive=True))


def rel(path):
    return os.path.relpath(path, ROOT)


def markers():
    """(file, line, number as written, command, quantity) for every marker; malformed ones as None.
    A marker quoted as code (in a fenced block or between backticks) only shows the syntax."""
    found = []
    for path in doc_files():
        fenced = False
        for number, line in enumerate(open(path).read().splitlines(), 1):
            if line.lstrip().startswith("```"):
                fenced = not fenced
            if fenced:
                continue
            line = re.sub(r"`[^`]*`", "", line)
            complete = {m.end(): m for m in NUMBER_MARKER.finditer(line)}
            for m in MARKER.finditer(line):
                good = complete.get(m.end())
                if good:
                    found.append((rel(path), number, good.group(1), good.group(2).strip(), good.group(3)))
                else:
                    found.append((rel(path), number, None, m.group(0), None))
    return found


def half_unit(written):
    """Half a unit of the last digit written: '0.0340725' -> 5e-8, '1.2e-05' -> 5e-7, '18565' -> 0.5."""
    mantissa, _, exponent = written.lower().partition("e")
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    return 0.5 * 10.0 ** (int(exponent or 0) - decimals)


def quantity(summary, name):
    results = summary.get("results", {})
    if name in results:
        return results[name]["computed"]
    head, _, field = name.rpartition(".")
    if head in results and field in ("computed", "reference", "rel_error"):
        return results[head][field]
    return summary.get(name)


@pytest.mark.heavy(seconds=39)
def test_docs_numbers():
    """Every marked number in the docs is what its command computes today, to the precision written."""
    found = markers()
    check(f"docs: markers found ({len(found)})", len(found) >= 12, f"{len(found)}")
    runs = {}
    for path, line, written, command, name in found:
        where = f"{path}:{line}"
        if written is None:
            check(f"{where}: well-formed marker", False, f"{command}: expected <number><!-- check: <driver> [args] -> <quantity> -->")
            continue
        if command not in runs:
            words = shlex.split(command)
            label = "docs " + re.sub(r"\W+", "_", command)
            code, output, _ = run_driver(words[0], words[1:], out(label))
            runs[command] = read_summary(out(label)) if code == 0 else None
            check(f"docs: `{command}` runs (exit 0)", code == 0, f"exit {code}: {output.strip().splitlines()[-2:]}")
        summary = runs[command]
        if summary is None:
            check(f"{where}: {written} ({command} -> {name})", False, "the run failed")
            continue
        value = quantity(summary, name)
        ok = isinstance(value, (int, float)) and abs(float(written) - value) <= half_unit(written) * (1 + 1e-9)
        check(f"{where}: {written} = {command} -> {name}", ok, f"computed {value!r}, written {written} (+-{half_unit(written):.1g})")


def strip_code(text):
    """The text without fenced code blocks and inline code, where brackets are not links."""
    text = re.sub(r"^```.*?^```", "", text, flags=re.S | re.M)
    return re.sub(r"`[^`\n]*`", "", text)


def test_docs_links():
    """Every relative link of README.md and docs/**/*.md points to a file or folder of the repository
    (anchors are not checked; web addresses are not followed)."""
    count = 0
    for path in doc_files():
        for target in LINK.findall(strip_code(open(path).read())):
            if re.match(r"[a-z][a-z0-9+.-]*:", target) or target.startswith("#"):
                continue
            count += 1
            file = os.path.normpath(os.path.join(os.path.dirname(path), target.split("#")[0]))
            check(f"{rel(path)}: link {target}", os.path.exists(file), rel(file))
    check(f"docs: relative links found ({count})", count > 0)


def test_docs_readme_length():
    """The README leads and the manual is in docs/: at most 200 lines."""
    lines = len(open(os.path.join(ROOT, "README.md")).read().splitlines())
    check(f"README.md has at most {README_MAX_LINES} lines", lines <= README_MAX_LINES, f"{lines} lines")


def test_docs_statuses():
    """Every status a step can record (IPOPT's names as include/solve/ipopt_problem.idp spells them,
    the suite's own, plain Newton's) is listed in docs/robustness.md's table of statuses, and the
    table names no status the code cannot produce."""
    code = "".join(open(os.path.join(ROOT, "include", "solve", f)).read() for f in ("ipopt_problem.idp", "newton.idp"))
    names = set(re.findall(r'return "([A-Z][A-Za-z_]+)(?:\(|")', code)) | set(re.findall(r'"(Newton_[A-Za-z_]+)"', code))
    names.discard("Internal_Error")
    page = open(os.path.join(ROOT, "docs", "robustness.md")).read()
    table = page.split("## Solver statuses", 1)[-1].split("\n## ", 1)[0]
    listed = set(re.findall(r"`([A-Z][A-Za-z_]+)(?:\(<why>\))?`", table.split("| try |", 1)[-1]))
    check("statuses: the code's names found (IPOPT's 19, the suite's, Newton's)", len(names) >= 28, str(sorted(names)))
    for name in sorted(names):
        check(f"statuses: {name} in docs/robustness.md's table", name in listed)
    for name in sorted(listed - names):
        check(f"statuses: the table's {name} is one the code produces", False)
