"""Figures of a sweep.

* :func:`plot_maps` -- maps over two swept keys (the V/H chart for ``E``, ``P``): the
  pattern centre's shift from the reference point as arrows on the flank axes (face,
  height) and as two maps, TE0, and with LTCA one row per torque (preview p_max, LCP
  p90, loaded TE p-p); the pattern-on-flank boundary and the failed cells on each.
* :func:`plot_design` -- the outputs over each swept design key (lines; one per torque
  for the loaded values); of a cylindrical pair, TE0 and loaded TE p-p, peak pressure
  and mean mesh stiffness.

Keys not drawn are held at their reference value: the grid value nearest 0 for an
assembly error, the middle of the range for a design key.
"""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

__all__ = ["plot_design", "plot_maps", "reference_index"]

_ASSEMBLY_LABELS = {"E_mm": "E, offset change (V)", "P_mm": "P, pinion axial (H)",
                    "G_mm": "G, gear axial", "alpha_deg": "alpha, shaft angle"}
_LOADED = (("preview_p_max_mpa", "preview p_max"), ("lcp_p90_mpa", "LCP p90"),
           ("lte_lcp_pp_arcsec", "loaded TE p-p (LCP)"))
#: The panels of a cylindrical pair's sweep (:mod:`.cylindrical`).
_CYLINDRICAL = ((("te0_pp_arcsec", "TE0 p-p"), ("te0_mean_arcsec", "TE0 mean")),)
_CYLINDRICAL_LOADED = (("lte_pp_arcsec", "loaded TE p-p"), ("p_max_mpa", "peak pressure"),
                       ("stiffness_mean_n_per_mm_um", "mesh stiffness, mean"))
_PER_TORQUE = {name for name, _ in (*_LOADED, *_CYLINDRICAL_LOADED)}


def _open(store):
    import xarray as xr

    return xr.open_zarr(store, consolidated=False).load()


def _is_design(ds, dim: str) -> bool:
    return "." in str(ds[dim].attrs.get("key", ""))


def _label(ds, dim: str) -> str:
    key = str(ds[dim].attrs.get("key", dim))
    if _is_design(ds, dim):         # table on a line of its own: keys are long
        table, name = key.rsplit(".", 1)
        return f"{name} ({ds[dim].attrs.get('units', '')})\n[{table}]"
    return f"{_ASSEMBLY_LABELS.get(dim, key)} ({ds[dim].attrs.get('units', '')})"


def reference_index(ds, dim: str) -> int:
    """Index of the reference value of a swept key (nearest 0 for an assembly error,
    the middle for a design key)."""
    values = ds[dim].values
    if _is_design(ds, dim):
        return len(values) // 2
    return int(np.argmin(np.abs(values)))


def _hold(ds, keep):
    """``ds`` with every swept key but ``keep`` (and the torques) at its reference."""
    return ds.isel({d: reference_index(ds, d) for d in ds.dims
                    if d not in (*keep, "torque_nm")})


def _marks(ax, ds2, xd, yd) -> None:
    """Pattern-on-flank boundary (white/black line, the off-flank side hatched) and
    failed cells (red x) on a map."""
    x, y = ds2[xd].values, ds2[yd].values
    inside = ds2["pattern_on_flank"].transpose(yd, xd).values.astype(float)
    if 0.0 < inside.mean() < 1.0 and min(inside.shape) > 1:
        ax.contourf(x, y, inside, levels=[-0.5, 0.5], colors="none", hatches=["//"])
        ax.contour(x, y, inside, levels=[0.5], colors="w", linewidths=2)
        ax.contour(x, y, inside, levels=[0.5], colors="k", linewidths=0.8,
                   linestyles="--")
    failed = ds2["status"].transpose(yd, xd).values == 2
    gx, gy = np.meshgrid(x, y)
    ax.plot(gx[failed], gy[failed], "rx", ms=7, mew=1.5)


def _map(fig, ax, ds2, xd, yd, z, label, cmap="viridis", *, centred: bool = False) -> None:
    """A map of ``z`` (rows y, columns x); ``centred``: colour limits symmetric about 0."""
    lim = float(np.nanmax(np.abs(z))) if centred and np.isfinite(z).any() else None
    im = ax.pcolormesh(ds2[xd].values, ds2[yd].values, z, shading="nearest", cmap=cmap,
                       vmin=-lim if lim else None, vmax=lim if lim else None)
    fig.colorbar(im, ax=ax, label=label)
    _marks(ax, ds2, xd, yd)
    ax.set_xlabel(_label(ds2, xd))
    ax.set_ylabel(_label(ds2, yd))


def plot_maps(store, path, *, title: str = "", dims: tuple | None = None) -> Path:
    """PNG of the maps over two swept keys (module docstring), every torque.

    Parameters
    ----------
    store : path
        The sweep's zarr store.
    path : path
        The PNG written.
    title : str
        Head of the figure title.
    dims : (str, str), optional
        The two dimensions drawn (x, y); default the first two swept assembly errors,
        else the first two swept keys.
    """
    ds = _open(store)
    swept = [d for d in ds.dims if d != "torque_nm"]
    if dims is None:
        assembly = [d for d in swept if not _is_design(ds, d)]
        dims = tuple((assembly if len(assembly) >= 2 else swept)[:2])
    xd, yd = dims
    ds2 = _hold(ds, dims)
    ref = {xd: reference_index(ds2, xd), yd: reference_index(ds2, yd)}
    loaded = [(n, t) for n, t in _LOADED if n in ds2]
    torques = ds2["torque_nm"].values
    n_col = 4
    rows = 1 + (len(torques) if loaded else 0)
    fig, axes = plt.subplots(rows, n_col, figsize=(4.4 * n_col, 3.7 * rows), squeeze=False)
    first = ds2.isel(torque_nm=0)       # the TCA values do not depend on the torque
    shift = {n: (first[n] - float(first[n].isel(ref))).transpose(yd, xd).values
             for n in ("pattern_face_mm", "pattern_height_mm")}
    ax = axes[0, 0]                     # V/H chart: the pattern's move on the flank
    gx, gy = np.meshgrid(first[xd].values, first[yd].values)
    ok = np.isfinite(shift["pattern_face_mm"]) & np.isfinite(shift["pattern_height_mm"])
    length = np.nanmax(np.hypot(shift["pattern_face_mm"], shift["pattern_height_mm"]))
    length = length if np.isfinite(length) and length > 0 else 1.0
    # drawn in screen units (the two swept keys may have different units): the
    # longest arrow spans 0.8 of a grid cell's width
    ax.quiver(gx[ok], gy[ok], shift["pattern_face_mm"][ok], shift["pattern_height_mm"][ok],
              angles="uv", scale_units="width", scale=length * first[xd].size / 0.8,
              color="C0", width=0.008)
    _marks(ax, first, xd, yd)
    for axis, v in ((ax.set_xlim, first[xd].values), (ax.set_ylim, first[yd].values)):
        pad = 0.15 * (np.ptp(v) or 1.0)
        axis(v.min() - pad, v.max() + pad)
    ax.set_xlabel(_label(first, xd))
    ax.set_ylabel(_label(first, yd))
    ax.set_title("V/H chart: pattern centre shift on the gear flank\n(right = to heel, "
                 f"up = to tip; longest arrow {length:.2g} mm)", fontsize=9)
    _map(fig, axes[0, 1], first, xd, yd, shift["pattern_face_mm"],
         "pattern shift along face, toe->heel (mm)", "RdBu_r", centred=True)
    _map(fig, axes[0, 2], first, xd, yd, shift["pattern_height_mm"],
         "pattern shift along profile, root->tip (mm)", "RdBu_r", centred=True)
    _map(fig, axes[0, 3], first, xd, yd, first["te0_pp_arcsec"].transpose(yd, xd).values,
         "TE0 peak to peak (arcsec)")
    for r, torque in enumerate(torques if loaded else [], start=1):
        cell = ds2.isel(torque_nm=r - 1)
        for c, (name, text) in enumerate(loaded):
            _map(fig, axes[r, c], cell, xd, yd, cell[name].transpose(yd, xd).values,
                 f"{text} ({cell[name].attrs.get('units', '')})", "magma")
            axes[r, c].set_title(f"{torque:g} N·m", fontsize=9)
        for c in range(len(loaded), n_col):
            axes[r, c].set_axis_off()
    held = [f"{_label(ds, d)} = {ds[d].values[reference_index(ds, d)]:g}".replace("\n", " ")
            for d in swept if d not in dims]
    note = ("white/black line: pattern-on-flank boundary, hatched: pattern leaves the "
            "flank; red x: failed cell; shifts from the point nearest the nominal")
    fig.suptitle("\n".join(s for s in (title, note, ", ".join(held)) if s), fontsize=10)
    fig.tight_layout()
    out = Path(path)
    fig.savefig(out, dpi=100)
    plt.close(fig)
    return out


def plot_design(store, path, *, title: str = "") -> Path:
    """PNG of the outputs over every swept design key (lines; module docstring)."""
    ds = _open(store)
    design = [d for d in ds.dims if d != "torque_nm" and _is_design(ds, d)]
    if "pattern_length_mm" in ds:
        panels = [(("te0_pp_arcsec", "TE0 p-p"),), (("pattern_length_mm", "pattern length"),
                                                     ("paint_major_mm", "paint ellipse 2a"))]
        panels += [(item,) for item in _LOADED if item[0] in ds]
    else:
        panels = [*_CYLINDRICAL, *((item,) for item in _CYLINDRICAL_LOADED if item[0] in ds)]
    n_col = 3
    per_dim = -(-len(panels) // n_col)          # rows of panels per design key
    fig, axes = plt.subplots(per_dim * len(design), n_col, squeeze=False,
                             figsize=(4.6 * n_col, 3.6 * per_dim * len(design)))
    for r in range(len(design)):
        for c in range(len(panels), per_dim * n_col):
            axes[r * per_dim + c // n_col, c % n_col].set_axis_off()
    for r, dim in enumerate(design):
        one = _hold(ds, (dim,))
        x = one[dim].values
        for c, panel in enumerate(panels):
            ax = axes[r * per_dim + c // n_col, c % n_col]
            for name, text in panel:
                if name in _PER_TORQUE:
                    for k, torque in enumerate(one["torque_nm"].values):
                        ax.plot(x, one[name].isel(torque_nm=k).values, "o-",
                                label=f"{text}, {torque:g} N·m")
                else:
                    ax.plot(x, one[name].isel(torque_nm=0).values, "o-", label=text)
                unit = one[name].attrs.get("units", "")
            failed = (one["status"] == 2).any("torque_nm").values
            for xf in x[failed]:
                ax.axvline(xf, color="r", lw=0.8, ls=":")
            ax.set_xlabel(_label(one, dim))
            ax.set_ylabel(f"{panel[0][1]} ({unit})" if len(panel) == 1 else f"({unit})")
            ax.legend(fontsize=7)
            ax.grid(alpha=0.3)
    held = [f"{_label(ds, d)} = {ds[d].values[reference_index(ds, d)]:g}"
            for d in ds.dims if d != "torque_nm" and not _is_design(ds, d)]
    note = "red dotted line: failed variant"
    fig.suptitle("\n".join(s for s in (title, note, ", ".join(held)) if s), fontsize=10)
    fig.tight_layout()
    out = Path(path)
    fig.savefig(out, dpi=100)
    plt.close(fig)
    return out
