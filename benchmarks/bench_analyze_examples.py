"""Benchmark: ``gearcontact analyze --pair examples/<pair>.toml`` with default options on
every shipped example (issue 28: the main job on ordinary pairs), wall and CPU time.

Each run is the console script in its own process (numba's on-disk cache as it is: run
``gearcontact warm-up`` first to exclude compilation), into a temporary directory. The
table gives wall time, the child's CPU time (user + system, the fairer figure on a
shared machine), the split of run.json's stage timings (ease-off synthesis, TCA, LTCA,
LTE, multi-tooth) and the load average before and after.

Measured on the project machine (2 cores, load 0.1-1.2, warm numba cache), wall / CPU
s: hypoid 11x41 168 / 162 (ease-off synthesis 144), F.2 spiral bevel 95 / 96 (73),
F.3 99 / 100 (77): the synthesis is 75-85 % of the main job on a pair without an
ease-off table; TCA 4.5-6.2 s, LTE 4.3-4.8 s, multi-tooth 1.2-1.3 s.

After the reduced-TCA synthesis (session 7, docs/synthesis.md; machine shared, load
5.5-7 on 2 cores, numba cache of a fresh worktree: the first run compiled), wall / CPU
s: hypoid 11x41 219 / 50 (ease-off synthesis 10.1), F.2 spiral bevel 176 / 32 (22.6),
F.3 158 / 31 (13.4): CPU time down 3.0-3.3x, the synthesis 6-14x; the wall times are
those of the load (the child had about a fifth of a core).

After the edge-contact check and the miter's synthesis (session 12; measured on 3c5d414,
warm cache, load 1.0 rising to 8), wall / CPU s, every example exit 0: hypoid 11x41 42.0 /
17.9 (synthesis 2.3, LTE 16.3), F.2 50.1 / 19.8 (3.3, 18.7), F.3 72.5 / 24.6 (3.6,
28.1); cylindrical EV 23x67 38.3 / 38.3 (Harris map 26.2), FZG C 32.9 / 24.6, spur
20x40 79.8 / 27.7.

Issue 28's acceptance audit (session 16, on 9c868c3: the operating-load edge law and the
degree-6 ROM merged; numba cache filled by ``gearcontact warm-up`` first, which took 293 s
CPU and 24.5 min wall into the fresh worktree's empty cache; load average 10-14 on the 2
cores, so wall is 5-7 times CPU), wall / CPU s, every example exit 0: hypoid 11x41 200 /
20.3, F.2 163 / 20.9, F.3 143 / 21.5; cylindrical EV 23x67 338 / 51.7, FZG C 115 / 25.9,
spur 20x40 104 / 30.0; the typed machine settings of F.2 (examples/machine_settings/) 145
/ 27.1.

The acceptance audit on the final tree (session 17, 332ef0b; ``--audit``; numba cache
filled by ``gearcontact warm-up``, 243 s CPU, 8.1 min wall; load average 3.3-15.6 on the
2 cores), analyze wall / CPU s, every example exit 0: hypoid 11x41 57 / 19.6, F.2 55 /
18.2, F.3 106 / 21.5; cylindrical EV 23x67 115 / 41.4, FZG C 70 / 24.2, spur 20x40 125 /
25.6; the typed machine settings of F.2 156 / 20.8. ``twin`` 6.1-15.5 s CPU on the
examples. All 58 runs of the 29 pairs: 56 exit 0, 2 named refusals before work (F.3 at
beta1 25 deg with c_ham 0.164: the blade point width); 1002 s CPU, 60 min wall. Table:
docs/performance.md, "Issue 28 acceptance audit".

Run: ``python benchmarks/bench_analyze_examples.py [--pair FILE ...]`` (``analyze`` on the
examples), or ``python benchmarks/bench_analyze_examples.py --audit DIR`` (issue 28's
acceptance audit: ``analyze`` and ``twin`` with default options on the 29 pairs of
:func:`audit_pairs`, one run at a time; the variant TOMLs are written into ``DIR/pairs``,
each run's files into ``DIR/runs``, one JSON line per run into ``DIR/audit.jsonl`` and the
table into ``DIR/audit.md``; ``--only TEXT`` and ``--command`` select runs).
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import re
import resource
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: Issue 28's F.3 variants and catalogue pairs: (name, label, example, fields changed) —
#: the example's file with ``name`` and those ``section.key`` values replaced
#: (docs/performance.md, "Issue 28 acceptance audit"; the c_ham values are those
#: docs/geometry.md sec. 7.2 names; F.2's 25.4 mm face is beyond the 20/20 pair's limit).
F3, F2 = "iso23509_f3.toml", "iso23509_f2_spiral_bevel.toml"
VARIANTS = (
    ("f2_20x20", "F.2 data, 20/20 miter", F2, {
        "teeth.pinion": 20, "teeth.gear": 20, "design.gear_face_width_mm": 25.0,
        "design.pinion_face_width_mm": 25.0}),
    ("cat_15x45_E0_b35", "F.3 data, 15/45, E 0, β1 35°", F3, {
        "teeth.pinion": 15, "teeth.gear": 45, "axes.offset_mm": 0.0,
        "design.pinion_spiral_angle_deg": 35.0}),
    ("cat_17x29_E12", "F.3 data, 17/29, E 12 mm", F3, {
        "teeth.pinion": 17, "teeth.gear": 29, "axes.offset_mm": 12.0}),
    ("cat_17x29_E12_cham038", "F.3 data, 17/29, E 12 mm, c_ham 0.038", F3, {
        "teeth.pinion": 17, "teeth.gear": 29, "axes.offset_mm": 12.0,
        "design.gear_addendum_factor": 0.038}),
    ("cat_8x39_E25", "F.3 data, 8/39, E 25 mm", F3, {
        "teeth.pinion": 8, "teeth.gear": 39, "axes.offset_mm": 25.0}),
    ("f3_9x37", "F.3, 9/37", F3, {"teeth.pinion": 9, "teeth.gear": 37}),
    ("f3_10x43", "F.3, 10/43", F3, {"teeth.pinion": 10, "teeth.gear": 43}),
    ("f3_13x45", "F.3, 13/45", F3, {"teeth.gear": 45}),
    *((f"f3_E{e:g}", f"F.3, E {e:g}" + (" mm" if e else ""), F3, {"axes.offset_mm": e})
      for e in (0.0, 10.0, 20.0, 30.0)),
    ("f3_left", "F.3, left hand", F3, {"design.pinion_hand": "left"}),
    *((f"f3_b{b:g}", f"F.3, β1 {b:g}°", F3, {"design.pinion_spiral_angle_deg": b})
      for b in (25.0, 30.0, 35.0, 40.0, 45.0)),
    ("f3_b25_cham0164", "F.3, β1 25°, c_ham 0.164", F3, {
        "design.pinion_spiral_angle_deg": 25.0, "design.gear_addendum_factor": 0.164}),
)

#: Design-space pairs of tests/design_space.py (``design_space_pair`` arguments, each its
#: own crowning, so no synthesized ease-off): the rattling miter pairs, MITER_PAIR and two
#: draws of the slow twin property test (tests/twin/test_design_space.py, derandomized).
RATTLING = (
    ("ds_miter", "MITER_PAIR (15/15, 23°, left)", (15, 1.0, 0.0, 23.0, 0.25, "drive", "left")),
    ("dsp3_12x12_b27p7_dl", "property test's 12/12, 27.7°, left",
     (12, 1.0, 0.0, 27.74456822895699, 0.1893217700722522, "drive", "left")),
    ("dsp5_15x15_b25p9_dl", "property test's 15/15, 25.9°, left",
     (15, 1.0, 0.0, 25.885061880332398, 0.198538005841265, "drive", "left")),
)


def _toml_value(v) -> str:
    return f'"{v}"' if isinstance(v, str) else repr(v)


def with_fields(text: str, fields: dict) -> str:
    """``text`` (a pair TOML) with each ``section.key`` line's value replaced."""
    for dotted, value in fields.items():
        section, _, key = dotted.rpartition(".")
        block = rf"^\[{section}\]\n(?:(?!^\[).*\n)*?" if section else r"\A(?:(?!^\[).*\n)*?"
        pattern = re.compile(rf"({block}^{key}\s*=\s*)[^\n#]*", re.M)
        text, n = pattern.subn(lambda m: m.group(1) + _toml_value(value), text)
        if n != 1:
            raise KeyError(f"{dotted} not found once in the pair file")
    return text


def audit_pairs(pairs_dir: Path) -> list[tuple[str, Path]]:
    """The 29 pairs of the audit, ``(label, TOML file)``: the shipped examples as they
    are, the variants written into ``pairs_dir`` (identical every time)."""
    sys.path.insert(0, str(ROOT / "tests"))
    from dataclasses import replace

    from design_space import MITER_PAIR, design_space_pair
    from gearcontact.geometry.pair import pair_to_toml

    assert RATTLING[0][2] == MITER_PAIR
    pairs_dir.mkdir(parents=True, exist_ok=True)
    out = [(f"examples/{p.relative_to(ROOT / 'examples').with_suffix('')}", p)
           for p in _examples()]
    for name, label, example, fields in VARIANTS:
        path = pairs_dir / f"{name}.toml"
        text = with_fields((ROOT / "examples" / example).read_text(), {"name": name, **fields})
        path.write_text(f"# {label}: examples/{example} with {fields}\n" + text)
        out.append((label, path))
    for name, label, point in RATTLING:
        path = pairs_dir / f"{name}.toml"
        path.write_text(f"# {label}: tests/design_space.py design_space_pair{point}\n"
                        + pair_to_toml(replace(design_space_pair(*point), name=name)))
        out.append((label, path))
    return out


def _examples() -> list[Path]:
    # every shipped pair, the typed machine settings in examples/machine_settings/ too
    return sorted(p for p in (ROOT / "examples").rglob("*.toml") if "[teeth]" in p.read_text())


def _timings(run_json: Path) -> dict:
    """Every float timing of run.json (seconds), flattened with dotted keys."""
    flat = {}

    def walk(prefix, obj):
        if isinstance(obj, dict):
            for k, v in obj.items():
                walk(f"{prefix}.{k}" if prefix else k, v)
        elif isinstance(obj, float):
            flat[prefix] = obj

    walk("", json.loads(run_json.read_text()).get("timings_s", {}))
    return flat


def _command() -> list[str]:
    # the console script, as a user runs it (python -m gearcontact where it is missing)
    exe = shutil.which("gearcontact")
    return [exe] if exe else [sys.executable, "-m", "gearcontact"]


#: Columns whose NaN is documented ("no such pair at this phase" in te0.csv, a cell off
#: the flank in gap_field.csv, a line with no painted part in contact_lines.csv): not a
#: missing result. preview.csv's golden_* / chain_* columns may be NaN where that row's
#: status is not "ok" (the status names why; a warning line counts them).
NAN_DOCUMENTED = {"te0.csv": ("te0_pair",), "gap_field.csv": ("gap_mm",),
                  "contact_lines.csv": ("painted_",)}


def _nan_cells(out: Path) -> dict:
    """NaN cells of a run's results (CSV columns and JSON values) that no documented
    meaning covers (:data:`NAN_DOCUMENTED`), per file."""
    found = {}
    for f in sorted(out.glob("*.csv")):
        with f.open(newline="") as fh:
            rows = list(csv.DictReader(fh))
        allowed = NAN_DOCUMENTED.get(f.name, ())
        n = 0
        for r in rows:
            for k, v in r.items():
                if v is None or v.strip().lower() != "nan" or k.startswith(allowed):
                    continue
                prefix = k.split("_", 1)[0]
                if r.get(f"{prefix}_status", "ok") != "ok":   # a named missing result
                    continue
                n += 1
        if n:
            found[f.name] = n
    for f in sorted(out.glob("*.json")):
        n = len(re.findall(r"\bNaN\b|\bnan\b", f.read_text()))
        if n:
            found[f.name] = n
    return found


def run_command(command: str, pair: Path, out: Path) -> dict:
    """``gearcontact COMMAND --pair PAIR --out OUT`` (default options) in its own process:
    exit code, wall and child CPU time, load average, stdout, stderr, NaN cells."""
    if out.exists():
        shutil.rmtree(out)
    load = os.getloadavg()[0]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    proc = subprocess.run([*_command(), command, "--pair", str(pair), "--out", str(out)],
                          capture_output=True, text=True, check=False)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    row = {"command": command, "pair_file": str(pair), "exit": proc.returncode,
           "wall_s": wall, "cpu_s": cpu, "load_before": load, "load_after": os.getloadavg()[0],
           "stdout": proc.stdout.strip().splitlines(),
           # stderr without the progress bars: warnings, notes, errors
           "stderr": [ln for ln in proc.stderr.strip().splitlines()
                      if ln.strip() and "%|" not in ln and "\x1b[A" not in ln],
           "nan_cells": _nan_cells(out) if out.is_dir() else {}}
    if command == "twin" and (out / "twin.json").is_file():
        s = json.loads((out / "twin.json").read_text())
        row["twin"] = {k: s.get(k) for k in ("dynamic_factor", "contact_loss", "dte_pp_arcsec",
                                             "mean_mesh_torque_nm")}
    if command == "analyze" and (out / "lte.json").is_file():
        s = json.loads((out / "lte.json").read_text())
        row["lte"] = {k: s.get(k) for k in ("te0_pp_arcsec", "te_lcp_pp_arcsec",
                                            "te_pre_pp_arcsec")}
    return row


def headline(row: dict) -> str:
    """One table cell: the key results and the stderr lines' count."""
    warnings = [ln for ln in row["stderr"] if ": warning:" in ln]
    parts = []
    if row["exit"] != 0:
        parts.append(f"`{row['stderr'][-1] if row['stderr'] else ''}`")
    elif row["command"] == "twin" and "twin" in row:
        t = row["twin"]
        parts.append(f"DF {t['dynamic_factor']:.2f}, loss {100 * t['contact_loss']:.1f} %, "
                     f"DTE {t['dte_pp_arcsec']:.1f}″, mean {t['mean_mesh_torque_nm']:.2f} N·m")
    elif row["stdout"]:
        line = next((ln for ln in reversed(row["stdout"]) if "TE0 p-p" in ln), row["stdout"][-1])
        parts.append(re.sub(r"^[^:]*: ", "", line.split(" -> ")[0]).replace(" arcsec", " ″"))
    if any("synthesized" in ln for ln in row["stdout"]):
        parts.append("ease-off synthesized")
    if row["nan_cells"]:
        parts.append("NaN in " + ", ".join(f"{k} ({v})" for k, v in row["nan_cells"].items()))
    parts.append(f"{len(warnings)} warning(s)")
    return "; ".join(parts)


def audit(out_dir: Path, *, only: str | None, commands: tuple[str, ...]) -> None:
    """Issue 28's acceptance audit into ``out_dir`` (module docstring)."""
    pairs = audit_pairs(out_dir / "pairs")
    log = out_dir / "audit.jsonl"
    for label, pair in pairs:
        if only and only not in label:
            continue
        for command in commands:
            slug = re.sub(r"[^A-Za-z0-9]+", "_", f"{pair.stem}_{command}")
            row = {"pair": label, **run_command(command, pair, out_dir / "runs" / slug)}
            with log.open("a") as f:
                f.write(json.dumps(row) + "\n")
            print(f"| {label} | {command} | {row['exit']} | {row['wall_s']:.0f} | "
                  f"{row['cpu_s']:.1f} | {row['load_before']:.1f} | {headline(row)} |",
                  flush=True)
    write_table(out_dir, [label for label, _ in pairs])


def write_table(out_dir: Path, labels: list[str]) -> None:
    """``out_dir/audit.md`` from ``audit.jsonl``: the last run of each pair and command,
    in the order of ``labels``; the NaN scan taken again from the run's files."""
    rows = {}
    for line in (out_dir / "audit.jsonl").read_text().splitlines():
        r = json.loads(line)
        run_dir = out_dir / "runs" / re.sub(r"[^A-Za-z0-9]+", "_",
                                            f"{Path(r['pair_file']).stem}_{r['command']}")
        if run_dir.is_dir():
            r["nan_cells"] = _nan_cells(run_dir)
        r["stderr"] = [ln for ln in r["stderr"] if "%|" not in ln and "\x1b[A" not in ln]
        rows[(r["pair"], r["command"])] = r
    table = ["| pair | command | exit | wall s | CPU s | load | headline |",
             "|---|---|---:|---:|---:|---:|---|"]
    order = {label: i for i, label in enumerate(labels)}
    for (label, command), r in sorted(rows.items(), key=lambda kv: (order.get(kv[0][0], 99),
                                                                   kv[0][1])):
        table.append(f"| {label} | {command} | {r['exit']} | {r['wall_s']:.0f} | "
                     f"{r['cpu_s']:.1f} | {r['load_before']:.1f} | {headline(r)} |")
    (out_dir / "audit.md").write_text("\n".join(table) + "\n")


def bench(pair: Path) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        proc = subprocess.run([*_command(), "analyze", "--pair", str(pair), "--out", tmp],
                              capture_output=True, text=True, check=False)
        wall = time.perf_counter() - t0
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        timings = _timings(Path(tmp) / "run.json") if proc.returncode == 0 else {}
    return {"pair": pair.stem, "exit": proc.returncode, "wall_s": wall, "cpu_s": cpu,
            "timings": timings, "stderr": proc.stderr.strip().splitlines()[-1:]}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--pair", action="append", type=Path, help="pair file (default: every "
                    "example in examples/)")
    ap.add_argument("--audit", type=Path, metavar="DIR", help="issue 28's acceptance audit "
                    "into DIR (analyze and twin on the 29 pairs)")
    ap.add_argument("--only", help="--audit: the pairs whose label holds this text")
    ap.add_argument("--command", choices=("analyze", "twin"), action="append",
                    help="--audit: this command only (default both)")
    ap.add_argument("--table-only", action="store_true", help="--audit: rewrite DIR/audit.md "
                    "from DIR/audit.jsonl, no run")
    args = ap.parse_args()
    if args.audit and args.table_only:
        write_table(args.audit, [label for label, _ in audit_pairs(args.audit / "pairs")])
        return
    if args.audit:
        audit(args.audit, only=args.only, commands=tuple(args.command or ("analyze", "twin")))
        return
    pairs = args.pair or _examples()
    print(f"load average before: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    rows = [bench(p) for p in pairs]
    print(f"{'pair':<28}{'exit':>5}{'wall s':>9}{'CPU s':>9}  stages (wall s)")
    for r in rows:
        stages = ", ".join(f"{k} {v:.1f}" for k, v in r["timings"].items() if v >= 0.5)
        print(f"{r['pair']:<28}{r['exit']:>5}{r['wall_s']:>9.1f}{r['cpu_s']:>9.1f}  "
              f"{stages or r['stderr']}")
    print(f"load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")


if __name__ == "__main__":
    main()
