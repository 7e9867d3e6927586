"""Independent references for the hydrostatics: exact box GZ by polygon clipping, and exact
submerged volume, centroid and free-trim GZ of a closed triangle mesh (no sections).

Mesh integration: divergence theorem with fields that vanish on the waterplane z_e = 0, so no cap is needed:
V = ∫_S z n_z dS, ∫x dV = ∫_S x z n_z dS, ∫y dV = ∫_S y z n_z dS, ∫z dV = ∫_S z^2/2 n_z dS over
the hull surface below the plane (earth frame). Used as the reference for the sectional method.
"""

from __future__ import annotations

import numpy as np
import trimesh

from stabflow.geometry.frames import earth_vertices


def submerged(mesh: trimesh.Trimesh, phi: float, theta: float, h: float):
    """Submerged volume [m^3] and centroid (earth frame) [m] below calm water z_e = 0."""
    ve = earth_vertices(np.asarray(mesh.vertices, dtype=np.float64), phi, theta, h)
    v, f, _ = trimesh.intersections.slice_faces_plane(ve, mesh.faces, plane_normal=[0, 0, -1.0], plane_origin=[0, 0, 0.0])
    tri = v[f]
    a, b, c = tri[:, 0], tri[:, 1], tri[:, 2]
    n = np.cross(b - a, c - a) * 0.5  # area-weighted normal
    # exact integrals over each triangle of z, xz, yz, z^2/2 (quadratic: 3-point edge-midpoint rule)
    m = np.stack([(a + b) / 2, (b + c) / 2, (c + a) / 2], axis=1)
    z = m[..., 2]
    nz = n[:, 2]
    V = float((z.mean(axis=1) * nz).sum())
    if V <= 0:
        return 0.0, np.zeros(3)
    Ix = float(((m[..., 0] * z).mean(axis=1) * nz).sum())
    Iy = float(((m[..., 1] * z).mean(axis=1) * nz).sum())
    Iz = float(((0.5 * z * z).mean(axis=1) * nz).sum())
    return V, np.array([Ix, Iy, Iz]) / V


def mesh_gz(mesh: trimesh.Trimesh, volume: float, lcg: float, kg: float, heel_deg) -> np.ndarray:
    """Free-trim GZ [m] by exact integration over the mesh (reference for the sectional method).

    Independent of stabflow's sections and equilibrium: at each heel the height is first bracketed
    and solved alone (brentq on the displaced volume at the current trim, from fully dry to fully
    immersed), then height and trim together (fsolve, volume and the longitudinal G-B offset),
    starting from the previous heel's trim. A heel where either solve fails raises ``RuntimeError``.
    """
    from scipy.optimize import brentq, fsolve

    L = float(np.ptp(mesh.vertices[:, 0]))
    zs = np.asarray(mesh.vertices, float)
    r = float(np.sqrt((zs**2).sum(axis=1).max()))  # any rotation keeps the hull within +-r
    out = []
    theta = 0.0
    for hd in np.atleast_1d(heel_deg):
        phi = np.radians(hd)

        def F(p):
            V, c = submerged(mesh, phi, p[1], p[0])
            G = earth_vertices(np.array([[lcg, 0.0, kg]]), phi, p[1], p[0])[0]
            return [(V - volume) / volume, (c[0] - G[0]) / L]

        h0 = brentq(lambda h: submerged(mesh, phi, theta, h)[0] - volume, -r, r, xtol=1e-12 * r)
        sol, info, ier, msg = fsolve(F, [h0, theta], xtol=1e-11, full_output=True)
        res = np.abs(F(sol))
        if ier != 1 or res.max() > 1e-8:
            raise RuntimeError(f"mesh_gz: no free-trim equilibrium at heel {hd:g} deg ({msg.strip()}; residual {res.max():.2e})")
        theta = float(sol[1])
        V, c = submerged(mesh, phi, sol[1], sol[0])
        G = earth_vertices(np.array([[lcg, 0.0, kg]]), phi, sol[1], sol[0])[0]
        out.append(G[1] - c[1])
    return np.array(out)


def exact_box_gz(length, breadth, depth, volume, kg, heel_deg) -> np.ndarray:
    """Exact GZ of a rectangular barge by polygon clipping (shapely), independent of stabflow.

    A prismatic box floats at zero trim, so the 2-D section problem is exact: find the inclined
    waterline that cuts the area volume/length (brentq), then GZ = y_G - y_B in earth axes.
    """
    from scipy.optimize import brentq
    from shapely.affinity import rotate
    from shapely.geometry import Polygon, box

    sec = Polygon([(-breadth / 2, 0), (breadth / 2, 0), (breadth / 2, depth), (-breadth / 2, depth)])
    area = volume / length
    out = []
    for hd in np.atleast_1d(heel_deg):
        # rotate the section about the origin (port up for positive heel), G moves with it
        r = rotate(sec, hd, origin=(0, 0))
        g = rotate(Polygon([(0, kg), (1e-9, kg), (0, kg + 1e-9)]), hd, origin=(0, 0)).exterior.coords[0]
        lo, hi = r.bounds[1], r.bounds[3]

        def f(zw):
            return r.intersection(box(-1e3, -1e3, 1e3, zw)).area - area

        zw = brentq(f, lo, hi, xtol=1e-13)
        wet = r.intersection(box(-1e3, -1e3, 1e3, zw))
        out.append(g[0] - wet.centroid.x)
    return np.array(out)


def exact_box_area(length, breadth, depth, volume, kg, a_deg, b_deg) -> float:
    """Area under the exact box GZ (:func:`exact_box_gz`, odd in heel) from ``a_deg`` to ``b_deg``
    [m rad] by adaptive quadrature, with the kinks at deck-edge immersion and bilge emergence."""
    import math

    from scipy.integrate import quad

    def gz(p):
        return math.copysign(float(exact_box_gz(length, breadth, depth, volume, kg, [abs(p)])[0]), p)

    draft = volume / (length * breadth)
    kinks = [s * math.degrees(math.atan(x)) for s in (-1, 1)
             for x in (2 * (depth - draft) / breadth, 2 * draft / breadth)]
    pts = [k for k in kinks if a_deg < k < b_deg]
    return quad(gz, a_deg, b_deg, points=pts or None, epsabs=1e-11, limit=200)[0] * math.pi / 180.0
