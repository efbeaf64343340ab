"""Slip of a wheel from its forward speed v [m/s] and rim speed ω·R_eff [m/s], in three
conventions (DESIGN.md §5, TERRAMECHANICS.md §5, docs/postprocess.md "Slip conventions").

- ``driving_slip``: s = 1 − v/(ω R_eff) (Wong; what the rig's ``slip`` observable holds).
  1 for a wheel spinning in place (v = 0, ω ≠ 0); undefined (NaN) when ω R_eff = 0.
- ``skid_slip``: s = (ω R_eff − v)/v, for braked and skidding wheels; −1 for a locked wheel
  (ω = 0, v ≠ 0); undefined (NaN) when v = 0.
- ``signed_slip`` (issue 11's ``slip`` column): the driving convention when |ω R_eff| ≥ |v|
  (s ≥ 0 for forward travel), the skid convention when |v| > |ω R_eff| (s < 0). It lies in
  [−1, 1] for forward travel (v ≥ 0, ω ≥ 0): −1 locked wheel, 0 free rolling, 1 spinning in
  place; NaN only for a wheel at rest (v = ω R_eff = 0).

The two conventions agree in sign and differ in scale: s_skid = s_driving / (1 − s_driving).
Each function takes numbers or numpy arrays (broadcast together) and returns a float for
scalar input, else an array.
"""

import numpy as np


def _result(value, *inputs):
    """A float when every input was a scalar, else the array."""
    if all(np.ndim(x) == 0 for x in inputs):
        return float(value)
    return value


def driving_slip(v, rim_speed):
    """1 − v/rim_speed (NaN where rim_speed = ω R_eff is 0)."""
    v_a, r_a = np.broadcast_arrays(np.asarray(v, dtype=float), np.asarray(rim_speed, dtype=float))
    with np.errstate(divide="ignore", invalid="ignore"):
        value = np.where(r_a != 0.0, 1.0 - v_a / np.where(r_a != 0.0, r_a, 1.0), np.nan)
    return _result(value, v, rim_speed)


def skid_slip(v, rim_speed):
    """(rim_speed − v)/v (NaN where v is 0); −1 for a locked wheel (rim_speed 0)."""
    v_a, r_a = np.broadcast_arrays(np.asarray(v, dtype=float), np.asarray(rim_speed, dtype=float))
    with np.errstate(divide="ignore", invalid="ignore"):
        value = np.where(v_a != 0.0, (r_a - v_a) / np.where(v_a != 0.0, v_a, 1.0), np.nan)
    return _result(value, v, rim_speed)


def signed_slip(v, rim_speed):
    """Driving convention where |rim_speed| ≥ |v| (and rim_speed ≠ 0), skid convention where
    |v| > |rim_speed|; NaN where both are 0."""
    v_a, r_a = np.broadcast_arrays(np.asarray(v, dtype=float), np.asarray(rim_speed, dtype=float))
    driving = np.asarray(driving_slip(v_a, r_a), dtype=float)
    skid = np.asarray(skid_slip(v_a, r_a), dtype=float)
    use_driving = (np.abs(r_a) >= np.abs(v_a)) & (r_a != 0.0)
    value = np.where(use_driving, driving, skid)
    return _result(value, v, rim_speed)


def forward_speed(rim_speed, slip):
    """The forward speed v [m/s] at which a wheel of rim speed ω R_eff has the signed slip `slip`
    (the inverse of signed_slip for forward travel): (1 − s) ω R_eff for s ≥ 0, ω R_eff / (1 + s)
    for −1 < s < 0; NaN for s ≤ −1 (a locked wheel's speed is not set by its rim)."""
    r_a, s_a = np.broadcast_arrays(np.asarray(rim_speed, dtype=float), np.asarray(slip, dtype=float))
    with np.errstate(divide="ignore", invalid="ignore"):
        skid = np.where(s_a > -1.0, r_a / np.where(s_a > -1.0, 1.0 + s_a, 1.0), np.nan)
        value = np.where(s_a >= 0.0, (1.0 - s_a) * r_a, skid)
    return _result(value, rim_speed, slip)


#: name -> function(v, rim_speed), in the order of the CSV columns.
CONVENTIONS = {
    "slip": driving_slip,
    "slip_skid": skid_slip,
    "slip_signed": signed_slip,
}
