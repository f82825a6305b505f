"""The package's mirrors of the C structs (egw._capi's ctypes structures and the numpy
dtypes of the array calls) against include/egw.h itself: every field at the offset C puts
it, every struct of the size C gives it (STYLE: C struct drift). The offsets come from a
small C program compiled against the header (skipped without a C compiler or the header,
as in an installed package without the repository)."""
import ctypes
import os
import shutil
import subprocess

import numpy as np
import pytest

from egw import _capi
from egw.params import PARAMS_DTYPE, RESULT_DTYPE

HEADER_DIR = os.path.join(os.path.dirname(__file__), "..", "..", "include")
MIRRORS = {"egw_params": _capi.Params, "egw_options": _capi.Options,
           "egw_result": _capi.Result, "egw_table_info": _capi.TableInfo,
           "egw_hysteresis_info": _capi.HysteresisInfo, "egw_scene": _capi.Scene,
           "egw_model_choice": _capi.ModelChoice}
DTYPES = {"egw_params": PARAMS_DTYPE, "egw_result": RESULT_DTYPE}


def c_layout(tmp_path):
    """{(struct, field or None): offset or size} as the C compiler lays the header out."""
    cc = shutil.which("cc") or shutil.which("gcc")
    if cc is None or not os.path.exists(os.path.join(HEADER_DIR, "egw.h")):
        pytest.skip("no C compiler or no include/egw.h")
    lines = ['#include "egw.h"', "#include <stdio.h>", "#include <stddef.h>", "int main(void) {"]
    for struct, mirror in MIRRORS.items():
        lines.append(f'printf("{struct} - %zu\\n", sizeof({struct}));')
        for field, _ in mirror._fields_:
            lines.append(f'printf("{struct} {field} %zu\\n", offsetof({struct}, {field}));')
    lines.append("return 0; }")
    src = tmp_path / "layout.c"
    src.write_text("\n".join(lines))
    exe = tmp_path / "layout"
    subprocess.run([cc, "-I", HEADER_DIR, str(src), "-o", str(exe)], check=True)
    out = subprocess.run([str(exe)], check=True, capture_output=True, text=True).stdout
    layout = {}
    for line in out.splitlines():
        struct, field, value = line.split()
        layout[(struct, None if field == "-" else field)] = int(value)
    return layout


def test_ctypes_and_numpy_mirrors_match_the_header(tmp_path):
    layout = c_layout(tmp_path)
    wrong = []
    for struct, mirror in MIRRORS.items():
        if ctypes.sizeof(mirror) != layout[(struct, None)]:
            wrong.append(f"{struct}: size {ctypes.sizeof(mirror)} vs C {layout[(struct, None)]}")
        for field, _ in mirror._fields_:
            if getattr(mirror, field).offset != layout[(struct, field)]:
                wrong.append(f"{struct}.{field}: offset {getattr(mirror, field).offset} vs C "
                             f"{layout[(struct, field)]}")
    for struct, dtype in DTYPES.items():
        if dtype.itemsize != layout[(struct, None)]:
            wrong.append(f"{struct} dtype: itemsize {dtype.itemsize}")
        for field in dtype.names:
            if dtype.fields[field][1] != layout[(struct, field)]:
                wrong.append(f"{struct} dtype .{field}: offset {dtype.fields[field][1]}")
    assert not wrong, "; ".join(wrong)
