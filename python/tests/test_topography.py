"""Height map -> GW parameters on synthetic Gaussian surfaces whose spectrum is prescribed
exactly: the surface is white noise whose Fourier amplitudes are replaced by a chosen
isotropic band-limited spectrum A(q) (phases kept, so the map is real and |FFT| = A
exactly). Its profile moments are then known in closed form as sums over the spectrum:
m0 = sum A^2 / N^2, m2x = sum qx^2 A^2 / N^2, m4x = sum qx^4 A^2 / N^2 (N = pixels)."""
import math
import os
import subprocess
import sys
import warnings

import numpy as np
import pytest

import egw
from egw import topography as topo


def synthetic(n=256, dx=1e-6, q_low=4, q_high=None, hurst=0.8, seed=1):
    """Self-affine isotropic spectrum C(q) ~ q^(-2(1+H)) between wavenumber indices q_low
    and q_high (in units of 2 pi/(n dx)); returns (HeightMap, exact |FFT| array)."""
    rng = np.random.default_rng(seed)
    q_high = q_high or n // 8
    kx = np.fft.fftfreq(n, 1.0 / n)
    k = np.hypot(kx[None, :], kx[:, None])
    amp = np.where((k >= q_low) & (k <= q_high), np.maximum(k, 1) ** (-(1 + hurst)), 0.0)
    noise = np.fft.fft2(rng.standard_normal((n, n)))
    spectrum = amp * noise / np.abs(noise)
    z = np.fft.ifft2(spectrum).real
    scale = 1e-6 / z.std()  # rms height 1 um
    return topo.HeightMap(z * scale, dx, dx), amp * scale


def exact_moments(amp, dx):
    n = amp.shape[0]
    q = 2 * np.pi * np.fft.fftfreq(n, dx)
    power = amp ** 2 / (n * n) ** 2
    m0 = power.sum()
    m2 = 0.5 * ((q[None, :] ** 2 * power).sum() + (q[:, None] ** 2 * power).sum())
    m4 = 0.5 * ((q[None, :] ** 4 * power).sum() + (q[:, None] ** 4 * power).sum())
    return m0, m2, m4


def test_fft_moments_equal_the_prescribed_spectrum():
    surface, amp = synthetic()
    m = topo.spectral_moments(surface, "fft")
    m0, m2, m4 = exact_moments(amp, surface.dx)
    # same sums in another order: rounding only (1e-12 relative)
    assert m.m0 == pytest.approx(m0, rel=1e-12)
    assert m.m2 == pytest.approx(m2, rel=1e-12)
    assert m.m4 == pytest.approx(m4, rel=1e-12)


def test_difference_moments_converge_to_the_spectrum():
    # central differences have transfer sin(q dx)/(q dx): with the shortest wavelength
    # 32 pixels (q dx <= 0.2) m2 and m4 are low by <= (q dx)^2/3 ~ 1.3 %; the border rows
    # left out add ~1 % of sampling noise: 3 % tolerance
    surface, amp = synthetic(q_high=256 // 32)
    m = topo.spectral_moments(surface, "difference")
    m0, m2, m4 = exact_moments(amp, surface.dx)
    assert m.m2 == pytest.approx(m2, rel=0.03)
    assert m.m4 == pytest.approx(m4, rel=0.03)


def test_mccool_formulas():
    m = topo.Moments(2.0e-12, 3.0e-2, 5.0e9)
    s = topo.mccool(m)
    alpha = 2.0e-12 * 5.0e9 / 3.0e-2 ** 2
    assert s.alpha == pytest.approx(alpha, rel=1e-15)
    assert s.summit_density == pytest.approx(5.0e9 / (6 * math.pi * math.sqrt(3) * 3.0e-2))
    assert s.summit_radius == pytest.approx(0.375 * math.sqrt(math.pi / 5.0e9))
    assert s.sigma_summits == pytest.approx(math.sqrt((1 - 0.8968 / alpha) * 2.0e-12))
    assert not s.warnings  # alpha = 11.1 > 8.97
    low = topo.mccool(topo.Moments(1.0, 1.0, 2.0))
    assert any("alpha" in w for w in low.warnings)


def test_summit_identification_agrees_with_nayak():
    # finely sampled (16 px per shortest wavelength): discrete 8-neighbour summits
    # approach the continuous surface's (Greenwood 1984). ~1600 summits: the statistical
    # error of a summit mean is 1/sqrt(N) ~ 2.5 %; tolerance 6 % (~2.5 standard errors)
    surface, _ = synthetic(n=1024, q_low=16, q_high=64, hurst=0.5, seed=3)
    spec = topo.mccool(topo.spectral_moments(surface, "fft"))
    found = topo.summit_statistics(surface, periodic=True)
    assert found.n_summits > 1000
    assert found.summit_density == pytest.approx(spec.summit_density, rel=0.06)
    assert found.summit_radius == pytest.approx(spec.summit_radius, rel=0.06)
    assert found.sigma_summits == pytest.approx(spec.sigma_summits, rel=0.06)
    assert found.mean_summit_height == pytest.approx(spec.mean_summit_height, rel=0.06)


def test_sum_surface_moments_add():
    a, _ = synthetic(seed=5)
    b, _ = synthetic(seed=6, hurst=0.3)
    ma, mb = topo.spectral_moments(a, "fft"), topo.spectral_moments(b, "fft")
    ms = topo.spectral_moments(topo.sum_surface(a, b), "fft")
    # independent random phases: cross terms ~ 1/sqrt(number of modes) ~ 3 %
    assert ms.m0 == pytest.approx((ma + mb).m0, rel=0.1)
    assert ms.m4 == pytest.approx((ma + mb).m4, rel=0.1)


def test_read_formats_and_detrend(tmp_path):
    surface, _ = synthetic(n=64)
    tilted = surface.heights + 1e-3 * np.arange(64)[None, :] + 5.0
    np.save(tmp_path / "z.npy", tilted)
    np.savetxt(tmp_path / "z.csv", tilted, delimiter=",")
    np.savetxt(tmp_path / "z.txt", tilted, header="heights in m")
    for name in ("z.npy", "z.csv", "z.txt"):
        hm = topo.detrend(topo.read_height_map(str(tmp_path / name), 1e-6))
        # the plane fit removes the tilt exactly up to the surface's own plane component
        assert abs(hm.heights.mean()) < 1e-15 and hm.heights.std() < 2e-6
    (tmp_path / "bad.txt").write_text("1 2\n3 nan\n")
    with pytest.raises(ValueError, match="at least 3 x 3|non-finite"):
        topo.read_height_map(str(tmp_path / "bad.txt"))


def test_egw_topo_command(tmp_path):
    surface, _ = synthetic(n=128)
    np.save(tmp_path / "s.npy", surface.heights)
    command = os.path.join(os.path.dirname(sys.executable), "egw-topo")  # the entry point
    run = subprocess.run([command, str(tmp_path / "s.npy"),
                          "--pixel-size", "1e-6", "--unit", "m", "--radius", "5e-4",
                          "--modulus", "1e11",
                          "--hardness", "2e9"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert "summit density" in run.stdout and "mu (R = 0.0005)" in run.stdout
    assert "psi" in run.stdout
    bad = subprocess.run([command, str(tmp_path / "none.npy"),
                          "--pixel-size", "1"], capture_output=True, text=True)
    assert bad.returncode == 2 and bad.stderr.startswith("egw-topo: ")
    assert "Traceback" not in bad.stderr


@pytest.mark.parametrize("pixel", [1e-300, 1e300, 1e-101, 1e101])
def test_pixel_size_beyond_the_doubles_named(tmp_path, pixel):
    # pixel sizes whose moments leave the doubles: a ValueError naming pixel_size, from
    # an array, a file and the command line (1e-300 raised ZeroDivisionError, 1e300
    # OverflowError, both as tracebacks of egw-topo)
    surface, _ = synthetic(n=32)
    with pytest.raises(ValueError, match="pixel_size"):
        topo.analyse(surface.heights, pixel_size=pixel, unit="m")
    np.save(tmp_path / "s.npy", surface.heights)
    with pytest.raises(ValueError, match="pixel_size"):
        topo.read_height_map(str(tmp_path / "s.npy"), pixel, "m")
    command = os.path.join(os.path.dirname(sys.executable), "egw-topo")
    run = subprocess.run([command, str(tmp_path / "s.npy"), "--pixel-size", repr(pixel),
                          "--unit", "m"], capture_output=True, text=True)
    assert run.returncode == 2 and run.stderr.startswith("egw-topo: pixel_size")
    assert "Traceback" not in run.stderr


def test_curvature_scale_beyond_the_doubles_named():
    # heights of 1 on pixels of 1e-60: z/dx**2 = 1e120, m4 ~ 1e240 * ... overflows
    surface, _ = synthetic(n=32)
    z = surface.heights / np.abs(surface.heights).max()
    with pytest.raises(ValueError, match="curvature scale"):
        topo.analyse(z, pixel_size=1e-60, unit="m")
    with pytest.raises(ValueError, match="heights up to"):
        topo.analyse(z * 1e200, pixel_size=1.0, unit="m")


def test_coarse_grain_is_the_block_mean():
    z = np.arange(36.0).reshape(6, 6)
    c = topo.coarse_grain(topo.HeightMap(z, 1.0, 2.0, "um", periodic=True), 2)
    # block (0, 0) holds 0, 1, 6, 7: mean 3.5; pixel sizes doubled
    assert c.heights.shape == (3, 3) and c.heights[0, 0] == 3.5 and (c.dx, c.dy) == (2, 4)
    assert c.periodic and c.unit == "um"
    with pytest.raises(ValueError, match="factor"):
        topo.coarse_grain(c, 2)


@pytest.mark.filterwarnings("ignore:summit identification and spectral")
@pytest.mark.parametrize("periodic", [True, False])
def test_roughness_down_to_the_pixel_is_flagged_resolution_dependent(periodic):
    # spectrum up to the Nyquist wavenumber (index n/2): m4 ~ q_max^(4 - 2H) with H = 0.8,
    # so doubling the pixel lowers m4 by ~2^2.4: beta rises ~130 %, eta falls ~70 %
    # (measured +130..+140 %, -70 %); a map whose shortest wavelength spans 16 pixels
    # changes by <= 3 % (measured). RESOLUTION_TOL = 25 % lies between with margin.
    rough, _ = synthetic(n=256, q_high=128)
    rough = topo.HeightMap(rough.heights, rough.dx, rough.dy, "m", periodic)
    with pytest.warns(topo.TopographyWarning, match="resolution: doubling the pixel") as rec:
        rep = topo.analyse(rough)
    assert rep.resolution["summit_radius"] > 1.0 and rep.resolution["summit_density"] < -0.5
    text = " ".join(str(w.message) for w in rec)
    assert "short-wavelength limit" in text and "Persson" in text
    smooth, _ = synthetic(n=256, q_high=16)
    smooth = topo.HeightMap(smooth.heights, smooth.dx, smooth.dy, "m", periodic)
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        rep = topo.analyse(smooth)
    assert max(abs(v) for v in rep.resolution.values()) < 0.05
    assert not any("resolution" in str(w.message) for w in rec)
    assert "resolution" in rep.to_dict()


def test_topography_keeps_every_public_name_of_its_modules():
    # egw.topography re-exports the public names its split modules define (audit10's
    # MAP_SCALE, merged into topo_maps by hand, was left out)
    import egw.topography as topography
    from egw import topo_analysis, topo_contact, topo_maps, topo_spectra, topo_summits
    for module in (topo_maps, topo_spectra, topo_summits, topo_analysis, topo_contact):
        for name, value in vars(module).items():
            if name.startswith("_") or getattr(value, "__module__", module.__name__) \
                    != module.__name__:
                continue
            if isinstance(value, type(topography)):
                continue
            assert getattr(topography, name, None) is value, f"{module.__name__}.{name}"


def test_egw_topo_command_line_advice_and_version(tmp_path):
    # audit23: --choose (and --model BEM) on a non-periodic map answered with the Python
    # keyword "periodic=True" and method='Persson'; egw-topo had no --version
    surface, _ = synthetic(n=32)
    np.save(tmp_path / "s.npy", surface.heights)
    command = os.path.join(os.path.dirname(sys.executable), "egw-topo")
    base = [command, str(tmp_path / "s.npy"), "--pixel-size", "1e-6", "--unit", "m"]
    for extra in (["--choose", "1e-2", "--radius", "1e-3", "--modulus", "1e9"],
                  ["--model", "BEM", "--modulus", "1e9"]):
        run = subprocess.run(base + extra, capture_output=True, text=True)
        assert run.returncode == 2 and run.stderr.startswith("egw-topo: "), run.stderr
        assert "--periodic" in run.stderr and "--model Persson" in run.stderr
        assert "periodic=True" not in run.stderr and "method=" not in run.stderr
        assert "Traceback" not in run.stderr
    run = subprocess.run([command, "--version"], capture_output=True, text=True)
    assert run.returncode == 0
    assert run.stdout.strip() == f"egw-topo {egw.__version__} (libegw {egw.version()})"
