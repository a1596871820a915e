"""The n-link chain (Rios 2017 ch. 4 §4.2) converging to the beam: error vs links vs seconds.

Chain from the beam by `chain_from_beam` (k = EI/l inside, 2 EI/l at the clamp); L = 1 m, EI = 1.
Scenes (`dt` is the refinement parameter named in `param`):
- `multilink_statics`: tip position error / L of the clamped chain (Newton, banded Hessian) for
  n = 2, 4, 8, ... links (param "links": the order is the slope in n, -2 expected) against
  (a) the elastica by scipy solve_bvp (tol 1e-10) at alpha = P L^2 / EI = 1 and 5 and under a
  uniform load q L^3 / EI = 3; (b) the exact circle of a uniform actuation kappa# L = 3;
  (c) the converged active C1 beam `beam.solve_cantilever` (128 elements, EA = GA_s = 1e7 EI/L^2
  so that it is practically inextensible and unshearable; it agrees with the elastica to ~5e-7 L,
  which floors that curve).
- `multilink_modes`: relative error of the first three natural frequencies of the linearised
  chain (eig of K*, M*(0)) against the Euler-Bernoulli cantilever (beta_i L = 1.8751, 4.6941,
  7.8548), param "links", n = 4 ... 128 (cond(K*, M*) ~ n^4: the round-off floor is reached
  near n = 512).
- `multilink_dynamics`: the n = 8 and n = 16 chains (rho A = 1 kg/m, gravity 3 m/s^2) released
  straight and horizontal, 2 s (about one first-mode period); max tip-position error / L on a
  0.1 s grid against DOP853 at rtol 1e-13, for scipy's RK45, DOP853, Radau and LSODA over a
  ladder of rtol (param "rtol"). The spring frequencies grow like n^2, so the implicit methods
  pay a finite-difference Jacobian per step while the explicit ones are step-limited.

`python -m benchmarks.accuracy.multilink --docs docs/img/multilink_convergence.png` draws the
README picture (chains of 2, 4, 8 links beside the beam, and the error vs links).
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
from scipy.linalg import eigh

from mf_envs._files import save_figure
from mf_envs.benchmarks._io import accuracy_row, observed_order, timed
from mf_envs.physics import multilink as ml
from mf_envs.physics.multilink.elastica import elastica_cantilever
from mf_envs.physics.multilink.solve import simulate, solve_static

ORDER = 45
L, EI = 1.0, 1.0
BETA_L = np.array([1.8751040687119611, 4.694091132973912, 7.854757438237613])
STATIC_CASES = {
    "tip load alpha=1 vs elastica": {"tip_force": (0.0, -1.0)},
    "tip load alpha=5 vs elastica": {"tip_force": (0.0, -5.0)},
    "uniform load qL^3/EI=3 vs elastica": {"distributed_load": (0.0, -3.0)},
}


def _links(quick: bool, top: int) -> list[int]:
    return [2**i for i in range(1, (7 if quick else top) + 1)]


def _static_rows(quick: bool) -> list[dict]:
    rows = []
    cases = {
        name: (kw, elastica_cantilever(L, EI, **kw).tip_position)
        for name, kw in STATIC_CASES.items()
    }
    kap = 3.0
    cases["actuation kappa#L=3 vs circle"] = (
        {"kappa": kap},
        np.array([np.sin(kap * L), 1 - np.cos(kap * L)]) / kap,
    )
    beam = _beam_reference()
    if beam is not None:
        cases["tip load alpha=5 vs C1 beam FE"] = ({"tip_force": (0.0, -5.0)}, beam)
    for name, (kw, ref) in cases.items():
        top = 8 if "beam" in name else 12  # the beam reference is good to ~5e-7 L
        for n in _links(quick, top):
            p = ml.chain_from_beam(L, EI, 1.0, n)
            kw2 = dict(kw)
            if "kappa" in kw2:
                kw2 = {"theta_sharp": ml.actuation_from_curvature(p, kw2.pop("kappa"))}
            st, sec = timed(lambda p=p, kw2=kw2: solve_static(p, **kw2), repeat=3)
            err = float(np.linalg.norm(st.tip_position - ref)) / L
            rows.append(
                accuracy_row(
                    "multilink_statics",
                    name,
                    n,
                    err,
                    sec,
                    "links",
                    links=n,
                    quantity="tip position error / L",
                )
            )
    return rows


def _beam_reference() -> np.ndarray | None:
    try:
        from mf_envs.physics.beam import solve_cantilever
    except ImportError:  # the beam module is optional for this benchmark
        return None
    big = 1e7 * EI / L**2
    return np.asarray(solve_cantilever(L, big, big, EI, 128, tip_force=(0.0, -5.0)).tip_position)


def _mode_rows(quick: bool) -> list[dict]:
    rows = []
    exact = BETA_L**2 * np.sqrt(EI / (1.0 * L**4))
    for n in _links(quick, 7)[1:]:  # beyond ~256 links eigh's round-off (cond ~ n^4) floors it
        p = ml.chain_from_beam(L, EI, 1.0, n)
        (w2, sec) = timed(
            lambda p=p, n=n: eigh(
                ml.stiffness_matrix(p),
                ml.mass_matrix(p, np.zeros(n)),
                eigvals_only=True,
                subset_by_index=[0, 2],
            ),
            repeat=3,
        )
        for i in range(3):
            err = abs(np.sqrt(w2[i]) / exact[i] - 1.0)
            rows.append(
                accuracy_row(
                    "multilink_modes",
                    f"mode {i + 1}",
                    n,
                    err,
                    sec,
                    "links",
                    links=n,
                    quantity="natural frequency rel. error",
                )
            )
    return rows


def _dynamic_rows(quick: bool) -> list[dict]:
    rows = []
    t_eval = np.linspace(0.0, 2.0, 21)
    for n in (8,) if quick else (8, 16):
        p = ml.chain_from_beam(L, EI, 1.0, n, gravity=(0.0, -3.0))

        def tips(tr, p=p):
            return np.array([ml.tip_position(p, q) for q in tr.q])

        z = np.zeros(n)
        ref = tips(simulate(p, z, z, 2.0, "DOP853", 1e-13, 1e-14, t_eval))
        rtols = (
            (1e-4, 1e-6, 1e-8) if quick or n > 8 else (1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10)
        )
        for method in ("RK45", "DOP853", "Radau", "LSODA"):
            if method == "Radau" and n > 8:
                continue  # a finite-difference Jacobian per step: minutes at n >= 16
            for rtol in rtols:
                tr, sec = timed(
                    lambda m=method, r=rtol, p=p, z=z: simulate(
                        p, z, z, 2.0, m, r, r * 1e-3, t_eval
                    ),
                    repeat=1,
                )
                err = float(np.max(np.linalg.norm(tips(tr) - ref, axis=1))) / L
                rows.append(
                    accuracy_row(
                        "multilink_dynamics",
                        method,
                        rtol,
                        err,
                        sec,
                        "rtol",
                        links=n,
                        nfev=tr.nfev,
                        quantity=f"tip error / L, n = {n}",
                    )
                )
    return rows


def rows(quick: bool) -> list[dict]:
    """All multilink rows; `observed_rate` (slope of log error vs log links) per method."""
    out = _static_rows(quick) + _mode_rows(quick) + _dynamic_rows(quick)
    for scene_method in {(r["scene"], r["method"]) for r in out if r["param"] == "links"}:
        sel = [r for r in out if (r["scene"], r["method"]) == scene_method]
        usable = [r for r in sel if r["error"] > 1e-12]
        rate = -observed_order([r["links"] for r in usable], [r["error"] for r in usable])
        for r in sel:
            r["observed_rate"] = rate
    return out


def plot(out: Path, rows_: list[dict]) -> list[Path]:
    """Convergence figure: chains of 2, 4, 8 links beside the beam, and the error vs links."""
    return [convergence_figure(out / "multilink_convergence.png", rows_)]


def convergence_figure(path: Path, rows_: list[dict], dpi: int = 110) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a0, a1) = plt.subplots(1, 2, figsize=(9.0, 3.6))
    line, label = elastica_cantilever(L, EI, tip_force=(0.0, -5.0)).centerline, "beam (elastica)"
    try:
        from mf_envs.physics.beam import solve_cantilever

        big = 1e7 * EI / L**2
        line = solve_cantilever(L, big, big, EI, 32, tip_force=(0.0, -5.0)).centerline
        label = "active C1 beam FE (32 el.)"
    except ImportError:  # the beam module is optional here
        pass
    a0.plot(line[:, 0], line[:, 1], "k-", lw=3, alpha=0.35, label=label)
    for n, c in zip((2, 4, 8), ("tab:green", "tab:blue", "tab:red")):
        st = solve_static(ml.chain_from_beam(L, EI, 1.0, n), tip_force=(0.0, -5.0))
        a0.plot(
            st.centerline[:, 0],
            st.centerline[:, 1],
            "o-",
            color=c,
            ms=3,
            lw=1.2,
            label=f"{n} links",
        )
    a0.set_aspect("equal")
    a0.set_title("cantilever, tip load PL²/EI = 5", fontsize=9)
    a0.set_xlabel("x [m]")
    a0.set_ylabel("z [m]")
    a0.legend(fontsize=7)
    a0.grid(alpha=0.3)
    for method in sorted({r["method"] for r in rows_ if r["scene"] == "multilink_statics"}):
        sel = sorted((r for r in rows_ if r["method"] == method), key=lambda r: r["links"])
        a1.loglog(
            [r["links"] for r in sel],
            [r["error"] for r in sel],
            "o-",
            ms=3,
            label=f"{method} (rate {sel[0]['observed_rate']:.2f})",
        )
    n = np.array([2.0, 4096.0])
    a1.loglog(n, 0.3 / n**2, "k:", lw=1, label="∝ 1/n²")
    a1.set_xlabel("links n")
    a1.set_ylabel("tip position error / L")
    a1.grid(True, which="both", alpha=0.3)
    a1.legend(fontsize=6)
    fig.tight_layout()
    return save_figure(fig, path, dpi=dpi)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="/tmp/multilink_bench", help="CSV + PNG folder")
    ap.add_argument("--docs", default=None, help="also write the small README picture here")
    ap.add_argument("--quick", action="store_true")
    args = ap.parse_args()
    from mf_envs.benchmarks._io import work_precision_plot, write_csv

    out = Path(args.out)
    rs = rows(args.quick)
    write_csv(out / "accuracy_multilink.csv", rs, ("scene", "method", "dt", "error", "seconds"))
    for scene in sorted({r["scene"] for r in rs}):
        work_precision_plot(
            out / f"accuracy_{scene}.png", [r for r in rs if r["scene"] == scene], scene
        )
    plot(out, rs)
    if args.docs:
        convergence_figure(
            Path(args.docs), [r for r in rs if r["scene"] == "multilink_statics"], dpi=80
        )
    for r in rs:
        print(
            f"{r['scene']:20s} {r['method']:36s} {r['dt']:>8g} {r['error']:.3e} "
            f"{r['seconds']:.2e}s rate={r.get('observed_rate', float('nan')):.3f}"
        )


if __name__ == "__main__":
    main()
