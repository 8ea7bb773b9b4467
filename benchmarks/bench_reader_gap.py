"""Measurement: what every reading command does with machine settings whose predicted
contact ratio is short (docs/machine_settings.md sec. 5, "The readers' verdict on a
short prediction"), on the family of ``bench_settings_gap.py``: the 39 pairs below
eps_p 0.85, their standard settings written to a pair file as ``design
--machine-settings`` writes them (the gapped ones too: ``design`` refuses those, a user
may still type them).

For each pair file and each command that reads a ``--pair`` (in this process, through
:func:`gearcontact.cli.main`, default options but those named in ``COMMANDS``):

- the exit code and whether stderr has a ``ContactRatioWarning`` and a gap refusal ("no
  tooth pair in contact"), or, for ``sweep`` (a gap is a cell's result, not a refusal),
  a failed cell naming ``ContactGap``;
- commands that run no TCA of the pair (``bending``, ``export flanks``) and, on the
  gap-free pairs, every command but ``tca`` are stopped where their analysis starts
  (the first library call that takes the prepared pair, as
  tests/cli/test_pair_preparation.py does): the warning is printed when the pair is
  read, before that call; ``tca`` runs to its end on every pair (its verdict is the
  truth, docs sec. 5). On the gap-free pairs only ``tca``, ``analyze`` (its own
  preparation, ``report.analyze.run_analysis``) and ``bending`` run unless
  ``--all-commands`` (the other commands read the pair as ``tca`` does,
  ``cli.options.load_pair_for``).

Expected (the rule of docs sec. 5): a gapped pair refused (exit 2, the gap named) by
every command with a TCA, its cell failed by ``sweep``; no ``ContactRatioWarning`` from
a command with a TCA; the warning from the two without one, on every pair.

Usage::

    python benchmarks/bench_reader_gap.py                # the 39 pairs
    python benchmarks/bench_reader_gap.py --first 3      # the first three only

Wall seconds depend on the load (printed before and after); the counts do not.
"""

from __future__ import annotations

import argparse
import contextlib
import importlib
import io
import sys
import tempfile
import time
import warnings
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_settings_gap import FAMILY, family_pair  # noqa: E402

from cpu_timing import load_average

#: Each reading command: its argv after ``--pair FILE --out DIR``, whether it runs a TCA
#: of the pair, and where its analysis starts (module, name) for a stopped run.
COMMANDS = {
    "tca": (["--no-figures", "--quiet"], True, ("gearcontact.cli.tca", "analyze_pair")),
    "ltca": (["--no-figures"], True, ("gearcontact.cli.ltca", "analyze_pair")),
    "lte": (["--no-figures"], True, ("gearcontact.cli.lte", "analyze_pair")),
    "analyze": (["--lte-phases", "0", "--torques", "64.5", "--no-figures", "--quiet"], True,
                ("gearcontact.report.analyze", "analyze_pair")),
    "sweep": (["--vary", "E=0:0:1", "--workers", "0", "--quiet", "--no-figures"], True,
              ("gearcontact.sweep.run", "run_sweep")),
    "twin": (["--no-figures", "--quiet", "--duration-ms", "1"], True,
             ("gearcontact.cli.twin", "model_for_pair")),
    "export fmu": ([], True, ("gearcontact.export.fmu", "export_mesh_fmu")),
    "bending": (["--no-figures"], False, ("gearcontact.cli.bending", "flank_compliance")),
    "export flanks": ([], False, ("gearcontact.export.flanks", "export_flanks")),
}


#: The commands run on a gap-free pair without ``--all-commands``.
GAP_FREE_COMMANDS = ("tca", "analyze", "bending")


class _Reached(Exception):
    """The command reached its analysis."""


def _stopped(module: str, name: str):
    """A context in which ``module.name`` stops the command (raises :class:`_Reached`)."""
    mod = importlib.import_module(module)
    real = getattr(mod, name)

    @contextlib.contextmanager
    def ctx():
        def reached(*args, **kwargs):
            raise _Reached

        setattr(mod, name, reached)
        try:
            yield
        finally:
            setattr(mod, name, real)
    return ctx()


def run_command(command: str, pair_file: Path, out: Path, *, stop: bool):
    """``(exit code or "stopped", stderr, CPU s)`` of ``command`` on ``pair_file``."""
    from gearcontact.cli import main

    extra, _, (module, name) = COMMANDS[command]
    argv = [*command.split(), "--pair", str(pair_file), "--out", str(out), *extra]
    err = io.StringIO()
    c0 = time.process_time()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()), \
            (_stopped(module, name) if stop else contextlib.nullcontext()):
        try:
            code = main(argv)
        except _Reached:
            code = "stopped"
    text = err.getvalue()
    if "(_Reached" in text:     # the command line's handler caught the stop
        code = "stopped"
    return code, text, time.process_time() - c0


def main() -> None:
    from gearcontact.geometry.basic_settings import standard_machine_pair
    from gearcontact.geometry.gear_generation import generation_of
    from gearcontact.geometry.generation import check_generation
    from gearcontact.geometry.pair import pair_to_toml

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--first", type=int, default=None, help="only the first N pairs")
    ap.add_argument("--gapped", action="store_true", help="only the gapped pairs")
    ap.add_argument("--gap-free", action="store_true", help="only the gap-free pairs")
    ap.add_argument("--all-commands", action="store_true",
                    help="every command on the gap-free pairs too")
    ap.add_argument("--commands", default=None, metavar="C1,C2",
                    help="only these commands (names as in COMMANDS)")
    ap.add_argument("--rows", default=":", metavar="START:STOP",
                    help="a slice of the rows selected (after --gapped / --gap-free)")
    ap.add_argument("--shard", default="0/1", metavar="I/N",
                    help="the I-th of N interleaved parts of the rows (default 0/1)")
    args = ap.parse_args()
    i, n = map(int, args.shard.split("/"))
    start, stop = (int(x) if x else None for x in args.rows.split(":"))
    rows = [r for r in FAMILY if r[7] < 0.85 and (r[8] or not args.gapped)
            and not (r[8] and args.gap_free)][:args.first][start:stop][i::n]
    chosen = list(COMMANDS) if args.commands is None else args.commands.split(",")
    print(f"load average {load_average()}")
    names = list(COMMANDS)
    print("| z1/z2 | E | face | beta | alpha | k_d | eps_p | gap (doc) | "
          + " | ".join(names) + " |")
    print("|" + "---|" * (8 + len(names)))
    tally: dict = {}
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for k, spec in enumerate(rows):
            with warnings.catch_warnings():     # the commands below keep Python's filters
                warnings.simplefilter("ignore")
                blank = family_pair(spec, tmp)
                boxes = check_generation(blank, contact_ratio=False)
                cut = standard_machine_pair(blank, gear_generation=generation_of(boxes))
            pair_file = tmp / f"settings_{k}.toml"
            pair_file.write_text(pair_to_toml(cut))
            cells = []
            for command in names:
                if command not in chosen or not (spec[8] or args.all_commands
                                                 or command in GAP_FREE_COMMANDS):
                    cells.append("-")
                    continue
                has_tca = COMMANDS[command][1]
                stop = not has_tca or (not spec[8] and command != "tca")
                code, err, cpu = run_command(command, pair_file, tmp / f"o{k}_{command}",
                                             stop=stop)
                warned = "ContactRatioWarning" in err
                gap = ("failed cells: ContactGap" in err if command == "sweep"
                       else "no tooth pair in contact" in err)
                cells.append(f"{code}{' W' if warned else ''}{' GAP' if gap else ''}"
                             f" {cpu:.1f}s")
                if spec[8] and has_tca:
                    ok = gap and not warned and (code == (0 if command == "sweep" else 2))
                elif has_tca:
                    ok = not warned and not gap and code in (0, "stopped")
                else:
                    ok = warned and code == "stopped"
                key = (command, "gapped" if spec[8] else "gap-free")
                tally.setdefault(key, [0, 0])[0 if ok else 1] += 1
                if not ok:
                    print(f"  unexpected: {command} on row {spec[:7]}: exit {code}, "
                          f"stderr {err.strip()[-400:]!r}", flush=True)
            z1, z2, E, face, beta, alpha, kd = spec[:7]
            print(f"| {z1}/{z2} | {E} | {face} | {beta} | {alpha} | {kd} | {spec[7]:.3f} | "
                  f"{'gap' if spec[8] else '-'} | " + " | ".join(cells) + " |", flush=True)
    print(f"load average {load_average()}")
    for (command, kind), (good, bad) in sorted(tally.items()):
        print(f"{command:14s} {kind:9s} as expected {good}, not {bad}")


if __name__ == "__main__":
    main()
