"""Maps of a two-dimensional sweep (the V/H chart): the pattern centre's shift along
face and profile from the grid's middle point, TE0 and (with LTCA) the preview p_max
over the two swept errors, the pattern-on-flank boundary drawn on each."""

from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

__all__ = ["plot_maps"]


def plot_maps(store, path, *, title: str = "", torque_index: int = 0) -> Path:
    """PNG of the maps of a sweep over two assembly errors at one torque."""
    import xarray as xr

    ds = xr.open_zarr(store, consolidated=False).isel(torque_nm=torque_index).load()
    xd, yd = [d for d in ds.dims if d != "torque_nm"]
    names = ["pattern_face_mm", "pattern_height_mm", "te0_pp_arcsec"]
    names += ["preview_p_max_mpa"] if "preview_p_max_mpa" in ds else []
    fig, axes = plt.subplots(1, len(names), figsize=(4.2 * len(names), 3.8))
    mid = {xd: ds[xd].size // 2, yd: ds[yd].size // 2}
    for ax, name in zip(np.atleast_1d(axes), names):
        z = ds[name].transpose(yd, xd).values
        label = f"{name} ({ds[name].attrs.get('units', '')})"
        if name.startswith("pattern_"):       # the shift from the grid's middle point
            z = z - float(ds[name].isel(mid))
            label = f"shift of {name} (mm)"
        im = ax.pcolormesh(ds[xd].values, ds[yd].values, z, shading="nearest")
        fig.colorbar(im, ax=ax, label=label)
        inside = ds["pattern_on_flank"].transpose(yd, xd).values.astype(float)
        if 0.0 < inside.mean() < 1.0 and min(inside.shape) > 1:
            ax.contour(ds[xd].values, ds[yd].values, inside, levels=[0.5], colors="w")
        failed = ds["status"].transpose(yd, xd).values == 2
        gx, gy = np.meshgrid(ds[xd].values, ds[yd].values)
        ax.plot(gx[failed], gy[failed], "rx", ms=6)
        ax.set_xlabel(f"{xd} ({ds[xd].attrs.get('units', '')})")
        ax.set_ylabel(f"{yd} ({ds[yd].attrs.get('units', '')})")
    fig.suptitle(f"{title}: white line = pattern on flank boundary, x = failed cell"
                 if title else "white line = pattern on flank boundary, x = failed cell",
                 fontsize=9)
    fig.tight_layout()
    out = Path(path)
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return out
