"""Markdown pieces shared by the report's sections (tables, relative differences)."""

from __future__ import annotations

__all__ = ["md_table", "pct_diff"]


def md_table(header: list[str], rows: list[list]) -> str:
    """A Markdown table: floats with 4 significant digits, None as an empty cell."""
    def fmt(x):
        if isinstance(x, float):
            return f"{x:.4g}"
        return "" if x is None else str(x)

    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(fmt(x) for x in r) + " |" for r in rows]
    return "\n".join(lines)


def pct_diff(a: float, b: float) -> float:
    """Relative difference of ``a`` from ``b``, %."""
    return 100.0 * (a / b - 1.0)
