"""Physical constants and unit factors, defined once for the whole package."""

#: standard acceleration of gravity [m/s^2] (CGPM 1901, the conventional value)
G = 9.80665

#: one knot [m/s]: the international nautical mile, 1852 m, per hour
KNOT = 1852.0 / 3600.0
