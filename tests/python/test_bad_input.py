"""Bad input raises ValueError with the CLI's one line (the same parser and checks), wrong
types TypeError, wrong shapes ValueError; nothing panics across the boundary."""

import math
import re

import numpy as np
import pytest

import bwcl
from bwcl._native import pythonic
from conftest import BASEBALL_TEXT, DATA, DSS

M = "--model=shc"
B = f"--base={DSS}"

# (the Python call, the same input to the program)
CASES = [
    ("v0 NaN", lambda: bwcl.cor("shc", base=DSS, v0=[1.0, math.nan]), ["cor", M, B, "--v0=1.0,NaN"]),
    ("v0 negative", lambda: bwcl.cor("shc", base=DSS, v0=[-1.0]), ["cor", M, B, "--v0=-1.0"]),
    ("v0 zero", lambda: bwcl.cor("shc", base=DSS, v0=[0.0]), ["cor", M, B, "--v0=0.0"]),
    ("v0 inf", lambda: bwcl.cor("shc", base=DSS, v0="inf"), ["cor", M, B, "--v0=inf"]),
    ("v0 empty", lambda: bwcl.cor("shc", base=DSS, v0=[]), ["cor", M, B, "--v0="]),
    ("v0 malformed", lambda: bwcl.cor("shc", base=DSS, v0="1,abc"), ["cor", M, B, "--v0=1,abc"]),
    ("v0 range float", lambda: bwcl.cor("shc", base=DSS, v0="0.9..1.1"), ["cor", M, B, "--v0=0.9..1.1"]),
    ("v0 rigorous bad", lambda: bwcl.cor_rigorous("shc", base=DSS, v0=["1", "x1"]),
     ["cor", M, B, "--v0=1,x1", "--rigorous"]),
    ("v0 rigorous empty range", lambda: bwcl.cor_rigorous("shc", base=DSS, v0=[(2, 1)]),
     ["cor", M, B, "--v0=2..1", "--rigorous"]),
    ("Γ outside 𝓟", lambda: bwcl.cor("shc", base=[1.43, -1.5, 0.632, 0.00715, 1.31, 1.27], v0=1),
     ["cor", M, "--base=1.43,-1.5,0.632,0.00715,1.31,1.27", "--v0=1"]),
    ("κ = 1", lambda: bwcl.cor("shc", nd=[1, 0, 1, 1, 1, 1]), ["cor", M, "--nd=1,0,1,1,1,1"]),
    ("n < 1", lambda: bwcl.cor("shc", nd="1,0,0.5,1,0.5,1"), ["cor", M, "--nd=1,0,0.5,1,0.5,1"]),
    ("maxwell p", lambda: bwcl.cor("maxwell", nd=[1, 0, 0.5, 1, 1, 1.5]),
     ["cor", "--model=maxwell", "--nd=1,0,0.5,1,1,1.5"]),
    ("B NaN", lambda: bwcl.cor("shc", nd=[math.nan, 0, 0.5, 1, 1, 1]), ["cor", M, "--nd=nan,0,0.5,1,1,1"]),
    ("five values", lambda: bwcl.cor("shc", nd=[1, 0, 0.5, 1, 1]), ["cor", M, "--nd=1,0,0.5,1,1"]),
    ("malformed decimal", lambda: bwcl.cor_rigorous("shc", base=["1.4.3", -1.42, 0.632, 0.00715, 1.31, 1.27], v0=1),
     ["cor", M, "--base=1.4.3,-1.42,0.632,0.00715,1.31,1.27", "--v0=1", "--rigorous"]),
    ("control characters", lambda: bwcl.cor("shc", nd="1\x1b[31m,0,0.5,1,1,1"),
     ["cor", M, "--nd=1\x1b[31m,0,0.5,1,1,1"]),
    ("range Γ reaching B", lambda: bwcl.cor_rigorous("shc", nd=[1, (0.5, 1), 0.5, 1, 1, 1]),
     ["cor", M, "--nd=1,0.5..1,0.5,1,1,1", "--rigorous"]),
    ("wrong model", lambda: bwcl.cor("kelvin", base=DSS, v0=1), ["cor", "--model=kelvin", B, "--v0=1"]),
    ("two sources", lambda: bwcl.cor("shc", base=DSS, nd=DSS, v0=1), ["cor", M, B, f"--nd={DSS}", "--v0=1"]),
    ("no source", lambda: bwcl.cor("shc", v0=1), ["cor", M, "--v0=1"]),
    ("nd with v0", lambda: bwcl.cor("shc", nd=DSS, v0=1), ["cor", M, f"--nd={DSS}", "--v0=1"]),
    ("base without v0", lambda: bwcl.cor("shc", base=DSS), ["cor", M, B]),
    ("rtol", lambda: bwcl.cor("shc", base=DSS, v0=1, rtol=2.0), ["cor", M, B, "--v0=1", "--rtol=2.0"]),
    ("atol 0", lambda: bwcl.cor("shc", base=DSS, v0=1, atol=0.0), ["cor", M, B, "--v0=1", "--atol=0.0"]),
    ("max_step", lambda: bwcl.cor("shc", base=DSS, v0=1, max_step=1e-12), ["cor", M, B, "--v0=1", "--max-step=1e-12"]),
    ("horizon NaN", lambda: bwcl.cor("shc", base=DSS, v0=1, horizon=math.nan), ["cor", M, B, "--v0=1", "--horizon=nan"]),
    ("horizon < 0", lambda: bwcl.cor("shc", base=DSS, v0=1, horizon=-1.0), ["cor", M, B, "--v0=1", "--horizon=-1.0"]),
    ("order", lambda: bwcl.cor_rigorous("shc", base=DSS, v0=1, order=1), ["cor", M, B, "--v0=1", "--rigorous", "--order=1"]),
    ("pieces", lambda: bwcl.cor_rigorous("shc", base=DSS, v0=1, pieces=0), ["cor", M, B, "--v0=1", "--rigorous", "--pieces=0"]),
    ("fallback bits", lambda: bwcl.cor_rigorous("shc", base=DSS, v0=1, fallback_bits=100),
     ["cor", M, B, "--v0=1", "--rigorous", "--fallback-bits=100"]),
    ("fallback seconds", lambda: bwcl.cor_rigorous("shc", base=DSS, v0=1, fallback_seconds=0.0),
     ["cor", M, B, "--v0=1", "--rigorous", "--fallback-seconds=0.0"]),
    ("physical malformed", lambda: bwcl.cor("shc", physical="m=0.1,k", v0=1), ["cor", M, "--physical=m=0.1,k", "--v0=1"]),
    ("physical alpha", lambda: bwcl.cor("shc", physical=BASEBALL_TEXT.replace("alpha=0.1", "alpha=1.5"), v0=1),
     ["cor", M, "--physical=" + BASEBALL_TEXT.replace("alpha=0.1", "alpha=1.5"), "--v0=1"]),
    ("points", lambda: bwcl.trajectory("shc", nd=DSS, points=1), ["trajectory", M, f"--nd={DSS}", "--points=1"]),
    ("t_end", lambda: bwcl.trajectory("shc", nd=DSS, t_end=0.0), ["trajectory", M, f"--nd={DSS}", "--t-end=0.0"]),
    ("physical units", lambda: bwcl.loop("shc", nd=DSS, physical_units=True),
     ["loop", M, f"--nd={DSS}", "--physical-units"]),
    ("fit starts 0", lambda: bwcl.fit("shc", DATA, starts=0), ["fit", M, f"--data={DATA}", "--starts=0"]),
    ("fit max_iter", lambda: bwcl.fit("shc", DATA, max_iter=0), ["fit", M, f"--data={DATA}", "--max-iter=0"]),
    ("fit seed", lambda: bwcl.fit("shc", DATA, seed=-1), ["fit", M, f"--data={DATA}", "--seed=-1"]),
    ("fit init p1", lambda: bwcl.fit("shc", DATA, init=DSS, p1=True), ["fit", M, f"--data={DATA}", f"--init={DSS}", "--p1"]),
    ("data missing", lambda: bwcl.cost("shc", "/nonexistent/d.csv", base=DSS),
     ["cost", M, B, "--data=/nonexistent/d.csv"]),
    ("cost base", lambda: bwcl.cost("shc", DATA, base="1,2,3"), ["cost", M, "--base=1,2,3", f"--data={DATA}"]),
]


OPTION = re.compile(r"--[a-z]")


@pytest.mark.parametrize("name,call,argv", CASES, ids=[c[0] for c in CASES])
def test_value_error_is_the_cli_line(name, call, argv, cli):
    """The program's one line, with its options written as the call's keyword arguments
    (``max_step``, not ``'--max-step <H>'``) and no pointer to ``--help``."""
    with pytest.raises(ValueError) as ex:
        call()
    code, out, err = cli(*argv)
    assert code == 2 and out == ""
    lines = err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("bwcl: error: ")
    assert str(ex.value) == pythonic(lines[0][len("bwcl: error: "):])
    assert not OPTION.search(str(ex.value)), str(ex.value)
    assert "help" not in str(ex.value)
    assert "\n" not in str(ex.value) and "\x1b" not in str(ex.value)


@pytest.mark.parametrize(
    "call,words",
    [
        (lambda: bwcl.cor("shc", base=DSS, v0=1, max_step=1e-12), ["max_step", "1e-12"]),
        (lambda: bwcl.cor("shc", base=DSS, v0=[]), ["v0"]),
        (lambda: bwcl.fit("shc", DATA, seed=-1), ["seed", "-1"]),
        (lambda: bwcl.cor_rigorous("shc", base=DSS, v0=1, time_limit=0), ["time_limit", "0"]),
        (lambda: bwcl.cor_rigorous("shc", base=DSS, v0=1, fallback_bits=100), ["fallback_bits", "100"]),
        (lambda: bwcl.trajectory("shc", nd=DSS, t_end=0.0), ["t_end"]),
    ],
    ids=["max_step", "v0 empty", "seed", "time_limit", "fallback_bits", "t_end"],
)
def test_messages_name_the_python_argument(call, words):
    with pytest.raises(ValueError) as ex:
        call()
    msg = str(ex.value)
    for w in words:
        assert w in msg, msg
    assert not OPTION.search(msg) and "help" not in msg, msg


def test_bad_data_file(tmp_path, cli):
    p = tmp_path / "d.csv"
    p.write_text("v0,e\n1,0.5\n2,1.5\n")
    with pytest.raises(ValueError) as ex:
        bwcl.cost("shc", p, base=DSS)
    code, out, err = cli("cost", "--model=shc", f"--base={DSS}", f"--data={p}")
    assert code == 2 and str(ex.value) == pythonic(err.strip()[len("bwcl: error: "):])


@pytest.mark.parametrize(
    "call",
    [
        lambda: bwcl.cor("shc", base=DSS, v0=np.ones((2, 2))),
        lambda: bwcl.cor("shc", base=np.ones((2, 3)), v0=1),
        lambda: bwcl.cor_rigorous("shc", base=DSS, v0=["1,2"]),
        lambda: bwcl.cost("shc", base=DSS, v0=np.ones((3, 1)), e=np.ones(3)),
        lambda: bwcl.cost("shc", base=DSS, v0=[1, 2], e=[0.5, 1.5]),
        lambda: bwcl.cost("shc", base=DSS, v0=[1, 2], e=[0.5]),
        lambda: bwcl.fit("shc", v0=[1.0]),
        lambda: bwcl.fit("shc", DATA, v0=[1.0], e=[0.5]),
        lambda: bwcl.cor("shc", base=DSS, v0=1, threads=0),
        lambda: bwcl.cor("shc", base=DSS, v0=1, threads=100000),
    ],
    ids=["v0 2-D", "base 2-D", "comma in item", "data 2-D", "e > 1", "lengths", "v0 without e",
         "data and arrays", "threads 0", "threads huge"],
)
def test_shapes_and_other_values(call):
    with pytest.raises(ValueError) as ex:
        call()
    assert str(ex.value) and "\n" not in str(ex.value)


@pytest.mark.parametrize(
    "call",
    [
        lambda: bwcl.cor(3, base=DSS, v0=1),
        lambda: bwcl.cor("shc", base={"B": 1}, v0=1),
        lambda: bwcl.cor("shc", base=DSS, v0=[True]),
        lambda: bwcl.cor("shc", base=[1, 2, 3, 4, 5, object()], v0=1),
        lambda: bwcl.cor("shc", physical=[1, 2], v0=1),
        lambda: bwcl.fit("shc", DATA, progress="yes"),
    ],
)
def test_wrong_types(call):
    with pytest.raises(TypeError):
        call()


def test_failed_integration_is_per_case():
    """Valid input that the engine cannot integrate (a step budget): reported per case."""
    r = bwcl.cor("shc", base=DSS, v0=[1.0], max_step=1e-9, horizon=1.0)
    assert not r.ok[0] and r.error[0] and np.isnan(r.e[0])


def test_a_panic_is_a_python_exception():
    for threads in (None, 1, 2):
        with pytest.raises(RuntimeError, match="internal error"):
            bwcl._bwcl.panic_for_test(threads)
    # and the interpreter goes on
    assert bwcl.cor("shc", base=DSS, v0=1).ok.all()


def test_inputs_read_as_something_else_are_refused():
    """Issue #34: bytes (b'1' iterated as the speed 49), a masked array's mask, None for a
    setting, SciPy's threads=-1, an underdetermined fit, --p1 where it means nothing."""
    with pytest.raises(TypeError, match="bytes"):
        bwcl.cor("shc", base=DSS, v0=b"1")
    with pytest.raises(TypeError, match="bytearray"):
        bwcl.cor_rigorous("shc", base=DSS, v0=bytearray(b"1"))
    masked = np.ma.masked_array([0.5, 1.0, 2.0], mask=[False, True, False])
    with pytest.raises(ValueError, match="masked"):
        bwcl.cor("shc", base=DSS, v0=masked)
    with pytest.raises(ValueError, match="masked"):
        bwcl.cost("shc", base=DSS, v0=masked, e=[0.9, 0.8, 0.7])
    # a masked array without masked entries is its data
    unmasked = np.ma.masked_array([0.5, 2.0], mask=False)
    assert bwcl.cor("shc", base=DSS, v0=unmasked).e.tolist() == bwcl.cor(
        "shc", base=DSS, v0=[0.5, 2.0]).e.tolist()
    for kw in ("rtol", "atol", "max_step"):
        with pytest.raises(TypeError, match=kw):
            bwcl.cor("shc", base=DSS, v0=1, **{kw: None})
    assert bwcl.cor("shc", base=DSS, v0=[1, 2], threads=-1).e.shape == (2,)
    with pytest.raises(ValueError, match="underdetermined"):
        bwcl.fit("shc", v0=[1.0], e=[0.8])
    with pytest.raises(ValueError, match=r"p1 .*fix=\{'p': 1\}"):
        bwcl.fit("shc", DATA, p1=True)



def test_review_of_the_python_terms():
    """Review of #34: the user's own values are echoed as written (a '--' inside them is not
    an option), empty sweeps and reversed ranges are one ValueError, a bad speed in a sweep
    is not blamed on a parameter set."""
    with pytest.raises(ValueError, match="sh--c"):
        bwcl.cor("sh--c", base=DSS, v0=1.0)
    with pytest.raises(ValueError, match=r"1--a"):
        bwcl.cor("shc", base="1.43,-1.42,0.632,0.00715,1.31,1--a", v0=1.0)
    with pytest.raises(ValueError, match="0 parameter sets"):
        bwcl.cor("shc", base=np.zeros((0, 6)), v0=1.0)
    with pytest.raises(ValueError, match="no parameter set"):
        bwcl.cor("hertz", base={"n": []}, v0=1.0)
    with pytest.raises(ValueError, match="lo < hi"):
        bwcl.prove_monotone("shc", base=DSS, v0=(2, 1))
    two = np.array([[1.43, -1.42, 0.632, 0.00715, 1.31, 1.27]] * 2)
    with pytest.raises(ValueError) as ex:
        bwcl.cor("shc", base=two, v0=[0.5, -1.0])
    assert "parameter set" not in str(ex.value) and "-1.0" in str(ex.value)


# found by a probe: values that the package spliced into the program's text as more than one
# item, and switches that took any truthy value
@pytest.mark.parametrize("call, error, words", [
    (lambda: bwcl.cor("shc", base=["1.43,-1.42", 0.632, 0.00715, 1.31, 1.27], v0=1),
     ValueError, "holds a comma"),
    (lambda: bwcl.cor("shc", base=np.array(["1.43,-1.42,0.632", "0.00715,1.31,1.27"]), v0=1),
     ValueError, "holds a comma"),
    (lambda: bwcl.cor("shc", physical={"m=0.146,k=117080063,c": 5854003, "n": 1.1}, v0=30),
     ValueError, "is not a parameter name"),
    (lambda: bwcl.fit("shc", DATA, fix={"kappa": 0.5, "n=2,p": 1.5}),
     ValueError, "is not a parameter name"),
    (lambda: bwcl.identify("shc", DATA, bounds={"kappa": (0.5, 0.7)}, error=0.02,
                           fix={"n=2,p": 1.5}),
     ValueError, "is not a parameter name"),
    (lambda: bwcl.fit("shc", DATA, bounds={"kappa": 5}), TypeError, "needs a pair (lo, hi)"),
    (lambda: bwcl.fit("shc", DATA, bounds={"kappa": (0.1, 0.2, 0.3)}), TypeError,
     "needs a pair (lo, hi)"),
    (lambda: bwcl.fit("shc", DATA, bounds={"kappa": "ab"}), TypeError, "needs a pair (lo, hi)"),
    (lambda: bwcl.cor_rigorous("shc", base=DSS, v0=1, sensitivities="no"), TypeError,
     "sensitivities must be True or False"),
    (lambda: bwcl.trajectory("shc", base=DSS, v0=1, rigorous="no"), TypeError,
     "rigorous must be True or False"),
    (lambda: bwcl.classical("hertz", rigorous="no"), TypeError, "rigorous must be True or False"),
    (lambda: bwcl.fit("shc", DATA, uncertainty="no"), TypeError,
     "uncertainty must be True or False"),
    # identify took its numbers with int()/float(): 2.9 became 2, True became 1.0
    (lambda: bwcl.identify("shc", DATA, bounds={"kappa": (0.5, 0.7)}, error=0.02, resolution=2.9),
     TypeError, "resolution = 2.9 must be a whole number"),
    (lambda: bwcl.identify("shc", DATA, bounds={"kappa": (0.5, 0.7)}, error=True),
     TypeError, "expected a number, got the bool"),
    (lambda: bwcl.identify("shc", DATA, bounds={"kappa": (0.5, 0.7)}, error=0.02, threads="2"),
     ValueError, "threads = '2' must be a whole number"),
    (lambda: bwcl.identify("shc", DATA, bounds={"kappa": (0.5, 0.7)}, error=0.02, no_tc="no"),
     TypeError, "no_tc must be True or False"),
    # the float engine's settings were silently unused with rigorous=True
    (lambda: bwcl.trajectory("shc", base=DSS, v0=1, rigorous=True, rtol=1e-5), ValueError,
     "rtol = 1e-05 is a setting of the float engine"),
    (lambda: bwcl.loop("shc", base=DSS, v0=1, rigorous=True, max_step=0.1), ValueError,
     "max_step = 0.1 is a setting of the float engine"),
])
def test_values_are_one_item_and_switches_are_bools(call, error, words):
    with pytest.raises(error, match=re.escape(words)):
        call()


def test_fix_takes_any_mapping():
    import types

    a = bwcl.fit("shc", DATA, fix=types.MappingProxyType({"kappa": 0.5}), starts=1, max_iter=5)
    b = bwcl.fit("shc", DATA, fix={"kappa": 0.5}, starts=1, max_iter=5)
    assert a.base == b.base and a.base[2] == 0.5
    # a Greek name is a parameter's name too
    c = bwcl.fit("shc", DATA, fix={"κ": 0.5}, starts=1, max_iter=5)
    assert c.base == b.base


def test_the_stub_names_everything_exported_with_its_arguments():
    """__init__.pyi declares every name of __all__ (profile, InterpBandResult and DERIVED were
    missing: found by a probe), and each function it declares has the implementation's
    arguments, in order."""
    import ast
    import inspect
    from pathlib import Path

    tree = ast.parse((Path(bwcl.__file__).parent / "__init__.pyi").read_text())
    names = set()
    for n in ast.walk(tree):
        if isinstance(n, (ast.FunctionDef, ast.ClassDef)):
            names.add(n.name)
        elif isinstance(n, ast.AnnAssign) and isinstance(n.target, ast.Name):
            names.add(n.target.id)
        elif isinstance(n, (ast.Import, ast.ImportFrom)):
            names.update(a.asname or a.name for a in n.names)
    assert set(bwcl.__all__) <= names, sorted(set(bwcl.__all__) - names)
    functions = [n for n in tree.body if isinstance(n, ast.FunctionDef)]
    assert len(functions) >= 6
    for f in functions:
        stub = [a.arg for a in f.args.posonlyargs + f.args.args + f.args.kwonlyargs]
        real = list(inspect.signature(getattr(bwcl, f.name)).parameters)
        assert stub == real, (f.name, stub, real)


def test_a_reason_names_the_python_argument():
    """A case's reason names the Python argument (time_limit), not the program's option."""
    r = bwcl.cor_rigorous("shc", base=DSS, v0=1, time_limit=1e-9)
    assert not r.proved[0] and "(time_limit)" in r.reason[0] and "--" not in r.reason[0], r.reason
