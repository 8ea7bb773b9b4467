"""The simulated SoC behind litex_server's protocol (gearcontact.hw.serve).

Truth: the golden C -> D chain (``chain_golden``) bit for bit through the whole board
path -- LiteX's ``RemoteClient`` (Etherbone records over TCP) to LiteX's own
``RemoteServer`` in ``gearcontact rtl serve`` to the Amaranth simulation of the tri_core
SoC; the SoC's constants (magic, identifier) through the same path; the comm's
incrementing and fixed bursts against single reads; a second server on a used port and
a bad port are named errors (exit 2).
"""

import socket
import subprocess
import sys

import numpy as np
import pytest

from gearcontact.hw.driver import ContactDriver, LiteXRemoteTransport, PreviewDriver
from gearcontact.hw.regmap import MAGIC, get_map
from gearcontact.hw.serve import SimComm, parse_address
from gearcontact.preview.chain import chain_golden
from gearcontact.preview.fit.golden import encode_gaps
from gearcontact.contract.stencil import stencil_coordinates
from gearcontact.preview.stimulus import STEEL_E_PRIME_CODE
from gearcontact.validation import InputRangeError


def test_remote_client_through_the_served_soc_is_the_golden_chain(served_tri_core):
    host, port = served_tri_core
    t = LiteXRemoteTransport(host=host, port=port)
    try:
        drv = PreviewDriver(t)                  # checks magic and identifier
        s, tt = stencil_coordinates()
        rng = np.random.default_rng(5)
        for _ in range(3):
            a, b = rng.uniform(0.01, 0.2), rng.uniform(0.001, 0.01)
            codes = encode_gaps(a * s * s + b * tt * tt + 0.001 * s * tt)
            w = int(rng.integers(256, 256 * 5000))
            rb = drv.run(codes, w)
            g = chain_golden(codes, w, e_prime_code=STEEL_E_PRIME_CODE)
            assert (rb.A, rb.B, rb.a, rb.b, rb.p_max, rb.k, rb.flags) == (
                g.fit.a_minus_code, g.fit.b_minus_code, g.hertz.a_code, g.hertz.b_code,
                g.hertz.p_max_code, g.hertz.k_code, g.flags)
        assert t.read(get_map("tri_core").addr("contact", "magic")) == MAGIC
        assert ContactDriver(t, kind="tri_core").read_contact().done
    finally:
        t.close()


def test_a_used_port_and_a_bad_one_are_named_errors(served_tri_core):
    _, port = served_tri_core
    run = [sys.executable, "-m", "gearcontact", "rtl", "serve", "--port"]
    r = subprocess.run(run + [str(port)], capture_output=True, text=True, timeout=120)
    assert r.returncode == 2 and "already in use" in r.stderr
    r = subprocess.run(run + ["70000"], capture_output=True, text=True, timeout=120)
    assert r.returncode == 2 and "--port" in r.stderr
    with pytest.raises(InputRangeError, match="--board"):
        parse_address("host:x", field="--board")


def test_comm_bursts_are_single_reads():
    comm = SimComm("tri_core")
    comm.open()
    try:
        m = get_map("tri_core")
        base = m.addr("identifier", "mem0")
        words = comm.read(base, 8)                       # incrementing burst
        assert bytes(words).startswith(b"gearcont")
        assert comm.read(base, 3, "fixed") == [words[0]] * 3
        comm.write(m.addr("ctrl", "scratch"), [0xDEADBEEF])
        assert comm.read(m.addr("ctrl", "scratch")) == 0xDEADBEEF
    finally:
        comm.close()
    with pytest.raises(InputRangeError, match="kind"):
        SimComm("quad_core")



def _first_line_of_serve(options) -> str:
    """The first stdout line of ``gearcontact rtl serve`` with ``options`` on a free
    port; the server is then stopped."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    proc = subprocess.Popen([sys.executable, "-m", "gearcontact", "rtl", "serve", "--port",
                             str(port), *options],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        return proc.stdout.readline()
    finally:
        proc.kill()
        proc.communicate(timeout=60)


def test_a_cylindrical_pair_bakes_its_own_e_prime(tmp_path):
    """`rtl serve --pair` takes a cylindrical pair as a bevel one: only the members'
    E' goes into the SoC (the line_core a cylindrical twin's ``--board`` drives). Truth:
    Hamrock-Brewe E' = 2 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2), written out here, rounded
    to the integer-MPa register code (half up) -- for a steel pinion on a bronze gear.
    The real command, its first line read, then stopped."""
    text = open("examples/ev_reducer_helical_23x67.toml", encoding="utf-8").read()
    head, sep, _ = text.partition("[material.pinion]")
    assert sep
    path = tmp_path / "bronze_gear.toml"
    path.write_text(head + "[material.pinion]\nyoungs_modulus_gpa = 210.0\n"
                    "poisson_ratio = 0.3\n\n[material.gear]\nyoungs_modulus_gpa = 110.0\n"
                    "poisson_ratio = 0.34\n", encoding="utf-8")
    e_prime = 2.0 / ((1 - 0.3**2) / 210e3 + (1 - 0.34**2) / 110e3)
    first = _first_line_of_serve(["--kind", "line_core", "--pair", str(path)])
    assert first.startswith("gearcontact rtl serve: simulated line_core (E' code "), first
    code = int(first.split("E' code ")[1].split(")")[0])
    assert code == int(e_prime + 0.5)


def test_a_cylindrical_pair_refuses_a_soc_its_twin_cannot_drive(tmp_path):
    """`rtl serve --kind tri_core --pair <cylindrical>` once served a SoC that the
    cylindrical twin's ``--board`` then refused by its identifier: now exit 2 before
    building, naming --kind, the value and the kind that serves a cylindrical pair
    (line_core, the line chain: twin.cosim). Without --kind a cylindrical pair gets
    line_core (the real command, its first line read, then stopped)."""
    example = "examples/ev_reducer_helical_23x67.toml"
    proc = subprocess.run([sys.executable, "-m", "gearcontact", "rtl", "serve", "--kind",
                           "tri_core", "--pair", example], capture_output=True, text=True,
                          timeout=120, check=False)
    assert proc.returncode == 2, proc.stderr
    assert "--kind" in proc.stderr and "tri_core" in proc.stderr
    assert "line_core" in proc.stderr and "cylindrical" in proc.stderr
    assert "simulated" not in proc.stdout          # nothing served
    first = _first_line_of_serve(["--pair", example])
    assert first.startswith("gearcontact rtl serve: simulated line_core "), first
