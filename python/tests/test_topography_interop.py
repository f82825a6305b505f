"""egw.topography as a numpy / SurfaceTopography user meets it (issue 24): surfaces made
here with a prescribed spectrum (self-affine and Gaussian, periodic and cropped, tilted,
offset, non-square, anisotropic); egw's sigma, eta, beta against (1) the spectral-moment
theory of the surface itself, computed here from exact (FFT) derivatives of the periodic
surface restricted to the map, and (2) a direct 8-neighbour summit count written here,
both within 2 %, from Python and from egw-topo --json; units, NaN pixels, warnings, the
contact in one call."""
import json
import math
import os
import subprocess
import sys
import warnings

import numpy as np
import pytest

import egw
from egw import topography as topo

TOL = 0.02


def make_surface(n=512, kind="self-affine", q_low=4, q_high=32, hurst=0.8, aniso=1.0,
                 seed=7):
    """One period (n x n) of a random surface with a prescribed isotropic (or, aniso != 1,
    stretched) spectrum between wavenumber indices q_low and q_high; rms 1 um, pixel 1 um.
    Returns the heights and its exact derivatives (zx, zy, zxx, zyy) by FFT."""
    rng = np.random.default_rng(seed)
    k1 = np.fft.fftfreq(n, 1.0 / n)
    kx, ky = k1[None, :], k1[:, None]
    k = np.hypot(kx * aniso, ky)
    band = (k >= q_low) & (k <= q_high)
    if kind == "self-affine":
        amp = np.where(band, np.maximum(k, 1) ** (-(1 + hurst)), 0.0)
    else:  # Gaussian autocorrelation: Gaussian spectrum
        amp = np.where(band, np.exp(-0.5 * (k / (0.4 * q_high)) ** 2), 0.0)
    noise = np.fft.fft2(rng.standard_normal((n, n)))
    zh = amp * noise / np.abs(noise)
    dx = 1e-6
    qx, qy = 2 * np.pi * np.fft.fftfreq(n, dx)[None, :], 2 * np.pi * np.fft.fftfreq(n, dx)[:, None]
    parts = [np.fft.ifft2(f * zh).real for f in (1, 1j * qx, 1j * qy, -qx ** 2, -qy ** 2)]
    scale = 1e-6 / parts[0].std()
    return [p * scale for p in parts], dx


def theory(z, zx, zy, zxx, zyy):
    """McCool/Nayak from the exact moments of the map (heights and slopes about their
    means over the map: what a mean or plane detrend leaves)."""
    m0 = np.mean((z - z.mean()) ** 2)
    m2 = 0.5 * (np.var(zx) + np.var(zy))
    m4 = 0.5 * (np.mean(zxx ** 2) + np.mean(zyy ** 2))
    alpha = m0 * m4 / m2 ** 2
    return {"summit_density": m4 / (6 * math.pi * math.sqrt(3) * m2),
            "summit_radius": 0.375 * math.sqrt(math.pi / m4),
            "sigma_summits": math.sqrt((1 - 0.8968 / alpha) * m0)}


def direct_count(z, dx, dy, periodic):
    """8-neighbour summits written independently of egw: a pixel above all eight
    neighbours (wrapping when periodic, interior pixels otherwise); eta, beta from the
    mean curvature -(z_xx + z_yy)/2 by central differences, sigma_s."""
    zp = np.pad(z, 1, mode="wrap") if periodic else z
    win = np.lib.stride_tricks.sliding_window_view(zp, (3, 3))
    centre = win[:, :, 1, 1]
    others = win.reshape(win.shape[0], win.shape[1], 9)
    top = np.all(others[:, :, [0, 1, 2, 3, 5, 6, 7, 8]] < centre[:, :, None], axis=2)
    zxx = (win[:, :, 1, 2] - 2 * centre + win[:, :, 1, 0]) / dx ** 2
    zyy = (win[:, :, 2, 1] - 2 * centre + win[:, :, 0, 1]) / dy ** 2
    kappa = -0.5 * (zxx + zyy)[top]
    ny, nx = z.shape
    area = nx * ny * dx * dy if periodic else (nx - 2) * (ny - 2) * dx * dy
    return {"summit_density": top.sum() / area, "summit_radius": 1 / kappa.mean(),
            "sigma_summits": centre[top].std()}


def _detrended(z, periodic):
    if periodic:
        return z - z.mean()
    ny, nx = z.shape
    y, x = np.mgrid[0:ny, 0:nx]
    a = np.column_stack([np.ones(z.size), x.ravel(), y.ravel()])
    coef, *_ = np.linalg.lstsq(a, z.ravel(), rcond=None)
    return z - (a @ coef).reshape(z.shape)


CASES = {
    "self-affine periodic": dict(kind="self-affine"),
    "gaussian periodic": dict(kind="gaussian", seed=11),
    "self-affine cropped non-square tilted offset": dict(kind="self-affine", crop=(300, 420),
                                                         tilt=(2e-3, -1e-3), offset=5e-3),
    "gaussian cropped non-square": dict(kind="gaussian", crop=(350, 260), seed=5),
    "anisotropic periodic": dict(kind="self-affine", aniso=1.6, seed=3),
}


def case(name):
    c = dict(CASES[name])
    crop, tilt, offset = c.pop("crop", None), c.pop("tilt", None), c.pop("offset", 0.0)
    (z, zx, zy, zxx, zyy), dx = make_surface(**c)
    periodic = crop is None
    if crop:
        sl = (slice(0, crop[0]), slice(0, crop[1]))
        z, zx, zy, zxx, zyy = (a[sl] for a in (z, zx, zy, zxx, zyy))
    heights = z.copy()
    if tilt:
        ny, nx = z.shape
        y, x = np.mgrid[0:ny, 0:nx]
        heights = heights + dx * (tilt[0] * x + tilt[1] * y)
    heights = heights + offset
    return heights, dx, periodic, theory(z, zx, zy, zxx, zyy)


@pytest.mark.parametrize("name", list(CASES))
def test_sigma_eta_beta_within_2_percent_of_theory_and_direct_count(name):
    heights, dx, periodic, spectral_theory = case(name)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", topo.TopographyWarning)
        rep = topo.analyse(heights, dx, "m", periodic=periodic)
    assert rep.detrend == ("mean" if periodic else "plane")
    assert rep.derivatives == ("fft" if periodic else "difference")
    direct = direct_count(_detrended(heights, periodic), dx, dx, periodic)
    for key in ("summit_density", "summit_radius", "sigma_summits"):
        assert getattr(rep.spectral, key) == pytest.approx(spectral_theory[key], rel=TOL), key
        assert getattr(rep.summits, key) == pytest.approx(direct[key], rel=TOL), key


@pytest.mark.parametrize("name", ["self-affine periodic",
                                  "self-affine cropped non-square tilted offset"])
def test_cli_json_equals_python(name, tmp_path):
    heights, dx, periodic, spectral_theory = case(name)
    np.save(tmp_path / "map.npy", heights)
    command = os.path.join(os.path.dirname(sys.executable), "egw-topo")
    args = [command, "--pixel-size", repr(dx), str(tmp_path / "map.npy"), "--unit", "m",
            "--json", "-"] + (["--periodic"] if periodic else [])
    run = subprocess.run(args, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    data = json.loads(run.stdout)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", topo.TopographyWarning)
        rep = topo.analyse(heights, dx, "m", periodic=periodic)
    for key in ("summit_density", "summit_radius", "sigma_summits", "y_s"):
        assert data["spectral"][key] == pytest.approx(
            getattr(rep.spectral, "mean_summit_height" if key == "y_s" else key), rel=1e-12)
    for key in ("summit_density", "summit_radius", "sigma_summits"):
        assert data["spectral"][key] == pytest.approx(spectral_theory[key], rel=TOL)
    text = subprocess.run([a for a in args if a not in ("--json", "-")],
                          capture_output=True, text=True).stdout
    assert "y_s" in text and "trust:" in text


def test_periodic_map_keeps_its_moments_plane_detrend_would_inflate_them():
    heights, dx, _, spectral_theory = case("self-affine periodic")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", topo.TopographyWarning)
        good = topo.analyse(heights, dx, "m", periodic=True)
    assert good.spectral.summit_density == pytest.approx(
        spectral_theory["summit_density"], rel=1e-9)


def test_disagreement_warns_which_to_trust():
    # broadband (alpha ~ 90) up to the Nyquist wavenumber: curvature wavelength ~5 pixels
    (z, *_), dx = make_surface(n=256, q_low=2, q_high=128, hurst=0.8)
    with pytest.warns(topo.TopographyWarning, match="trust the spectral estimate: sampling"):
        rep = topo.analyse(z, dx, "m", periodic=True)
    assert rep.trust == "spectral" and max(rep.disagreement.values()) > 0.10


def test_units_and_nan_refused_with_a_message(tmp_path):
    heights, dx, _, _ = case("gaussian periodic")
    with pytest.raises(ValueError, match="unit"):
        topo.analyse(heights, dx)                     # no unit
    with pytest.raises(ValueError, match="mixed units"):
        topo.height_map(heights, 1.0, "um", height_unit="nm")
    with pytest.raises(ValueError, match="unit = 'furlong'"):
        topo.height_map(heights, 1.0, "furlong")
    bad = heights.copy()
    bad[3, 4] = np.nan
    with pytest.raises(ValueError, match="1 NaN or infinite pixels"):
        topo.analyse(bad, dx, "m")
    np.save(tmp_path / "m.npy", heights)
    command = os.path.join(os.path.dirname(sys.executable), "egw-topo")
    run = subprocess.run([command, str(tmp_path / "m.npy"), "--pixel-size", "1"],
                         capture_output=True, text=True)
    assert run.returncode == 2 and "--unit" in run.stderr and "Traceback" not in run.stderr
    # a map in um gives the same statistics in metres after to_metres
    um = topo.height_map(heights * 1e6, dx * 1e6, "um").to_metres()
    assert um.heights == pytest.approx(heights, rel=1e-12) and um.unit == "m"


def test_surface_topography_objects():
    st = pytest.importorskip("SurfaceTopography")
    heights, dx, _, _ = case("self-affine periodic")
    ny, nx = heights.shape
    t = st.Topography(heights.T.copy(), (nx * dx, ny * dx), periodic=True, unit="m")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", topo.TopographyWarning)
        a = topo.analyse(t)
        b = topo.analyse(heights, dx, "m", periodic=True)
    assert a.periodic and a.unit == "m"
    assert a.spectral.summit_density == b.spectral.summit_density
    assert a.summits.n_summits == b.summits.n_summits
    with pytest.raises(ValueError, match="mixed units"):
        topo.height_map(t, unit="um")
    no_unit = st.Topography(heights.T.copy(), (nx * dx, ny * dx), periodic=True)
    with pytest.raises(ValueError, match="unit"):
        topo.analyse(no_unit)


def test_contact_from_topography_one_call():
    heights, dx, _, _ = case("gaussian periodic")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", topo.TopographyWarning)
        p, rep = egw.contact_from_topography(heights, None, radius=2.5e-3, E1=210e9,
                                             nu1=0.3, model="EP-GW", hardness=7e9,
                                             pixel_size=dx, unit="m")
        stats = topo.analyse(heights, dx, "m", periodic=False).recommended
    assert isinstance(p, egw.Params) and p.model == "EP-GW" and p.psi > 0
    assert p.modulus == pytest.approx(210e9 / (2 * (1 - 0.09)))
    assert p.mu == pytest.approx(egw.mu_from_summits(
        summit_density=rep.summit_density, summit_radius=rep.summit_radius, sigma=rep.sigma,
        radius=2.5e-3))
    assert rep.y_s > 0 and rep.sigma == p.sigma
    assert p.sigma == pytest.approx(stats.sigma_summits, rel=1e-12)
    # a flat needs no radius: flat_pressure does not depend on it
    flat, frep = egw.contact_from_topography(topo.Moments(4e-14, 2.5e-3, 2.5e9), radius=None,
                                             E1=210e9, nu1=0.3)
    other = flat.replace(radius=4.0, mu=flat.mu * 2.0)   # mu ~ sqrt(R)
    assert egw.flat_pressure(flat, 1e-7) == pytest.approx(egw.flat_pressure(other, 1e-7),
                                                          rel=1e-14)
    assert frep.radius is None and any("flat" in n for n in frep.notes)


def test_worked_example_of_doc_parameters_runs_through_contact_from_topography(repo):
    out = subprocess.run([sys.executable, os.path.join(repo, "tools", "worked_example.py")],
                         check=True, capture_output=True, text=True).stdout
    # doc/parameters.md section 4: mu = 4.87, psi = 1.99, 15.26 N at 5 sigma
    assert "mu = 4.866, psi = 1.994" in out and "1.5260e+01 N" in out
