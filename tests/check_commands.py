#!/usr/bin/env python3
"""Which external programs the suite calls, and whether each is provided: by
scripts/install_deps.sh (its `need COMMAND PACKAGE` lines) or by every Debian system (the
Essential and required packages a minimal debootstrap root has). Scans the Makefile's recipes,
the shell and Python scripts' subprocess calls and the FreeFEM files' exec() strings.
    python3 tests/check_commands.py   prints each program with where it is used"""

import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
# coreutils, bash, grep, sed, mawk, findutils, mount (mount, umount): Essential or required in Debian
# (minbase has them)
BASE = {"sh", "bash", "cd", "test", "[", "echo", "cat", "rm", "mv", "mkdir", "touch", "cp", "sort", "date", "sleep",
        "printf", "true", "false", "exit", "env", "dirname", "ls", "grep", "sed", "tail", "head", "set", "command",
        "mapfile", "id", "export", "for", "do", "done", "if", "then", "fi", "return", "pwd", "dpkg", "apt-get", "make",
        "sudo", "mount", "umount", "stat"}
SHELL_SPLIT = re.compile(r"&&|\|\||;|\|")


def provided():
    text = open(os.path.join(ROOT, "scripts", "install_deps.sh")).read()
    return set(re.findall(r"^need (\S+) \S+", text, re.M)) | BASE


def shell_commands(fragment):
    """First words of each command of a shell fragment."""
    words = []
    for piece in SHELL_SPLIT.split(fragment):
        tokens = piece.strip().lstrip("@").split()
        while tokens and "=" in tokens[0] and not tokens[0].startswith("-"):   # VAR=value prefixes
            tokens = tokens[1:]
        if tokens and not tokens[0].startswith("$") and not tokens[0].startswith("-"):
            words.append(tokens[0].strip("'\"{}()"))
    return [w for w in words if w]


def used():
    """{program: [file, ...]}"""
    found = {}

    def add(program, where):
        found.setdefault(program, set()).add(os.path.relpath(where, ROOT))
    with open(os.path.join(ROOT, "Makefile")) as f:
        for line in f:
            if line.startswith("\t"):
                for w in shell_commands(line):
                    add(w, f.name)
    for folder in ("scripts", "tests", "bench", ".ci"):
        for dirpath, _, files in os.walk(os.path.join(ROOT, folder)):
            for name in files:
                path = os.path.join(dirpath, name)
                text = open(path, errors="replace").read()
                if name.endswith(".py"):
                    for m in re.finditer(r"(?:subprocess\.\w+|Popen|command\s*=)\s*\(?\s*\[\s*\"([^\"]+)\"", text):
                        add(m.group(1), path)
                elif name.endswith(".sh") or name == "run":
                    functions = set(re.findall(r"^(\w+)\(\)", text, re.M))
                    heredoc = None
                    for line in text.splitlines():
                        stripped = line.strip()
                        if heredoc:
                            heredoc = None if stripped == heredoc else heredoc
                            continue
                        m = re.search(r"<<-?'?(\w+)'?", line)
                        if m:
                            heredoc = m.group(1)
                        if not stripped or stripped.startswith("#") or re.match(r"^\w+=", stripped):
                            continue
                        for w in shell_commands(line):
                            if w not in functions and re.fullmatch(r"[\w+./-]+", w):
                                add(w, path)
    for folder in ("include", "benchmarks", "bench", "tests", "docs"):
        for dirpath, _, files in os.walk(os.path.join(ROOT, folder)):
            for name in files:
                if name.endswith((".idp", ".edp")):
                    path = os.path.join(dirpath, name)
                    for m in re.finditer(r"(?:exec\(|command = )\"([^\"]*)\"", open(path).read()):
                        for w in shell_commands(m.group(1)):
                            add(w, path)
    return found


def unprovided():
    """([(program, files)] not provided, {program: files})"""
    found, have = used(), provided()
    return [(p, sorted(w)) for p, w in sorted(found.items()) if p not in have], found


if __name__ == "__main__":
    missing, found = unprovided()
    for program, where in sorted(found.items()):
        print(f"{program:20s} {'ok' if (program, sorted(where)) not in missing else 'NOT PROVIDED'}  {', '.join(sorted(where))}")
    sys.exit(1 if missing else 0)
