"""FloatingGOWEC-v0's surge and heave (issue 29): the time-domain 3-dof model against its own
frequency-domain solution, the effect of freeing surge on pitch, and the table's RAO.

The frequency-domain reference solves, at each period, the linear surge/heave/pitch system of
the same model: masses and A_inf, the hydrostatic and mooring stiffness, and the radiation
memory of each kernel as its state-space fit's transfer function G(w) = C (-i w - A)^-1 B
(e^{-i w t}). The time-domain run starts on that steady state (radiation states included), so
any departure over ten periods is the implementation's (RK4 at 5 ms is far more accurate)."""

import math

import numpy as np
import pytest

from mf_envs.physics.gowec import GOWECParams
from mf_envs.physics.gowec.hydro import floating as fl
from mf_envs.physics.gowec.hydro.devices import DEVICES
from mf_envs.physics.gowec.hydro.model import FloatingModel
from mf_envs.physics.waves import regular_wave

DEV = DEVICES["iswec_class"]
PERIODS = (4.5, 5.5, 6.0, 7.0, 9.0)  # s: below, at and above the pitch resonance (5.8 s)
A_WAVE = 0.1  # m


def _model(surge: bool) -> FloatingModel:
    three = DEV.three_dof_table()
    gyro = GOWECParams(DEV.rotor_inertia, DEV.rotor_speed, gimbal_inertia=DEV.gimbal_inertia)
    pto = dict(damping=0.0, stiffness=0.0, max_torque=1e9, max_power=1e12, eta_generator=1.0,
               eta_motor=1.0)  # fmt: skip
    m = FloatingModel(DEV.hull(), gyro, pto, gyroscopic=False, units=2, three_dof=three)
    if surge:
        m.set_translation(True, DEV.mooring_stiffness)
    return m


def _G(A, B, C, w):
    """Transfer function of x' = A x + B v, y = C x at e^{-i w t}, and the state per unit v."""
    X = np.linalg.solve(-1j * w * np.eye(A.shape[0]) - A, B)
    return complex((C @ X).item()), X


def _frequency_domain(m: FloatingModel, w: float, surge: bool):
    """(Theta, S, Z) complex amplitudes (rad, m, m) per the module doc, head sea (alpha = -theta)
    and the states' complex amplitudes for the time-domain start."""
    three = m.three
    wave = regular_wave(A_WAVE, 2 * math.pi / w, math.pi / 2)
    m.set_sea(wave)
    X = lambda mode: complex(  # noqa: E731
        np.interp(w, three.omega, three.excitation[:, mode].real)
        + 1j * np.interp(w, three.omega, three.excitation[:, mode].imag)
    )
    M, _, _, _ = fl.mass_and_rhs(np.zeros(3), np.zeros(3), m.p.inertia, m.p.gyro, 0.0)
    In = M[0, 0]
    g55, x55 = _G(m.p.Ar[0], m.p.Br[0, :, None], m.p.Cr[0], w)
    iw = -1j * w
    if not surge:
        Al = X(2) * A_WAVE / (-(w**2) * In + m.p.stiffness[0] + g55 * iw)
        return -Al, 0.0, 0.0, {"x55": x55[:, 0] * iw * (-Al)}
    tp, As, Bs, Cs = m._tr
    o = [int(tp[i]) for i in (fl.TP_O11, fl.TP_O15, fl.TP_O51, fl.TP_O33, fl.TP_NT)]
    blocks = {}
    for name, (lo, hi) in zip(("11", "15", "51", "33"), zip(o[:-1], o[1:])):
        blocks[name] = _G(As[lo:hi, lo:hi], Bs[lo:hi, None], Cs[lo:hi], w)
    M1, a15, k, M3, C33 = (tp[i] for i in (fl.TP_M1, fl.TP_A15, fl.TP_K, fl.TP_M3, fl.TP_C33))
    Z = np.array(
        [
            [-(w**2) * M1 + k + blocks["11"][0] * iw, -(w**2) * a15 + blocks["15"][0] * iw],
            [-(w**2) * a15 + blocks["51"][0] * iw, -(w**2) * In + m.p.stiffness[0] + g55 * iw],
        ]
    )
    S, Al = np.linalg.solve(Z, np.array([X(0), X(2)]) * A_WAVE)
    Zh = X(1) * A_WAVE / (-(w**2) * M3 + C33 + blocks["33"][0] * iw)
    states = {
        "x55": x55[:, 0] * iw * (-Al),
        "trans": np.concatenate(
            [
                blocks["11"][1][:, 0] * iw * S,
                blocks["15"][1][:, 0] * iw * Al,
                blocks["51"][1][:, 0] * iw * S,
                blocks["33"][1][:, 0] * iw * Zh,
            ]  # fmt: skip
        ),
    }
    return -Al, S, Zh, states


def _time_domain(m: FloatingModel, w: float, surge: bool):
    """Run 10 periods from the frequency-domain steady state; max |error| / amplitude of
    theta, s and z against Re(amplitude e^{-i w t})."""
    Th, S, Z, st = _frequency_domain(m, w, surge)
    y = m.initial_state()
    nr = m.p.Ar.shape[1]
    y[0], y[3] = Th.real, (-1j * w * Th).real
    y[6 : 6 + nr] = st["x55"].real
    if surge:
        b = 6 + 2 * nr
        y[b : b + 4] = (S.real, Z.real, (-1j * w * S).real, (-1j * w * Z).real)
        y[b + 4 : b + 4 + st["trans"].size] = st["trans"].real
    T = 2 * math.pi / w
    dt, t, err = 0.005, 0.0, np.zeros(3)
    n = int(round(T / 20 / dt))
    for _ in range(200):
        y = m.step(t, y, 0.0, dt, n)
        t += n * dt
        e = np.exp(-1j * w * t)
        err[0] = max(err[0], abs(y[0] - (Th * e).real) / abs(Th))
        if surge:
            b = 6 + 2 * nr
            err[1] = max(err[1], abs(y[b] - (S * e).real) / abs(S))
            err[2] = max(err[2], abs(y[b + 1] - (Z * e).real) / abs(Z))
    return err, abs(Th)


@pytest.mark.parametrize("T", PERIODS)
def test_time_domain_matches_frequency_domain_rao(T):
    """Surge, heave, pitch of the time-domain 3-dof model within 1 % of the frequency-domain
    RAO of the same system at five periods (issue 29 acceptance)."""
    w = 2 * math.pi / T
    err, _ = _time_domain(_model(True), w, True)
    assert np.all(err < 0.01), err


def test_freeing_surge_changes_pitch_as_the_rao_predicts():
    """Pitch amplitude with surge free / held: time domain equals the frequency domain's ratio
    to 1 %, and the ratio is not 1 (surge matters on this hull)."""
    ratios = []
    for T in (5.0, 6.0, 7.0):
        w = 2 * math.pi / T
        fd = abs(_frequency_domain(_model(True), w, True)[0]) / abs(
            _frequency_domain(_model(False), w, False)[0]
        )
        (e1, a1), (e0, a0) = _time_domain(_model(True), w, True), _time_domain(_model(False), w,
                                                                                False)  # fmt: skip
        assert e1[0] < 0.01 and e0[0] < 0.01
        assert a1 / a0 == pytest.approx(fd, rel=0.01)
        ratios.append(fd)
    assert max(abs(r - 1.0) for r in ratios) > 0.03, ratios


def test_fitted_rao_near_the_table_rao():
    """The model's pitch RAO (radiation fits) against the BEM table's own frequency-domain RAO
    (A(w), B(w) interpolated): the fits' error, stated in docs/gowec_v1.md (here <= 10 %
    away from the resonance peak's sharpest point)."""
    m = _model(True)
    three = m.three
    for T in (4.5, 7.0, 9.0):
        w = 2 * math.pi / T
        Th = abs(_frequency_domain(m, w, True)[0])
        A = np.array([[np.interp(w, three.omega, three.added_mass[:, i, j]) for j in (0, 2)]
                      for i in (0, 2)])  # fmt: skip
        B = np.array([[np.interp(w, three.omega, three.damping[:, i, j]) for j in (0, 2)]
                      for i in (0, 2)])  # fmt: skip
        A = 0.5 * (A + A.T)
        B = 0.5 * (B + B.T)
        M, _, _, _ = fl.mass_and_rhs(np.zeros(3), np.zeros(3), m.p.inertia, m.p.gyro, 0.0)
        In = M[0, 0] - m.p.inertia[0] + three.mass_matrix[2, 2]
        Mm = np.diag([three.mass_matrix[0, 0], In])
        Cm = np.diag([m.mooring_stiffness, m.p.stiffness[0]])
        X = np.array([np.interp(w, three.omega, three.excitation[:, i].real)
                      + 1j * np.interp(w, three.omega, three.excitation[:, i].imag)
                      for i in (0, 2)])  # fmt: skip
        xi = np.linalg.solve(-(w**2) * (Mm + A) - 1j * w * B + Cm, X * A_WAVE)
        assert Th == pytest.approx(abs(xi[1]), rel=0.10)
