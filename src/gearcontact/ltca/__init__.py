"""Loaded tooth contact analysis (LTCA) of a gear pair on the elastic half-space.

The gear side of loaded contact, built on :mod:`gearcontact.halfspace`: the single-pair
LTCA at a mesh phase (:mod:`.pair_ltca`), the loaded transmission error over one pitch
with every pair that can touch (:mod:`.lte`, :mod:`.lte_pairs`, :mod:`.mesh_lcp`), the
multi-tooth LTCA at P0 (:mod:`.multitooth`), the shell bending of both teeth in the
coupled LCP (:mod:`.tooth_bending`; cylindrical pairs :mod:`.cylindrical_lte`, its
tip-edge blocks :mod:`.cylindrical_edges` and :mod:`.cylindrical_bending`) and the export of one LCP problem
(:mod:`.problem_export`). The unloaded TCA (:mod:`gearcontact.tca`) gives the mating
points, normals and curvatures these start from.
"""
