"""One pair preparation for every command that analyses a --pair
(:func:`gearcontact.tca.synthesis.prepare_pair`, through
:func:`gearcontact.cli.options.load_pair_for`).

Truth: a pair file without an [easeoff.drive] table reaches the analysis of every such
command (tca, ltca, lte, analyze, sweep, twin, bending) with the same ease-off: the
coefficients of one real local synthesis of that pair, and the table marked as given
(``easeoff_tables``). The synthesis is deterministic (the same pair, the same
coefficients: `tests/cli/test_sweep.py` compares tca and sweep results exactly, and the
slow test here runs it in every command). The flanks the synthesis built (the
conjugate flanks with the synthesized ease-off applied, ``geometry.flank.with_easeoff``)
are the very object every command analyses: none builds them a second time.
"""

import dataclasses
import pytest

import gearcontact.tca.synthesis as synthesis
from gearcontact.cli import main
from gearcontact.geometry.pair import load_pair

#: The command, its extra options, and where its analysis starts (module, function): the
#: first call that takes the prepared pair.
COMMANDS = {
    "tca": ([], "gearcontact.cli.tca", "analyze_pair"),
    "ltca": ([], "gearcontact.cli.ltca", "analyze_pair"),
    "lte": ([], "gearcontact.cli.lte", "analyze_pair"),
    "analyze": (["--lte-phases", "0"], "gearcontact.report.analyze", "analyze_pair"),
    "sweep": (["--vary", "E=0:0:1", "--workers", "0"], "gearcontact.sweep.run",
              "run_sweep"),
    "twin": ([], "gearcontact.cli.twin", "model_for_pair"),
    "bending": ([], "gearcontact.cli.bending", "flank_compliance"),
}


class _Reached(Exception):
    """The command reached its analysis (the pair is captured)."""


@pytest.fixture(scope="module")
def synthesized(bare_pair_file):
    """One real synthesis of the bare pair's drive side."""
    prepared = synthesis.prepare_pair(load_pair(str(bare_pair_file)), side="drive")
    assert prepared.synthesized and "drive" in prepared.pair.easeoff_tables
    return prepared


def _capture(monkeypatch, module: str, name: str, seen: list):
    """Replace ``module.name`` by a function that records the pair it is given and stops
    the command there."""
    def reached(*args, **kwargs):
        pair = next(a for a in (*args, *kwargs.values()) if hasattr(a, "easeoff_drive"))
        seen.append((pair, kwargs.get("flanks")))
        raise _Reached

    monkeypatch.setattr(f"{module}.{name}", reached)


@pytest.mark.parametrize("command", sorted(COMMANDS))
def test_every_pair_command_gets_the_prepared_pair(command, bare_pair_file, synthesized,
                                                  monkeypatch, tmp_path, capsys):
    """Each command synthesizes once (through prepare_pair, the synthesis replaced by the
    fixture's real result to keep the suite fast) and analyses the pair with exactly
    those coefficients and the flanks the preparation built; the note on stdout names the
    synthesis without a time and the file holding its TOML block (analyze prints it at
    the end)."""
    calls = []

    def synthesize_pair(pair, *, sides, **_):
        calls.append(tuple(sides))
        return synthesized.pair, {"drive": synthesized.synthesis}

    monkeypatch.setattr(synthesis, "synthesize_pair", synthesize_pair)
    built = []

    def with_easeoff(*args, _real=synthesis.with_easeoff):
        built.append(_real(*args))
        return built[-1]

    monkeypatch.setattr(synthesis, "with_easeoff", with_easeoff)
    seen = []
    extra, module, name = COMMANDS[command]
    if command == "sweep":      # the sweep command imports run_sweep when it runs
        import gearcontact.sweep.run  # noqa: F401
    _capture(monkeypatch, module, name, seen)
    main([command, "--pair", str(bare_pair_file), "--side", "drive", *extra,
          "--out", str(tmp_path / "out")])
    assert calls == [("drive",)]
    ((pair, flanks),) = seen
    assert len(built) == 1 and flanks is built[0]       # the synthesis' flanks, once
    assert pair.easeoff_drive == synthesized.pair.easeoff_drive
    assert "drive" in pair.easeoff_tables
    if command != "analyze":    # analyze prints it when done (and writes it to summary.md)
        out = capsys.readouterr().out
        assert "has no [easeoff.drive] table: ease-off synthesized" in out
        assert f"{synthesized.synthesis.evaluations} TCA runs)" in out
        # the TOML block goes to a file named on stdout, as analyze names summary.md
        # (before: the whole table printed on stdout; the file itself:
        # tests/export/test_fmu.py, a whole run)
        toml = tmp_path / "out" / "easeoff.toml"
        assert f"(the TOML block is in {toml})" in out
        assert "\n[easeoff.drive]" not in out and out.count("\n") == 1


def test_the_note_holds_no_timing(synthesized):
    """The note (summary.md's ease-off block) is the same whatever the synthesis took;
    the time is in timings_s (run.json) only."""
    slow = dataclasses.replace(synthesized, synthesis=dataclasses.replace(
        synthesized.synthesis, seconds=synthesized.synthesis.seconds + 1234.5))
    assert slow.note == synthesized.note
    assert slow.timings_s["easeoff_synthesis_s"] == synthesized.synthesis.seconds + 1234.5
    assert " s)" not in synthesized.note.partition("\n")[0]


@pytest.mark.slow
def test_every_pair_command_synthesizes_the_same_easeoff(bare_pair_file, synthesized,
                                                         monkeypatch, tmp_path):
    """Without the stand-in: each command's own synthesis gives the fixture's
    coefficients exactly (7 syntheses, ~15 s each on the project machine)."""
    seen = []
    for command, (extra, module, name) in sorted(COMMANDS.items()):
        if command == "sweep":
            import gearcontact.sweep.run  # noqa: F401
        with monkeypatch.context() as m:
            _capture(m, module, name, seen)
            main([command, "--pair", str(bare_pair_file), "--side", "drive", *extra,
                  "--out", str(tmp_path / command)])
    assert len(seen) == len(COMMANDS)
    for pair in seen:
        assert pair.easeoff_drive == synthesized.pair.easeoff_drive
