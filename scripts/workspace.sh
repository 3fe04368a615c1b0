#!/usr/bin/env bash
# `make workspace DIR=<folder>`: a folder of your own for your own problem, outside the suite. The
# folder is the argument, or DIR from the environment (make exports it, never pastes it into a
# command).
# Copies the template driver docs/template/my_problem.edp there (unless the folder has one) and
# writes <folder>/freefem++.pref, the one setting that lets FreeFem++, started in that folder,
# find the suite: its include/ folder, its plugins (plugin/*.so) and Debian's
# plugin folder (Debian's own /etc/freefem++.pref names one that does not exist). The same lines
# in ~/.freefem++.pref make the suite available in every folder.
set -euo pipefail
dir=${1:-${DIR:-}}
if [ -z "$dir" ]; then echo "error: give the folder: make workspace DIR=<folder>"; exit 2; fi
root=$(cd -- "$(dirname -- "$0")/.." && pwd)
mkdir -p -- "$dir"
[ -f "$dir/my_problem.edp" ] || cp -- "$root/docs/template/my_problem.edp" "$dir/"
cat > "$dir/freefem++.pref" <<PREF
loadpath += "/usr/lib/freefem++"
loadpath += "$root/plugin"
includepath += "$root/include"
load += "headless"
verbosity = 0
PREF
printf 'workspace %s: my_problem.edp and freefem++.pref (the suite: %s)\n' \
  "$(cd -- "$dir" && pwd)" "$root"
printf 'run it there: cd %q && FreeFem++ -nw my_problem.edp\n' "$dir"   # (quoted: safe to paste)
