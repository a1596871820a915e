"""Commercial gyro stabilizers shared by the ship and the GOWEC models (Rios 2017 ch. 3 Table 3-1).

    SEAKEEPER[model] = (rotor speed in rpm, spin angular momentum H in N m s, spool-up power W)

Used by `mf_envs.physics.ship.params.seakeeper_gyro` (a gyro unit on a hull) and by the GOWEC's
net-power estimates (`mf_envs.physics.gowec.seakeeper_net_power`, `power_map`).
"""

SEAKEEPER: dict[str, tuple[float, float, float]] = {
    "3DC": (6400.0, 3000.0, 900.0),
    "5": (10700.0, 5000.0, 2000.0),
    "9": (9000.0, 9000.0, 2000.0),
    "16": (6130.0, 16000.0, 3000.0),
    "26": (5000.0, 26000.0, 3000.0),
    "35": (5150.0, 35000.0, 5000.0),
}
