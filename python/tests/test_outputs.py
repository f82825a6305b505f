"""egw's CSV outputs read with numpy and pandas as they are: the column header is the first
line and the metadata are '#' lines, so pandas.read_csv(path, comment="#"),
numpy.loadtxt(path, delimiter=",", skiprows=1) and numpy.genfromtxt(path, delimiter=",",
names=True) need nothing else."""
import glob
import os
import subprocess

import numpy as np
import pytest

import egw

P = egw.Params(model="E-GW", radius=5e-4, modulus=3.678e10, sigma=1e-6, mu=4.0)


def read_all_ways(path, first_column):
    a = np.loadtxt(path, delimiter=",", skiprows=1)
    g = np.genfromtxt(path, delimiter=",", names=True)
    assert g.dtype.names[0] == first_column
    np.testing.assert_array_equal(g[first_column], a[:, 0])
    try:
        import pandas as pd
    except ImportError:
        return a
    df = pd.read_csv(path, comment="#")
    assert list(df.columns)[0] == first_column
    np.testing.assert_array_equal(df.to_numpy(), a)
    return a


def test_table_csv_reads_with_numpy_and_pandas(tmp_path):
    t = egw.Table.build(P, -2e-6, 2e-5, rel_tol=1e-4)
    path = tmp_path / "t.csv"
    t.write(path, "csv")
    rows = read_all_ways(path, "delta")
    assert rows.shape == (t.info.n_nodes, 5)
    # the nodes are the table: evaluating there returns the written force (17 digits),
    # except in the separated tail (delta < 0), whose resampled pieces (doc/formats.md,
    # after rule 4) stay within 5e-2 rel_tol of the interpolant through the nodes
    tail = rows[:, 0] < 0
    np.testing.assert_allclose(t.eval(rows[~tail, 0])[0], rows[~tail, 1], rtol=1e-13)
    np.testing.assert_allclose(t.eval(rows[tail, 0])[0], rows[tail, 1], rtol=5e-2 * 1e-4)


def test_table_csv_format_1_still_reads(tmp_path):
    # format 1 (egw 0.1.0): metadata first, then the column header
    t = egw.Table.build(P, -2e-6, 2e-5, rel_tol=1e-4)
    new = tmp_path / "new.csv"
    t.write(new, "csv")
    # (format 1 had no checksum line, which format 3 files end with)
    lines = [line for line in new.read_text().splitlines(keepends=True)
             if not line.startswith("# fnv1a32")]
    header, rest = lines[0], lines[1:]
    n_meta = next(i for i, line in enumerate(rest) if not line.startswith("#"))
    old_text = "".join(rest[:n_meta] + [header] + rest[n_meta:]).replace("format 3", "format 1")
    old = tmp_path / "old.csv"
    old.write_text(old_text)
    d = np.linspace(-2e-6, 2e-5, 41)
    np.testing.assert_array_equal(egw.Table.read(old).eval(d)[0], t.eval(d)[0])


def test_egw_table_curves_read_with_numpy_and_pandas(repo, tmp_path):
    exes = sorted(glob.glob(os.path.join(repo, "build", "*", "app", "egw-table")),
                  key=os.path.getmtime)
    if not exes:
        pytest.skip("egw-table not built (make test builds it)")
    run = subprocess.run([exes[-1], "--quiet", "--formats", "csv", "--out", str(tmp_path)],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    read_all_ways(tmp_path / "scene_table.csv", "delta")
    hertz = read_all_ways(tmp_path / "hertz_force.csv", "delta")
    assert hertz.shape[1] == 4 and np.all(np.diff(hertz[:, 1]) >= 0)
    flat = read_all_ways(tmp_path / "rough_flat_pressure.csv", "separation")
    assert flat.shape[1] == 3 and np.all(flat[:, 1] > 0)
