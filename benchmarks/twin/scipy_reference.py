#!/usr/bin/python3
"""Independent reference for the twin benchmark: the same gear equations (model.md §2-§5,
kinematic input, linear angle-periodic stiffness, sharp backlash dead zone, Coulomb drag)
written again here and solved with scipy's solve_ivp (RK45) at the same tolerances.

Reads case.json and the C++ samples written by `twin_benchmark --out DIR`, prints the wall
time ratio and the difference between the two answers. Needs Debian's python3-scipy.
"""
import json
import math
import sys
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp


def load(path):
    return np.fromfile(path, dtype=np.float64)


def make_rhs(c):
    n_ratio = c["ratio"]
    inv_n = 1.0 / n_ratio
    j1, j2, cj, cz = c["j1"], c["j2"], c["cj"], c["cz"]
    cmesh, half = c["mesh_damping"], c["half_backlash"]
    speed, ramp = c["speed"], c["ramp_time"]
    drag, drag_speed, load0 = c["drag"], c["drag_speed"], c["load_offset"]
    k0 = c["k0"]
    kh = [tuple(h) for h in c.get("k_harmonics") or []]
    te = [tuple(t) for t in c["te_terms"]]
    sin, cos, tanh = math.sin, math.cos, math.tanh

    def motion(t):
        if ramp > 0 and t < ramp:
            if t <= 0:
                return 0.0, 0.0, 0.0
            acc = speed / ramp
            return 0.5 * acc * t * t, acc * t, acc
        if ramp > 0:
            return speed * (t - 0.5 * ramp), speed, 0.0
        return speed * t, speed, 0.0

    def rhs(t, y):
        q, r = y[0], y[1]
        th1, w1, a1 = motion(t)
        th2 = th1 * inv_n - q
        w2 = w1 * inv_n - r
        e = 0.0
        de = 0.0
        for amp, a, b, phi in te:
            arg = a * th1 + b * th2 + phi
            e += amp * sin(arg)
            de += amp * (a * w1 + b * w2) * cos(arg)
        delta = q - e
        ddelta = r - de
        if abs(delta) <= half:
            x, slope = 0.0, 0.0
        else:
            x, slope = delta - math.copysign(half, delta), 1.0
        k = k0
        for amp, a, b, phi in kh:
            k += amp * cos(a * th1 + b * th2 + phi)
        spring = k * x
        damp = cmesh * slope * ddelta
        # No pulling torque, damping never larger than the spring torque (ElastoBacklash).
        if x > 0:
            gear = 0.0 if spring + damp <= 0 else spring + min(damp, spring)
        elif x < 0:
            gear = 0.0 if spring + damp >= 0 else spring + max(damp, spring)
        else:
            gear = 0.0
        dr = drag * tanh(w2 / drag_speed) if drag != 0 else 0.0
        load = load0 + dr
        w2dot = (gear - cz * w2 - load) / j2
        loss = (gear - spring) * ddelta + cj * w1 * w1 + cz * w2 * w2 + dr * w2
        return [r, a1 * inv_n - w2dot, loss]

    def alpha2(t, y):
        q, r = y[0], y[1]
        return rhs(t, y)[1] * -1.0 + motion(t)[2] * inv_n

    return rhs, alpha2


def fit_lines(t, x, freqs):
    cols = []
    for f in freqs:
        w = 2 * math.pi * f
        cols += [np.sin(w * t), np.cos(w * t)]
    cols += [np.ones_like(t), t - t[0]]
    a = np.stack(cols, axis=1)
    coef, *_ = np.linalg.lstsq(a, x, rcond=None)
    return [math.hypot(coef[2 * k], coef[2 * k + 1]) for k in range(len(freqs))]


def main():
    out = Path(sys.argv[1] if len(sys.argv) > 1 else "out/twin-benchmark")
    c = json.loads((out / "case.json").read_text())
    rhs, alpha2 = make_rhs(c)
    t_eval = load(out / "cpp_t.f64")
    y0 = c["y0"]
    atol = [c["atol"] * s for s in c["scale"]]
    start = time.perf_counter()
    sol = solve_ivp(rhs, (0.0, c["t_end"]), y0, method="RK45", rtol=c["rtol"], atol=atol,
                    t_eval=t_eval)
    wall = time.perf_counter() - start
    if not sol.success:
        print("scipy: solve_ivp failed:", sol.message)
        return 1
    te_py = -sol.y[0]
    a2_py = np.array([alpha2(t, sol.y[:, i]) for i, t in enumerate(sol.t)])
    te_cpp = load(out / "cpp_te.f64")
    te_ref = load(out / "ref_te.f64")
    a2_cpp = load(out / "cpp_alpha2.f64")
    i0 = int(round(c["record_from"] * c["rate"]))
    freqs = c["freqs"]
    arcsec = 180 * 3600 / math.pi
    print(f"scipy solve_ivp RK45, rtol {c['rtol']:.0e}: wall {wall:.2f} s, "
          f"{sol.nfev} RHS evaluations")
    print(f"C++ wall {c['cpp_wall_s']:.3f} s -> scipy / C++ = {wall / c['cpp_wall_s']:.0f}x")
    d_cpp = te_cpp - te_ref
    d_py = te_py - te_ref
    print(f"TE max |C++ - reference| = {np.max(np.abs(d_cpp)) * arcsec:.3e} arcsec, "
          f"max |scipy - reference| = {np.max(np.abs(d_py)) * arcsec:.3e} arcsec, "
          f"max |C++ - scipy| = {np.max(np.abs(te_cpp - te_py)) * arcsec:.3e} arcsec "
          f"(TE p2p {np.ptp(te_ref[i0:]) * arcsec:.2f} arcsec)")
    print(f"{'freq [Hz]':>10} {'channel':>7} {'C++':>13} {'scipy':>13} {'rel. diff':>10}")
    rows = []
    for name, xc, xp in (("alpha2", a2_cpp, a2_py), ("te", te_cpp, te_py)):
        ac = fit_lines(t_eval[i0:], xc[i0:], freqs)
        ap = fit_lines(t_eval[i0:], xp[i0:], freqs)
        for f, u, v in zip(freqs, ac, ap):
            rel = abs(u - v) / max(abs(u), 1e-300)
            rows.append({"freq_hz": f, "channel": name, "cpp": u, "scipy": v, "rel_diff": rel})
            print(f"{f:10.3f} {name:>7} {u:13.6e} {v:13.6e} {rel:10.2e}")
    (out / "scipy_report.json").write_text(json.dumps(
        {"scipy_wall_s": wall, "scipy_nfev": int(sol.nfev), "cpp_wall_s": c["cpp_wall_s"],
         "ratio": wall / c["cpp_wall_s"], "lines": rows}, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
