"""The mesh FMU's contact law in Python: the twin's law at one instant, no state.

:class:`MeshLawTable` holds what ``gearcontact export fmu --kind mesh`` bakes into the
FMU (the loaded flank's :class:`~gearcontact.twin.mesh.MeshTable` rows, curvatures the
TCA's A-, B-); :func:`mesh_outputs` evaluates the outputs of the FMU at given inputs
with the twin's own compiled contact law (:func:`gearcontact.twin.contact_law._kappa`,
``curvatures="exact"``; rigid teeth, or the pairs' tooth bending in series,
:func:`gearcontact.twin.contact_law._pair_load`), the reference the C code of the FMU is tested
against (docs/export.md, "The mesh FMU").

The law, at pinion and gear angles ``psi_p``, ``psi_g`` along the motion (rad, the
twin's coordinates, :mod:`gearcontact.twin.mesh`) and their speeds:

* row interval ``(i, f)`` of ``psi_p`` modulo the pitch, ``eps`` and ``deps/dpsi``
  interpolated, ``theta = psi_p / u + eps - psi_g``, ``theta' = w_p (1/u + eps') - w_g``;
* per pair valid at both rows with ``d_j = l_j theta - g_j > 0``: ``kappa_j`` from one
  preview (stage D on the interpolated A-, B-) at the load ``W_eval``, ``W_j = (d_j /
  kappa_j)^(3/2)`` (with tooth bending, ``d_j = kappa_j W_j^(2/3) + c_b W_j`` by the
  twin's Newton, started afresh: no state). The twin samples the preview at the pair's load of its previous
  step; the FMU has no step of its own (model exchange), so it samples twice: at 1 N
  (:data:`~gearcontact.twin.contact_law.W_EVAL_MIN_N`), then at the load that gives,
  clamped to the datapath envelope (1 .. 2^17 N). fp64: kappa is the approach at 1 N
  in both passes (the twin's law, :func:`~gearcontact.twin.contact_law._kappa_reference`),
  a, b, p_max scaled from there; golden: the fixed point's rounding at the actual load;
* the domain counts: per closed pair its last preview (the one at 1 N where it has no
  law, else the one at its load) counted as the twin's ``_fp64_law`` counts previews
  (``tcount[3]``: outside the datapath's domain, the fp64 law evaluating it;
  ``tcount[5]``: without a contact law, the pair then carries nothing);
* ``T = max(sum_j 1e-3 W_j l_j + 1e-3 c_m l_0^2 theta', 0)`` (gear torque along the
  motion, N·m) while ``T_el > 0``; the pinion's torque is ``-T (1/u + eps')`` (the
  twin's equation of motion); TE in the TCA's sign ``m (eps - theta)`` arcsec.
  ``theta < 0``: the loaded flank is open (the reverse flank is not in this element),
  every output but the TE 0.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..tca.types import ARCSEC_PER_RAD
from ..preview.hertz.formats import DEFAULT_HERTZ_FORM
from ..preview.fit.golden import element_constants
from ..preview.fit.pinv import N_COEFFS, N_TAPS
from ..preview.hertz.golden import encode_e_prime
from ..preview.hertz.golden_vec import golden_constants
from ..preview.hertz.reference import ENVELOPE
from ..twin import layout as L
from ..validation import InputRangeError
from ..twin.exact_hertz import exact_hertz_table
from ..twin.contact_law import W_EVAL_MIN_N, _W_EVAL_MAX_N, _kappa, _pair_load

__all__ = ["MeshLawTable", "MeshOutputs", "mesh_law_table", "mesh_outputs", "BACKENDS", "law_of",
           "closed_pairs"]

#: The FMU's ``backend`` parameter: name -> enumeration value (the twin's backend).
BACKENDS = {"fp64": 0, "golden": 1}


@dataclass(frozen=True, eq=False)
class MeshLawTable:
    """The loaded flank's mesh rows baked into the FMU (module docstring).

    Attributes
    ----------
    eps_rad : ndarray (K,)
        Unloaded TE envelope along the motion, rad of gear rotation.
    lever_mm, opening_mm, A_minus_per_mm, B_minus_per_mm : ndarray (P, K)
        Per pair and row (0 where not valid).
    valid : ndarray (P, K) of bool
    step_rad, pitch_rad : float
        Row step and pinion pitch, rad.
    ratio : float
        ``u = z2 / z1``.
    reference_lever_mm : float
        Lever of the mesh damping, mm.
    e_prime_mpa : float
        Effective modulus E', MPa.
    motion_sign : int
        ``m`` of the TCA (+1 / -1).
    bending_mm_per_n : ndarray (P, K) or None
        Tooth-bending compliance of each pair, mm/N (None: rigid teeth).
    hertz_form : str
        The fp64 law's Hertz form (``"exact"``: the twin's exact Hertz,
        :mod:`gearcontact.twin.exact_hertz`; the table's rows are then the twin's exact
        form's, :func:`gearcontact.twin.model.exact_form_mesh`).
    """

    eps_rad: np.ndarray
    lever_mm: np.ndarray
    opening_mm: np.ndarray
    A_minus_per_mm: np.ndarray
    B_minus_per_mm: np.ndarray
    valid: np.ndarray
    step_rad: float
    pitch_rad: float
    ratio: float
    reference_lever_mm: float
    e_prime_mpa: float
    motion_sign: int
    bending_mm_per_n: np.ndarray | None = None
    hertz_form: str = DEFAULT_HERTZ_FORM

    def to_npz(self, path) -> None:
        """Write the table as ``.npz`` (every attribute under its name; no
        ``bending_mm_per_n`` for rigid teeth, no ``hertz_form`` for the default form)."""
        np.savez(path, **{k: np.asarray(v) for k, v in self.__dict__.items()
                          if v is not None
                          and not (k == "hertz_form" and v == DEFAULT_HERTZ_FORM)})

    @classmethod
    def from_npz(cls, path) -> "MeshLawTable":
        """Read a table written by :meth:`to_npz`."""
        with np.load(path) as z:
            kw = {k: z[k] for k in z.files}
        for k in ("step_rad", "pitch_rad", "ratio", "reference_lever_mm", "e_prime_mpa"):
            kw[k] = float(kw[k])
        kw["motion_sign"] = int(kw["motion_sign"])
        if "hertz_form" in kw:
            kw["hertz_form"] = str(kw["hertz_form"])
        return cls(**kw)


def mesh_law_table(mesh, *, hertz_form: str = DEFAULT_HERTZ_FORM) -> MeshLawTable:
    """The FMU's table of a :class:`~gearcontact.twin.mesh.MeshTable` (loaded flank);
    its bending compliance if any pair has one (else rigid teeth); ``hertz_form`` the
    fp64 law's (``mesh`` already the form's, :func:`gearcontact.twin.model.
    exact_form_mesh`)."""
    cb = mesh.bending_mm_per_n
    return MeshLawTable(
        eps_rad=np.asarray(mesh.eps_rad, float), lever_mm=np.asarray(mesh.lever_mm, float),
        opening_mm=np.asarray(mesh.opening_mm, float),
        A_minus_per_mm=np.asarray(mesh.A_minus_per_mm, float),
        B_minus_per_mm=np.asarray(mesh.B_minus_per_mm, float),
        valid=np.asarray(mesh.valid, bool), step_rad=float(mesh.step_rad),
        pitch_rad=float(mesh.pitch_rad), ratio=float(mesh.ratio),
        reference_lever_mm=float(mesh.reference_lever_mm),
        e_prime_mpa=float(mesh.e_prime_mpa), motion_sign=int(mesh.motion_sign),
        bending_mm_per_n=None if cb is None or not np.any(np.asarray(cb) > 0.0)
        else np.asarray(cb, float), hertz_form=hertz_form)


@dataclass(frozen=True)
class MeshOutputs:
    """The mesh FMU's outputs at one instant (units in the names)."""

    torque_pinion_nm: float
    torque_gear_nm: float
    mesh_force_n: float
    te_arcsec: float
    p_max_mpa: float
    a_mm: float
    b_mm: float
    active_pairs: int
    #: closed pairs whose preview lies outside the datapath's domain, and closed pairs
    #: without a contact law, as the twin counts previews (module docstring; a
    #: cylindrical pair's: :mod:`.line_mesh_law`)
    pairs_outside_datapath: int
    pairs_without_contact_law: int


class _Law:
    """The twin kernel's arguments for one table (built once per table)."""

    def __init__(self, tab: MeshLawTable):
        self.prm = np.zeros(L.N_PRM)
        self.prm[L.P_EP] = tab.e_prime_mpa
        self.prm[L.P_ECODE] = encode_e_prime(tab.e_prime_mpa)
        self.prm[L.P_STAGEC] = L.CURVATURE_SOURCES["exact"]
        self.prm[L.P_CLO], self.prm[L.P_CHI] = ENVELOPE["curvature_per_mm"]
        self.prm[L.P_AHI] = ENVELOPE["alpha"][1]
        if tab.hertz_form != DEFAULT_HERTZ_FORM:    # the twin's exact form (model._prm)
            self.prm[L.P_HFORM] = L.HERTZ_FORM_CODES[tab.hertz_form]
            self.prm = np.concatenate([self.prm, exact_hertz_table()])
        self.cv = np.stack([tab.A_minus_per_mm, tab.B_minus_per_mm], axis=-1)[None].copy()
        self.pow_lut, self.cbrt_lut, self.cst = golden_constants()
        fit_w, fit_cst = element_constants()
        self.fit = (fit_w, fit_cst, np.zeros((1, N_TAPS), np.int64),
                    np.zeros((1, N_COEFFS), np.int64), np.zeros((0, N_TAPS), np.int64))
        self.trace = np.zeros((0, 9), np.int64)
        self.tcount = np.zeros(L.N_COUNT, np.int64)

    def kappa(self, j, i, f, we, backend, out3):
        return _kappa(0, j, i, f, we, self.prm, self.cv, backend, self.pow_lut,
                      self.cbrt_lut, self.cst, self.trace, self.tcount, self.fit, out3)


_LAWS: dict = {}


def mesh_outputs(tab: MeshLawTable, phi_pinion_rad: float, phi_gear_rad: float,
                 omega_pinion_rad_s: float, omega_gear_rad_s: float, *, backend: str,
                 mesh_damping_n_s_per_mm: float = 0.0) -> MeshOutputs:
    """Outputs of the mesh FMU at one instant (module docstring for the law).

    Parameters
    ----------
    tab : MeshLawTable
        The baked table.
    phi_pinion_rad, phi_gear_rad : float
        Pinion and gear angles along the motion, rad (the twin's ``psi_p``, ``psi_g``).
    omega_pinion_rad_s, omega_gear_rad_s : float
        Their speeds, rad/s.
    backend : str
        ``"fp64"`` or ``"golden"`` (:data:`BACKENDS`).
    mesh_damping_n_s_per_mm : float
        Mesh damping ``c_m`` on the line of action, N·s/mm.
    """
    if tab.hertz_form != DEFAULT_HERTZ_FORM and backend != "fp64":
        raise InputRangeError("backend", backend, f"fp64 with the {tab.hertz_form} Hertz "
                                                  "form (the golden stage D is "
                                                  "Hamrock-Brewe's)")
    law = law_of(tab, _Law)
    code = BACKENDS[backend]
    i, f, de, theta, theta_dot, te = _kinematics(tab, phi_pinion_rad, phi_gear_rad,
                                                 omega_pinion_rad_s, omega_gear_rad_s)
    if theta < 0.0:
        return MeshOutputs(0.0, 0.0, 0.0, te, 0.0, 0.0, 0.0, 0, 0, 0)
    out3 = np.zeros(L.N_PREVIEW)
    t_el = w_tot = w_max = 0.0
    abp = (0.0, 0.0, 0.0)
    pairs = 0
    cbs = tab.bending_mm_per_n
    tc = law.tcount
    counts = np.zeros(2, np.int64)      # the pairs' last previews' tcount[3], tcount[5]
    for j, lv, d in closed_pairs(tab, i, f, theta):
        before = tc[3], tc[5]
        kap = law.kappa(j, i, f, W_EVAL_MIN_N, code, out3)
        if kap <= 0.0:      # no contact law (a saddle): the pair carries nothing
            counts += (tc[3] - before[0], tc[5] - before[1])
            continue
        cb = 0.0 if cbs is None else cbs[j, i] + f * (cbs[j, i + 1] - cbs[j, i])
        we = min(max(_pair_load(d, kap, cb, 0.0)[0], W_EVAL_MIN_N), _W_EVAL_MAX_N)
        before = tc[3], tc[5]
        kap = law.kappa(j, i, f, we, code, out3)
        counts += (tc[3] - before[0], tc[5] - before[1])
        if kap <= 0.0:
            continue
        w = _pair_load(d, kap, cb, 0.0)[0]
        t_el += 1e-3 * w * lv
        w_tot += w
        pairs += 1
        if w > w_max:
            w_max = w
            # Hertz similarity a, b, p ~ W^(1/3) from the load they hold at
            scale = (w / out3[L.PV_LOAD]) ** (1.0 / 3.0)
            abp = (out3[0] * scale, out3[1] * scale, out3[2] * scale)
    return _outputs(tab, t_el, w_tot, abp, pairs, de, theta_dot, te,
                    mesh_damping_n_s_per_mm, counts=(int(counts[0]), int(counts[1])))


def law_of(tab, factory):
    """The compiled law's arguments of ``tab`` (``factory(tab)``), built once per table."""
    law = _LAWS.get(id(tab))
    if law is None or law[0] is not tab:
        law = _LAWS[id(tab)] = (tab, factory(tab))
    return law[1]


def closed_pairs(tab, i, f, theta):
    """``(j, lever mm, approach d mm)`` of every pair valid at both rows (i, i + 1) whose
    approach ``d = l theta - g`` at the fraction f is positive (kernel._elastic's test)."""
    for j in range(tab.lever_mm.shape[0]):
        if not (tab.valid[j, i] and tab.valid[j, i + 1]):
            continue
        lv = tab.lever_mm[j, i] + f * (tab.lever_mm[j, i + 1] - tab.lever_mm[j, i])
        g = tab.opening_mm[j, i] + f * (tab.opening_mm[j, i + 1] - tab.opening_mm[j, i])
        d = lv * theta - g
        if d > 0.0:
            yield j, lv, d


def _kinematics(tab, phi_pinion_rad, phi_gear_rad, omega_pinion_rad_s, omega_gear_rad_s):
    """``(i, f, eps', theta, theta', TE arcsec)`` of the inputs on the table's rows
    (module docstring)."""
    u = tab.ratio
    k_rows = tab.eps_rad.shape[0]
    x = phi_pinion_rad - tab.pitch_rad * math.floor(phi_pinion_rad / tab.pitch_rad)
    q = x / tab.step_rad
    i = min(int(q), k_rows - 2)
    f = q - i
    eps = tab.eps_rad
    e = eps[i] + f * (eps[i + 1] - eps[i])
    de = (eps[i + 1] - eps[i]) / tab.step_rad
    theta = phi_pinion_rad / u + e - phi_gear_rad
    theta_dot = omega_pinion_rad_s * (1.0 / u + de) - omega_gear_rad_s
    te = tab.motion_sign * (e - theta) * ARCSEC_PER_RAD
    return i, f, de, theta, theta_dot, te


def _outputs(tab, t_el, w_tot, abp, pairs, de, theta_dot, te, damping, *,
             counts) -> MeshOutputs:
    """The outputs of the pairs' elastic torque ``t_el`` (N·m) with the mesh damping;
    ``counts``: the domain counts (:class:`MeshOutputs`), whatever the torque."""
    if t_el <= 0.0:
        return MeshOutputs(0.0, 0.0, 0.0, te, 0.0, 0.0, 0.0, 0, *counts)
    l0 = tab.reference_lever_mm
    t = max(t_el + 1e-3 * damping * l0 * l0 * theta_dot, 0.0)
    return MeshOutputs(-t * (1.0 / tab.ratio + de), t, w_tot, te, abp[2], abp[0], abp[1],
                       pairs, *counts)
