"""Physics models as plain functions and frozen parameter dataclasses (no Gymnasium).

One subpackage per model, each with a small public face in its `__init__`:

    rigid_body/  torque-free body, exact Jacobi-elliptic solution (ch. 2)
    multibody/   the general moving-frame B-matrix engine (ch. 3 Eqs. 5-75)
    gowec/       gyroscopic wave energy converter, prescribed buoy (ch. 3 Sec. 3.2)
    ship/        ship with gyro roll stabilizers (ch. 3 Sec. 3.3)
    beam/        C1 beam element and solvers (ch. 4); beam/contact/: friction feet, soil
    multilink/   planar n-link chain (ch. 4 Sec. 4.2)
    actuators/   the curvature actuator of the active beam (lag, rate limit, power)
    inchworm/    active beam robot (ch. 4), on the two above

Shared beside them: `constants` (G, RHO_SEAWATER, RPM: one definition each), `gyros`
(Seakeeper Table 3-1), `waves` (linear sea states), `terrain` (soil models; a beam's soil
contact is `beam/contact/terrain`). The Lie-group kernel and the one RK4 / RKMK4 stepper every
model steps with are in `mf_envs.frames.kernels` and `mf_envs.frames.steppers`.
"""
