"""One definition each (issue 11): Rodrigues exp, dexp^-1, the RK4/RKMK4 stage loop, g and the
sea-water density appear once in the package's code (docstrings and comments are ignored).

Fingerprints, searched in the code tokens of every module under mf_envs/:
- Rodrigues exp: the coefficient sin(x)/x of R = I + sin(x)/x W + ... (ch. 2 Eq. 29);
- dexp^-1: the 1/12 leading term of its coefficient c(x) = 1/12 + x^2/720 + ...;
- the Runge-Kutta stage combination k1 + 2 k2 + 2 k3 + k4 (RK4 and RKMK4 templates);
- g: a literal 9.8...; sea-water density: a literal 1020 or 1025.
The speed benchmark's plain-numpy RK4 loop (benchmarks/speed/rigid_body.py) is excluded from the
stage-loop count on purpose: it is the hand-written baseline the numba kernels are timed against.
"""

import io
import re
import tokenize
from pathlib import Path

import mf_envs

ROOT = Path(mf_envs.__file__).parent


def _code(path: Path) -> tuple[str, list[str]]:
    """(code text without strings and comments, numeric literals) of one module."""
    toks = list(tokenize.generate_tokens(io.StringIO(path.read_text()).readline))
    keep = [t.string for t in toks if t.type not in (tokenize.STRING, tokenize.COMMENT)]
    nums = [t.string for t in toks if t.type == tokenize.NUMBER]
    return " ".join(keep), nums


def _hits(pattern: str, skip: tuple[str, ...] = ()) -> list[str]:
    rx = re.compile(pattern)
    out = []
    for p in sorted(ROOT.rglob("*.py")):
        rel = str(p.relative_to(ROOT))
        if rel.startswith(skip):
            continue
        text, _ = _code(p)
        out += [rel] * len(rx.findall(text))
    return out


def _literals(values: set[float]) -> list[str]:
    return [
        str(p.relative_to(ROOT))
        for p in sorted(ROOT.rglob("*.py"))
        for n in _code(p)[1]
        if re.fullmatch(r"[\d_.eE+-]+", n) and float(n) in values
    ]


def test_one_rodrigues_exp():
    assert _hits(r"sin \( (\w+) \) / \1\b") == ["frames/kernels.py"]


def test_one_dexpinv():
    assert _hits(r"1\.0 / 12\.0") == ["frames/kernels.py"]
    assert {h for h in _hits(r"def \w*dexpinv\w*")} == {"frames/kernels.py"}


def test_one_runge_kutta_stage_loop():
    rk = r"\b2(?:\.0)? \* \w+(?: \[ [^\]]* \])? \+ 2(?:\.0)? \* \w+"
    hits = _hits(rk, skip=("benchmarks/speed/",))
    assert hits == ["frames/steppers.py"]  # `_rk4_combine`, used by the RK4 and RKMK4 templates


def test_one_g_and_one_sea_water_density():
    assert _literals({9.81, 9.80665, 9.8}) == ["physics/constants.py"]
    assert _literals({1020.0, 1025.0}) == ["physics/constants.py"]
