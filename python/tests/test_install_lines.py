"""The install lines of the docs run as written: egw is not on PyPI, so every `pip install`
that names egw installs it from the repository's python/ folder (a path from the repository
root) with extras the package declares; every other name is a PyPI package, never egw."""
import glob
import os
import re
import shlex

import pytest

REPO = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
DOCS = ["README.md", "python/README.md", "example/README.md"] + sorted(
    os.path.relpath(p, REPO) for p in glob.glob(os.path.join(REPO, "doc", "*.md")))


def declared_extras():
    tomllib = pytest.importorskip("tomllib")   # Python >= 3.11
    with open(os.path.join(REPO, "python", "pyproject.toml"), "rb") as f:
        return set(tomllib.load(f)["project"]["optional-dependencies"])


def commands(text):
    """The shell commands of a Markdown text: the lines of its code blocks and its inline
    code spans (a span may break across lines)."""
    for k, part in enumerate(text.split("```")):
        if k % 2:
            yield from part.replace("\\\n", " ").splitlines()
        else:
            yield from (" ".join(span.split()) for span in re.findall(r"`([^`]+)`", part))


def pip_requirements(text):
    """(command, requirement) of every `pip install` in the text's commands."""
    for cmd in commands(text):
        for m in re.finditer(r"pip install\s([^#&;]*)", cmd):
            for w in shlex.split(m.group(1)):
                if not w.startswith("-"):
                    yield m.group(0).strip(), w


def test_every_documented_pip_install_line_names_an_installable_egw():
    extras = declared_extras()
    seen_egw = 0
    for doc in DOCS:
        path = os.path.join(REPO, doc)
        if not os.path.exists(path):
            continue
        with open(path, encoding="utf-8") as f:
            text = f.read()
        for line, req in pip_requirements(text):
            name = re.match(r"^([^\[]+)(?:\[([^\]]*)\])?$", req)
            assert name, f"{doc}: cannot read requirement {req!r} in {line!r}"
            target, extra = name.group(1), name.group(2)
            assert target.lower() != "egw", (
                f"{doc}: {line!r}: egw is not on PyPI; install the path ./python")
            if target.startswith((".", "/")):
                # a path from the repository root (where the docs say to run it)
                assert os.path.isfile(os.path.join(REPO, target, "pyproject.toml")), (
                    f"{doc}: {line!r}: {target} holds no pyproject.toml")
                seen_egw += 1
                for e in filter(None, (extra or "").split(",")):
                    assert e.strip() in extras, f"{doc}: {line!r}: no extra {e!r}"
    assert seen_egw >= 3    # README, python/README, doc/parameters.md


def test_every_documented_shared_pkg_config_link_line_finds_libegw_at_run_time():
    # a program linked with `pkg-config --libs egw` (the shared library) builds but stops
    # at start (libegw.so.0.3 not found) unless the line records the rpath or the loader is
    # told (LD_LIBRARY_PATH); egw-static needs neither
    checked = 0
    for doc in DOCS:
        path = os.path.join(REPO, doc)
        if not os.path.exists(path):
            continue
        with open(path, encoding="utf-8") as f:
            text = f.read()
        for cmd in commands(text):
            links = re.match(r"\s*(cc|c\+\+|gcc|g\+\+|gfortran)\s", cmd)
            if links and re.search(r"pkg-config[^)]*--libs egw\)", cmd):
                checked += 1
                assert "-Wl,-rpath" in cmd or "LD_LIBRARY_PATH" in cmd, f"{doc}: {cmd!r}"
    assert checked >= 4    # README: C and Fortran; example/README: C and Fortran
