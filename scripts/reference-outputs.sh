#!/usr/bin/env bash
# Writes every output that a refactoring must leave byte-identical, with one vbi binary, into one
# directory; compare two such directories with `diff -r`.
#
#   scripts/reference-outputs.sh target/release/vbi /tmp/before      # on the old build
#   scripts/reference-outputs.sh target/release/vbi /tmp/after       # on the new build
#   diff -r /tmp/before /tmp/after && echo byte-identical
#
# What it writes: the JSON summary and the CSV files of `vbi run` on the built-in scenario and on
# every example scenario; `measure.json` and the CSV files of `vbi measure` on every example
# measurement (each file alone; the input paths it records made relative); the tables of the built-in quick study and of the paper's full study
# (figures off: the figures are drawn from the same tables). Timings and the study manifest are
# left out: they are not results. Set VBI_SKIP_PAPER=1 to leave out the paper study (about a
# minute on 2 cores).
set -euo pipefail
if [ $# -ne 2 ]; then
  echo "usage: $0 VBI_BINARY OUT_DIR" >&2
  exit 2
fi
vbi=$(realpath "$1")
out=$2
root=$(cd "$(dirname "$0")/.." && pwd)
rm -rf "$out"
mkdir -p "$out/run" "$out/study"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

run_one() { # name, scenario file or empty for the built-in one
  local name=$1 file=${2:-}
  "$vbi" run ${file:+"$file"} --format json --out "$work/$name" > "$out/run/$name.json"
  for f in "$work/$name"/*.csv "$work/$name"/summary.json; do
    cp "$f" "$out/run/$name.$(basename "$f")"
  done
}

run_one built-in
for file in "$root"/examples/scenarios/*.toml; do
  run_one "$(basename "$file" .toml)" "$file"
done

measure_one() { # measurement file
  local file=$1 name
  name=$(realpath --relative-to="$root/examples/measurements" "$file" | tr / _)
  name=${name%.toml}
  # A file that is only another's crawl run is refused alone: its message is the output.
  { "$vbi" measure "$file" --out "$work/measure-$name" 2>&1 || echo "exit $?"; } \
    | sed "s#$work/##g; s#$root/##g" > "$out/measure/$name.txt"
  [ -f "$work/measure-$name/measure.json" ] || return 0
  sed "s#$root/##g" "$work/measure-$name/measure.json" > "$out/measure/$name.measure.json"
  for f in "$work/measure-$name"/*.csv; do
    [ -e "$f" ] && cp "$f" "$out/measure/$name.$(basename "$f")"
  done
}

mkdir -p "$out/measure"
shopt -s nullglob
for file in "$root"/examples/measurements/*.toml "$root"/examples/measurements/*/*.toml; do
  case $file in *_scenario.toml) continue ;; esac
  measure_one "$file"
done

study_one() { # name, study file or empty for the built-in one
  local name=$1 file=${2:-}
  "$vbi" study ${file:+"$file"} --out "$work/study-$name" --no-figures > /dev/null 2>&1
  mkdir -p "$out/study/$name"
  cp "$work/study-$name"/*.csv "$out/study/$name/"
}

study_one quick
if [ "${VBI_SKIP_PAPER:-0}" != 1 ]; then
  study_one paper "$root/examples/studies/paper.toml"
fi
echo "wrote $out"
