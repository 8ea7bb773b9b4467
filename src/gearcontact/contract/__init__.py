"""The data contract between the host and the datapath: Q formats, the 7 x 7 stencil and
the input envelope of stage D.

Both sides use it and neither owns it: the host TCA writes the phase table in these
fixed-point formats and samples the gap on the stencil (:mod:`gearcontact.tca`); the
three datapath stages (:mod:`gearcontact.preview`) read them, and stage D accepts the
input codes of :mod:`.envelope`. docs/spec.md sec. 6.
"""
