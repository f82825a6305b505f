#!/usr/bin/env python3
"""List the public procedures of src/egw/ and their dummy arguments that FORD shows bare.

FORD (ford.md: docmark `<`, predocmark `>`) documents a procedure from the `!>` lines just
above it and an argument from a `!<` comment on its declaration or the `!>` lines just
above that. This check reads every module of src/egw/ (gauss_fits.f90, generated, is left
out as ford.md leaves it out) and reports, one line each:
  - a public procedure (named in a `public ::` list, directly or through a public generic
    interface, or a `bind(C)` entry point of the C layer) with no `!>` line above it;
  - a dummy argument of such a procedure whose declaration carries neither.
Interface blocks that bind C or library routines (libc, LAPACK, FFTW) are private
plumbing and are not read; a public separate module procedure is checked where its
interface stands. Ends "N public procedures, N arguments, N gaps".

Usage: python3 tools/check_docs.py [--self-test] [--summary] [ROOT]   (ROOT: the repository)
  --summary   the gaps counted per file instead of listed
Exits 1 when there are gaps (or the self-test fails), 0 otherwise.
"""
import os
import re
import sys
import tempfile

SKIP_FILES = {"gauss_fits.f90"}
PREFIX = (r"(?:(?:pure|elemental|recursive|impure|module|integer|logical|real|complex|"
          r"character|type|class)(?:\s*\([^()]*\))?\s+)*")
PROC_RE = re.compile(r"^\s*" + PREFIX + r"(subroutine|function)\s+(\w+)\s*(?:\(([^)]*)\))?",
                     re.IGNORECASE)
END_PROC_RE = re.compile(r"^\s*end\s+(subroutine|function)\b", re.IGNORECASE)
INTERFACE_RE = re.compile(r"^\s*(abstract\s+)?interface\b\s*(\w*)", re.IGNORECASE)
END_INTERFACE_RE = re.compile(r"^\s*end\s+interface\b", re.IGNORECASE)
PUBLIC_RE = re.compile(r"^\s*public\s*::\s*(.*)$", re.IGNORECASE)
GENERIC_RE = re.compile(r"^\s*interface\s+(\w+)\s*$", re.IGNORECASE)


def strip_comment(line):
    """The code of a line without its ! comment (a ! inside quotes is kept)."""
    quote = None
    for i, ch in enumerate(line):
        if quote:
            if ch == quote:
                quote = None
        elif ch in "'\"":
            quote = ch
        elif ch == "!":
            return line[:i]
    return line


def statements(lines):
    """(first line, last line, code) of each statement, continuation lines joined."""
    out = []
    i = 0
    while i < len(lines):
        first = i
        parts = [strip_comment(lines[i]).rstrip()]
        while parts[-1].endswith("&") and i + 1 < len(lines):
            i += 1
            parts[-1] = parts[-1][:-1]
            parts.append(strip_comment(lines[i]).strip().lstrip("&").rstrip())
        out.append((first, i, " ".join(parts)))
        i += 1
    return out


def public_names(stmts):
    """The names a module makes public, with the specifics of its public generics."""
    names = set()
    for _, _, code in stmts:
        m = PUBLIC_RE.match(code)
        if m:
            names |= {n.strip().lower() for n in m.group(1).split(",") if n.strip()}
    generic = None
    for _, _, code in stmts:
        m = GENERIC_RE.match(code)
        if m:
            generic = m.group(1).lower()
            continue
        if END_INTERFACE_RE.match(code):
            generic = None
            continue
        m = re.match(r"^\s*module\s+procedure\s+(.*)$", code, re.IGNORECASE)
        if generic in names and m:
            names |= {n.strip().lower() for n in m.group(1).split(",") if n.strip()}
    return names


def documented_above(lines, index):
    """Whether the nearest non-blank line above lines[index] is a `!>` comment."""
    j = index - 1
    while j >= 0 and not lines[j].strip():
        j -= 1
    return j >= 0 and lines[j].strip().startswith("!>")


def entity_names(declaration):
    """The entity names of the part of a declaration after `::`."""
    depth = 0
    flat = []
    for ch in declaration:
        if ch == "(":
            depth += 1
        elif ch == ")":
            depth -= 1
        elif depth == 0:
            flat.append(ch)
    return [e.split("=")[0].strip().lower() for e in "".join(flat).split(",")]


def check_file(path, rel):
    """(procedures, arguments, gaps) of one source file."""
    lines = open(path, encoding="utf-8").read().splitlines()
    stmts = statements(lines)
    public = public_names(stmts)
    n_proc = n_args = 0
    gaps = []
    in_interface = False
    for k, (first, _, code) in enumerate(stmts):
        if INTERFACE_RE.match(code) and not re.match(r"^\s*end\b", code, re.IGNORECASE):
            in_interface = True
            continue
        if END_INTERFACE_RE.match(code):
            in_interface = False
            continue
        m = PROC_RE.match(code)
        if not m or re.match(r"^\s*end\b", code, re.IGNORECASE):
            continue
        name = m.group(2).lower()
        c_entry = not in_interface and "bind(c" in code.lower().replace(" ", "")
        if name not in public and not c_entry:
            continue
        if in_interface and not re.match(r"^\s*" + PREFIX, code, re.IGNORECASE):
            continue
        if in_interface and "module" not in code.lower().split(m.group(1).lower())[0]:
            continue      # a binding of a C or library routine
        n_proc += 1
        if not documented_above(lines, first):
            gaps.append(f"{rel}:{first + 1}: {name}: no !> above it")
        args = [a.strip().lower() for a in (m.group(3) or "").split(",") if a.strip()]
        docs = {}
        for first2, last2, code2 in stmts[k + 1:]:
            if END_PROC_RE.match(code2) or re.match(r"^\s*contains\b", code2, re.IGNORECASE):
                break
            if "::" not in code2:
                continue
            raw = "\n".join(lines[first2:last2 + 1])
            ok = "!<" in raw or documented_above(lines, first2)
            for entity in entity_names(code2.split("::", 1)[1]):
                if entity in args and entity not in docs:
                    docs[entity] = ok
        for arg in args:
            n_args += 1
            if not docs.get(arg, False):
                gaps.append(f"{rel}:{first + 1}: {name}: argument {arg} has no !< or !>")
    return n_proc, n_args, gaps


def check(root):
    """(procedures, arguments, gaps) of every library source below root/src/egw."""
    n_proc = n_args = 0
    gaps = []
    base = os.path.join(root, "src", "egw")
    for dirpath, dirs, files in os.walk(base):
        dirs.sort()
        for name in sorted(files):
            if not name.endswith(".f90") or name in SKIP_FILES:
                continue
            path = os.path.join(dirpath, name)
            p, a, g = check_file(path, os.path.relpath(path, root))
            n_proc += p
            n_args += a
            gaps += g
    return n_proc, n_args, gaps


SELF_TEST = {
    "clean": """module m
   implicit none
   private
   public :: f, g
   interface
      !> a C routine: not checked
      function c_f(x) result(y) bind(C, name="f")
         import :: c_int
         integer(c_int), value :: x
         integer(c_int) :: y
      end function c_f
   end interface
contains
   !> f doubles
   pure real function f(x, n) result(y)
      real, intent(in) :: x   !< the value
      !> how often
      integer, intent(in) :: n
      y = 2*x*n
   end function f
   !> g
   subroutine g(a, &
      & b)
      real, intent(in) :: a, b(:)   !< two inputs
   end subroutine g
   subroutine private_one(z)
      real :: z
   end subroutine private_one
end module m
""",
    "no_doc": """module m
   implicit none
   private
   public :: f
contains
   pure real function f(x) result(y)
      real, intent(in) :: x   !< the value
      y = x
   end function f
end module m
""",
    "bare_argument": """module m
   implicit none
   private
   public :: g
contains
   !> g
   subroutine g(a, b)
      real, intent(in) :: a   !< documented
      real, intent(out) :: b
      b = a
   end subroutine g
end module m
""",
    "generic_specific": """module m
   implicit none
   private
   public :: h
   interface h
      module procedure h1
   end interface h
contains
   subroutine h1(q)
      real :: q   !< q
   end subroutine h1
end module m
""",
    "c_entry": """module m
   implicit none
   private
contains
   !> C: c_g
   function c_g(v) result(s) bind(C, name="c_g")
      integer, value :: v
      integer :: s
      s = v
   end function c_g
end module m
""",
}
EXPECTED_GAPS = {"clean": 0, "no_doc": 1, "bare_argument": 1, "generic_specific": 1,
                 "c_entry": 1}


def self_test():
    """Runs the check on small made-up modules; True when each finds what it should."""
    ok = True
    with tempfile.TemporaryDirectory() as tmp:
        for name, text in SELF_TEST.items():
            path = os.path.join(tmp, name + ".f90")
            with open(path, "w", encoding="utf-8") as f:
                f.write(text)
            _, _, gaps = check_file(path, name + ".f90")
            if len(gaps) != EXPECTED_GAPS[name]:
                print(f"self-test {name}: {len(gaps)} gaps, expected "
                      f"{EXPECTED_GAPS[name]}: {gaps}")
                ok = False
    print("self-test: " + ("passed" if ok else "FAILED"))
    return ok


def main(argv):
    args = [a for a in argv if not a.startswith("--")]
    if "--self-test" in argv and not self_test():
        return 1
    root = args[0] if args else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    n_proc, n_args, gaps = check(root)
    if "--summary" in argv:
        counts = {}
        for gap in gaps:
            counts[gap.split(":", 1)[0]] = counts.get(gap.split(":", 1)[0], 0) + 1
        for path, n in sorted(counts.items(), key=lambda item: -item[1]):
            print(f"{n:5d} {path}")
    else:
        for gap in gaps:
            print(gap)
    print(f"{n_proc} public procedures, {n_args} arguments, {len(gaps)} gaps")
    return 1 if gaps else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
