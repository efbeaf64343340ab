"""soil_lab_py: the analysis layer of the virtual soil lab (docs/soil-lab.md).

fits      Bekker plate sinkage, unloading stiffness, Mohr–Coulomb, Janosi, peak and residual
repose    angle of repose from a heap's free-surface profile
scm_file  an SCM soil file (inputs/scm_soils format) fitted from a DEM soil
report    the lab's PNG plots

Pure functions on arrays (SI units); reading the decks' output files is not done here.
"""
