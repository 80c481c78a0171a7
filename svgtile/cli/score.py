"""``svgtile score``: how well a texture reproduces its exemplar (figures of :mod:`svgtile.metrics`)."""

from __future__ import annotations

import ctypes
import gc
import html
import json
import multiprocessing
import os
import re
import signal
import stat
import sys
from collections.abc import Iterator
from concurrent.futures import Executor, ProcessPoolExecutor
from contextlib import contextmanager
from pathlib import Path

import click

from svgtile.cli.output import Ending
from svgtile.core.worker import worker_submit

#: prctl(2)'s option that has Linux signal a process when its parent ends.
_PR_SET_PDEATHSIG = 1


@click.command(name="score")
@click.argument("exemplar", type=click.Path(dir_okay=False))
@click.argument("texture", type=click.Path(dir_okay=False))
@click.option("--json", "as_json", is_flag=True, help="Print machine-readable JSON.")
@click.option("--exact", is_flag=True,
              help="Measure every figure on every motif, however large the texture (slower).")  # fmt: skip
@click.option("--jobs", type=click.IntRange(min=1), default=None,
              help="Processes to read and measure in: 2 reads half of a large texture and measures half of the figures in a second one (on Linux; the default where a second core is idle), 1 all of them in this one. The figures are the same.")  # fmt: skip
@click.option("--import/--no-import", "as_tile", default=None,
              help="EXEMPLAR is a seamless pattern tile: import it first, as 'synth --import' did. By default it is imported when TEXTURE's run record says it was made so from a file of EXEMPLAR's name and EXEMPLAR is not itself svgtile's import of a tile.")  # fmt: skip
def score(exemplar, texture, as_json, exact, jobs, as_tile):
    """Measure how well TEXTURE (an SVG svgtile made from EXEMPLAR) reproduces EXEMPLAR.

    Figures are measured on the texture's interior (the region shrunk by one exemplar width);
    lengths are in the exemplar's mean spacing. What each means, and the ideal:

    \b
      overlapping pairs            motifs whose footprints share area           0
      distance-rule violators      motifs closer than the exemplar allows       0
      density / ρ                  ink over the exemplar's                      1
      density CV, min, max         the same in exemplar-sized windows           0; 1; 1
      kind mix TV                  kind frequencies against the exemplar's,     0
                                   kinds drawn a few times each pooled by shape
        per kind, its noise        each kind apart, and what a fair draw of     near the noise:
                                   as many motifs gives (where kinds pool)      chance
      orientation outside arcs     motifs turned as the exemplar never does     0
      structure: nearest-gap W1    gaps to the nearest neighbour of each kind   0 (below its noise:
                                   against the exemplar's                       as good as can be told)
      structure: pair correlation  neighbour distances up to 3 spacings         0
      repetition                   motifs repeating at one displacement more    0 (tile of
                                   often than the exemplar itself does there    irregular content: 1)
        incl. exemplar's lattice   the same at every displacement               1 for a lattice
      coverage                     largest empty disc over the exemplar's       1
      neighbourhood distance       each motif's 6 nearest neighbours (where,    0
                                   which kind) against the most alike
                                   exemplar neighbourhood (Ma et al. 2011);
                                   printed with tile's and random's
      likeness L                   that distance between the two baselines:     1 (or above)
                                   1 = tile's (stamped copies), 0 = random's

    Read them against svgtile compare's tile and random columns; the README defines each.

    A texture of more than 100,000 motifs in its interior has its structure figures (nearest
    gaps, pair correlation) measured on 9 windows spread over the interior (about 20,000
    motifs; the report says so) and its largest empty disc searched on a coarser raster; every
    other figure, overlaps and violators first, is measured over every motif as always.
    --exact measures everything on every motif.
    """
    heads = _heads(exemplar, texture)
    _check_order(exemplar, texture, heads)
    if as_tile is None:
        as_tile = heads is not None and _made_from_imported(heads[1], exemplar) and not _IMPORTED.search(heads[0])
        if as_tile:
            click.echo(f"svgtile: {texture} was made from a tile named {Path(exemplar).name} imported as a pattern "
                       f"(synth --import): importing {exemplar} too (--no-import not to)", err=True)  # fmt: skip
    # the collector paused from the heavy imports on (they alone ran it ≈ 130 times, ≈ 0.05 s) to
    # the process's end: all is printed and no file written, the interpreter's teardown would
    # only free memory (Ending)
    with _no_cycle_collection_to_the_end():
        # imported here, not at the module's head: the other commands do not load them; the worker
        # is forked after them (at its first task) and inherits them (forked before them, it imported
        # them again at the same time as this process: measured no faster where a core was idle and
        # 0.6–1.5 s slower where none was, benchmarks/README.md, "score11d")
        from svgtile.apps.compare import format_score
        from svgtile.cli.common import json_safe, load, warn_if_few
        from svgtile.errors import TextureKindError
        from svgtile.metrics import score as measure
        from svgtile.metrics.likeness import baseline_distances
        from svgtile.svg.texture import start_reading

        with _second_process(jobs) as pool:
            ex, stats = load(exemplar, as_tile=as_tile)
            # the worker, forked once the file is read (it finds its part of the <use> lines in its
            # own memory), scans the last 40 % of them first, then measures the baselines while this
            # process scans the rest and measures the figures up to E
            reading = start_reading(texture, pool=pool)
            baselines = worker_submit(pool, baseline_distances, ex, stats)
            try:
                arr, region = reading.finish(ex)
            except TextureKindError as exc:
                if as_tile:
                    raise
                raise TextureKindError(f"{exc} (or from this one imported as a pattern tile? then pass --import)") from None
            del reading  # the document's bytes and text (twice 19 MB on 177k motifs): not needed again
            result = measure(ex, stats, arr, region, exact=exact, pool=pool, baselines=baselines)
        warn_if_few(result.motifs, texture)
        if as_json:
            out = {"exemplar": Path(exemplar).name, "texture": Path(texture).name, **result.to_dict()}
            click.echo(json.dumps(json_safe(out), indent=2, allow_nan=False))
        else:
            click.echo(f"{Path(texture).name} against {Path(exemplar).name}: {len(arr)} motifs centred in its region "
                       "(motifs the region's edge cuts, centred outside it, are not counted)")
            if result.sample is not None:
                click.echo(f"sampled: {result.sample.describe()} (structure: nearest gaps, pair correlation; "
                           "--exact to measure it on every motif)")  # fmt: skip
            click.echo(format_score(result))


#: An exemplar file that svgtile wrote as a texture with more motifs than this, scored against
#: a texture svgtile did not write, is taken for the arguments swapped: a drawn exemplar holds
#: tens of motifs, and analysing a texture of 81,000 as an exemplar ran for a minute and ended
#: out of memory.
SWAPPED_ABOVE = 2_000
#: svgtile's run record at the head of every texture it writes (:func:`svgtile.svg.writer.svg_document_parts`).
_RUN = re.compile(rb'<svgtile:run\b[^>]*?\bmotifs="(\d+)"')
_RUN_TAG = re.compile(rb"<svgtile:run\b[^>]*>")
#: What marks an exemplar that is already svgtile's import of a tile (svgtile.tiles.write): its
#: note, or the period on its region; such a file is never imported again.
_IMPORTED = re.compile(rb'Imported by svgtile from|:period="')
_HEAD = 1 << 16


def _heads(exemplar: str, texture: str) -> tuple[bytes, bytes] | None:
    """The first 64 KiB of both files, where svgtile's run record is; None if either is not a
    regular file or cannot be read (left to their readers, which also refuse what is not a
    regular file: a pipe or a device would block here)."""
    heads = []
    for path in (exemplar, texture):
        try:
            if not stat.S_ISREG(os.stat(path).st_mode):
                return None
            with open(path, "rb") as f:
                heads.append(f.read(_HEAD))
        except OSError:
            return None
    return heads[0], heads[1]


def _made_from_imported(head: bytes, exemplar: str) -> bool:
    """Whether a texture's run record (in ``head``) says it was made from a file of
    ``exemplar``'s name imported as a pattern tile (``synth --import``)."""
    run = _RUN_TAG.search(head)
    if run is None or not re.search(rb'\simported="tile"', run.group(0)):
        return False
    named = re.search(rb'\bexemplar="([^"]*)"', run.group(0))
    return named is not None and html.unescape(named.group(1).decode("utf-8", "replace")) == Path(exemplar).name


def _check_order(exemplar: str, texture: str, heads: tuple[bytes, bytes] | None = None) -> None:
    """Refuse ``svgtile score TEXTURE EXEMPLAR`` at once: EXEMPLAR is a texture svgtile wrote
    (its run record, in the file's first 64 KiB) of more than :data:`SWAPPED_ABOVE` motifs and
    TEXTURE has no run record.  Both textures (a texture scored against itself, or made from a
    texture) and large drawn exemplars (no run record) go on; unreadable files are left to their
    readers.  ``heads``: :func:`_heads` of the two, if already read."""
    heads = heads or _heads(exemplar, texture)
    if heads is None:
        return
    made = _RUN.search(heads[0])
    if made is None or int(made.group(1)) <= SWAPPED_ABOVE or b"<svgtile:run" in heads[1]:
        return
    raise click.UsageError(
        f"{exemplar} is a texture svgtile wrote ({int(made.group(1)):,} motifs) and {texture} is not: the "
        f"arguments look swapped; the exemplar comes first (svgtile score {texture} {exemplar})"
    )


@contextmanager
def _second_process(jobs: int | None) -> Iterator[Executor | None]:
    """One worker process forked from this one, or None (``jobs`` 1, or not on Linux).

    Forked at its first task, after this process imported the analysis stage, scipy and shapely
    (the worker inherits them); on Linux only, where forking a process that has used numpy and
    GEOS is safe (macOS's system libraries are not fork-safe, Windows cannot fork).
    A process, not a thread: most of the figures' time is Python and numpy calls that hold the
    GIL (benchmarks/README.md, "`svgtile score` on two cores").  Forked at the first
    ``submit``, before the executor starts its thread."""
    if jobs is None:
        jobs = _default_jobs()
    if jobs < 2 or not sys.platform.startswith("linux"):
        yield None
        return
    pool = ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("fork"), initializer=_worker_signals,
                               initargs=(os.getpid(),))  # fmt: skip
    try:
        yield pool
    except BaseException:  # a bad texture, ^C: the worker's figure is not wanted, nor waited for
        _stop_worker(pool)
        raise
    finally:  # the worker's exit is waited for at the interpreter's, while the figures are printed
        pool.shutdown(wait=False, cancel_futures=True)


def _stop_worker(pool: ProcessPoolExecutor) -> None:
    """End ``pool``'s worker now: the interpreter's exit would otherwise wait for the figure it
    is measuring (the baselines: about a second on an FGDC tile, after the error was printed).
    SIGKILL, not SIGTERM: a worker just forked still has the command's SIGTERM handler until its
    initializer has run, and a SIGTERM then printed a traceback under the error (a bad texture
    is read in well under that window's length on a busy machine); it has nothing to clean up.
    The executor has no public way to do this before Python 3.14's ``terminate_workers``."""
    for process in list((getattr(pool, "_processes", None) or {}).values()):
        if process.is_alive():
            process.kill()


def _default_jobs() -> int:
    """2 where a second core is free — this process may use two cores or more and the 1-minute
    load average leaves a whole core idle — else 1: on a busy machine a second process only
    competes for the same cores, and the command took as long or longer (benchmarks/README.md,
    "`svgtile score` on two cores")."""
    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1
    try:
        load = os.getloadavg()[0]
    except (AttributeError, OSError):  # no load average here: trust the cores
        load = 0.0
    return 2 if cores >= 2 and load <= cores - 1 else 1


def _worker_signals(parent: int) -> None:
    """The worker leaves ^C to the command (which reports it and stops the worker at the end of
    its figure) and dies quietly on SIGTERM or SIGHUP: it has nothing to clean up, nor to say.

    It also dies with the command: a command killed outright (SIGKILL, the out-of-memory
    killer) runs no cleanup, and its worker would otherwise wait for work for ever, an orphan.
    Linux sends it SIGTERM when the thread that forked it ends (``PR_SET_PDEATHSIG``; the pool
    is forked by the main thread, at its first ``submit``); ``parent`` is the command's pid."""
    for signum in (signal.SIGTERM, signal.SIGHUP):  # first: the command's handlers raise
        signal.signal(signum, signal.SIG_DFL)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(_PR_SET_PDEATHSIG, signal.SIGTERM, 0, 0, 0)
    except (OSError, AttributeError):  # no prctl: the worker ends with the pool, as before
        return
    if os.getppid() != parent:  # the command died before the request was made
        os._exit(0)


@contextmanager
def _no_cycle_collection_to_the_end():
    """CPython's cyclic collector paused: reading and measuring a large texture makes hundreds
    of thousands of objects that hold no reference cycles (the strings of the ``<use>`` scan,
    one shapely footprint per motif), and the collector would walk them all again and again.

    When the block ends (all printed) the command asks to end the process
    (:class:`~svgtile.cli.output.Ending`); if the process will end so, the collector stays
    paused (resuming ran one collection of everything made meanwhile, ≈ 0.02 s), else (an error,
    ``main([...])`` from Python, click's test runner) it resumes."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    except BaseException:
        if enabled:
            gc.enable()
        raise
    if enabled and not Ending.will_end:
        gc.enable()
    Ending.ask()
