"""Structural compliance of the teeth: shell Rayleigh-Ritz model and 3D finite elements.

- :mod:`.tooth`: one tooth between its real drive and coast flanks (mid-surface,
  thickness, flank load points), and the rectangular test plate;
- :mod:`.cylindrical_tooth`: the involute (spur/helical) tooth as such a body, with its
  fillet, rim and calibrated shell;
- :mod:`.rim`: the root fillet and rim segment below a tooth's root line, one geometry
  for the shell and the FE;
- :mod:`.root_fillet`: the real root of a cut tooth (its cutter's fillets, the slot
  bottoms, the rim block) for the FE, and its ISO 6336-3 30 deg critical section;
- :mod:`.shell`: Mindlin-Reissner plate Rayleigh-Ritz compliance operator (low rank)
  over the tooth, its fillet and rim;
- :mod:`.fe`: 3D finite elements of the tooth with its rim segment (scikit-fem, the
  optional ``fe`` extra), the independent truth of the shell model;
- :mod:`.compliance`: flank-grid compliance tables of a pair (shell and FE), as the
  ``gearcontact bending`` command writes them.
"""
