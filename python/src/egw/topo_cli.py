"""egw-topo, the command line of egw.topography: a height map's GW parameters, a rough-flat
law or a model choice, printed or as JSON."""
from __future__ import annotations

import argparse
import json
import os
import sys
import warnings
from typing import List, Optional, Sequence, Tuple

from .errors import EgwError, version
from .params import Params
from .functions import mu_from_summits
from .topo_maps import HeightMap, _unit_factor, height_map, sum_surface
from .topo_summits import SummitStatistics
from .topo_analysis import analyse
from .topo_contact import psi_from_hardness


def _write_flat_law(surface: HeightMap, args) -> List[str]:
    """egw-topo --model: the surface's law (and the sphere's table) written, as lines."""
    from .flat_law import FlatLaw
    from .tables import Table
    if args.modulus is None:
        raise ValueError("--model needs --modulus (E* in Pa)")
    if args.model == "BEM" and not surface.periodic:
        raise ValueError("--model BEM needs a periodic map (the periodic BEM would wrap "
                         "its edges onto each other): add --periodic if the map is one "
                         "period of a periodic surface, or use --model Persson")
    law = FlatLaw.from_topography(surface, args.modulus, args.model)
    law.write(args.law)
    lines = [f"{args.model} rough-flat law: length {law.length:.6g} m, u in "
             f"[{law.separation_range[0]:.6g}, {law.separation_range[1]:.6g}] m: "
             f"wrote {args.law}"]
    if args.radius is not None:
        r = args.radius * _unit_factor(surface.unit)
        t = Table.build(Params(radius=r, modulus=args.modulus, flat_law=law),
                        -3 * law.length, 10 * law.length, 1e-4)
        t.write(args.table, "csv")
        lines.append(f"sphere R = {r:.6g} m on the law: 1-D table, overlaps from the mean "
                     f"plane [-3, 10] x {law.length:.6g} m: wrote {args.table}")
    return lines


def _choose_lines(surface: HeightMap, args) -> List[str]:
    """egw-topo --choose: every model against the surface's BEM law, as lines."""
    from .surface_choice import choose_for_surface
    if args.radius is None or args.modulus is None:
        raise ValueError("--choose needs --radius and --modulus (E* in Pa)")
    if not surface.periodic:
        raise ValueError("--choose judges the models against the surface's BEM law, which "
                         "needs a periodic map: add --periodic if the map is one period of "
                         "a periodic surface (a non-periodic map has no BEM law; --model "
                         "Persson writes its Persson law)")
    try:
        lo, hi = (float(v) for v in args.overlaps.split(","))
    except ValueError:
        raise ValueError(f"--overlaps {args.overlaps!r}: MIN,MAX (numbers)") from None
    r = args.radius * _unit_factor(surface.unit)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")   # the summit advice is printed above already
        c = choose_for_surface(surface, radius=r, modulus=args.modulus, tol=args.choose,
                               delta_min_sigma=lo, delta_max_sigma=hi)
    lines = [f"model choice against the surface's BEM law (R = {r:.6g} m, E* = "
             f"{args.modulus:g} Pa, delta_m in [{lo:g}, {hi:g}] rms heights, error "
             f"{'relative to the largest force' if c.relative_to_max else 'pointwise'}):"]
    for m in c.candidates[:-1]:
        lines.append(f"  {m.model:8s} error {m.error:.3g}  (y_s {m.y_s:.4g} m, set-up "
                     f"{m.seconds:.3g} s)")
    lines.append(f"  choice: {c.reason}")
    return lines


def _report(stats: SummitStatistics, radius, modulus, hardness, k, unit) -> List[str]:
    u = f" {unit}" if unit else ""
    lines = [f"{stats.method}:",
             f"  summit density eta     {stats.summit_density:.6g} per{u}^2",
             f"  summit radius beta     {stats.summit_radius:.6g}{u}",
             f"  summit height std      {stats.sigma_summits:.6g}{u}",
             f"  surface rms height     {stats.sigma_surface:.6g}{u}",
             f"  y_s (mean summit plane above the mean plane)  "
             f"{stats.mean_summit_height:.6g}{u}"]
    if stats.n_summits is not None:
        lines.append(f"  summits found          {stats.n_summits}")
    if stats.alpha is not None:
        lines.append(f"  bandwidth alpha        {stats.alpha:.6g}")
    if radius is not None:
        mu = mu_from_summits(summit_density=stats.summit_density,
                             summit_radius=stats.summit_radius, sigma=stats.sigma_summits,
                             radius=radius)
        lines.append(f"  mu (R = {radius:g})        {mu:.6g}")
    if modulus is not None and hardness is not None:
        psi = psi_from_hardness(modulus=modulus, hardness=hardness, sigma=stats.sigma_summits,
                                summit_radius=stats.summit_radius, hardness_coeff=k)
        lines.append(f"  psi (E* = {modulus:g}, H = {hardness:g}, K = {k:g})  {psi:.6g}")
    return lines


def _pixel_size(text: str) -> Tuple[float, float]:
    parts = text.replace(",", " ").split()
    try:
        values = [float(p) for p in parts]
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r}: dx or dx,dy (numbers)") from None
    if len(values) not in (1, 2):
        raise argparse.ArgumentTypeError(f"{text!r}: dx or dx,dy")
    return (values[0], values[-1])


def main(argv: Optional[Sequence[str]] = None) -> int:
    """egw-topo: GW parameters of one height map, or of the sum surface of two.

    Parameters
    ----------
    argv : sequence of str, optional
        The command line without the program name (default: sys.argv[1:]).

    Returns
    -------
    int
        The exit status: 0, or 2 after a message on stderr (bad map, unit, file).

    Raises
    ------
    SystemExit
        From argparse, for bad options or --help.
    """
    ap = argparse.ArgumentParser(
        prog="egw-topo", description="Greenwood-Williamson parameters (sigma, eta, beta, "
        "y_s) of a measured height map, by summit identification and by spectral moments, "
        "with which to trust. Options may come in any order.")
    from . import __version__   # egw's __init__ imports this module: read it here
    ap.add_argument("--version", action="version",
                    version=f"egw-topo {__version__} (libegw {version()})")
    ap.add_argument("maps", nargs="+", help="height map(s): .npy, .csv or a text matrix "
                    "(with --pixel-size and --unit), or an instrument file SurfaceTopography "
                    "reads (x3p, datx, opd, gwy, ...); two maps: their sum surface")
    ap.add_argument("--pixel-size", type=_pixel_size, metavar="D",
                    help="pixel size dx or dx,dy in the unit of the heights")
    ap.add_argument("--unit", help="length unit of the heights and pixel size (m, mm, um, "
                    "nm, ...); required for plain maps")
    ap.add_argument("--radius", type=float, help="equivalent sphere radius R (in --unit): "
                    "print mu")
    ap.add_argument("--modulus", type=float, help="effective modulus E*: with --hardness, psi")
    ap.add_argument("--hardness", type=float, help="hardness H (units of --modulus)")
    ap.add_argument("--K", type=float, default=0.6, help="ZMC hardness coefficient (0.6)")
    ap.add_argument("--derivatives", choices=["difference", "fft"], default=None,
                    help="derivatives for the moments (default: fft for periodic maps, "
                    "central differences otherwise)")
    ap.add_argument("--detrend", choices=["mean", "plane"], default=None,
                    help="default: mean for periodic maps, plane otherwise")
    ap.add_argument("--periodic", action="store_true", default=None,
                    help="the map is periodic")
    ap.add_argument("--json", metavar="PATH", help="also write the report as JSON to PATH "
                    "('-': standard output, instead of the text)")
    ap.add_argument("--model", choices=["BEM", "Persson"], default=None,
                    help="also compute the surface's rough-flat law (needs --modulus in Pa; "
                    "BEM needs a periodic map) and write it to --law; with --radius also "
                    "the sphere's force table to --table (lengths in m, forces in N)")
    ap.add_argument("--law", metavar="PATH", default="flat_law.csv",
                    help="where --model writes the law (default flat_law.csv)")
    ap.add_argument("--table", metavar="PATH", default="flat_law_table.csv",
                    help="where --model with --radius writes the sphere's 1-D table "
                    "(egw CSV, overlaps -3 to 10 law lengths, tol 1e-4; default "
                    "flat_law_table.csv)")
    ap.add_argument("--choose", metavar="TOL", type=float, default=None,
                    help="also choose the cheapest model (Hertz, GW, E-GW, Persson, the BEM "
                    "law) whose sphere force stays within TOL of the sphere with the "
                    "surface's BEM law (needs --radius, --modulus in Pa, a periodic map)")
    ap.add_argument("--overlaps", metavar="MIN,MAX", default="0.5,10",
                    help="--choose's overlap range with the mean plane, in rms heights "
                    "(default 0.5,10)")
    args = ap.parse_args(argv)
    try:
        if len(args.maps) > 2:
            raise ValueError("give one height map, or two for their sum surface")
        maps = [height_map(m, args.pixel_size, args.unit, periodic=args.periodic)
                for m in args.maps]
        surface = maps[0] if len(maps) == 1 else sum_surface(*maps)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            rep = analyse(surface, detrend_mode=args.detrend, derivatives=args.derivatives)
        lines = [f"egw-topo: {' + '.join(args.maps)}, {rep.shape[1]} x {rep.shape[0]} "
                 f"pixels, unit {rep.unit}, {'periodic' if rep.periodic else 'not periodic'}"
                 f" (detrend {rep.detrend}, derivatives {rep.derivatives})"]
        for stats in (rep.summits, rep.spectral):
            lines += _report(stats, args.radius, args.modulus, args.hardness, args.K,
                             rep.unit)
        lines.append(f"trust: {rep.trust} ({rep.reason})")
        lines += [f"WARNING: {w.message}" for w in caught]
        if args.model is not None:
            lines += _write_flat_law(surface, args)
        if args.choose is not None:
            lines += _choose_lines(surface, args)
        data = rep.to_dict()
        if args.json == "-":
            print(json.dumps(data, indent=2))
        else:
            print("\n".join(lines))
            if args.json:
                tmp = args.json + ".tmp"
                with open(tmp, "w") as f:
                    json.dump(data, f, indent=2)
                os.replace(tmp, args.json)
    except (ValueError, OSError, ImportError, EgwError, MemoryError) as exc:
        # egw's own errors too (NotConvergedError is no ValueError): one line, never a traceback
        print(f"egw-topo: {exc}", file=sys.stderr)
        return 2
    return 0
