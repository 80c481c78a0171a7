"""Discrete element texture optimisation (Ma, Wei & Tong 2011) in 2-D: the ``optimize`` engine
and ``--refine N`` for every engine.

Read in this order: :mod:`.samples` (§3.1, the exemplar's elements and neighbourhoods, and the
k-coherence similarity sets of §4.2), :mod:`.match` (§3.2 eq. (1), greedy pairing, returning the
pairing), :mod:`.search` (§4.2), :mod:`.assign` (§4.3 eq. (3)–(5)), :mod:`.controls` (§5: flow and
the interleaved non-penetration step), :mod:`.solver` (§4 Pseudocode 1), :mod:`.init` (§4.1, the
patch start), :mod:`.engine`, and :mod:`.edit` (§6.3, ``svgtile propagate``).
"""
