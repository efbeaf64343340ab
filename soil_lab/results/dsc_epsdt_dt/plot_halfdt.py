"""The 0.32 m plate at the soil's time step and at half of it (same bed, same speed), on case 3's
sand with its shipped rolling model (cdt, μr 0.45; soil_lab/archive/dry_sand_coarse_dt/) and on
the near-calibrated epsdt recipe of the same sand (μr 0.03; soil_lab/archive/dsc_epsdt_dt/): the
pressure against the sinkage over the loading, unloading and reloading. Run from the repository
root with Debian's python3: /usr/bin/python3 soil_lab/results/dsc_epsdt_dt/plot_halfdt.py
(writes plate_halfdt.png beside this file)."""
from pathlib import Path

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

here = Path(__file__).resolve().parent
archive = here.parents[1] / "archive"
labs = (("dry_sand_coarse_dt", "cdt, μr 0.45 (shipped; case 3's soil)"),
        ("dsc_epsdt_dt", "epsdt, μr 0.03 (the recipe on trial)"))
fig, axes = plt.subplots(1, 2, figsize=(11, 4.8), sharey=True)
for ax, (lab, title) in zip(axes, labs):
    for run, label in (("plate_b0.32", "dt (the soil's)"), ("plate_b0.32_halfdt", "dt / 2")):
        d = np.loadtxt(archive / lab / run / "plate.csv")
        d = d[d[:, 5] >= 1]   # loading (1), unloading (2), reloading (3)
        ax.plot(1e3 * d[:, 1], d[:, 3] / 1e3, lw=0.8, label=label)
    ax.set_title(title, fontsize=10)
    ax.set_xlabel("sinkage z [mm]")
    ax.grid(alpha=0.3)
    ax.legend(loc="upper left")
axes[0].set_ylabel("plate pressure p [kPa]")
fig.suptitle("dry_sand_coarse (16–40 mm): the 0.32 m plate at the soil's time step and at half "
             "of it, same bed and speed")
fig.tight_layout()
fig.savefig(here / "plate_halfdt.png", dpi=110)
