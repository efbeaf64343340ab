#!/usr/bin/env python3
"""Golden values for tests/contact/test_contact_law.cpp, computed from LIGGGHTS 3.8's formulas.

An independent, straight-line transcription (plain floats, no shared code with the C++) of the
wall-contact formulas documented in docs/contact-law.md:
global_properties.cpp (Yeff, Geff, betaeff), normal_model_hertz.h, normal_model_edinburgh.h,
cohesion_model_sjkr.h, tangential_model_history.h, rolling_model_epsd2.h, and wheelsim's own
rolling_friction krot (docs/contact-law.md, no LIGGGHTS source), with the wall
conventions of fix_wall_gran.cpp (reff = R, meff = m, r = R - delta, c_r = R - delta/2).
Each case is one evaluation from a given history. Run: python3 golden_values.py (prints the
numbers pasted into the Golden.* tests, 17 significant digits).
"""
import math

# materials shared by all cases
E1, NU1 = 5.0e7, 0.3   # particle
E2, NU2 = 2.0e11, 0.3  # wheel
YEFF = 1.0 / ((1 - NU1**2) / E1 + (1 - NU2**2) / E2)
GEFF = 1.0 / (2 * (2 - NU1) * (1 + NU1) / E1 + 2 * (2 - NU2) * (1 + NU2) / E2)
R, M, DT = 2.0e-3, 8.0e-5, 1.0e-6
S56 = math.sqrt(5.0 / 6.0)


def beta(e):
    le = math.log(e)
    return le / math.sqrt(le * le + math.pi**2)


def hertz_case():
    # e = 0.5, mu = 0.5, sjkr k_coh = 1e5 J/m^3, epsd2 mu_r = 0.1
    e, mu, kcoh, mur = 0.5, 0.5, 1.0e5, 0.1
    d = 1.0e-5
    vn = -0.1                       # vRel = (0.01, 0, -0.1), n = z
    vt = (0.01, 0.0, 0.0)
    omega = (0.0, 5.0, 0.0)
    sq = math.sqrt(R * d)
    Sn, St = 2 * YEFF * sq, 8 * GEFF * sq
    kn = 4.0 / 3.0 * YEFF * sq
    gn = -2 * S56 * beta(e) * math.sqrt(Sn * M)
    gt = -2 * S56 * beta(e) * math.sqrt(St * M)
    Fn = kn * d - gn * vn
    r = R - d
    Fcoh = -kcoh * math.pi * (R * R - r * r)
    shear = [vt[0] * DT, 0.0, 0.0]
    Ft = [-St * shear[0] - gt * vt[0], 0.0, 0.0]   # below the cap
    assert St * abs(shear[0]) <= mu * abs(Fn)
    cr = R - d / 2
    # torque = -cr * n x Ft; n = z: n x (Fx,0,0) = (0, Fx, 0)
    tq = [0.0, -cr * Ft[0], 0.0]
    wr = [cr / r * w for w in omega]               # tangential already (n = z)
    Mr = [St * R * R * DT * w for w in wr]
    cap = abs(Fn) * R * mur
    mag = math.sqrt(sum(x * x for x in Mr))
    if mag > cap:
        Mr = [x * cap / mag for x in Mr]
    tq = [tq[i] - Mr[i] for i in range(3)]
    F = [Ft[0], 0.0, Fn + Fcoh]
    return dict(F=F, T=tq, shear=shear, rollTorque=Mr, Fn=Fn)


def eepa_default_case():
    # model edinburgh, fixKc off, limitForce on (default); n = 1.5, X = 1.5, k2/k1 = 5,
    # f0 = 0, surfaceEnergy = 0.1 (no effect on a wall). History: deltaMax (plastic) = 1.2e-5,
    # oldDelta = 1.6e-5; now delta = 1.5e-5 (unloading), vn = +0.002 (separating)
    e, kr, dex, cex = 0.5, 5.0, 1.5, 1.5
    d, vn = 1.5e-5, 0.002
    kn = 4.0 / 3.0 * YEFF * math.sqrt(R)
    k1, k2 = kn, kn * kr
    gn = math.sqrt(4 * M * kn / (1 + (math.pi / math.log(e))**2))
    lam = (1 - k1 / k2)**(1 / dex)
    dpmax = max(1.2e-5, lam * d)
    ftmp = k2 * (d**dex - dpmax**dex)
    assert ftmp < k1 * d**dex and ftmp > 0
    Fc = ftmp
    Fn = -gn * vn + Fc
    if Fn < 0:  # limitForce: no adhesion active (k_adh = 0 on a wall) and f0 = 0
        Fn = 0.0
    return dict(Fn=Fn, deltaMax=dpmax, kt=8 * GEFF * math.sqrt(R * d))


def eepa_fixkc_case():
    # fixKc on, limitForce off; n = 1.5, X = 1.5, k2/k1 = 5, kc/k1 = 0.5, f0 = -1e-3 N.
    # History deltaMax = 2e-5; now delta = 1.58e-5, vn = 0 (adhesive branch reached?)
    kr, kcr, dex, cex, f0 = 5.0, 0.5, 1.5, 1.5, -1.0e-3
    d = 1.58e-5
    kn = 4.0 / 3.0 * YEFF * math.sqrt(R)
    k1, k2, kc = kn, kn * kr, kn * kcr
    dmax = 2.0e-5
    ftmp = k2 * (d**dex - dmax**dex) + k1 * dmax**dex
    if ftmp >= k1 * d**dex:
        Fc, newmax = k1 * d**dex, dmax
    elif ftmp > -kc * d**cex:
        Fc, newmax = ftmp, dmax
    else:
        Fc, newmax = -kc * d**cex, (k2 + kc) / (k2 - k1) * d
    return dict(Fn=Fc + f0, deltaMax=newmax, branch=ftmp)


def krot_case():
    # k_r = 5e-5 N m/rad; a stored moment partly along the new normal n = (0.6, 0, 0.8); particle
    # spin (3, -4, 7), wheel spin (0, 1.5, 0); vRel = 0 (the torque is the rolling moment alone)
    kr = 5.0e-5
    n = (0.6, 0.0, 0.8)
    m_old = (2.0e-7, -1.0e-7, 3.0e-8)
    w = (3.0 - 0.0, -4.0 - 1.5, 7.0 - 0.0)
    before = math.sqrt(sum(x * x for x in m_old))
    mn = sum(a * b for a, b in zip(m_old, n))
    m_t = [a - mn * b for a, b in zip(m_old, n)]
    after = math.sqrt(sum(x * x for x in m_t))
    m_t = [x * before / after for x in m_t]
    wn = sum(a * b for a, b in zip(w, n))
    w_t = [a - wn * b for a, b in zip(w, n)]
    m_new = [a + kr * DT * b for a, b in zip(m_t, w_t)]
    return dict(torque=[-x for x in m_new], rollTorque=m_new)


if __name__ == "__main__":
    for name, case in (("hertz+sjkr+epsd2", hertz_case()), ("eepa default", eepa_default_case()),
                       ("eepa fixKc", eepa_fixkc_case()), ("krot", krot_case())):
        print(name)
        for k, v in case.items():
            if isinstance(v, list):
                print(f"  {k} = " + ", ".join(f"{x:.17g}" for x in v))
            else:
                print(f"  {k} = {v:.17g}")
