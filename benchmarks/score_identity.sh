#!/bin/sh
# svgtile score's text and --json, before and after a change, on textures of the bundled exemplars.
#
#   sh benchmarks/score_identity.sh BEFORE_PKG_DIR AFTER_PKG_DIR
#
# Each *_PKG_DIR is a `git archive COMMIT | tar -x` of the commit to run: each command runs in
# that directory (`python -m` puts the working directory before PYTHONPATH on sys.path, so a
# command run from a checkout imports that checkout's svgtile, whatever PYTHONPATH says).  The textures are synthesized once, with BEFORE; then both score each of them
# and the outputs are compared with `diff -r` (exit status 0: identical).  Both also score each
# with --exact (directories before-exact/, after-exact/), which must be identical on every
# texture, where the plain outputs may differ on textures above the sampling threshold
# (SAMPLE_ABOVE motifs, issue 11: the 3000² gravel texture) — the script lists those.  (A BEFORE
# without --exact, older than the sampling, is compared plain against AFTER's --exact.)  Run
# from the repository root.  SCORE_ARGS is added to AFTER's commands, e.g. SCORE_ARGS="--jobs 2"
# (by default score uses a second process only where the load average leaves a core idle).
set -e
PY=${PY:-$(pwd)/.venv/bin/python}
OUT=${TMPDIR:-/tmp}/svgtile-score-identity
rm -rf "$OUT"; mkdir -p "$OUT/tex" "$OUT/before" "$OUT/after" "$OUT/before-exact" "$OUT/after-exact"
synth() { cd "$1" && PYTHONPATH="$1" "$PY" -m svgtile synth "exemplars/$2.svg" -o "$OUT/tex/$2-$3.svg" --seed "$4" --force --size "$5" ${6:+--engine $6}; cd - > /dev/null; }
for e in gravel till breccia sand shale marsh; do synth "$1" $e patch 3 400x400; done
synth "$1" gravel tile 2 500x300 tile
synth "$1" till random 2 500x500 random
synth "$1" gravel big 1 3000x3000
# one process per package scores every texture, text and --json, as `svgtile score` prints them
score_all() {  # PKG_DIR OUT_SUBDIR [OPTIONS…]
  pkg=$1; sub=$2; shift 2
  (cd "$pkg" && PYTHONPATH="$pkg" "$PY" - "$OUT/tex" "$OUT/$sub" "$@" <<'PY'
import contextlib, io, sys
from pathlib import Path
from svgtile.cli.main import main
tex, out, *flag = sys.argv[1:]
for t in sorted(Path(tex).glob("*.svg")):
    for ext, extra in (("json", ["--json"]), ("txt", [])):
        buf = io.StringIO()
        with contextlib.redirect_stdout(buf):
            main(["score", f"exemplars/{t.stem.split('-')[0]}.svg", str(t), *extra, *flag])
        Path(out, f"{t.stem}.{ext}").write_text(buf.getvalue())
PY
  )
}
score_all "$1" before
score_all "$2" after $SCORE_ARGS
score_all "$2" after-exact --exact $SCORE_ARGS
if grep -q -- "--exact" "$1/svgtile/cli/score.py"; then score_all "$1" before-exact --exact
else rmdir "$OUT/before-exact"; ln -s before "$OUT/before-exact"; fi
echo "differ before → after (sampled above the threshold):"; diff -rq "$OUT/before" "$OUT/after" || true
diff -r "$OUT/before-exact/" "$OUT/after-exact/" && echo "identical before → after with --exact: $(ls "$OUT/after-exact" | wc -l) outputs"
