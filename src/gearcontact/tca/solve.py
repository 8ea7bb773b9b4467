"""Unloaded tooth contact analysis (TCA): the mating point of two flanks per mesh phase.

At a pinion rotation ``phi1`` the posed flanks touch where they share position and
normal (Litvin & Fuentes 2004, sec. 9.4 and ch. 15 "TCA"):

.. math::

    \\mathbf r_f^{(1)}(u_1, v_1, \\phi_1) - \\mathbf r_f^{(2)}(u_2, v_2, \\phi_2) = 0
    \\quad (3), \\qquad
    (\\mathbf n_f^{(1)} + \\mathbf n_f^{(2)}) \\cdot \\mathbf t_{a,b} = 0 \\quad (2),

with both unit normals pointing out of their own tooth (so ``n1 = -n2`` at contact) and
``t_a, t_b`` an orthonormal basis of the gear's tangent plane. The five unknowns are
``(u1, v1, u2, v2, phi2)`` for a given ``phi1``; :func:`solve_mating_point` can fix any
one of the six variables instead (e.g. the gear's profile parameter, to start the path
exactly at the mean point). Newton's method uses the analytic Jacobian from the
surface derivatives: ``d n / d(u, v) = -[r_u r_v] I^-1 II`` (Weingarten equations, do
Carmo 1976, sec. 3-3) and ``d X_f / d phi = w x (X_f - c)`` for a rotation about an
axis ``w`` through ``c``. The term ``(n1 + n2) . d t`` is dropped: it vanishes at the
solution, so convergence stays quadratic.

Member 1 is the pinion, member 2 the gear; poses come from
:class:`~gearcontact.geometry.kinematics.MeshKinematics` (assembly errors included).
Iterates are kept inside the flanks' parameter boxes: a solution that would lie
outside is reported as *edge contact* (:class:`EdgeContact`), never extrapolated.

Transmission error (docs/geometry.md sec. 4):
``TE0 = (phi2 - phi2_0) - (z1/z2)(phi1 - phi1_0)`` converted to arcsec
(x 206264.806), relative to the reference (mean) mating point ``(phi1_0, phi2_0)``.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
from tqdm import tqdm

from ..errors import CheckFailed
from ..geometry.kinematics import MeshKinematics
from ..geometry.surface import Surface, SurfacePoint
from ..validation import check_positive

__all__ = ["ARCSEC_PER_RAD", "EDGE_TE_LIMIT_ARCSEC", "VARIABLES", "ContactGuess",
           "MatingPoint", "TcaPath", "EdgeContact", "TcaConvergenceError",
           "solve_mating_point", "solve_tca",
           "posed_point", "normal_derivatives"]

#: Arc seconds per radian (180 * 3600 / pi).
ARCSEC_PER_RAD = 206264.80624709636
#: Default limit of a path's edge tails: an edge contact whose TE0 lies this far behind
#: the path's first touch ends the path (arcsec); the nominal s0003 meshes have TE0 p-p
#: of ~3 arcsec, and :func:`~gearcontact.tca.mesh.mesh_cycle` widens the limit when a
#: mesh's TE0 p-p exceeds half of it.
EDGE_TE_LIMIT_ARCSEC = 20.0
#: Order of the six contact variables in every vector of this module.
VARIABLES = ("u1", "v1", "u2", "v2", "phi1", "phi2")


class EdgeContact(Exception):
    """The mating point left a flank's parameter box (edge contact).

    Attributes
    ----------
    phi1_rad : float
        Pinion mesh phase at which the contact left the flank, rad.
    where : str
        The boundary, e.g. ``"pinion v max"``.
    """

    def __init__(self, phi1_rad: float, where: str):
        self.phi1_rad = float(phi1_rad)
        self.where = where
        super().__init__(f"edge contact at phi1 = {np.degrees(phi1_rad):.6f} deg: the "
                         f"mating point leaves the flank at the {where} boundary")


class TcaConvergenceError(CheckFailed):
    """Newton's method did not converge at a mesh phase (a failed check, exit 4, when it
    escapes a run).

    Attributes
    ----------
    phi1_rad : float
        Pinion mesh phase, rad.
    residual : float
        Final residual norm (mm for position, dimensionless for the normal part).
    """

    def __init__(self, phi1_rad: float, residual: float, iterations: int):
        self.phi1_rad = float(phi1_rad)
        self.residual = float(residual)
        super().__init__(f"TCA Newton solve did not converge at mesh phase phi1 = "
                         f"{np.degrees(phi1_rad):.6f} deg: residual {residual:.3e} after "
                         f"{iterations} iterations")


@dataclass(frozen=True)
class ContactGuess:
    """A (guessed or known) contact state: both parameter pairs and both rotations.

    Parameters are the flank parameters of pinion (``u1, v1``) and gear (``u2, v2``)
    and the rotations ``phi1_rad`` (pinion, about -x) and ``phi2_rad`` (gear, about +z).
    """

    u1: float
    v1: float
    u2: float
    v2: float
    phi1_rad: float
    phi2_rad: float

    def vector(self) -> np.ndarray:
        """The state as a (6,) array in the order of :data:`VARIABLES`."""
        return np.array([self.u1, self.v1, self.u2, self.v2, self.phi1_rad, self.phi2_rad])

    @classmethod
    def from_vector(cls, x) -> "ContactGuess":
        return cls(*(float(xi) for xi in x))


@dataclass(frozen=True)
class MatingPoint:
    """TCA result at one mesh phase.

    Attributes
    ----------
    phi1_rad, phi2_rad : float
        Pinion and gear rotations, rad.
    u1, v1, u2, v2 : float
        Flank parameters of the mating point on pinion and gear.
    point_mm : ndarray (3,)
        Mating point in the meshing frame, mm.
    normal : ndarray (3,)
        Common unit normal in the meshing frame: the gear's normal, out of the gear
        tooth (into the pinion tooth).
    te0_arcsec : float
        Unloaded transmission error relative to the path's reference point, arcsec.
    residual : float
        Final residual norm of the five equations.
    iterations : int
        Newton iterations used.
    edge : bool
        True if the pair has no contact at this phase: no interior mating point and no
        edge touching the other flank (:mod:`gearcontact.tca.edge_contact`); all
        geometric fields are then NaN and ``edge_where`` names the boundary crossed.
    edge_where : str
        Boundary crossed (``""`` for interior contact).
    edge_contact : str
        ``""`` for surface-to-surface contact; else the flank edge (``"pinion toe"``,
        ...) whose point ``(u, v)`` (on that member's boundary) touches the other
        flank's surface: an edge contact, with finite fields (``normal``: the touched
        surface's, oriented like every mating normal).
    """

    phi1_rad: float
    phi2_rad: float
    u1: float
    v1: float
    u2: float
    v2: float
    point_mm: np.ndarray
    normal: np.ndarray
    te0_arcsec: float = 0.0
    residual: float = 0.0
    iterations: int = 0
    edge: bool = False
    edge_where: str = ""
    edge_contact: str = ""

    def as_guess(self) -> ContactGuess:
        return ContactGuess(self.u1, self.v1, self.u2, self.v2, self.phi1_rad, self.phi2_rad)

    @classmethod
    def edge_phase(cls, phi1_rad: float, where: str) -> "MatingPoint":
        nan3 = np.full(3, np.nan)
        nan = float("nan")
        return cls(float(phi1_rad), nan, nan, nan, nan, nan, nan3, nan3, nan, nan, 0,
                   True, where)


@dataclass(frozen=True)
class TcaPath:
    """Mating points of one tooth pair over a sequence of mesh phases.

    Attributes
    ----------
    points : tuple of MatingPoint
        One per requested phase, in the order requested (edge phases included).
    phi1_ref_rad, phi2_ref_rad : float
        Reference (mean-point) rotations of the TE0 definition, rad.
    ratio : float
        z2 / z1.
    """

    points: tuple[MatingPoint, ...]
    phi1_ref_rad: float
    phi2_ref_rad: float
    ratio: float
    _cache: dict = field(default_factory=dict, repr=False, compare=False)

    def _stack(self, name: str) -> np.ndarray:
        if name not in self._cache:
            self._cache[name] = np.array([getattr(p, name) for p in self.points])
        return self._cache[name]

    @property
    def phi1_rad(self) -> np.ndarray:
        return self._stack("phi1_rad")

    @property
    def phi2_rad(self) -> np.ndarray:
        return self._stack("phi2_rad")

    @property
    def te0_arcsec(self) -> np.ndarray:
        return self._stack("te0_arcsec")

    @property
    def points_mm(self) -> np.ndarray:
        """(N, 3) mating points in the meshing frame, mm (NaN at edge phases)."""
        return self._stack("point_mm")

    @property
    def normals(self) -> np.ndarray:
        return self._stack("normal")

    @property
    def edge(self) -> np.ndarray:
        return self._stack("edge")

    @property
    def surface(self) -> np.ndarray:
        """Per point: a surface-to-surface contact (neither a phase without contact nor
        an edge touching the other flank)."""
        if "surface" not in self._cache:
            self._cache["surface"] = ~self.edge & (self._stack("edge_contact") == "")
        return self._cache["surface"]

    def parameters(self, member: str) -> np.ndarray:
        """(N, 2) flank parameters (u, v) of ``"pinion"`` or ``"gear"``."""
        k = {"pinion": ("u1", "v1"), "gear": ("u2", "v2")}[member]
        return np.column_stack([self._stack(k[0]), self._stack(k[1])])


def normal_derivatives(sp: SurfacePoint) -> tuple[np.ndarray, np.ndarray]:
    """Derivatives ``(n_u, n_v)`` of the unit normal (Weingarten equations).

    ``[n_u n_v] = -[r_u r_v] I^-1 II`` with II taken w.r.t. ``sp.n``
    (do Carmo 1976, sec. 3-3, eq. 3).
    """
    first, second = sp.fundamental_forms()
    (e, f), (_, g) = first
    w = np.array([[g, -f], [-f, e]]) @ second / (e * g - f * f)   # I^-1 II (2 x 2)
    jac = np.column_stack([sp.r_u, sp.r_v])
    dn = -jac @ w
    return dn[:, 0], dn[:, 1]


def posed_point(surface: Surface, pose: tuple[np.ndarray, np.ndarray],
                u: float, v: float) -> tuple[SurfacePoint, np.ndarray, np.ndarray]:
    """Evaluate ``surface`` at ``(u, v)`` and pose it: ``(sp, X_f, n_f)``."""
    sp = surface.point(u, v)
    rot, t = pose
    return sp, rot @ sp.r + t, rot @ sp.n


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``a x b`` of two 3-vectors (np.cross without its per-call overhead)."""
    a0, a1, a2 = a
    b0, b1, b2 = b
    return np.array([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0])


def _tangent_basis(n: np.ndarray) -> np.ndarray:
    """An orthonormal (3, 2) basis of the plane normal to unit ``n``."""
    a = np.array([1.0, 0.0, 0.0]) if abs(n[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    ta = a - (a @ n) * n
    ta /= np.linalg.norm(ta)
    return np.column_stack([ta, _cross(n, ta)])


def _clamp(x: np.ndarray, boxes: np.ndarray) -> tuple[np.ndarray, list[str]]:
    """Clamp the flank parameters of the state ``x`` into their boxes."""
    names = ("pinion u", "pinion v", "gear u", "gear v")
    hit = []
    y = x.copy()
    for i in range(4):
        lo, hi = boxes[i]
        if y[i] < lo:
            y[i] = lo
            hit.append(f"{names[i]} min")
        elif y[i] > hi:
            y[i] = hi
            hit.append(f"{names[i]} max")
    return y, hit


def _residual_and_jacobian(pinion: Surface, gear: Surface, kin: MeshKinematics,
                           x: np.ndarray, *, jacobian: bool = True):
    """Residual F (5,) and Jacobian dF/dx (5, 6) of the contact equations at state x."""
    u1, v1, u2, v2, phi1, phi2 = x
    pose1 = kin.pinion_pose(phi1)
    pose2 = kin.gear_pose(phi2)
    sp1, x1, n1 = posed_point(pinion, pose1, u1, v1)
    sp2, x2, n2 = posed_point(gear, pose2, u2, v2)
    basis = _tangent_basis(n2)
    res = np.concatenate([x1 - x2, basis.T @ (n1 + n2)])
    if not jacobian:
        return res, (x2, n2), None
    r1, r2 = pose1[0], pose2[0]
    w1 = -kin.pinion_axis            # the pinion turns about -x (tilted by alpha)
    w2 = kin.gear_axis
    n1u, n1v = normal_derivatives(sp1)
    n2u, n2v = normal_derivatives(sp2)
    jac = np.empty((5, 6))
    jac[:3, 0] = r1 @ sp1.r_u
    jac[:3, 1] = r1 @ sp1.r_v
    jac[:3, 2] = -(r2 @ sp2.r_u)
    jac[:3, 3] = -(r2 @ sp2.r_v)
    jac[:3, 4] = _cross(w1, x1 - pose1[1])
    jac[:3, 5] = -_cross(w2, x2 - pose2[1])
    dn = np.column_stack([r1 @ n1u, r1 @ n1v, r2 @ n2u, r2 @ n2v,
                          _cross(w1, n1), _cross(w2, n2)])
    jac[3:, :] = basis.T @ dn
    return res, (x2, n2), jac


def _boxes(pinion: Surface, gear: Surface) -> np.ndarray:
    return np.array([pinion.u_range, pinion.v_range, gear.u_range, gear.v_range], float)


def solve_mating_point(pinion: Surface, gear: Surface, kin: MeshKinematics,
                       guess: ContactGuess, *, fixed: str | tuple[str, ...] = "phi1",
                       tol_mm: float = 1e-10, max_iter: int = 40) -> MatingPoint:
    """Solve the five contact equations by Newton's method with one variable fixed.

    Parameters
    ----------
    pinion, gear : Surface
        Flanks of member 1 and member 2 in their body frames (normals out of the tooth).
    kin : MeshKinematics
        Poses of both members (assembly errors included).
    guess : ContactGuess
        Starting state; the variable named by ``fixed`` keeps its value.
    fixed : str or tuple of str
        Variable(s) of :data:`VARIABLES` held at their guessed values; ``"phi1"`` is
        ordinary TCA at a given mesh phase. With two fixed variables the five equations
        in four unknowns are solved by Gauss-Newton (least squares); they converge only
        if the system is consistent - e.g. along the contact line of a conjugate
        (line-contact) pair, ``fixed=("phi1", "v2")``.
    tol_mm : float
        Convergence tolerance on the position residual, mm; the normal residual must
        fall below ``tol_mm / 1 mm``.
    max_iter : int
        Newton iteration limit.

    Returns
    -------
    MatingPoint
        With ``te0_arcsec = 0`` (the path sets it relative to its reference).

    Raises
    ------
    EdgeContact
        The solution lies outside a parameter box (iterates are clamped to the boxes).
    TcaConvergenceError
        No convergence; the message names the mesh phase and the residual.
    """
    check_positive("tol_mm", tol_mm)
    names = (fixed,) if isinstance(fixed, str) else tuple(fixed)
    unknown = [n for n in names if n not in VARIABLES]
    if unknown or not 1 <= len(set(names)) <= 2:
        raise ValueError(f"fixed = {fixed!r}: give one or two of {VARIABLES}")
    free = [i for i, n in enumerate(VARIABLES) if n not in names]
    boxes = _boxes(pinion, gear)
    x, hit = _clamp(guess.vector(), boxes)
    res, (x2, n2), jac = _residual_and_jacobian(pinion, gear, kin, x)
    norm = np.linalg.norm(res)
    clamped_iters = 0
    for it in range(1, max_iter + 1):
        if len(free) == 5:
            try:
                step = np.linalg.solve(jac[:, free], -res)
            except np.linalg.LinAlgError:
                step = np.linalg.lstsq(jac[:, free], -res, rcond=None)[0]
        else:
            step = np.linalg.lstsq(jac[:, free], -res, rcond=None)[0]
        lam = 1.0
        while True:
            trial = x.copy()
            trial[free] += lam * step
            trial, hit = _clamp(trial, boxes)
            res_t, geo_t, jac_t = _residual_and_jacobian(pinion, gear, kin, trial)
            norm_t = np.linalg.norm(res_t)
            if norm_t < norm or lam < 1e-3:
                break
            lam *= 0.5
        x, res, (x2, n2), jac, norm = trial, res_t, geo_t, jac_t, norm_t
        clamped_iters = clamped_iters + 1 if hit else 0
        if np.all(np.abs(res[:3]) < tol_mm) and np.all(np.abs(res[3:]) < tol_mm) and not hit:
            return MatingPoint(x[4], x[5], x[0], x[1], x[2], x[3], x2, n2,
                               residual=float(norm), iterations=it)
        if clamped_iters >= 3:
            raise EdgeContact(x[4], hit[0])
    raise TcaConvergenceError(x[4], norm, max_iter)


def _predict(prev: MatingPoint, prev2: MatingPoint | None, phi1: float,
             ratio: float) -> ContactGuess:
    """Continuation predictor at ``phi1``: secant through the last two solutions, or
    the last one turned by the nominal ratio."""
    x_prev = prev.as_guess().vector()
    if prev2 is None:
        x_pred = x_prev.copy()
        x_pred[5] += (phi1 - x_prev[4]) / ratio
    else:
        x_old = prev2.as_guess().vector()
        x_pred = x_prev + (x_prev - x_old) * (phi1 - x_prev[4]) / (x_prev[4] - x_old[4])
    x_pred[4] = phi1
    return ContactGuess.from_vector(x_pred)


def solve_tca(pinion: Surface, gear: Surface, kin: MeshKinematics, phi1_rad,
              *, start: ContactGuess, start_fixed: str = "phi1", tol_mm: float = 1e-10,
              max_iter: int = 40, max_step_rad: float | None = None,
              edges: bool = True, edge_te_limit_arcsec: float = EDGE_TE_LIMIT_ARCSEC,
              progress: bool = False) -> TcaPath:
    """TCA of one tooth pair over the mesh phases ``phi1_rad`` by continuation.

    The reference (mean) mating point is solved first from ``start`` with
    ``start_fixed`` held (``"phi1"``: at ``start.phi1_rad``; ``"u2"``: the path point
    through the gear's profile parameter ``start.u2``). The path is then continued
    from it upwards and downwards in ``phi1`` with a secant predictor. Where the
    surface mating point leaves a flank, the path switches to edge-to-surface contact
    (:mod:`gearcontact.tca.edge_contact`; ``edges=True``): at each further phase the
    first of the edge contact and a surface mating point (re-entry) to touch is kept,
    until no edge touches the other flank either; all further phases in that direction
    are then phases without contact (never extrapolated). With ``edges=False`` the
    path stops at the first boundary (surface contact only).

    Parameters
    ----------
    pinion, gear : Surface
        The two flanks (see :func:`solve_mating_point`).
    kin : MeshKinematics
        Kinematics with assembly errors.
    phi1_rad : array_like
        Strictly increasing pinion phases, rad.
    start : ContactGuess
        Guess of the reference mating point.
    start_fixed : str
        Variable held fixed while solving the reference point (an edge contact, when the
        surface point lies beyond a flank, holds ``phi1``).
    max_step_rad : float, optional
        Largest continuation step in ``phi1``: a wider gap between two requested
        phases is crossed in equal unrecorded substeps (a coarse phase grid then
        follows the path as far as a fine one; a too wide secant step can run into a
        parameter box early and end the path there). Default: no substeps.
    edges : bool
        Continue through edge-to-surface contact (default) or stop at the boundary.
    edge_te_limit_arcsec : float
        An edge contact whose TE0 lies more than this behind the path's first touch so
        far (its TE0 extreme) ends the path in that direction: it can carry only if the
        mesh's TE0 peak-to-peak exceeds the limit (:func:`~gearcontact.tca.mesh.mesh_cycle`
        then widens it). Keeps the cost of the edge tails bounded.
    progress : bool
        Show a tqdm progress bar over the phases.

    Returns
    -------
    TcaPath
        With TE0 relative to the reference point, arcsec.
    """
    from .edge_contact import contact_state, inward_slope, pushes_forward, solve_edge_contact
    from .edges import solver_boundary

    phis = np.asarray(phi1_rad, dtype=float).ravel()
    if phis.size == 0 or np.any(np.diff(phis) <= 0.0):
        raise ValueError("phi1_rad must be a non-empty, strictly increasing sequence")
    if edges:
        ref = contact_state(pinion, gear, kin, start, fixed=start_fixed, tol_mm=tol_mm,
                            max_iter=max_iter)
    else:
        ref = solve_mating_point(pinion, gear, kin, start, fixed=start_fixed,
                                 tol_mm=tol_mm, max_iter=max_iter)
    forward = pushes_forward(gear, kin, ref.as_guess())
    results: list[MatingPoint | None] = [None] * phis.size
    i0 = int(np.searchsorted(phis, ref.phi1_rad))
    bar = tqdm(total=phis.size, desc="TCA phases", disable=not progress, leave=False)

    def first_touch(a: MatingPoint | None, b: MatingPoint | None) -> MatingPoint | None:
        if a is None or b is None:
            return a if b is None else b
        return a if (a.phi2_rad >= b.phi2_rad) == forward else b

    for direction, indices in ((+1, range(i0, phis.size)), (-1, range(i0 - 1, -1, -1))):
        prev, prev2 = ref, None
        stopped: str | None = None
        best = 0.0                  # the path's first touch so far (TE0 extreme), arcsec
        for i in indices:
            bar.update(1)
            if stopped is not None:
                results[i] = MatingPoint.edge_phase(phis[i], stopped)
                continue
            mp = None
            if not prev.edge_contact:
                gap = phis[i] - prev.phi1_rad
                subs = 1 if max_step_rad is None else max(1, int(np.ceil(abs(gap) / max_step_rad)))
                try:
                    for j in range(1, subs + 1):
                        phi = phis[i] if j == subs else prev.phi1_rad + gap / (subs - j + 1)
                        step = solve_mating_point(pinion, gear, kin,
                                                  _predict(prev, prev2, phi, kin.ratio),
                                                  tol_mm=tol_mm, max_iter=max_iter)
                        if abs(step.phi1_rad - prev.phi1_rad) > 0.0:
                            prev2 = prev
                        prev = step
                        gap = phis[i] - prev.phi1_rad
                    mp = step
                except (EdgeContact, TcaConvergenceError) as exc:
                    if not edges and isinstance(exc, TcaConvergenceError):
                        raise
                    stopped = exc.where if isinstance(exc, EdgeContact) else "no convergence"
                    if not edges:
                        results[i] = MatingPoint.edge_phase(phis[i], stopped)
                        continue
                    stopped = None
                    mp = solve_edge_contact(pinion, gear, kin, phis[i], guess=prev.as_guess(),
                                            forward=forward, tol_mm=tol_mm)
                    if mp is None and isinstance(exc, TcaConvergenceError):
                        raise
                    where = exc.where if isinstance(exc, EdgeContact) else "no convergence"
            else:
                # edge mode: the edge contact, or the surface point if it is back on the
                # flanks and touches first
                where = solver_boundary(prev.edge_contact)
                edge = solve_edge_contact(pinion, gear, kin, phis[i], guess=prev.as_guess(),
                                          forward=forward, tol_mm=tol_mm)
                surface = None
                # the flank behind the edge dips towards the other flank: the surface
                # contact is back inside the flanks
                if edge is None or inward_slope(pinion, gear, kin, edge) < 0.0:
                    guess = replace(prev.as_guess(), phi1_rad=phis[i], phi2_rad=prev.phi2_rad
                                    + (phis[i] - prev.phi1_rad) / kin.ratio)
                    try:
                        surface = solve_mating_point(pinion, gear, kin, guess, tol_mm=tol_mm,
                                                     max_iter=max_iter)
                    except (EdgeContact, TcaConvergenceError):
                        pass
                mp = first_touch(surface, edge)
            if mp is None:
                stopped = where
                results[i] = MatingPoint.edge_phase(phis[i], stopped)
                continue
            te = ((mp.phi2_rad - ref.phi2_rad) - (mp.phi1_rad - ref.phi1_rad) / kin.ratio)
            te *= ARCSEC_PER_RAD
            if mp.edge_contact and (best - te if forward else te - best) > edge_te_limit_arcsec:
                # an edge contact this far behind the path's first touch cannot carry
                stopped = solver_boundary(mp.edge_contact)
                results[i] = MatingPoint.edge_phase(phis[i], stopped)
                continue
            best = max(best, te) if forward else min(best, te)
            if prev is not mp:      # a switch between surface and edge contact
                prev2, prev = None, mp
            results[i] = replace(mp, te0_arcsec=te)
    bar.close()
    return TcaPath(tuple(results), ref.phi1_rad, ref.phi2_rad, kin.ratio)
