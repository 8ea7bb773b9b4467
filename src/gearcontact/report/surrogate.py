"""Physics-direct preview vs a neural surrogate (docs/spec.md sec. 8, item 3).

Two studies (design and reasoning: docs/reproduce.md sec. 2): :func:`synthetic_study`
labels random (A-, B-, W) with the exact elliptic Hertz p_max and tests a network
trained for W <= 3000 N inside and outside that box; :func:`anchored_study` labels the
loads with the LCP p90 of s0003 at the design phase and extrapolates beyond the training
torques. Errors are RMSE of the relative error in %. The network (:class:`MlpSpec`) is
scikit-learn's ``MLPRegressor`` behind ``StandardScaler``, seeded, trained with BLAS
limited to one thread. :func:`plot_surrogate` draws the two-panel figure.

Requires the ``report`` extra (``pip install 'gearcontact[report]'``: scikit-learn).
"""

from __future__ import annotations

import time
import warnings
from dataclasses import dataclass, field

import numpy as np

from ..analytic.hertz import exact_elliptic_hertz, hamrock_brewe_hertz_array
from ..figure_files import save_figure
from ..materials import STEEL, effective_modulus_mpa
from ..validation import InputRangeError, check_positive
from .analyze import published_values

__all__ = ["BOX", "MlpSpec", "SyntheticStudy", "AnchoredStudy", "fit_mlp",
           "relative_rmse_pct", "synthetic_study", "anchored_study", "plot_surrogate",
           "PUBLISHED_SYNTHETIC", "PUBLISHED_ANCHORED", "PUBLISHED_LCP_S_PER_SOLVE"]

#: Sampling box of study (a): half relative curvatures (1/mm) and loads (N). It holds
#: the s0003 mean point (A- ~ 0.06, B- ~ 0.001 1/mm) and keeps the radius ratio <= 120,
#: inside the preview's envelope (alpha <= 128).
BOX = {"A_min_per_mm": (5e-4, 1e-2), "B_max_per_mm": (1e-2, 6e-2),
       "load_train_n": (100.0, 3000.0), "load_out_n": (3000.0, 9000.0)}
_PUBLISHED = published_values("s0003")
#: Published RMSE of study (a), %: MLP in / out of the box, preview (physics) ~ 0
#: (``data/published/s0003.json``).
PUBLISHED_SYNTHETIC = {f"{ours}_pct": _PUBLISHED["surrogate_synthetic_rmse_pct"][name]
                       for ours, name in (("mlp_in", "mlp_in_box"),
                                          ("mlp_out", "mlp_out_of_box"),
                                          ("preview", "preview"))}
#: Published errors of study (b), %: network / physics on the trained and extrapolated
#: loads (``data/published/s0003.json``).
PUBLISHED_ANCHORED = {f"{model}_{loads}_pct": _PUBLISHED["surrogate_anchored_rmse_pct"][
                          f"{model}_{name}"]
                      for model in ("mlp", "preview")
                      for loads, name in (("train", "trained"), ("extrap", "extrapolated"))}
#: Published host LCP cost, s per solve (docs/spec.md sec. 5).
PUBLISHED_LCP_S_PER_SOLVE = 2.005


@dataclass(frozen=True)
class MlpSpec:
    """Architecture and training of the surrogate (scikit-learn ``MLPRegressor``).

    Attributes
    ----------
    hidden_layers : tuple of int
        Neurons per hidden layer.
    activation : str
        Hidden activation (``"tanh"``: smooth, as the target).
    solver : str
        ``"lbfgs"`` (full-batch quasi-Newton; right for a few thousand samples).
    alpha : float
        L2 penalty, dimensionless (on standardised data).
    max_iter : int
        L-BFGS iterations.
    seed : int
        ``random_state`` of the weight initialisation.
    """

    hidden_layers: tuple[int, ...] = (32, 32)
    activation: str = "tanh"
    solver: str = "lbfgs"
    alpha: float = 1e-4
    max_iter: int = 500
    seed: int = 0

    def describe(self) -> str:
        """One-line statement of the architecture and training."""
        layers = " x ".join(str(n) for n in self.hidden_layers)
        return (f"MLPRegressor, hidden layers {layers} ({self.activation}), "
                f"{self.solver.upper()} {self.max_iter} iterations, L2 {self.alpha:g}, "
                f"seed {self.seed}; inputs and target standardised on the training set")


def fit_mlp(x, y, spec: MlpSpec = MlpSpec()):
    """Fit the surrogate: standardised inputs -> MLP -> de-standardised target.

    Parameters
    ----------
    x : array_like, shape (n, d)
        Inputs (physical units; standardised inside).
    y : array_like, shape (n,)
        Labels (physical units).
    spec : MlpSpec

    Returns
    -------
    (model, seconds)
        The fitted scikit-learn estimator (``predict`` takes physical inputs) and the
        wall time of the fit, s.
    """
    from sklearn.compose import TransformedTargetRegressor
    from sklearn.exceptions import ConvergenceWarning
    from sklearn.neural_network import MLPRegressor
    from sklearn.pipeline import make_pipeline
    from sklearn.preprocessing import StandardScaler
    from threadpoolctl import threadpool_limits

    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    if x.ndim != 2 or len(x) != len(y) or len(y) < 2:
        raise InputRangeError("x, y (training set)", f"{x.shape}, {y.shape}",
                              "x of shape (n, d) and y of shape (n,), n >= 2")
    net = MLPRegressor(hidden_layer_sizes=spec.hidden_layers, activation=spec.activation,
                       solver=spec.solver, alpha=spec.alpha, max_iter=spec.max_iter,
                       tol=1e-10, random_state=spec.seed)
    model = TransformedTargetRegressor(regressor=make_pipeline(StandardScaler(), net),
                                       transformer=StandardScaler())
    t0 = time.perf_counter()
    with threadpool_limits(1), warnings.catch_warnings():
        # the iteration budget is part of the stated training, not a failure
        warnings.simplefilter("ignore", ConvergenceWarning)
        model.fit(x, y)
    return model, time.perf_counter() - t0


def relative_rmse_pct(pred, truth) -> float:
    """Root mean square of the relative error ``pred / truth - 1``, in %."""
    pred = np.asarray(pred, dtype=float)
    truth = np.asarray(truth, dtype=float)
    return float(100.0 * np.sqrt(np.mean((pred / truth - 1.0) ** 2)))


@dataclass(frozen=True, eq=False)
class SyntheticStudy:
    """Study (a): MLP and preview against exact Hertz and Hamrock–Brewe.

    Attributes
    ----------
    spec : MlpSpec
    n_train, n_test : int
        Training samples (W <= 3000 N) and test samples per region (in / out of box).
    rmse_pct : dict
        ``rmse_pct[model][truth][region]``, % — model ``"mlp"`` | ``"preview"``, truth
        ``"exact"`` | ``"hamrock_brewe"``, region ``"in_box"`` | ``"out_of_box"``.
    train_s : float
        Wall time of the MLP fit, s.
    label_s : float
        Wall time of the exact-Hertz labels of the training set, s.
    load_n, mlp_err_pct, preview_err_pct : ndarray
        Test loads (in and out, N) and the signed relative errors vs exact Hertz, %
        (for the figure).
    box : dict
        The sampling box (:data:`BOX`).
    """

    spec: MlpSpec
    n_train: int
    n_test: int
    rmse_pct: dict
    train_s: float
    label_s: float
    load_n: np.ndarray = field(repr=False)
    mlp_err_pct: np.ndarray = field(repr=False)
    preview_err_pct: np.ndarray = field(repr=False)
    box: dict = field(default_factory=lambda: dict(BOX))

    def as_dict(self) -> dict:
        """JSON-ready summary (no per-sample arrays)."""
        return {"model": self.spec.describe(), "n_train": self.n_train,
                "n_test_per_region": self.n_test, "box": {k: list(v) for k, v in
                                                          self.box.items()},
                "rmse_pct": self.rmse_pct, "train_s": self.train_s,
                "label_s": self.label_s, "published": PUBLISHED_SYNTHETIC}


def _sample(rng, n, load_range):
    a = rng.uniform(*BOX["A_min_per_mm"], n)
    b = rng.uniform(*BOX["B_max_per_mm"], n)
    w = rng.uniform(*load_range, n)
    return a, b, w


def _exact_p_max(a, b, w, e_prime):
    return np.array([exact_elliptic_hertz(x, y, z, e_prime_mpa=e_prime).p_max_mpa
                     for x, y, z in zip(a, b, w)])


def synthetic_study(*, n_train: int = 2000, n_test: int = 1000, seed: int = 0,
                    spec: MlpSpec = MlpSpec(), material=STEEL) -> SyntheticStudy:
    """Study (a) on the box :data:`BOX` (steel on steel by default).

    Parameters
    ----------
    n_train : int
        Training samples, W in ``BOX["load_train_n"]`` (>= 50).
    n_test : int
        Test samples in the box and out of it (each >= 50).
    seed : int
        Seed of the samples (the network's seed is ``spec.seed``).
    spec : MlpSpec
    material : Material
        Both members (E' = 2 E*).
    """
    for name, n in (("n_train", n_train), ("n_test", n_test)):
        if int(n) < 50:
            raise InputRangeError(name, n, ">= 50 samples")
    from ..preview.engine import get_engine

    ep = effective_modulus_mpa(material)
    rng = np.random.default_rng(seed)
    a, b, w = _sample(rng, int(n_train), BOX["load_train_n"])
    t0 = time.perf_counter()
    y = _exact_p_max(a, b, w, ep)
    label_s = time.perf_counter() - t0
    model, train_s = fit_mlp(np.column_stack([a, b, w]), y, spec)
    preview = get_engine("reference", material=material)
    rmse = {"mlp": {"exact": {}, "hamrock_brewe": {}},
            "preview": {"exact": {}, "hamrock_brewe": {}}}
    loads, mlp_err, pre_err = [], [], []
    for region, load_range in (("in_box", BOX["load_train_n"]),
                               ("out_of_box", BOX["load_out_n"])):
        ta, tb, tw = _sample(rng, int(n_test), load_range)
        exact = _exact_p_max(ta, tb, tw, ep)
        hb = hamrock_brewe_hertz_array(ta, tb, tw, e_prime_mpa=ep)["p_max_mpa"]
        mlp = model.predict(np.column_stack([ta, tb, tw]))
        pre = preview.hertz_batch(ta, tb, tw).p_max_mpa
        for name, pred in (("mlp", mlp), ("preview", pre)):
            rmse[name]["exact"][region] = relative_rmse_pct(pred, exact)
            rmse[name]["hamrock_brewe"][region] = relative_rmse_pct(pred, hb)
        loads.append(tw)
        mlp_err.append(100.0 * (mlp / exact - 1.0))
        pre_err.append(100.0 * (pre / exact - 1.0))
    return SyntheticStudy(spec=spec, n_train=int(n_train), n_test=int(n_test),
                          rmse_pct=rmse, train_s=train_s, label_s=label_s,
                          load_n=np.concatenate(loads), mlp_err_pct=np.concatenate(mlp_err),
                          preview_err_pct=np.concatenate(pre_err))


@dataclass(frozen=True, eq=False)
class AnchoredStudy:
    """Study (b): MLP and preview against the LCP p90 of one pair at its design phase.

    Attributes
    ----------
    spec : MlpSpec
    train_torques_nm, extrap_torques_nm : tuple of float
        Gear torques of the training set and of the extrapolation set, N·m.
    train_load_n, extrap_load_n : ndarray
        Normal loads, N.
    train_p90_mpa, extrap_p90_mpa : ndarray
        LCP p90 labels, MPa.
    preview_train_mpa, preview_extrap_mpa : ndarray
        Preview p_max at the same loads, MPa.
    mlp_train_mpa, mlp_extrap_mpa : ndarray
        MLP predictions, MPa.
    rmse_pct : dict
        ``{"mlp": {"train", "extrap"}, "preview": {"train", "extrap"}}``, %.
    lcp_solves : int
        LCP solves of the training set.
    lcp_wall_s : float
        Wall time of those solves (gap field + LCP per torque) on this machine, s.
    lcp_solver_s : float
        The solver's own time summed over them, s.
    train_s : float
        Wall time of the MLP fit, s.
    edge_contact : tuple of bool
        Edge contact per training + extrapolation case.
    model : object
        The fitted estimator (``predict`` takes loads in N, shape (n, 1)).
    """

    spec: MlpSpec
    train_torques_nm: tuple
    extrap_torques_nm: tuple
    train_load_n: np.ndarray
    extrap_load_n: np.ndarray
    train_p90_mpa: np.ndarray
    extrap_p90_mpa: np.ndarray
    preview_train_mpa: np.ndarray
    preview_extrap_mpa: np.ndarray
    mlp_train_mpa: np.ndarray
    mlp_extrap_mpa: np.ndarray
    rmse_pct: dict
    lcp_solves: int
    lcp_wall_s: float
    lcp_solver_s: float
    train_s: float
    edge_contact: tuple
    model: object = field(repr=False, default=None)

    def as_dict(self) -> dict:
        """JSON-ready summary."""
        return {"model": self.spec.describe() + "; input: normal load W (N)",
                "label": "LCP p90 (MPa) at the design mesh phase",
                "train_torques_nm": list(self.train_torques_nm),
                "extrap_torques_nm": list(self.extrap_torques_nm),
                "train_load_n": self.train_load_n.tolist(),
                "extrap_load_n": self.extrap_load_n.tolist(),
                "train_p90_mpa": self.train_p90_mpa.tolist(),
                "extrap_p90_mpa": self.extrap_p90_mpa.tolist(),
                "preview_train_mpa": self.preview_train_mpa.tolist(),
                "preview_extrap_mpa": self.preview_extrap_mpa.tolist(),
                "mlp_train_mpa": self.mlp_train_mpa.tolist(),
                "mlp_extrap_mpa": self.mlp_extrap_mpa.tolist(),
                "rmse_pct": self.rmse_pct,
                "training_cost": {"lcp_solves": self.lcp_solves,
                                  "lcp_wall_s": self.lcp_wall_s,
                                  "lcp_solver_s": self.lcp_solver_s,
                                  "wall_s_per_solve": self.lcp_wall_s / self.lcp_solves,
                                  "published_s_per_solve": PUBLISHED_LCP_S_PER_SOLVE,
                                  "published_s": PUBLISHED_LCP_S_PER_SOLVE * self.lcp_solves},
                "train_s": self.train_s, "edge_contact": list(self.edge_contact),
                "published": PUBLISHED_ANCHORED}


def anchored_study(tca, flanks, pair, *, train_torques_nm, extrap_torques_nm,
                   side: str | None = None, extrap_cases=(), spec: MlpSpec = MlpSpec(),
                   solver: str = "pk_cg") -> AnchoredStudy:
    """Study (b): train on the LCP p90 at ``train_torques_nm``, extrapolate.

    Parameters
    ----------
    tca, flanks, pair
        As for :func:`gearcontact.ltca.pair_ltca.single_pair_ltca` (the TCA of the
        pair on ``side``).
    train_torques_nm : sequence of float
        Gear torques of the training set, N·m (>= 2, > 0); every one costs one timed
        LCP solve.
    extrap_torques_nm : sequence of float
        Gear torques to extrapolate to, N·m (>= 1, each above every training torque).
    side : str, optional
        Flank pair; default the pair's ``design_side``.
    extrap_cases : sequence of PairLoadCase
        Already solved cases (e.g. from :func:`gearcontact.report.analyze.run_analysis`)
        reused for extrapolation torques they match (not counted as training cost).
    spec : MlpSpec
    solver : str
        LCP solver.
    """
    from ..ltca.pair_ltca import single_pair_ltca
    from ..halfspace.patch import ContactAtEdgeWarning

    train = sorted(check_positive("train_torques_nm (N·m)", t) for t in train_torques_nm)
    extrap = sorted(check_positive("extrap_torques_nm (N·m)", t) for t in extrap_torques_nm)
    if len(train) < 2:
        raise InputRangeError("train_torques_nm", train_torques_nm, "at least 2 torques")
    if not extrap or extrap[0] <= train[-1]:
        raise InputRangeError("extrap_torques_nm", extrap_torques_nm,
                              f"at least one torque, each > {train[-1]:g} N·m (the training "
                              "range)")
    side = pair.design_side if side is None else side

    def solve(torque):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ContactAtEdgeWarning)
            return single_pair_ltca(tca, flanks, pair, torque, side=side, solver=solver)

    train_cases = []
    t0 = time.perf_counter()
    for t in train:
        train_cases.append(solve(t))
    wall = time.perf_counter() - t0
    reuse = {round(c.torque_nm, 9): c for c in extrap_cases}
    extrap_list = [reuse.get(round(t, 9)) or solve(t) for t in extrap]

    def arr(cases, get):
        return np.array([get(c) for c in cases], dtype=float)

    w_tr, w_ex = arr(train_cases, lambda c: c.load_n), arr(extrap_list, lambda c: c.load_n)
    y_tr = arr(train_cases, lambda c: c.patch.p90_mpa)
    y_ex = arr(extrap_list, lambda c: c.patch.p90_mpa)
    pre_tr = arr(train_cases, lambda c: c.preview.p_max_mpa)
    pre_ex = arr(extrap_list, lambda c: c.preview.p_max_mpa)
    model, train_s = fit_mlp(w_tr[:, None], y_tr, spec)
    mlp_tr, mlp_ex = model.predict(w_tr[:, None]), model.predict(w_ex[:, None])
    rmse = {"mlp": {"train": relative_rmse_pct(mlp_tr, y_tr),
                    "extrap": relative_rmse_pct(mlp_ex, y_ex)},
            "preview": {"train": relative_rmse_pct(pre_tr, y_tr),
                        "extrap": relative_rmse_pct(pre_ex, y_ex)}}
    return AnchoredStudy(
        spec=spec, train_torques_nm=tuple(train), extrap_torques_nm=tuple(extrap),
        train_load_n=w_tr, extrap_load_n=w_ex, train_p90_mpa=y_tr, extrap_p90_mpa=y_ex,
        preview_train_mpa=pre_tr, preview_extrap_mpa=pre_ex, mlp_train_mpa=mlp_tr,
        mlp_extrap_mpa=mlp_ex, rmse_pct=rmse, lcp_solves=len(train_cases), lcp_wall_s=wall,
        lcp_solver_s=sum(c.patch.lcp.solve_time_ms for c in train_cases) * 1e-3,
        train_s=train_s, edge_contact=tuple(bool(c.edge_contact)
                                            for c in train_cases + extrap_list),
        model=model)


def plot_surrogate(synthetic: SyntheticStudy, anchored: AnchoredStudy | None, path, *,
                   title: str = ""):
    """Two panels: (a) relative p_max error vs load, MLP and preview against exact Hertz,
    training limit marked; (b) LCP p90 labels, MLP and preview over the load."""
    from .figures import plt

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    ax = axes[0]
    w_lim = BOX["load_train_n"][1]
    ax.scatter(synthetic.load_n, synthetic.mlp_err_pct, s=3, alpha=0.35, color="C3",
               label="MLP")
    ax.scatter(synthetic.load_n, synthetic.preview_err_pct, s=3, alpha=0.35, color="C0",
               label="preview (Hamrock–Brewe)")
    ax.axvline(w_lim, color="0.3", ls="--", lw=1.0, label=f"training limit {w_lim:g} N")
    ax.axhline(0.0, color="0.6", lw=0.6)
    r = synthetic.rmse_pct
    ax.set_title(f"(a) synthetic (A-, B-, W): RMSE vs exact Hertz\nMLP "
                 f"{r['mlp']['exact']['in_box']:.2f} % in / "
                 f"{r['mlp']['exact']['out_of_box']:.1f} % out of box; preview "
                 f"{r['preview']['exact']['in_box']:.2f} / "
                 f"{r['preview']['exact']['out_of_box']:.2f} %\n(published MLP "
                 f"{PUBLISHED_SYNTHETIC['mlp_in_pct']:g} / {PUBLISHED_SYNTHETIC['mlp_out_pct']:g}"
                 f" % vs Hamrock–Brewe)", fontsize=9)
    ax.set_xlabel("normal load W (N)")
    ax.set_ylabel("p_max error vs exact Hertz (%)")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8, loc="upper left", markerscale=4)
    ax = axes[1]
    if anchored is None:
        ax.text(0.5, 0.5, "anchored study not run", ha="center", va="center",
                transform=ax.transAxes)
        ax.set_axis_off()
    else:
        a = anchored
        ww = np.linspace(0.8 * a.train_load_n.min(), 1.05 * a.extrap_load_n.max(), 200)
        ax.plot(a.train_load_n, a.train_p90_mpa, "o", color="k", label="LCP p90 (training)")
        ax.plot(a.extrap_load_n, a.extrap_p90_mpa, "s", mfc="none", color="k",
                label="LCP p90 (extrapolation)")
        ax.plot(ww, a.model.predict(ww[:, None]), "-", color="C3", label="MLP")
        wp = np.concatenate([a.train_load_n, a.extrap_load_n])
        pp = np.concatenate([a.preview_train_mpa, a.preview_extrap_mpa])
        ax.plot(wp, pp, "^-", color="C0", label="preview p_max")
        ax.axvline(a.train_load_n.max(), color="0.3", ls="--", lw=1.0,
                   label="end of training loads")
        r = a.rmse_pct
        ax.set_title(f"(b) anchored to LCP p90 ({a.lcp_solves} training solves)\nMLP "
                     f"{r['mlp']['train']:.1f} % trained / {r['mlp']['extrap']:.1f} % "
                     f"extrapolated; preview {r['preview']['train']:.1f} / "
                     f"{r['preview']['extrap']:.1f} %\n(published MLP "
                     f"{PUBLISHED_ANCHORED['mlp_train_pct']:g} / "
                     f"{PUBLISHED_ANCHORED['mlp_extrap_pct']:g} %, preview "
                     f"{PUBLISHED_ANCHORED['preview_train_pct']:g} / "
                     f"{PUBLISHED_ANCHORED['preview_extrap_pct']:g} %)", fontsize=9)
        ax.set_xlabel("normal load W (N)")
        ax.set_ylabel("pressure (MPa)")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8, loc="upper left")
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    path = save_figure(fig, path)
    plt.close(fig)
    return path
