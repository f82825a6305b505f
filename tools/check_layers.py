#!/usr/bin/env python3
"""Check that egw's `use` arrows point one way between the layers of src/egw/.

Each folder of src/egw/ is a layer (doc/architecture.md); a module may `use` modules of
its own layer and of the layers listed for it below, nothing else. src/*.f90 is the
facade (`use egw`, `use egw_all`); app/ and bench/ are programs and reach the library
only through the facade. The check reads every `use` statement (and every submodule's
parent) of those files, and fails on:
  - an arrow to a layer not allowed (e.g. kernels/ using solver/, or anything using capi/),
  - a source file outside the known folders, or a module defined twice,
  - a program using a library module other than the facade,
  - a layer folder without its README.md,
  - a module named as a C binding label (`bind(C, name="...")`): both are global
    identifiers, and gfortran 12 then resolved a call inside that C routine to the routine
    itself (egw_hysteresis_energy recursed until the stack overflowed) without a word.
Prints one line per failure and ends "N passed, N failed" (one check per file, and one
per layer README). `--self-test` first runs the check on small made-up trees, one clean
and one with each kind of fault, and fails if any fault goes unseen.

Usage: python3 tools/check_layers.py [--self-test] [ROOT]   (ROOT: the repository)
"""
import os
import re
import sys
import tempfile

# layer -> the layers it may use besides itself (lowest first). Keep in step with
# doc/architecture.md and the READMEs of src/egw/*/.
LAYERS = {
    "core": [],
    "kernels": ["core"],
    "laws": ["core", "kernels"],
    "solver": ["core", "kernels", "laws"],
    "tables": ["core", "kernels", "laws", "solver"],
    "formats": ["core", "kernels", "laws", "solver", "tables"],
    "scene": ["core", "kernels", "laws", "solver", "tables"],
    "capi": ["core", "kernels", "laws", "solver", "tables", "formats", "scene"],
}
FACADE = "facade"  # src/*.f90: may use every layer but the C layer
FACADE_USES = ["core", "kernels", "laws", "solver", "tables", "formats", "scene"]
PROGRAM_DIRS = ["app", "bench"]  # programs: the library through the facade only

USE_RE = re.compile(r"^\s*use\s*(?:,\s*(intrinsic|non_intrinsic)\s*::)?\s*(?:::)?\s*(\w+)",
                    re.IGNORECASE | re.MULTILINE)
MODULE_RE = re.compile(r"^\s*module\s+(?!procedure\b|function\b|subroutine\b)(\w+)\s*$",
                       re.IGNORECASE | re.MULTILINE)
BIND_RE = re.compile(r"""\bbind\s*\(\s*c\s*,\s*name\s*=\s*["'](\w+)["']""", re.IGNORECASE)
SUBMODULE_RE = re.compile(r"^\s*submodule\s*\(\s*(\w+)(?:\s*:\s*\w+)?\s*\)\s*(\w+)",
                          re.IGNORECASE | re.MULTILINE)


def strip_comments(text):
    """Fortran text without ! comments (no `!` appears inside a string before a `use`)."""
    return "\n".join(line.split("!", 1)[0] for line in text.splitlines())


def layer_of(root, path):
    """The layer of a library source (None if it lies outside every known folder)."""
    rel = os.path.relpath(path, os.path.join(root, "src")).split(os.sep)
    if len(rel) == 1:
        return FACADE
    if len(rel) == 3 and rel[0] == "egw" and rel[1] in LAYERS:
        return rel[1]
    return None


def fortran_files(top):
    found = []
    for dirpath, _, names in os.walk(top):
        found += [os.path.join(dirpath, n) for n in names if n.lower().endswith(".f90")]
    return sorted(found)


def check(root):
    """Failure messages and the number of checks made."""
    failures = []
    checks = 0
    src = os.path.join(root, "src")
    defined = {}  # module name -> (layer, file)
    arrows = {}   # file -> [(used module, line text)]
    labels = {}   # C binding label (lower case) -> file
    submodules = set()
    for path in fortran_files(src):
        rel = os.path.relpath(path, root)
        layer = layer_of(root, path)
        if layer is None:
            failures.append(f"{rel}: outside the layer folders src/egw/{{{','.join(LAYERS)}}}/")
            continue
        text = strip_comments(open(path, encoding="utf-8").read())
        uses = [(m.group(2).lower(), m.group(0).strip()) for m in USE_RE.finditer(text)
                if (m.group(1) or "").lower() != "intrinsic"]
        for m in SUBMODULE_RE.finditer(text):
            uses.append((m.group(1).lower(), m.group(0).strip()))
        names = [m.group(1).lower() for m in MODULE_RE.finditer(text)]
        subs = [m.group(2).lower() for m in SUBMODULE_RE.finditer(text)]
        submodules.update(subs)   # named within their ancestor: not global identifiers
        names += subs
        for name in names:
            if name in defined:
                failures.append(f"{rel}: module {name} is also defined in {defined[name][1]}")
            defined[name] = (layer, rel)
        arrows[rel] = (layer, uses)
        for m in BIND_RE.finditer(text):
            labels.setdefault(m.group(1).lower(), rel)
    checks += 1
    for name, (_, rel) in defined.items():
        if name in labels and name not in submodules:
            failures.append(f"{rel}: module {name} has the name of the C binding label in "
                            f"{labels[name]} (one global identifier: rename the module)")
    for rel, (layer, uses) in arrows.items():
        checks += 1
        allowed = set(FACADE_USES if layer == FACADE else LAYERS[layer] + [layer])
        bad = []
        for name, line in uses:
            if name not in defined:
                continue  # iso_c_binding, omp_lib, ...: not egw's
            target = defined[name][0]
            if target not in allowed:
                bad.append(f"{line!r} reaches {target}/ ({defined[name][1]})")
        if bad:
            failures.append(f"{rel} [{layer}]: " + "; ".join(bad)
                            + f" (allowed: {', '.join(sorted(allowed))})")
    facade = {n for n, (layer, _) in defined.items() if layer == FACADE}
    for folder in PROGRAM_DIRS:
        for path in fortran_files(os.path.join(root, folder)):
            checks += 1
            rel = os.path.relpath(path, root)
            text = strip_comments(open(path, encoding="utf-8").read())
            bad = [m.group(0).strip() for m in USE_RE.finditer(text)
                   if m.group(2).lower() in defined and m.group(2).lower() not in facade]
            if bad:
                failures.append(f"{rel}: a program uses library internals ({'; '.join(bad)}); "
                                f"use the facade ({', '.join(sorted(facade))})")
    for layer in LAYERS:
        checks += 1
        readme = os.path.join(src, "egw", layer, "README.md")
        if not os.path.isfile(readme):
            failures.append(f"src/egw/{layer}/README.md: missing (what lives there, what it may use)")
    return failures, checks


def self_test():
    """Run check() on made-up trees; return the faults it missed (empty when all seen)."""
    with tempfile.TemporaryDirectory(prefix="egw_layers_") as scratch:
        return _self_test(scratch)


def _self_test(scratch):
    """self_test's body: every made-up tree in a fresh folder under scratch (removed
    with it)."""
    def tree(files):
        root = tempfile.mkdtemp(dir=scratch)
        for layer in LAYERS:
            os.makedirs(os.path.join(root, "src", "egw", layer))
            open(os.path.join(root, "src", "egw", layer, "README.md"), "w").close()
        for rel, text in files.items():
            os.makedirs(os.path.dirname(os.path.join(root, rel)), exist_ok=True)
            with open(os.path.join(root, rel), "w") as f:
                f.write(text)
        return root
    clean = {
        "src/egw/core/kinds.f90": "module egw_kinds\nend module egw_kinds\n",
        "src/egw/kernels/k.f90": "module egw_k\n use egw_kinds, only: dp\n"
                                 " use, intrinsic :: iso_c_binding\nend module egw_k\n",
        "src/egw/tables/t.f90": "module egw_t\n use egw_k\nend module egw_t\n",
        "src/egw/tables/t_build.f90": "submodule (egw_t) egw_t_build\nend submodule\n",
        "src/egw.f90": "module egw\n use egw_t\nend module egw\n",
        "app/main.f90": "program main\n use egw\nend program main\n",
    }
    faults = {
        "a kernel using a table": {"src/egw/kernels/k2.f90":
                                   "module egw_k2\n  use egw_t, only: x\nend module\n"},
        "core using the C layer": {"src/egw/capi/c.f90": "module egw_c\nend module\n",
                                   "src/egw/core/s.f90": "module egw_s\nuse egw_c\nend module\n"},
        "the facade using the C layer": {"src/egw/capi/c.f90": "module egw_c\nend module\n",
                                         "src/egw_all.f90": "module egw_all\nuse egw_c\nend module\n"},
        "a submodule of a higher layer's module": {
            "src/egw/kernels/sub.f90": "submodule (egw_t) egw_t_k\nend submodule\n"},
        "a file outside the layers": {"src/egw/misc/m.f90": "module egw_m\nend module\n"},
        "a module defined twice": {"src/egw/core/k2.f90": "module egw_kinds\nend module\n"},
        "a program using internals": {"bench/b.f90": "program b\n use egw_k\nend program\n"},
        "a module named as a C binding label": {
            "src/egw/capi/c.f90": "module egw_c\ncontains\n function egw_t_eval() &\n"
                                  "   & bind(C, name=\"egw_t\")\n end function\nend module\n"},
    }
    missed = []
    failures, _ = check(tree(clean))
    if failures:
        missed.append("the clean tree fails: " + "; ".join(failures))
    for what, extra in faults.items():
        failures, _ = check(tree({**clean, **extra}))
        if not failures:
            missed.append(f"not seen: {what}")
    root = tree(clean)
    os.remove(os.path.join(root, "src", "egw", "scene", "README.md"))
    if not check(root)[0]:
        missed.append("not seen: a layer without README.md")
    return missed


def main(argv):
    args = [a for a in argv if a != "--self-test"]
    root = os.path.abspath(args[0] if args else os.path.join(os.path.dirname(__file__), ".."))
    passed = failed = 0
    if "--self-test" in argv:
        missed = self_test()
        for m in missed:
            print(f"FAIL self-test: {m}")
        print(f"self-test: made-up trees with 9 kinds of fault: {'all seen' if not missed else 'MISSED'}")
        passed += 0 if missed else 1
        failed += 1 if missed else 0
    failures, checks = check(root)
    for f in failures:
        print(f"FAIL {f}")
    print(f"layers: {checks} checks ({len(LAYERS)} layers of src/egw, the facade, "
          f"{', '.join(PROGRAM_DIRS)}): {'one-way' if not failures else 'arrows against the layers'}")
    passed += checks - min(len(failures), checks)
    failed += min(len(failures), checks)
    print(f"{passed} passed, {failed} failed")
    return 0 if failed == 0 else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
