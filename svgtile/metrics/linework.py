"""Likeness of linework: does a cellular texture look like its tile, the way a reader sees it?

A bedded or brick pattern (FGDC limestones, the interbedded series, osm-carto hatching) is
drawn as lines, not as motifs, so the motif figures (density ρ, likeness L) do not apply to it.
What a cartographer checks, looking at the legend beside the map, is (a) whether the fill is as
dark as the tile and (b) whether its lines run the same ways at the same spacings.  Both are
measured on the two drawings **rendered at one scale over one window** (the caller renders:
:func:`svgtile.apps.linework.measure_tile` stamps the tile and draws the texture with resvg):

* **ink** — the texture's mean ink over the tile's, both as grey levels (0 white … 1 black)
  over the window: the analogue of density ρ, 1 as dark as the tile (bound 0.9–1.1, as for ρ);
* **structure** S — the power spectrum of each image (a Hann window, mean removed) summed in
  bins of orientation (:data:`ORIENTATIONS` of 180°/n) × spacing (:data:`OCTAVES` octaves in
  half-octave bins, up from :data:`FINEST` pixels; each wave shared linearly between its two
  nearest bins of each axis), weighted by the wavelength (a thin stroke's harmonics, at 1/k of its
  spacing, weigh 1/k: the spacing the eye reads leads) and normalised to total 1, so S sees
  *where the ink runs and how far apart* and not how much of it there is.  The distance ``D`` is
  half the L1 distance of the two normalised spectra — the share of the tile's line energy that
  sits at another orientation or spacing in the texture — and is placed between the tile (D 0)
  and the tile's own ink scattered as dust (its pixels shuffled with :data:`BASELINE_SEED`:
  every orientation and spacing alike)::

      S = 1 − D(texture, tile) / D(dust, tile)

  S = 1: the same orientations and spacings as the tile; S = 0: no more like it than its ink
  sprinkled at random; below 0, less (a nearly isotropic tile whose dust lies close to it).  A
  flat tile (a solid fill, :data:`FLAT`) has no spectrum: S is 1 if the
  texture is flat too, else 0.  A grid of straight lines for wavy contorted gneiss, bricks without a
  tile's ticks, a fine grid for rows of root marks all move energy to other bins.

The images are compared in the same pixels, so the window and the scale must be the same for
both (the window is chosen away from the texture's clipped edge by the caller).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

#: Orientation bins over [0°, 180°).
ORIENTATIONS = 12
#: Spacing bins: half-octaves of the wavelength, from :data:`FINEST` pixels up over this many octaves.
OCTAVES = 6
#: The finest wavelength measured, pixels (finer is the strokes' own anti-aliased width).
FINEST = 3.0
#: A grey image whose 1st and 99th percentile levels differ by less than this is flat: a solid fill
#: (the percentiles, not the extremes: a stamped fill shows hairline seams where its tiles meet).
FLAT = 0.05
#: Seed of the dust baseline's shuffle.
BASELINE_SEED = 0
#: A texture as dark as its tile: ink ratio within these bounds (as density ρ).
INK_BOUNDS = (0.9, 1.1)
#: A texture whose lines run like its tile's: structure S at least this.  On lines 16 px apart
#: (tests/test_cellular_linework.py): 17 px apart scores 0.87, 24 px 0.66, 8 px 0.41, turned 90° < 0;
#: the bound lies between "a hair off" and "half as far again".
STRUCTURE_MIN = 0.75


@dataclass(frozen=True)
class Linework:
    """The figures of one texture against its tile (module docstring).

    ink : texture ink ÷ tile ink over the window (1 as dark; NaN for a blank tile)
    structure : S, 1 − D / D_dust (1 the tile's orientations and spacings, 0 dust)
    distance : D, half the L1 distance of the normalised spectra (0 … 1)
    dust : D of the tile's ink scattered as dust (the baseline)
    """

    ink: float
    structure: float
    distance: float
    dust: float

    @property
    def passes(self) -> bool:
        return INK_BOUNDS[0] <= self.ink <= INK_BOUNDS[1] and self.structure >= STRUCTURE_MIN


def spectrum(img: np.ndarray) -> np.ndarray:
    """(ORIENTATIONS, 2·OCTAVES) the power spectrum of the grey image ``img`` (h, w; 0 … 1 ink)
    summed by orientation of the lines (the wave vector turned by 90°) and half-octave of their
    spacing (wavelength from :data:`FINEST` pixels up), normalised to total 1 (all zeros for a
    blank image)."""
    h, w = img.shape
    a = (img - img.mean()) * np.outer(np.hanning(h), np.hanning(w))
    p = np.abs(np.fft.rfft2(a)) ** 2  # (h, w//2 + 1)
    fy = np.broadcast_to(np.fft.fftfreq(h)[:, None], p.shape)
    fx = np.broadcast_to(np.fft.rfftfreq(w)[None, :], p.shape)
    f = np.hypot(fx, fy)  # cycles per pixel
    keep = (f > 0) & (f <= 1.0 / FINEST) & ~((fx == 0) & (fy < 0))  # the rfft's x = 0 column holds each wave twice
    bands = 2 * OCTAVES
    # each wave shared linearly between the two nearest bins of each axis (soft bins: a spacing a
    # hair either side of a bin's edge weighs alike)
    b = 2.0 * np.log2(1.0 / (FINEST * f[keep])) - 0.5  # half-octaves up from the finest, bin centres at integers
    o = ((np.degrees(np.arctan2(fy[keep], fx[keep])) + 90.0) % 180.0) / (180.0 / ORIENTATIONS) - 0.5
    weight = p[keep] / f[keep]  # × wavelength: a stroke's harmonics weigh 1/k, its spacing leads
    b0, o0 = np.floor(b), np.floor(o)
    tb, to = b - b0, o - o0
    out = np.zeros(ORIENTATIONS * bands)
    for db, wb in ((0, 1.0 - tb), (1, tb)):
        bi = b0.astype(np.int64) + db
        inside = (bi >= 0) & (bi < bands)
        for do, wo in ((0, 1.0 - to), (1, to)):
            oi = (o0.astype(np.int64) + do) % ORIENTATIONS  # orientation wraps round
            out += np.bincount((oi * bands + bi)[inside], weights=(weight * wb * wo)[inside], minlength=out.size)
    total = out.sum()
    return (out / total if total > 0 else out).reshape(ORIENTATIONS, bands)


def distance(a: np.ndarray, b: np.ndarray) -> float:
    """Half the L1 distance of two normalised spectra (:func:`spectrum`): 0 the same, 1 disjoint."""
    return 0.5 * float(np.abs(a - b).sum())


def dust(img: np.ndarray, seed: int = BASELINE_SEED) -> np.ndarray:
    """``img``'s pixels shuffled (explicit generator): the same ink, no lines."""
    flat = img.ravel().copy()
    np.random.default_rng(seed).shuffle(flat)
    return flat.reshape(img.shape)


def measure(tile: np.ndarray, texture: np.ndarray) -> Linework:
    """The figures of ``texture`` against ``tile``: two grey images (h, w; 0 white … 1 black) of
    the same window at the same scale (the stamped tile and the synthesized texture)."""
    if tile.shape != texture.shape:
        raise ValueError(f"images differ in shape: {tile.shape} and {texture.shape}")
    ink_tile = float(tile.mean())
    ink = float(texture.mean()) / ink_tile if ink_tile > 0 else math.nan
    if _flat(tile):  # a solid fill (FGDC 658, Equinor 21000): alike if the texture is flat too
        d = 0.0 if _flat(texture) else 1.0
        return Linework(ink=ink, structure=1.0 - d, distance=d, dust=1.0)
    st = spectrum(tile)
    d = distance(spectrum(texture), st)
    base = distance(spectrum(dust(tile)), st)
    s = 1.0 - d / base if base > 0 else math.nan
    return Linework(ink=ink, structure=s, distance=d, dust=base)


def _flat(img: np.ndarray) -> bool:
    lo, hi = np.percentile(img, [1.0, 99.0])
    return bool(hi - lo < FLAT)


def grey(png: bytes) -> np.ndarray:
    """(h, w) ink of a rendered PNG on white: 0 white … 1 black (float64)."""
    import io

    from PIL import Image

    return 1.0 - np.asarray(Image.open(io.BytesIO(png)).convert("L"), dtype=np.float64) / 255.0
