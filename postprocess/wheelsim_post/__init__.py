"""wheelsim-post: post-processing of wheelsim run files (docs/postprocess.md).

Modules: ``runfile`` reads run files, ``metadata`` finds the grouping keys of a run,
``steady`` computes steady-state statistics, ``plotting`` holds matplotlib helpers, ``csvio``
writes and reads CSV files with comment headers, ``vtk`` reads the fix's wheel-surface files
and ``cmd_*`` implement the subcommands wired together by ``cli``.
"""

__version__ = "0.1.0"
