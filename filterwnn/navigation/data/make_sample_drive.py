"""Regenerate ``sample_drive.csv``: ``python filterwnn/navigation/data/make_sample_drive.py`` (seed fixed).

A simulated 3-minute town drive at 10 Hz with phone-grade sensors: it starts from rest,
stops at a light for 20 s, turns; the heading has a 1-degree bias and 1-degree noise, the
CAN speed a 2 % scale error and creeps at 0.005 m/s (0.01 mph) while the car stands; 1 Hz
GPS fixes as latitude/longitude with a reported accuracy of 3-6 m (and errors drawn with
that accuracy); the truth as latitude/longitude.
"""

import os

import numpy as np

from filterwnn.navigation.scenarios import Scenario, en_to_latlon, simulate_scenario

ORIGIN = (48.137, 11.575)


def make(path, seed=2024):
    sc = Scenario(name="sample_drive", duration=180.0, dt=0.1, speed=0.0, heading=30.0,
                  speed_changes=((3.0, 11.0, 12.0), (55.0, 63.0, -12.0), (83.0, 90.0, 10.0),
                                 (140.0, 146.0, 4.0)),
                  turns=((30.0, 38.0, 90.0), (100.0, 108.0, -90.0), (120.0, 126.0, 45.0)),
                  sigma_heading=1.0, sigma_odometer=0.02, t_switch=np.inf, heading_bias=1.0,
                  odometer_scale=1.02, gps_rate=0.0)
    rng = np.random.default_rng(seed)
    run = simulate_scenario(sc, rng=rng)
    t = np.concatenate([[0.0], run.t])
    x = np.vstack([run.x0, run.x_true])
    heading = np.concatenate([[np.deg2rad(sc.heading + sc.heading_bias)], run.z_dr[:, 0]])
    speed = np.concatenate([[0.0], run.z_dr[:, 1] / sc.dt])
    standing = np.hypot(x[:, 1], x[:, 4]) == 0
    speed = np.where(standing, 0.005 * rng.random(len(t)), speed)  # CAN creep while standing
    fix = np.zeros(len(t), dtype=bool)
    fix[10::10] = True
    acc = rng.uniform(3.0, 6.0, len(t))
    ge = x[:, 0] + acc * rng.standard_normal(len(t))
    gn = x[:, 3] + acc * rng.standard_normal(len(t))
    glat, glon = en_to_latlon(ge, gn, *ORIGIN)
    tlat, tlon = en_to_latlon(x[:, 0], x[:, 3], *ORIGIN)
    with open(path, "w") as fh:
        fh.write("time,heading,speed,gps_lat,gps_lon,gps_sigma,true_lat,true_lon\n")
        for k in range(len(t)):
            g = (f"{glat[k]:.8f},{glon[k]:.8f},{acc[k]:.1f}" if fix[k] else ",,")
            fh.write(f"{t[k]:.1f},{heading[k]:.5f},{speed[k]:.3f},{g},{tlat[k]:.8f},{tlon[k]:.8f}\n")


if __name__ == "__main__":
    make(os.path.join(os.path.dirname(os.path.abspath(__file__)), "sample_drive.csv"))
