"""Shared fixtures: the repository, the `bwcl` program (the CLI whose values and messages
the package must reproduce) and the paper's sets."""

import json
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
DSS = "1.43,-1.42,0.632,0.00715,1.31,1.27"
BASEBALL = {
    "m": 0.146, "k": 117080063, "c": 5854003, "n": 1.1, "p": 1.7,
    "alpha": 0.1, "beta": 981.05, "gamma": -961.4, "A": 0.925,
}
BASEBALL_TEXT = "m=0.146,k=117080063,c=5854003,n=1.1,p=1.7,alpha=0.1,beta=981.05,gamma=-961.4,A=0.925"
DATA = ROOT / "paper_repro" / "data" / "synthetic_dss.csv"


def _cli_path() -> Path:
    env = os.environ.get("BWCL_BIN")
    if env:
        return Path(env)
    target = Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    return target / "release" / "bwcl"


@pytest.fixture(scope="session")
def cli():
    """Runs the `bwcl` program: returns (exit code, stdout, stderr)."""
    path = _cli_path()
    if not path.exists():
        pytest.skip(f"the bwcl program is not built at {path} (cargo build --release --bin bwcl, or set BWCL_BIN)")

    def run(*args):
        p = subprocess.run([str(path), *args], capture_output=True, text=True, timeout=600)
        return p.returncode, p.stdout, p.stderr

    return run


@pytest.fixture(scope="session")
def cli_json(cli):
    """The JSON output of the program, every number kept as its text (parse_float=str)."""

    def run(*args):
        code, out, err = cli(*args, "--format=json")
        assert code in (0, 1), err
        return json.loads(out, parse_float=str)

    return run
