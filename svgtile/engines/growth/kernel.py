"""The per-seed work of local growth as numba kernels (Ijiri et al. 2008, §5.2 and §5.4).

Growth is sequential: each placement changes the next seed's neighbourhood, so there is no batch
to vectorise over.  The work per seed is small — a 3 × 3 block of buckets, a dozen candidate
neighbours, a few hundred (reference, shift) pairs — and in numpy it was some forty small array
operations per seed (~1.5 ms a motif).  Here it is one compiled loop (``cache=True``: compiled once
per machine, about 10 s, then loaded from ``__pycache__``):

* :func:`ring_order` — the Gabriel ring of a seed's placed neighbours, counter-clockwise from the
  open side (what :func:`svgtile.engines.growth.connectivity.ring_of` returns);
* :func:`match` — eq. (1)–(4): every reference ring of at least as many neighbours under every
  cyclic shift, the best ``top`` (what :func:`svgtile.engines.growth.matching.best_match` returns);
* :func:`run` — the loop of :func:`svgtile.engines.growth.grow.grow`: a heap of seeds, bucket
  grids of placed motifs and live seeds as linked lists in arrays, the Fig. 6 heuristics.  It is
  resumable: it returns when its arrays are full or a relaxation is due, and the caller grows the
  arrays or relaxes and calls it again with the same state;
* :func:`ring_slots` and :func:`normal_equations` — the assembly of relaxation's least-squares
  problem (§5.5, :mod:`svgtile.engines.growth.relax`), a few thousand small array operations a
  run in numpy.

The floating-point operations are those of the numpy version, in the same order (sums in
numpy's pairwise order, :func:`_sum`), so that a texture grown by either is the same to the last
written digit.  Where a cheaper test stands in for one of them (:func:`closer` for a ``hypot``
compared with a threshold, a bound from square roots in :func:`match`), it only ever settles
cases the exact test would settle the same way, and leaves the others to it.
"""

from __future__ import annotations

import numba
import numpy as np

#: Codes :func:`run` returns.
DONE, FULL, RELAX = 0, 1, 2
#: The Gabriel circle is enlarged by this factor, so points exactly on it (a lattice) shadow
#: (:mod:`svgtile.engines.growth.connectivity`).
GABRIEL_SLACK = 1.05
#: The rotation modes of §5.3.
NONE, FIT, FLOW = 0, 1, 2
TWO_PI = 2.0 * np.pi


@numba.njit(cache=True)
def _sum(a, n):  # pragma: no cover
    """Σ a[:n] in the order of numpy's ``add.reduce`` over a contiguous axis (pairwise: eight
    running sums from n = 8 on), so results match numpy's to the bit."""
    if n < 8:
        res = 0.0
        for i in range(n):
            res += a[i]
        return res
    r0, r1, r2, r3, r4, r5, r6, r7 = a[0], a[1], a[2], a[3], a[4], a[5], a[6], a[7]
    i = 8
    end = n - n % 8
    while i < end:
        r0 += a[i]
        r1 += a[i + 1]
        r2 += a[i + 2]
        r3 += a[i + 3]
        r4 += a[i + 4]
        r5 += a[i + 5]
        r6 += a[i + 6]
        r7 += a[i + 7]
        i += 8
    res = ((r0 + r1) + (r2 + r3)) + ((r4 + r5) + (r6 + r7))
    for j in range(end, n):
        res += a[j]
    return res


@numba.njit(cache=True)
def closer(dx, dy, t):  # pragma: no cover
    """``np.hypot(dx, dy) < t``, decided as that expression decides it, mostly without ``hypot``.

    ``hypot`` costs ~16 ns here against ~2 for a sum of squares, and the loop asks this question
    some thousand times a motif.  ``dx² + dy²`` (relative error ≤ 2 ulp) against ``t²`` settles
    every case farther than 1e-12 relative from the threshold; the few nearer are asked of
    ``hypot`` itself, so the answer is always the one ``hypot`` gives."""
    s = dx * dx + dy * dy
    t2 = t * t
    if s > t2 * (1.0 + 1e-12):
        return False
    if s < t2 * (1.0 - 1e-12):
        return True
    return np.hypot(dx, dy) < t


@numba.njit(cache=True)
def ring_order(rel, out):  # pragma: no cover
    """The Gabriel neighbours of the origin among ``rel`` ((q, 2) float, relative to the seed),
    counter-clockwise, starting after the widest angular gap (§5.2); written to ``out`` ((q,)
    int), their number returned."""
    q = rel.shape[0]
    r = np.empty(q)
    for e in range(q):
        r[e] = np.hypot(rel[e, 0], rel[e, 1]) / 2 * GABRIEL_SLACK
    keep = np.empty(q, np.int64)
    nk = 0
    for e in range(q):
        mx, my = rel[e, 0] / 2, rel[e, 1] / 2
        shadowed = False
        for o in range(q):
            if o != e and closer(rel[o, 0] - mx, rel[o, 1] - my, r[e]):
                shadowed = True
                break
        if not shadowed:
            keep[nk] = e
            nk += 1
    if nk == 0:
        return 0
    ang = np.empty(nk)
    for i in range(nk):
        ang[i] = np.arctan2(rel[keep[i], 1], rel[keep[i], 0])
    by = np.argsort(ang, kind="mergesort")
    first = 0
    if nk > 1:
        best = -np.inf
        for i in range(nk):
            a = ang[by[i]]
            b = ang[by[i + 1]] if i + 1 < nk else ang[by[0]] + TWO_PI
            if b - a > best:
                best = b - a
                first = i
        first = (first + 1) % nk
    for i in range(nk):
        out[i] = keep[by[(first + i) % nk]]
    return nk


@numba.njit(cache=True)
def match(rel, size, rkind, nkind, nsub, mean_length, tar, tkind, tsub, want, mode, fa, w1, w2, w3, noise, top,
          out_r, out_k, out_theta, out_err):  # fmt: skip  # pragma: no cover
    """Eq. (1)–(4): the ``top`` best (reference ring, shift) pairs for the target ring ``tar``
    ((t, 2) float, kinds ``tkind``, sub-ids ``tsub``), best first, written to the ``out_*``
    arrays; their number returned.  Arguments as :func:`svgtile.engines.growth.matching.best_match`
    (``mode``: :data:`NONE`, :data:`FIT`, :data:`FLOW`; ``w1, w2, w3``: eq. (2)'s weights)."""
    R, M = rel.shape[0], rel.shape[1]
    t = tar.shape[0]
    cand = np.empty(R, np.int64)
    c = 0
    for r in range(R):
        if size[r] >= t and (want < 0 or rkind[r] == want):
            cand[c] = r
            c += 1
    if c == 0:
        return 0
    if t == 0:
        theta0 = fa if mode == FLOW else 0.0
        key = np.empty(c)
        for i in range(c):
            key[i] = noise[cand[i]]
        by = np.argsort(key, kind="mergesort")
        got = min(top, c)
        for i in range(got):
            out_r[i], out_k[i], out_theta[i], out_err[i] = cand[by[i]], 0, theta0, 0.0
        return got
    # the best `top` pairs so far, sorted by (error, flat index): a stable selection.  A pair is
    # abandoned as soon as a lower bound of its error (the kind terms, then the distances summed so
    # far) exceeds the worst kept by more than rounding could account for: it could not be kept.
    got = 0
    px = np.empty(t)
    py = np.empty(t)
    slot = np.empty(t, np.int64)
    prune = w1 >= 0 and w2 >= 0 and w3 >= 0
    co0, si0 = np.cos(fa if mode == FLOW else 0.0), np.sin(fa if mode == FLOW else 0.0)
    for i in range(c):
        r = cand[i]
        m = size[r]
        tiny = 1e-9 * noise[r]
        for k in range(M):
            if k >= m:
                continue  # np.inf in the numpy version: never chosen
            bad = 0
            same = 0
            for j in range(t):
                slot[j] = k + j - m if k + j >= m else k + j  # (k + j) mod m, without a division
                bad += nkind[r, slot[j]] != tkind[j]
                same += nsub[r, slot[j]] == tsub[j]
            base = (w2 * bad if w2 else 0.0) + (w3 * same if w3 else 0.0)
            bound = out_err[got - 1] * (1.0 + 1e-12) + 1e-300 if prune and got == top else np.inf
            if base > bound:
                continue
            if mode == FIT:
                for j in range(t):
                    s = slot[j]
                    px[j] = rel[r, s, 0] * tar[j, 0] + rel[r, s, 1] * tar[j, 1]
                    py[j] = rel[r, s, 0] * tar[j, 1] - rel[r, s, 1] * tar[j, 0]
                theta = np.arctan2(_sum(py, t), _sum(px, t))
                co, si = np.cos(theta), np.sin(theta)
            else:
                theta = fa if mode == FLOW else 0.0
                co, si = co0, si0
            if bound < np.inf:
                # the distance sum from square roots (~1 ulp off hypot's) less a margin is below
                # the sum the loop below makes: a pair whose bound already exceeds the worst
                # kept is one that loop abandons too, found at a seventh of the cost
                low = 0.0
                for j in range(t):
                    s = slot[j]
                    dx = co * rel[r, s, 0] - si * rel[r, s, 1] - tar[j, 0]
                    dy = si * rel[r, s, 0] + co * rel[r, s, 1] - tar[j, 1]
                    low += np.sqrt(dx * dx + dy * dy)
                if w1 * (low * (1.0 - 1e-12)) / mean_length + base > bound:
                    continue
            run = 0.0
            over = False
            for j in range(t):
                s = slot[j]
                rx = co * rel[r, s, 0] - si * rel[r, s, 1]
                ry = si * rel[r, s, 0] + co * rel[r, s, 1]
                px[j] = np.hypot(rx - tar[j, 0], ry - tar[j, 1])
                run += px[j]
                if w1 * run / mean_length + base > bound:
                    over = True
                    break
            if over:
                continue
            err = w1 * _sum(px, t) / mean_length
            if w2:
                err = err + w2 * bad
            if w3:
                err = err + w3 * same
            err = err + tiny
            if got == top and err >= out_err[got - 1]:
                continue
            at = got if got < top else top - 1
            while at > 0 and out_err[at - 1] > err:
                if at < top:
                    out_r[at], out_k[at], out_theta[at], out_err[at] = (out_r[at - 1], out_k[at - 1],
                                                                        out_theta[at - 1], out_err[at - 1])
                at -= 1
            out_r[at], out_k[at], out_theta[at], out_err[at] = r, k, theta, err
            if got < top:
                got += 1
    return got


@numba.njit(cache=True)
def inside(x, y, coords, starts):  # pragma: no cover
    """Is ``(x, y)`` in the interior of the polygon whose rings are ``coords[starts[i]:starts[i +
    1]]`` (closed)?  Even–odd crossings; a point on the boundary is outside (as
    ``shapely.contains_xy``)."""
    crossings = 0
    for g in range(starts.shape[0] - 1):
        for e in range(starts[g], starts[g + 1] - 1):
            x1, y1, x2, y2 = coords[e, 0], coords[e, 1], coords[e + 1, 0], coords[e + 1, 1]
            o = (x2 - x1) * (y - y1) - (x - x1) * (y2 - y1)
            if o == 0.0 and min(x1, x2) <= x <= max(x1, x2) and min(y1, y2) <= y <= max(y1, y2):
                return False
            if (y1 > y) != (y2 > y) and (o > 0.0) == (y2 > y1):
                crossings += 1
    return crossings % 2 == 1


@numba.njit(cache=True)
def _heap_push(hkey, hid, hn, key, q):  # pragma: no cover
    i = hn
    hkey[i], hid[i] = key, q
    while i > 0:
        p = (i - 1) // 2
        if hkey[p] < hkey[i] or (hkey[p] == hkey[i] and hid[p] < hid[i]):
            break
        hkey[p], hkey[i] = hkey[i], hkey[p]
        hid[p], hid[i] = hid[i], hid[p]
        i = p
    return hn + 1


@numba.njit(cache=True)
def _heap_pop(hkey, hid, hn):  # pragma: no cover
    """Removes the least (key, id) from the heap of ``hn`` entries; returns it and the new size."""
    key, q = hkey[0], hid[0]
    hn -= 1
    hkey[0], hid[0] = hkey[hn], hid[hn]
    i = 0
    while True:
        a, b, s = 2 * i + 1, 2 * i + 2, i
        if a < hn and (hkey[a] < hkey[s] or (hkey[a] == hkey[s] and hid[a] < hid[s])):
            s = a
        if b < hn and (hkey[b] < hkey[s] or (hkey[b] == hkey[s] and hid[b] < hid[s])):
            s = b
        if s == i:
            break
        hkey[s], hkey[i] = hkey[i], hkey[s]
        hid[s], hid[i] = hid[i], hid[s]
        i = s
    return key, q, hn


@numba.njit(cache=True)
def bucket(grid, x, y):  # pragma: no cover
    """The bucket of ``(x, y)`` in ``grid = (size, a0, b0, na, nb)`` (clamped to the grid)."""
    size = grid[0]
    a = min(max(int(x // size) - int(grid[1]), 0), int(grid[3]) - 1)
    b = min(max(int(y // size) - int(grid[2]), 0), int(grid[4]) - 1)
    return b * int(grid[3]) + a


@numba.njit(cache=True)
def link(grid, head, nxt, xy, ids):  # pragma: no cover
    """Puts the points ``xy[ids]`` into the buckets of ``grid`` (``head``: each bucket's last id,
    ``nxt``: the id before it in its bucket)."""
    for i in ids:
        b = bucket(grid, xy[i, 0], xy[i, 1])
        nxt[i] = head[b]
        head[b] = i


@numba.njit(cache=True)
def _near(grid, head, nxt, x, y, out):  # pragma: no cover
    """The ids in the 3 × 3 buckets round ``(x, y)``, written to ``out``; their number returned."""
    size = grid[0]
    a0, b0, na, nb = int(grid[1]), int(grid[2]), int(grid[3]), int(grid[4])
    a, b = int(x // size) - a0, int(y // size) - b0
    c = 0
    for db in (-1, 0, 1):
        for da in (-1, 0, 1):
            u, v = min(max(a + da, 0), na - 1), min(max(b + db, 0), nb - 1)
            if u != a + da or v != b + db:
                continue
            i = head[v * na + u]
            while i >= 0:
                if c == out.shape[0]:
                    return -1
                out[c] = i
                c += 1
                i = nxt[i]
    return c


@numba.njit(cache=True)
def run(state, ivars, fvars, rel, size, rkind, relem, nkind, nsub, priority, centre_gap, coords, starts, flow,
        draws):  # fmt: skip  # pragma: no cover
    """Grow from the seeds in ``state`` until no seed is left (:data:`DONE`), an array is full
    (:data:`FULL`: enlarge and call again) or a relaxation is due (:data:`RELAX`).

    ``state`` is the tuple :func:`svgtile.engines.growth.grow.grow` builds (motifs, seeds, heap,
    bucket grids); ``ivars`` (int64: n, seeds, heap size, start ring, f, limit, relax_every,
    mode, top, levels, top priority, M) and ``fvars`` (float: r_short, reach, wait, mean length,
    w1, w2, w3, start x, start y) its counters and constants; ``flow`` = ``(table, x0, y0,
    step)``.  See that function for the rules; this is its loop."""
    (exy, ekind, esub, ering, etheta, enext, ehead, egrid, sxy, skind, alive, skey, snext, shead, whead, wnext,
     wgrid, hkey, hid) = state  # fmt: skip
    n, ns, hn, start_ring, f, limit, relax_every, mode, top, levels, toplevel, M = ivars[:12]
    r_short, reach, wait, mean_length, w1, w2, w3, sx0, sy0 = fvars[:9]
    R = rel.shape[0]
    ecap, scap = exy.shape[0], sxy.shape[0]
    table, fx0, fy0, fstep = flow
    ids = np.empty(256, np.int64)
    order = np.empty(256, np.int64)
    out_r = np.empty(top, np.int64)
    out_k = np.empty(top, np.int64)
    out_theta = np.empty(top)
    out_err = np.empty(top)
    while hn > 0 and n - f < limit:
        if n >= ecap or ns + M >= scap:
            break
        d0, s, hn = _heap_pop(hkey, hid, hn)
        if not alive[s]:
            continue
        x, y = sxy[s, 0], sxy[s, 1]
        want = skind[s]
        if levels:
            mine = toplevel if want < 0 else priority[want]
            c = _near(wgrid, whead, wnext, x, y, ids)
            while c < 0:
                ids = np.empty(2 * ids.shape[0], np.int64)
                c = _near(wgrid, whead, wnext, x, y, ids)
            later = -np.inf
            for i in range(c):
                q = ids[i]
                if (alive[q] and q != s and skind[q] >= 0 and priority[skind[q]] > mine
                        and (sxy[q, 0] - x) ** 2 + (sxy[q, 1] - y) ** 2 < wait * wait):  # fmt: skip
                    later = max(later, skey[q])
            if later > -np.inf:  # wait behind the farthest-queued higher-priority seed nearby
                skey[s] = max(d0, later) + 1e-9
                hn = _heap_push(hkey, hid, hn, skey[s], s)
                continue
        alive[s] = False
        c = _near(egrid, ehead, enext, x, y, ids)
        while c < 0:
            ids = np.empty(2 * ids.shape[0], np.int64)
            order = np.empty(ids.shape[0], np.int64)
            c = _near(egrid, ehead, enext, x, y, ids)
        # the placed motifs within reach, in the order found
        close = np.empty(c, np.int64)
        dist = np.empty(c)
        q = 0
        dmin = np.inf
        for i in range(c):
            e = ids[i]
            if closer(exy[e, 0] - x, exy[e, 1] - y, reach):
                d = np.hypot(exy[e, 0] - x, exy[e, 1] - y)
                close[q], dist[q] = e, d
                dmin = min(dmin, d)
                q += 1
        if q and dmin < r_short:
            continue  # merged (Fig. 6b)
        rel_t = np.empty((q, 2))
        for i in range(q):
            rel_t[i, 0], rel_t[i, 1] = exy[close[i], 0] - x, exy[close[i], 1] - y
        if order.shape[0] < q:
            order = np.empty(ids.shape[0], np.int64)
        t = ring_order(rel_t, order)
        tar = np.empty((t, 2))
        tkind = np.empty(t, np.int64)
        tsub = np.empty(t, np.int64)
        for j in range(t):
            tar[j, 0], tar[j, 1] = rel_t[order[j], 0], rel_t[order[j], 1]
            tkind[j], tsub[j] = ekind[close[order[j]]], esub[close[order[j]]]
        fa = 0.0
        if mode == FLOW:
            fi = min(max(int(np.rint((y - fy0) / fstep)), 0), table.shape[0] - 1)
            fj = min(max(int(np.rint((x - fx0) / fstep)), 0), table.shape[1] - 1)
            fa = table[fi, fj]
        if start_ring >= 0 and s == 0 and t == 0:
            got = 1
            out_r[0], out_k[0], out_theta[0], out_err[0] = start_ring, 0, fa, 0.0
        else:
            noise = draws.random(R)
            got = match(rel, size, rkind, nkind, nsub, mean_length, tar, tkind, tsub, want, mode, fa, w1, w2, w3,
                        noise, top, out_r, out_k, out_theta, out_err)  # fmt: skip
        # the best match whose element does not collide (Fig. 6d); none: the seed is dropped
        pick = -1
        for o in range(got):
            kind = rkind[out_r[o]]
            hit = False
            for i in range(q):
                if dist[i] < centre_gap[kind, ekind[close[i]]]:
                    hit = True
                    break
            if not hit:
                pick = o
                break
        if pick < 0:
            continue
        r, k, theta = out_r[pick], out_k[pick], out_theta[pick]
        exy[n, 0], exy[n, 1] = x, y
        ekind[n], esub[n], ering[n - f], etheta[n - f] = rkind[r], relem[r], r, theta
        b = bucket(egrid, x, y)
        enext[n] = ehead[b]
        ehead[b] = n
        n += 1

        # new seeds: the ring slots not matched with a placed neighbour (§5.4, Fig. 2f–g)
        m = size[r]
        matched = np.zeros(m, np.bool_)
        for j in range(t):
            matched[(k + j) % m] = True
        co, si = np.cos(theta), np.sin(theta)
        for slot in range(m):
            if matched[slot]:
                continue
            vx, vy = rel[r, slot, 0], rel[r, slot, 1]
            px = x + co * vx - si * vy
            py = y + si * vx + co * vy
            if not inside(px, py, coords, starts):
                continue
            c = _near(egrid, ehead, enext, px, py, ids)
            while c < 0:
                ids = np.empty(2 * ids.shape[0], np.int64)
                c = _near(egrid, ehead, enext, px, py, ids)
            taken = False
            for i in range(c):
                if closer(exy[ids[i], 0] - px, exy[ids[i], 1] - py, r_short):
                    taken = True
                    break
            if taken:
                continue
            c = _near(egrid, shead, snext, px, py, ids)  # seeds share the motifs' grid geometry
            while c < 0:
                ids = np.empty(2 * ids.shape[0], np.int64)
                c = _near(egrid, shead, snext, px, py, ids)
            for i in range(c):
                g = ids[i]
                if alive[g] and (sxy[g, 0] - px) ** 2 + (sxy[g, 1] - py) ** 2 < r_short * r_short:
                    taken = True
                    break
            if taken:
                continue
            ns = _add_seed(state, ns, px, py, nkind[r, slot], np.hypot(px - sx0, py - sy0), levels)
            hn = _heap_push(hkey, hid, hn, skey[ns - 1], ns - 1)
        if relax_every and (n - f) % relax_every == 0:
            ivars[0], ivars[1], ivars[2] = n, ns, hn
            return RELAX
    ivars[0], ivars[1], ivars[2] = n, ns, hn
    return DONE if hn == 0 or n - f >= limit else FULL


@numba.njit(cache=True)
def plant(state, xy, kind, key, levels):  # pragma: no cover
    """Adds the initial seeds ``xy`` ((s, 2) float; kinds (s,) int, −1 any; queue keys (s,)
    float) to the empty seed arrays, grids and heap; returns the heap size.  The first always
    enters the priority grid (as in the numpy version), the others when ``levels``."""
    hn = 0
    for q in range(xy.shape[0]):
        _add_seed(state, q, xy[q, 0], xy[q, 1], kind[q], key[q], levels or q == 0)
        hn = _heap_push(state[17], state[18], hn, key[q], q)
    return hn


@numba.njit(cache=True)
def _add_seed(state, ns, x, y, kind, key, levels):  # pragma: no cover
    """Appends seed ``ns`` to the seed arrays and grids; returns the new count (the caller queues it)."""
    sxy, skind, alive, skey, snext, shead, whead, wnext, egrid, wgrid = (state[8], state[9], state[10], state[11],
                                                                        state[12], state[13], state[14], state[15],
                                                                        state[7], state[16])  # fmt: skip
    sxy[ns, 0], sxy[ns, 1] = x, y
    skind[ns], alive[ns], skey[ns] = kind, True, key
    b = bucket(egrid, x, y)
    snext[ns] = shead[b]
    shead[b] = ns
    if levels:
        w = bucket(wgrid, x, y)
        wnext[ns] = whead[w]
        whead[w] = ns
    return ns + 1


@numba.njit(cache=True)
def normal_equations(ci, cj, b, f, pull):  # pragma: no cover
    """``AᵀA + λI`` as CSC arrays ``(data, indices, indptr)`` and ``Aᵀb`` ((f, 2) float) of the
    rows ``x_cj − x_ci = b`` ((e,) int, (e,) int, (e, 2) float; −1 marks a fixed end) over ``f``
    unknowns, λ = ``pull``: :func:`svgtile.engines.growth.relax._normal_equations`, which says
    why these are the sparse products bit for bit (off the diagonal sums of −1, exact in any
    order; ``Aᵀb`` summed row by row, the ``cj`` term of a row before its ``ci`` term)."""
    e = ci.shape[0]
    count = np.zeros(f, np.int64)  # rows per unknown: the diagonal of AᵀA
    rhs = np.zeros((f, 2))
    both = 0
    for q in range(e):
        if cj[q] >= 0:
            count[cj[q]] += 1
            rhs[cj[q], 0] += b[q, 0]
            rhs[cj[q], 1] += b[q, 1]
        if ci[q] >= 0:
            count[ci[q]] += 1
            rhs[ci[q], 0] += -b[q, 0]
            rhs[ci[q], 1] += -b[q, 1]
        if ci[q] >= 0 and cj[q] >= 0:
            both += 1
    key = np.empty(f + 2 * both, np.int64)  # column · f + row, as the canonical CSC order sorts
    for p in range(f):
        key[p] = p * f + p
    at = f
    for q in range(e):
        if ci[q] >= 0 and cj[q] >= 0:
            key[at] = cj[q] * f + ci[q]
            key[at + 1] = ci[q] * f + cj[q]
            at += 2
    key = np.sort(key)
    data = np.empty(key.shape[0])
    indices = np.empty(key.shape[0], np.int32)
    indptr = np.zeros(f + 1, np.int32)
    n = 0
    for p in range(key.shape[0]):
        if n and key[p] == key[p - 1]:
            data[n - 1] -= 1.0
            continue
        col, row = key[p] // f, key[p] % f
        data[n] = count[col] + pull if row == col else -1.0
        indices[n] = row
        indptr[col + 1] += 1
        n += 1
    for p in range(f):
        indptr[p + 1] += indptr[p]
    return data[:n].copy(), indices[:n].copy(), indptr, rhs


@numba.njit(cache=True)
def ring_slots(rel, size, ring, co, si, first):  # pragma: no cover
    """Where each grown motif's ring wants its neighbours (§5.5): for motif ``first + g`` copying
    reference ring ``ring[g]`` turned by the angle of cosine ``co[g]`` and sine ``si[g]``, one
    row per slot of that ring, in order — the motif's index ((s,) int) and the slot's offset
    ((s, 2) float, user units).  ``co``, ``si`` come from numpy (its cos and sin may differ from
    compiled code's in the last bit)."""
    total = 0
    for g in range(ring.shape[0]):
        total += size[ring[g]]
    idx = np.empty(total, np.int64)
    want = np.empty((total, 2))
    at = 0
    for g in range(ring.shape[0]):
        r = ring[g]
        for slot in range(size[r]):
            idx[at] = first + g
            want[at, 0] = co[g] * rel[r, slot, 0] - si[g] * rel[r, slot, 1]
            want[at, 1] = si[g] * rel[r, slot, 0] + co[g] * rel[r, slot, 1]
            at += 1
    return idx, want
