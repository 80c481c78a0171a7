"""Where ``svgtile score`` spends its CPU, step by step, in one process (issue 11).

    python benchmarks/score_phases.py EXEMPLAR TEXTURE

Prints one line of CPU seconds (``time.process_time``): the imports of ``svgtile.cli.score``,
loading and analysing the exemplar, reading the texture, the baselines' E (computed once per
exemplar and process, :func:`svgtile.metrics.likeness.baseline_distances`), the other figures
(:func:`svgtile.metrics.score`, the baselines already known), and the total — with the cyclic
collector paused as the command pauses it.  Run it in the directory of the package to measure
(``cd PKG && PYTHONPATH=PKG python …``: ``python`` puts the script's directory, not the working
directory, first on ``sys.path``, so PYTHONPATH decides which svgtile is imported).
"""

from __future__ import annotations

import gc
import sys
import time

start = time.process_time()
import svgtile.cli.score  # noqa: E402
from svgtile.cli.common import load  # noqa: E402
from svgtile.metrics import score  # noqa: E402
from svgtile.metrics.likeness import baseline_distances  # noqa: E402
from svgtile.svg.texture import read_texture  # noqa: E402

marks = [("imports", time.process_time())]
exemplar, texture = sys.argv[1:3]
ex, stats = load(exemplar)
marks.append(("exemplar", time.process_time()))
gc.disable()
arr, region = read_texture(texture, ex)
marks.append(("read", time.process_time()))
baseline_distances(ex, stats)
marks.append(("baselines", time.process_time()))
score(ex, stats, arr, region)
marks.append(("figures", time.process_time()))
gc.enable()
last, parts = start, []
for name, t in marks:
    parts.append(f"{name} {t - last:.2f}")
    last = t
print(f"{svgtile.__file__}: " + " · ".join(parts) + f" · total {last - start:.2f} s CPU")
