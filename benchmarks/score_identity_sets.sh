#!/bin/sh
# svgtile score's text and --json, before and after a change, on textures of the bundled
# exemplars and of imported map-pattern tiles (FGDC 601, OSM scrub and orchard), each scored in
# a fresh `python -m svgtile score` process (the command line's own path, its early exit and
# its worker included) with --jobs 1 and --jobs 2 (score11d, issue 11).
#
#   sh benchmarks/score_identity_sets.sh BEFORE_PKG_DIR AFTER_PKG_DIR
#
# Each *_PKG_DIR is `git archive COMMIT svgtile exemplars | tar -x` of the commit to run (run in
# that directory: `python -m` puts the working directory first on sys.path).  The exemplars are
# imported and the textures synthesized once, with BEFORE; `diff -r` of the two output folders
# is the verdict (exit status 0: identical).  Needs ../shared/data beside the repository.
set -e
ROOT=$(pwd)
PY=${PY:-$ROOT/.venv/bin/python}
DATA=${DATA:-$ROOT/../shared/data}
OUT=${TMPDIR:-/tmp}/svgtile-score-identity-sets
rm -rf "$OUT"; mkdir -p "$OUT/ex" "$OUT/tex"
cd "$1"
"$PY" -m svgtile import "$DATA/fgdc-geologic-patterns/lithology/601.svg" -o "$OUT/ex/fgdc601.svg"
"$PY" -m svgtile import "$DATA/osm-carto/generating_patterns/scrub.svg" -o "$OUT/ex/osmscrub.svg"
"$PY" -m svgtile import "$DATA/osm-carto/patterns/orchard.svg" -o "$OUT/ex/osmorchard.svg"
cp exemplars/marsh.svg exemplars/gravel.svg exemplars/till.svg "$OUT/ex/"
synth() { "$PY" -m svgtile synth "$OUT/ex/$1.svg" -o "$OUT/tex/$2.svg" --size "$3" --seed "$4" --force ${5:+--engine $5}; }
synth marsh marsh 400x400 2
synth fgdc601 fgdc601 600x600 2
synth osmscrub osmscrub 600x600 2
synth osmorchard osmorchard 600x600 2
synth till till 500x500 2
synth till till-random 500x500 2 random
synth gravel gravel-tile 500x300 2 tile
synth marsh marsh-big 2500x2500 1
synth gravel gravel-big 3000x3000 1
score_all() {  # PKG_DIR OUT_SUBDIR
  mkdir -p "$OUT/$2"; cd "$1"
  for t in "$OUT"/tex/*.svg; do
    n=$(basename "$t" .svg); e=${n%%-*}
    for j in 1 2; do
      "$PY" -m svgtile score "$OUT/ex/$e.svg" "$t" --jobs $j > "$OUT/$2/$n-j$j.txt"
      "$PY" -m svgtile score "$OUT/ex/$e.svg" "$t" --jobs $j --json > "$OUT/$2/$n-j$j.json"
    done
  done
}
score_all "$1" before
score_all "$2" after
diff -r "$OUT/before" "$OUT/after" && echo "identical: $(ls "$OUT/after" | wc -l) outputs"
