"""Run the robustness corpus (``cases.py``) or every SVG of a data folder, and classify each run.

    python tools/robustness/run.py                      # the whole corpus
    python tools/robustness/run.py --sample 20          # every 20th case (what CI runs)
    python tools/robustness/run.py --data ../shared/data --jobs 2 --timeout 90
    python tools/robustness/run.py --only structure     # one group (a substring of group or name)

Each run gets a fresh folder, a time limit (``--timeout``) and an address-space limit, and is
classified as the worst of what applies:

=================  ==================================================================
fetch attempted    a request reached the runner's HTTP listener, or the watched pipe
                   (``@SECRET@``) was opened
input changed      a file that was there before the run differs or is gone
internal           exit 70, a traceback, or killed by a signal svgtile did not send
timeout            over ``--timeout`` seconds (default 60) of CPU time (user + system, the
                   run and the workers it waited for), or still running after ``--wall``
                   seconds (default four times ``--timeout``)
memory             peak resident memory over ``--memory`` MB (default 2048), or MemoryError
output left        a temporary file after the run, or any new file after a failed run
clear refusal      exit 1 or 2 with one ``svgtile: error:`` line
ok                 exit 0 (or the reader of ``| head`` left: exit 1 and nothing said)
=================  ==================================================================

The limit is CPU time, not wall time: on a shared machine a run waiting for a core is not a
run that goes on for minutes, and on a quiet machine the two are the same.  The wall limit is
the backstop that ends a run that waits for ever (a FIFO with no writer).

The summary table (``--markdown``) is what docs/robustness.md shows.  ``--json`` is written a
line per run as runs end, and ``--resume`` skips the runs a previous ``--json`` file holds, so a
sweep of hours survives an interruption.
"""

from __future__ import annotations

import argparse
import collections
import hashlib
import http.server
import json
import os
import resource
import shutil
import signal
import socketserver
import stat
import subprocess
import sys
import tempfile
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from dataclasses import asdict, dataclass
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parents[1]
sys.path.insert(0, str(HERE))

from cases import Case, generate  # noqa: E402

OUTCOMES = ("ok", "clear refusal", "output left", "memory", "timeout", "internal", "input changed",
            "fetch attempted")  # fmt: skip
EXEMPLAR = REPO / "exemplars" / "gravel.svg"
SPARSE_BYTES = 200 * 2**20


@dataclass
class Outcome:
    name: str
    group: str
    outcome: str
    flags: list[str]
    code: int | None
    seconds: float
    peak_mb: float
    message: str
    cpu: float = 0.0


class _Fetches:
    """An HTTP listener on the loopback: any request for ``/CASE/…`` counts against CASE."""

    def __init__(self) -> None:
        hits = self.hits = collections.Counter()

        class Handler(http.server.BaseHTTPRequestHandler):
            def do_GET(self):
                hits[self.path.strip("/").split("/")[0]] += 1
                self.send_response(404)
                self.end_headers()

            do_POST = do_HEAD = do_GET

            def log_message(self, *args):
                pass

        self.server = socketserver.ThreadingTCPServer(("127.0.0.1", 0), Handler)
        self.server.daemon_threads = True
        self.url = f"http://127.0.0.1:{self.server.server_address[1]}"
        threading.Thread(target=self.server.serve_forever, daemon=True).start()


def _fill(text: bytes | str, values: dict[str, str]) -> bytes | str:
    for key, value in values.items():
        if isinstance(text, bytes):
            text = text.replace(key.encode(), value.encode())
        else:
            text = text.replace(key, value)
    return text


def _snapshot(folder: Path) -> dict[str, str]:
    """Digest of every regular file below ``folder`` (pipes and devices are never opened)."""
    out = {}
    for p in sorted(folder.rglob("*")):
        try:
            st = os.lstat(p)
        except OSError:
            continue
        if stat.S_ISREG(st.st_mode):
            out[str(p.relative_to(folder))] = hashlib.sha256(p.read_bytes()).hexdigest()
        elif stat.S_ISLNK(st.st_mode):
            out[str(p.relative_to(folder))] = "link:" + os.readlink(p)
        else:
            out[str(p.relative_to(folder))] = "special"
    return out


def _make_special(folder: Path, spec: str) -> None:
    kind, name = spec.split(":", 1)
    path = folder / name
    if kind == "fifo":
        os.mkfifo(path)
    elif kind == "loop":
        path.symlink_to(name)
    elif kind == "dev":
        path.symlink_to("/dev/zero")
    elif kind == "sparse":
        with open(path, "wb") as fh:
            fh.truncate(SPARSE_BYTES)


def _watch_secret(path: Path, stop: threading.Event, seen: list[bool]) -> None:
    """Open the pipe for writing whenever a reader has it open: that reader fetched it."""
    while not stop.is_set():
        try:
            fd = os.open(path, os.O_WRONLY | os.O_NONBLOCK)
        except OSError:  # ENXIO: nobody reading
            time.sleep(0.02)
            continue
        seen[0] = True
        os.close(fd)
        return


def run_case(case: Case, fetches: _Fetches, *, timeout: float, memory_mb: float, keep: bool = False,
             command: list[str] | None = None, wall: float | None = None) -> Outcome:
    """Run one case in a fresh folder and classify it.

    ``command`` replaces ``-m svgtile ARGS`` (placeholders filled): the runner's own test runs a
    stand-in that misbehaves, to show each outcome can be seen.  ``timeout`` is CPU seconds (the
    kernel's ``RLIMIT_CPU`` ends the run a second later); ``wall`` (default ``4 * timeout``) ends
    a run that waits.
    """
    wall = 4 * timeout if wall is None else wall
    root = Path(tempfile.mkdtemp(prefix="svgtile-robust-"))
    work, outside = root / "work", root / "outside"
    work.mkdir()
    outside.mkdir()
    secret = outside / "secret"
    os.mkfifo(secret)
    case_id = case.name.replace("/", "_")
    values = {"@HTTP@": f"{fetches.url}/{case_id}", "@SECRET@": str(secret), "@EXEMPLAR_BYTES@": EXEMPLAR.read_text(),
              "@EXEMPLAR@": "gravel.svg"}  # fmt: skip
    shutil.copy(EXEMPLAR, work / "gravel.svg")
    for name, data in case.files.items():
        (work / name).parent.mkdir(parents=True, exist_ok=True)
        (work / name).write_bytes(_fill(data, values))
    for spec in case.special:
        _make_special(work, spec)
    args = [_fill(a, values) for a in case.args]
    before = _snapshot(work)
    stop, seen = threading.Event(), [False]
    watcher = threading.Thread(target=_watch_secret, args=(secret, stop, seen), daemon=True)
    watcher.start()

    def limits() -> None:
        os.setsid()
        cap = int(max(memory_mb * 2, 4096) * 2**20)  # a backstop; the classification uses the peak
        resource.setrlimit(resource.RLIMIT_AS, (cap, cap))
        seconds = int(timeout) + 1
        resource.setrlimit(resource.RLIMIT_CPU, (seconds, seconds + 1))
        if case.stdout == "closed":
            os.close(1)

    out_path = root / "stdout"
    stdout = {"file": open(out_path, "wb"), "closed": subprocess.DEVNULL, "full": open("/dev/full", "wb"),
              "head": subprocess.PIPE}[case.stdout]  # fmt: skip
    err_path = root / "stderr"
    start = time.monotonic()
    with open(err_path, "wb") as err:
        argv = [_fill(a, values) for a in command] if command else ["-m", "svgtile", *args]
        proc = subprocess.Popen([sys.executable, *argv], cwd=work, stdin=subprocess.DEVNULL,
                                stdout=stdout, stderr=err, preexec_fn=limits)  # fmt: skip
        if case.stdout == "head":
            proc.stdout.read(100)
            proc.stdout.close()
        timed_out = False
        while True:
            pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
            if pid:
                break
            if time.monotonic() - start > wall:
                timed_out = True
                os.killpg(proc.pid, signal.SIGKILL)
                pid, status, usage = os.wait4(proc.pid, 0)
                break
            time.sleep(0.02)
    proc.returncode = os.waitstatus_to_exitcode(status)
    try:
        os.killpg(proc.pid, signal.SIGKILL)  # anything the run left behind (workers)
    except ProcessLookupError:
        pass
    if stdout not in (subprocess.DEVNULL, subprocess.PIPE):
        stdout.close()
    seconds = time.monotonic() - start
    stop.set()
    watcher.join(1)
    peak_mb = usage.ru_maxrss / 1024
    cpu = usage.ru_utime + usage.ru_stime
    timed_out = timed_out or cpu > timeout  # RLIMIT_CPU's SIGXCPU comes a second past the limit
    message = err_path.read_bytes().decode("utf-8", "replace")
    after = _snapshot(work)
    code = None if timed_out else proc.returncode
    flags = []
    if fetches.hits.get(case_id) or seen[0]:
        flags.append("fetch attempted")
    if any(after.get(k) != v for k, v in before.items()):
        flags.append("input changed")
    if code is not None and (code == 70 or code < 0 or "Traceback" in message or "internal error" in message):
        flags.append("internal")
    if timed_out:
        flags.append("timeout")
    if peak_mb > memory_mb or "MemoryError" in message or "out of memory" in message:
        flags.append("memory")
    new = set(after) - set(before)
    if any(n.endswith(".tmp") for n in new) or (code not in (0, None) and new and case.stdout != "head"):
        flags.append("output left")
    lines = [ln for ln in message.splitlines() if ln.strip()]
    errors = [ln for ln in lines if ln.startswith("svgtile: error:") or ln.startswith("svgtile: stopped")]
    if code == 0 or (case.stdout == "head" and code == 1 and not errors):
        flags.append("ok")
    elif code in (1, 2) and len(errors) == 1:
        flags.append("clear refusal")
    elif not flags:
        flags.append("internal")  # a failure without its one line
    outcome = max(flags, key=OUTCOMES.index)
    if not keep:
        shutil.rmtree(root, ignore_errors=True)
    last = errors[-1] if errors else (lines[-1] if lines else "")
    return Outcome(case.name, case.group, outcome, flags, code, round(seconds, 2), round(peak_mb, 1), last[:300],
                   round(cpu, 2))


def data_cases(folder: Path) -> list[Case]:
    """``analyze``, ``synth`` 200 × 200 and ``import`` of every SVG under ``folder``."""
    out = []
    for path in sorted(folder.rglob("*.svg")):
        rel = str(path.relative_to(folder))
        data = path.read_bytes()
        group = rel.split("/")[0]
        out += [Case(f"{rel}.analyze", group, ["analyze", "in.svg"], {"in.svg": data}),
                Case(f"{rel}.synth", group, ["synth", "in.svg", "--size", "200x200", "--seed", "1", "-o", "out.svg"], {"in.svg": data}),
                Case(f"{rel}.import", group, ["import", "in.svg", "-o", "out.svg"], {"in.svg": data})]  # fmt: skip
    return out


def summary(results: list[Outcome]) -> str:
    """A markdown table: runs per group and outcome, then every run that is neither ok nor refused."""
    groups = sorted({r.group for r in results}, key=[r.group for r in results].index)
    head = "| group | runs | " + " | ".join(OUTCOMES) + " | most CPU s | longest wall s | peak MB |"
    lines = [head, "|" + "---|" * (len(OUTCOMES) + 5)]
    for g in [*groups, "all"]:
        rs = [r for r in results if g in ("all", r.group)]
        counts = collections.Counter(r.outcome for r in rs)
        cells = " | ".join(str(counts.get(o, 0)) for o in OUTCOMES)
        name = f"**{g}**" if g == "all" else g
        lines.append(f"| {name} | {len(rs)} | {cells} | {max(r.cpu for r in rs):.1f} | {max(r.seconds for r in rs):.1f} "
                     f"| {max(r.peak_mb for r in rs):.0f} |")
    bad = [r for r in results if r.outcome not in ("ok", "clear refusal")]
    if bad:
        lines += ["", "| run | outcome | exit | CPU s | wall s | MB | message |", "|---|---|---|---|---|---|---|"]
        lines += [f"| {r.name} | {r.outcome} | {r.code} | {r.cpu} | {r.seconds} | {r.peak_mb} | {r.message.replace('|', '/')} |"
                  for r in bad]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--data", type=Path, help="classify every SVG under this folder instead of the corpus")
    ap.add_argument("--sample", type=int, default=1, help="run every Nth case")
    ap.add_argument("--only", default=None, help="cases whose group or name contains this")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--timeout", type=float, default=60.0, help="CPU seconds per run")
    ap.add_argument("--wall", type=float, default=None, help="wall seconds per run (default 4 x --timeout)")
    ap.add_argument("--memory", type=float, default=2048.0, help="MB of peak resident memory per run")
    ap.add_argument("--json", type=Path, help="write every outcome here (JSON lines, as runs end)")
    ap.add_argument("--resume", action="store_true", help="keep the runs --json already holds; run the rest")
    ap.add_argument("--markdown", type=Path, help="write the summary table here")
    ap.add_argument("--keep", action="store_true", help="keep each run's folder")
    args = ap.parse_args(argv)
    cases = data_cases(args.data) if args.data else generate()
    if args.only:
        cases = [c for c in cases if args.only in c.group or args.only in c.name]
    cases = cases[:: max(1, args.sample)]
    fetches = _Fetches()
    done: dict[str, Outcome] = {}
    if args.resume and args.json and args.json.exists():
        for line in args.json.read_text().splitlines():
            if line.strip():
                r = Outcome(**json.loads(line))
                done[r.name] = r
    elif args.json:
        args.json.write_text("")
    lock = threading.Lock()

    def one(case: Case) -> Outcome:
        if case.name in done:
            return done[case.name]
        r = run_case(case, fetches, timeout=args.timeout, memory_mb=args.memory, keep=args.keep, wall=args.wall)
        print(f"{r.outcome:<15} {r.cpu:6.1f}s CPU {r.seconds:6.1f}s {r.peak_mb:7.0f}MB  {r.name}  {r.message[:120]}",
              flush=True)  # fmt: skip
        if args.json:
            with lock, args.json.open("a") as f:
                f.write(json.dumps(asdict(r)) + "\n")
        return r

    with ThreadPoolExecutor(max_workers=args.jobs) as pool:
        results = list(pool.map(one, cases))
    table = summary(results)
    print(table)
    if args.markdown:
        args.markdown.write_text(table + "\n")
    bad = [r for r in results if r.outcome not in ("ok", "clear refusal")]
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
