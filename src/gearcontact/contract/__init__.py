"""The data contract between the host and the datapath: Q formats and the 7 x 7 stencil.

Both sides use it and neither owns it: the host TCA writes the phase table in these
fixed-point formats and samples the gap on the stencil (:mod:`gearcontact.tca`); the
three datapath stages (:mod:`gearcontact.preview`) read them. docs/spec.md sec. 6.
"""
