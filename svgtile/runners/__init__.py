"""Runners: how a region or a whole map is cut into units of work and where those units run.

* :mod:`~svgtile.runners.tiling` — one region cut into world-anchored tiles, each synthesized
  with a halo of its engine's ``reach``; the union is the whole run, byte for byte;
* :mod:`~svgtile.runners.schedule` — units of work run by Dask: its local scheduler on this
  machine, a ``distributed.LocalCluster`` of worker processes, or a cluster at an address;
  results are handed over as they finish, failures one line each;
* :mod:`~svgtile.runners.spool` — finished pieces kept on disk until the output file is
  assembled in world order (the writer never holds the whole map).
"""
