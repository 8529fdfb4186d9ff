"""Ctrl-C during a call (issue #34, item 1): a real SIGINT from a timer, in a fresh interpreter
(so that the first call of a process is covered), raises KeyboardInterrupt within 0.5 s — not
when the computation would have ended, and not as a PanicException — and the process can go
on computing afterwards."""

import subprocess
import sys
import textwrap

import pytest

from conftest import DATA, DSS

# the child prints "KI <seconds from the signal to the exception>", then "AFTER <e>" from a
# call made after the interrupt
CHILD = textwrap.dedent(
    """
    import os, signal, sys, threading, time
    # Python's own Ctrl-C handler, as in a terminal: a parent that ignores SIGINT (a background
    # job of a non-interactive shell) hands SIG_IGN down, and Python then installs none
    signal.signal(signal.SIGINT, signal.default_int_handler)
    import numpy as np
    import bwcl
    DSS = {dss!r}
    if {warm}:
        bwcl.cor("shc", base=DSS, v0=1.0)
    sent = []
    def fire():
        sent.append(time.perf_counter())
        os.kill(os.getpid(), signal.SIGINT)
    threading.Timer({delay}, fire).start()
    try:
        {call}
        print("FINISHED", flush=True)
    except KeyboardInterrupt:
        print("KI", time.perf_counter() - sent[0], flush=True)
    r = bwcl.cor_rigorous("shc", base=DSS, v0=1.0)
    print("AFTER", r.status[0], r.e[0].tolist(), flush=True)
    """
)

CALLS = {
    # 2000 proved CoRs: ≈ 4 s on 2 cores
    "cor_rigorous": 'bwcl.cor_rigorous("shc", base=DSS, v0=np.linspace(0.1, 5, 2000))',
    # 16 starts of the fit: tens of seconds
    "fit": "bwcl.fit('shc', data={data!r}, starts=16, seed=3)",
    # a million float CoRs: minutes
    "cor": 'bwcl.cor("shc", base=DSS, v0=np.linspace(0.1, 5, 10**6))',
    # the ten damping formulas' proved errors: ≈ 17 s (MPFR brackets and pavings)
    "laws": "bwcl.laws()",
    # the issue #31 2-D paving: minutes
    "identify": ("bwcl.identify('shc', {data!r}, error=0.02, base=DSS, resolution=128, "
                 "bounds={{'sigma_b': (0.001, 0.1), 'kappa': (0.4, 0.8)}}, time_limit=600)"),
}


def _run(call, warm, delay=1.0):
    code = CHILD.format(dss=DSS, warm=warm, delay=delay, call=call.format(data=str(DATA)))
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    return p.returncode, p.stdout, p.stderr


@pytest.mark.parametrize("name", sorted(CALLS))
@pytest.mark.parametrize("warm", [False, True], ids=["first call", "later call"])
def test_ctrl_c_raises_keyboard_interrupt_promptly(name, warm):
    code, out, err = _run(CALLS[name], warm)
    assert code == 0, err
    assert "panicked" not in err and "PanicException" not in err, err
    lines = out.split("\n")
    ki = [l for l in lines if l.startswith("KI ")]
    assert ki, f"no KeyboardInterrupt: {out!r} {err!r}"
    assert float(ki[0].split()[1]) < 0.5, out
    # the process goes on: a proved CoR after the interrupt
    after = [l for l in lines if l.startswith("AFTER ")]
    assert after and after[0].split()[1] == "proved", out
