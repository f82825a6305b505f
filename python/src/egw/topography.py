"""From a measured height map to Greenwood-Williamson parameters.

Reads a height map (plain-text matrix, CSV, numpy .npy), removes its mean plane, and
computes the GW statistics two ways:

* spectral (Nayak 1971; McCool 1986): the profile moments m0 = <z^2>, m2 = <z'^2>,
  m4 = <z''^2> (averaged over the x and y directions), the bandwidth parameter
  alpha = m0 m4/m2^2, and from them the summit density eta = m4/(6 pi sqrt(3) m2), the mean
  summit radius beta = (3/8) sqrt(pi/m4), the std of summit heights
  sigma_s = sqrt((1 - 0.8968/alpha) m0) and the offset of the mean summit height above the
  mean plane y_s = 4 sqrt(m0/(pi alpha));
* by summit identification: pixels higher than their 8 neighbours; eta = count/area,
  sigma_s = their height std, beta = 1/mean(kappa) with kappa = -(z_xx + z_yy)/2 the mean
  curvature at the summit (central differences).

Derivatives: 'fft' (spectral, exact for a periodic band-limited map such as a synthetic
surface) or 'difference' (central differences, for measured, non-periodic maps).
The contact parameters (mu for a sphere radius R, psi for E*, H) are computed by the C
library (egw_mu_from_summits, egw_psi_from_hardness); GW's assumptions are flagged when
alpha is small or few summits were found.

Both estimates see the surface only down to the pixel. On a map rough down to the pixel
(no short-wavelength cut-off in the data) m2 and m4 grow as the pixel shrinks, and eta,
beta (so mu, psi) are those of the sampling: analyse() coarse-grains the map by 2 and
warns when the spectral eta or beta changes by more than RESOLUTION_TOL. Then cut the map
off at a physical short-wavelength limit (coarse_grain, a low-pass filter) until they stop
changing, or use a contact law that needs no summit statistics (Persson's theory, a
boundary-element rough-flat law).

This module gathers the public names; the code lives by subject in egw.topo_maps (height
maps, units, detrending, the defaults), egw.topo_spectra (the moments), egw.topo_summits
(McCool's and the identified summit statistics), egw.topo_analysis (analyse),
egw.topo_contact (psi, contact_from_topography) and egw.topo_cli (egw-topo).
"""
from __future__ import annotations

import sys

from .topo_maps import (  # noqa: F401
    LENGTH_UNITS, HeightMap, read_height_map, detrend, sum_surface, DEFAULTS,
    default_detrend, default_derivatives, height_map, coarse_grain, MAP_SCALE)
from .topo_spectra import Moments, spectral_moments  # noqa: F401
from .topo_summits import (  # noqa: F401
    ALPHA_WARN, SUMMITS_WARN, TopographyWarning, SummitStatistics, mccool, identify_summits,
    summit_statistics)
from .topo_analysis import (  # noqa: F401
    AGREEMENT_TOL, PIXELS_PER_WAVELENGTH_MIN, SUMMITS_STATISTICS_MIN, RESOLUTION_TOL,
    TopographyReport, resolution_dependence, analyse)
from .topo_contact import (  # noqa: F401
    psi_from_hardness, SUMMIT_PLANE_MODELS, reference_plane_offset, ContactReport,
    contact_from_topography)
from .topo_cli import main  # noqa: F401

if __name__ == "__main__":
    sys.exit(main())
