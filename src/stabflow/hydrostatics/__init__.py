"""Calm-water hydrostatics on the sections: equilibrium with free trim, particulars, GZ to 180°.

The sectional volume kernel (``_kernels``: clipping each station's contour by the inclined, or
wave-following, waterline) also serves the wave pass (:mod:`stabflow.stability_in_waves`) and the
time-domain FK + HS loads (:mod:`stabflow.dynamics`).
"""
