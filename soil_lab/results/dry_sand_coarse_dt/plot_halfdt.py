"""The 10 kPa shear box of this lab at the soil's time step and at half of it (same bed, same
speed): shear stress and lid against the shear displacement. Run from the repository root with
Debian's python3: /usr/bin/python3 soil_lab/results/dry_sand_coarse_dt/plot_halfdt.py
(reads soil_lab/archive/dry_sand_coarse_dt/, writes shear_halfdt.png beside this file)."""
from pathlib import Path

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

here = Path(__file__).resolve().parent
archive = here.parents[2] / "soil_lab" / "archive" / "dry_sand_coarse_dt"
fig, (ax, lid) = plt.subplots(2, 1, figsize=(8, 7), sharex=True,
                              gridspec_kw={"height_ratios": [2, 1]})
for run, label in (("shear_s10000", "dt 4.87e-5 s (the soil's)"),
                   ("shear_s10000_halfdt", "dt 2.44e-5 s (half)")):
    d = np.loadtxt(archive / run / "shear.csv")
    s = d[d[:, 6] == 2]   # the shear phase
    j = 1e3 * (s[:, 1] - s[0, 1])
    ax.plot(j, s[:, 3] / 1e3, lw=0.8,
            label=f"{label}: unsmoothed max {s[:, 3].max() / 1e3:.2f} kPa")
    lid.plot(j, 1e3 * (s[:, 5] - s[0, 5]), lw=1.0, label=label)
ax.set_ylabel("shear stress τ [kPa]")
ax.set_title("dry_sand_coarse (cdt, μr 0.45): 10 kPa box at the soil's step and at half of it")
ax.grid(alpha=0.3)
ax.legend(loc="lower right")
lid.set_xlabel("shear displacement j [mm]")
lid.set_ylabel("lid [mm]\n(< 0: compaction)")
lid.grid(alpha=0.3)
fig.tight_layout()
fig.savefig(here / "shear_halfdt.png", dpi=110)
