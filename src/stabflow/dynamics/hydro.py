"""Wave-body coefficients and linear peer RAOs from Capytaine (BEM, linear potential flow).

The hull mesh is placed at its calm-water equilibrium (earth frame, waterline z = 0), clipped to
its immersed part, with rigid-body heave, roll and pitch about G. Added mass and radiation damping
are taken at each mode's natural frequency, found by fixed-point iteration
w = sqrt(C / (M + A(w))). Linear RAOs (Froude-Krylov + diffraction + radiation, stabflow's own
hydrostatic stiffness and viscous roll damping) are the peer comparison for the time-domain model.
Capytaine uses the e^{-i w t} convention; only amplitudes are compared.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

from stabflow.geometry.frames import earth_vertices
from stabflow.io import annotate
from stabflow.constants import G
from stabflow.waves.synthesis import one_blas_thread

DOFS = ["Heave", "Roll", "Pitch"]


def bem_mesh(ship, max_faces: int = 20000):
    """Triangle mesh for the BEM: the ship's STL (with its transform) or, for the box barge, a
    box panelled at 4 m. Raises StabflowError for hulls without a usable mesh."""
    import trimesh

    from stabflow import StabflowError
    from stabflow.geometry.mesh import ship_mesh

    h = ship.hull
    if h["source"] == "box":
        m = trimesh.creation.box(extents=[h["length"], h["breadth"], h["depth"]])
        m.apply_translation([0, 0, 0.5 * h["depth"]])
        v, f = trimesh.remesh.subdivide_to_size(m.vertices, m.faces, max_edge=4.0)
        return trimesh.Trimesh(v, f, process=False)
    if h["source"] != "mesh":
        raise StabflowError(f"{ship.path}: hull.source: Capytaine needs a mesh or box hull, not {h['source']!r}")
    m = ship_mesh(ship)
    if len(m.faces) > max_faces:
        raise StabflowError(f"{ship.hull_file()}: {len(m.faces)} triangles is too many for a dense BEM (max {max_faces})")
    return m


def _earth_hull(mesh, h0, th0, xg, zg):
    """(Capytaine Mesh of the whole hull, rigid-body dofs about G) in the earth frame at the
    equilibrium (heave h0 [m], trim th0 [rad]; G at body x ``xg``, z ``zg`` [m])."""
    import capytaine as cpt

    cpt.set_logging("ERROR")
    ve = earth_vertices(np.asarray(mesh.vertices, float), 0.0, th0, h0)
    ge = earth_vertices(np.array([[xg, 0.0, zg]]), 0.0, th0, h0)[0]
    return cpt.Mesh(vertices=ve, faces=np.asarray(mesh.faces)), cpt.rigid_body_dofs(rotation_center=tuple(ge))


def immersed_body(mesh, h0, th0, xg, zg):
    """Capytaine FloatingBody of the immersed hull with heave/roll/pitch about G."""
    import capytaine as cpt

    hull, dofs = _earth_hull(mesh, h0, th0, xg, zg)
    return cpt.FloatingBody(mesh=hull, dofs=dofs).immersed_part().with_only_dofs(DOFS)


def lidded_body(mesh, h0, th0, xg, zg, dofs):
    """Capytaine FloatingBody of the immersed hull at its equilibrium (heave h0 [m], trim th0 [rad])
    with a lid on the inner waterplane (irregular-frequency removal) and the rigid-body modes ``dofs``
    about G (``xg``, ``zg`` [m], body axes): the body of the frequency sweeps (the heave-pitch
    radiation, the diffraction force)."""
    import capytaine as cpt

    hull, rigid = _earth_hull(mesh, h0, th0, xg, zg)
    hull = hull.immersed_part()
    lid = hull.generate_lid(z=-1e-3 * float(np.ptp(hull.vertices[:, 2])))
    return cpt.FloatingBody(mesh=hull, lid_mesh=lid, dofs=rigid).with_only_dofs(list(dofs))


def radiation(body, omega, rho, solver=None):
    """(A, B): 3x3 added mass and radiation damping for (heave, roll, pitch) at ``omega``."""
    import capytaine as cpt

    solver = solver or cpt.BEMSolver()
    with one_blas_thread():  # the BEM solve's rounding depends on BLAS's threads: the same in every job
        res = [solver.solve(cpt.RadiationProblem(body=body, radiating_dof=d, omega=omega, rho=rho, g=G)) for d in DOFS]
    A = np.array([[r.added_mass[d] for r in res] for d in DOFS])
    B = np.array([[r.radiation_damping[d] for r in res] for d in DOFS])
    return A, B


def manoeuvring_added_mass(mesh, h0, th0, xg, zg, rho) -> np.ndarray:
    """Added mass (3, 3) of surge, sway and yaw about G [kg, kg m, kg m^2] at zero frequency (the
    manoeuvring limit, free surface as a rigid wall for w -> 0) for the hull at its upright
    equilibrium (heave h0 [m], trim th0 [rad]), symmetrised."""
    import capytaine as cpt

    dofs = ["Surge", "Sway", "Yaw"]
    hull, rigid = _earth_hull(mesh, h0, th0, xg, zg)
    body = cpt.FloatingBody(mesh=hull, dofs=rigid).immersed_part().with_only_dofs(dofs)
    solver = cpt.BEMSolver()
    # on one BLAS thread: the solve's rounding depends on BLAS's threads, and every 6-DOF job solves
    # it again (a two-thread split-time job's trawler records parted from the one-thread shards'
    # by this, 3e-11 relative in the added mass: found 2026-12-02)
    with one_blas_thread():
        res = [solver.solve(cpt.RadiationProblem(body=body, radiating_dof=d, omega=0.0, rho=rho, g=G)) for d in dofs]
    A = np.array([[r.added_mass[d] for r in res] for d in dofs])
    return 0.5 * (A + A.T)


def excitation(body, omega, heading_deg, rho, solver=None) -> np.ndarray:
    """Complex Froude-Krylov + diffraction force (heave, roll, pitch) per unit wave amplitude."""
    import capytaine as cpt
    from capytaine.bem.airy_waves import froude_krylov_force

    solver = solver or cpt.BEMSolver()
    pb = cpt.DiffractionProblem(body=body, omega=omega, wave_direction=np.radians(heading_deg), rho=rho, g=G)
    res = solver.solve(pb)
    fk = froude_krylov_force(pb)
    return np.array([fk[d] + res.forces[d] for d in DOFS])


def natural_coefficients(body, masses, stiff, rho, iterations=3, modes=("heave", "roll", "pitch")) -> dict:
    """(w, A_jj, B_jj) at each mode's natural frequency (fixed point on w = sqrt(C/(M + A))), for
    ``modes`` (``masses`` and ``stiff`` are given for heave, roll and pitch, in that order)."""
    import capytaine as cpt

    solver = cpt.BEMSolver()
    out = {}
    for j, mode in enumerate(["heave", "roll", "pitch"]):
        if mode not in modes:
            continue
        a = 0.0
        for _ in range(iterations):
            w = np.sqrt(stiff[j] / (masses[j] + a))
            r = solver.solve(cpt.RadiationProblem(body=body, radiating_dof=DOFS[j], omega=w, rho=rho, g=G))
            a, b = r.added_mass[DOFS[j]], r.radiation_damping[DOFS[j]]
        out[mode] = (float(np.sqrt(stiff[j] / (masses[j] + a))), a, b)
    return out


def hydro_dataset(mesh, st, co, rho, heading_deg, lwl, ratios, C, h0, th0) -> xr.Dataset:
    """Coefficients at the natural frequencies and linear Capytaine RAOs over lambda/L, for the hull
    at its upright equilibrium (heave h0 [m], trim th0 [rad])."""
    import capytaine as cpt

    body = immersed_body(mesh, h0, th0, float(st["lcg"]), float(st["kg"]))
    masses = [co.mass, co.i44, co.i55]
    nat = natural_coefficients(body, masses, [C[0, 0], C[1, 1], C[2, 2]], rho)
    solver = cpt.BEMSolver()
    M = np.diag(masses)
    rao = []
    for r in ratios:
        k = 2 * np.pi / (r * lwl)
        w = np.sqrt(G * k)
        A, B = radiation(body, w, rho, solver)
        Bv = np.diag([0.0, co.b44, 0.0])  # viscous roll damping of the ship config
        F = excitation(body, w, heading_deg, rho, solver)
        X = np.linalg.solve(-w**2 * (M + A) - 1j * w * (B + Bv) + C, F)
        a = 1.0
        rao.append([abs(X[0]) / a, abs(X[1]) / (k * a), abs(X[2]) / (k * a)])
    rao = np.array(rao)
    ds = xr.Dataset(
        {
            "heave_rao": ("wavelength_ratio", rao[:, 0], {"units": "1", "long_name": "Capytaine linear heave / a"}),
            "roll_rao": ("wavelength_ratio", rao[:, 1], {"units": "1", "long_name": "Capytaine linear roll / ka"}),
            "pitch_rao": ("wavelength_ratio", rao[:, 2], {"units": "1", "long_name": "Capytaine linear pitch / ka"}),
        },
        coords={"wavelength_ratio": np.asarray(ratios, float)},
        attrs={"heading_deg": heading_deg, "panels": int(body.mesh.nb_faces)},
    )
    for mode, (w, a, b) in nat.items():
        ds[f"omega_{mode}"] = xr.DataArray(w, attrs={"units": "rad/s", "long_name": f"{mode} natural frequency"})
        ds[f"added_{mode}"] = xr.DataArray(a, attrs={"units": "kg" if mode == "heave" else "kg m2",
                                                      "long_name": f"{mode} added mass/inertia at its natural frequency"})
        ds[f"damping_{mode}"] = xr.DataArray(b, attrs={"units": "N s/m" if mode == "heave" else "N m s",
                                                        "long_name": f"{mode} radiation damping at its natural frequency"})
    return annotate(ds)

