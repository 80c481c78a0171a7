"""The wall-clock timeline of one ``svgtile score`` run, in both of its processes (issue 11).

    python benchmarks/score_timeline.py EXEMPLAR TEXTURE [SCORE OPTIONS…]

Runs ``python -m svgtile score EXEMPLAR TEXTURE OPTIONS`` as a child process whose phases are
wrapped with timestamps (wall clock, ``time.time``, seconds since the child was launched): the
imports, the exemplar, the texture's read, each figure handed to the worker and the wait for
it, the figures, the print, and the end of the child's teardown as its parent sees it.  Each
line names the process that wrote it ("cmd" or "worker") and gives that process's CPU time so
far (``time.process_time``: a forked worker's starts at 0; score11e).  Nothing in the package is changed:
the wrappers are put in place in the child only, before the command runs (the worker is forked
from it, and finds them by the same module attributes).  Run it from the root of the package to
measure.
"""

from __future__ import annotations

import functools
import importlib
import importlib.util
import os
import subprocess
import sys
import tempfile
import time


def _child(t0: float, argv: list[str]) -> None:

    def mark(what: str) -> None:
        who = "cmd" if os.getpid() == main_pid else "worker"
        os.write(2, f"@timeline {time.time() - t0:7.3f} cpu {time.process_time():6.3f} {who:6s} {what}\n".encode())

    main_pid = os.getpid()
    mark("interpreter up")
    import svgtile.cli.main as cli_main
    import svgtile.cli.score as cmd
    import svgtile.metrics.scoring as scoring

    mark("imports done")

    def wrap(module, name, label):  # what this commit's package has (it may be an older one)
        inner = getattr(module, name, None) if module is not None else None
        if inner is None:
            return

        @functools.wraps(inner)
        def timed(*args, **kwargs):
            mark(f"{label} start")
            try:
                return inner(*args, **kwargs)
            finally:
                mark(f"{label} end")

        setattr(module, name, timed)

    wrap(cmd, "load", "exemplar")
    import svgtile.svg.texture as texture

    wrap(cmd, "read_texture", "read")
    wrap(cmd, "start_reading", "read the file")
    wrap(getattr(texture, "Reading", None), "finish", "read: the rest")
    wrap(texture, "_scan", "scan of <use> lines")  # before the split
    uselines = importlib.util.find_spec("svgtile.svg.uselines") and importlib.import_module("svgtile.svg.uselines")
    wrap(uselines or None, "scan", "scan of <use> lines")
    wrap(cmd, "worker_result", "wait for worker")
    wrap(cmd, "measure", "figures (this process)")
    wrap(scoring, "worker_result", "wait for worker")
    wrap(scoring, "_footprint_figures", "footprint figures")
    wrap(scoring, "ready_worker", "worker ready")  # before score11e
    for name in ("kind_trees", "structure", "repetition", "measure_likeness", "conflict_counts", "largest_empty_disc"):
        wrap(scoring, name, name)
    import svgtile.metrics.likeness as likeness

    wrap(likeness, "baseline_distances", "baselines")
    # the command's names of what it hands the worker: the wrappers (pickled by their names)
    for name, module in (("baseline_distances", likeness), ("ready_worker", scoring)):
        if hasattr(cmd, name):
            setattr(cmd, name, getattr(module, name))
    wrap(cmd, "format_score", "format")
    import atexit
    import threading

    atexit.register(mark, "atexit handlers (after the threads were joined)")
    threading._register_atexit(mark, "interpreter exit begins")  # runs before the executor's
    import svgtile.cli.common as common

    if hasattr(common, "Ending"):  # a package that ends the process once the figures are out
        ending = common.Ending.end

        def end(code):
            mark(f"command returned ({code}); asked to end now: {common.Ending.asked}")
            ending(code)

        common.Ending.end = end
    sys.argv = ["svgtile", "score", *argv]  # as the command line runs it: main() reads sys.argv
    code = cli_main.main()
    mark(f"command returned ({code})")
    sys.exit(code)

def main() -> None:
    if len(sys.argv) > 2 and sys.argv[1] == "--child":
        _child(float(sys.argv[2]), sys.argv[3:])
        return
    with tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err:
        # files, not pipes: a pipe's reader would wait for the worker too, which holds it open
        t0 = time.time()
        child = subprocess.Popen([sys.executable, __file__, "--child", repr(t0), *sys.argv[1:]], stdout=out,
                                 stderr=err)  # fmt: skip
        code = child.wait()
        end = time.time() - t0
        time.sleep(0.5)  # the worker's last lines
        out.seek(0), err.seek(0)
        printed, stderr = out.read(), err.read().splitlines()
    lines = [ln for ln in stderr if ln.startswith("@timeline ")]
    others = [ln for ln in stderr if not ln.startswith("@timeline ")]
    for ln in sorted(lines, key=lambda s: float(s.split()[1])):
        print(ln.removeprefix("@timeline "))
    print(f"{end:7.3f} parent sees the child end (exit {code}); {len(printed)} chars printed")
    for ln in others:
        print("stderr:", ln)


if __name__ == "__main__":
    main()
