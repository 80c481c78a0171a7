#!/bin/sh
# svgtile score against svgtile synth on one large texture, alternated in one shell (issue 11).
#
#   sh benchmarks/score_vs_synth.sh [ROUNDS] [BASE_PKG_DIR]
#
# Each round: synth the 3000×3000 gravel texture (177,723 <use>), then score it; with
# BASE_PKG_DIR (a `git archive` of another commit, unpacked) also score it with that package,
# so before and after meet the same load (run in BASE_PKG_DIR: `python -m` puts the working
# directory before PYTHONPATH on sys.path, so run from the repository root it would import the
# repository's svgtile whatever PYTHONPATH says).  Prints one Markdown row per command: wall, CPU
# (user + sys), peak RSS, and the 1-minute load average when it started.  Run from the
# repository root with the venv's python on PATH or as PY.  SCORE_ARGS is added to the score
# command (not the base's), e.g. SCORE_ARGS="--jobs 2": by default score uses a second process
# only where the load average leaves a core idle.  BASE_ARGS is added to the base's score command.
set -e
ROUNDS=${1:-3}
BASE=$2
PY=${PY:-$(pwd)/.venv/bin/python}
OUT=${TMPDIR:-/tmp}/svgtile-score-bench
mkdir -p "$OUT"
row() {  # label, command…
  label=$1; shift
  load=$(cut -d' ' -f1 /proc/loadavg)
  /usr/bin/time -f "%e %U %S %M" -o "$OUT/time" "$@" > "$OUT/stdout"
  set -- $(cat "$OUT/time")
  echo "| $label | $load | $1 s | $(echo "$2 + $3" | bc) s ($2 + $3) | $(($4 / 1024)) |"
}
echo "| command | load | wall | CPU (user + sys) | peak MiB |"
echo "|---|---:|---:|---:|---:|"
for r in $(seq "$ROUNDS"); do
  row "synth, round $r" "$PY" -m svgtile synth exemplars/gravel.svg -o "$OUT/big.svg" --size 3000x3000 --seed 1 --force
  if [ -n "$BASE" ]; then
    row "score (base)${BASE_ARGS:+ $BASE_ARGS}, round $r" env -C "$BASE" PYTHONPATH="$BASE" "$PY" -m svgtile score exemplars/gravel.svg "$OUT/big.svg" $BASE_ARGS
  fi
  row "score${SCORE_ARGS:+ $SCORE_ARGS}, round $r" "$PY" -m svgtile score exemplars/gravel.svg "$OUT/big.svg" $SCORE_ARGS
done
md5sum "$OUT/big.svg"
