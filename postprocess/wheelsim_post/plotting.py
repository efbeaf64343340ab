"""matplotlib helpers (Agg backend): figure grids, phase shading, saving.

matplotlib is imported on the first plot, not with this module: pyplot costs ~0.5 s of start-up
that the commands which write no PNG (results, statistics, --help, ...) need not pay."""

import os

import numpy as np

from .errors import PostError
from .steady import PHASES

PHASE_COLOURS = {0: "tab:gray", 1: "tab:blue", 2: "tab:orange", 3: "tab:green"}


def pyplot():
    """matplotlib.pyplot on the Agg backend (imported on first use)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def panel_grid(count, columns=2, width=5.0, height=3.5, sharex=False):
    """A figure with ``count`` axes in a grid (unused cells removed); returns (fig, axes)."""
    columns = min(columns, count)
    rows = (count + columns - 1) // columns
    fig, grid = pyplot().subplots(
        rows,
        columns,
        figsize=(width * columns, height * rows),
        squeeze=False,
        sharex=sharex,
    )
    axes = list(grid.ravel())
    for extra in axes[count:]:
        fig.delaxes(extra)
    return fig, axes[:count]


def shade_phases(ax, time, phase, label=True):
    """Shades the spans of each phase (codes in PHASES) behind the data of ``ax``."""
    if len(time) == 0:
        return
    codes = np.rint(phase).astype(int)
    change = np.flatnonzero(np.diff(codes)) + 1
    starts = np.concatenate(([0], change))
    ends = np.concatenate((change, [len(codes)]))
    seen = set()
    for a, b in zip(starts, ends):
        code = int(codes[a])
        t_end = time[b] if b < len(time) else time[-1]
        name = PHASES.get(code, f"phase {code}")
        ax.axvspan(
            time[a],
            t_end,
            color=PHASE_COLOURS.get(code, "tab:purple"),
            alpha=0.12,
            lw=0,
            label=name if label and code not in seen else None,
        )
        seen.add(code)


def save(fig, path, tight=True):
    """Saves ``fig`` as PNG to ``path`` and closes it (PostError if the directory is missing);
    ``tight``: apply tight_layout first (False if the caller laid the figure out)."""
    directory = os.path.dirname(os.path.abspath(path))
    plt = pyplot()
    if not os.path.isdir(directory):
        plt.close(fig)
        raise PostError(
            f"cannot write '{path}': directory '{directory}' does not exist"
        )
    if tight:
        fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
