"""`python -m egw --version`: the package's and the loaded libegw's versions."""
from __future__ import annotations

import argparse
import sys
from typing import List, Optional


def main(argv: Optional[List[str]] = None) -> int:
    """Print the versions (``--version``) or a short help; returns the exit status."""
    import egw

    # raw text: argparse would wrap the version line at the terminal's width, splitting the
    # library's path (a line to copy whole)
    parser = argparse.ArgumentParser(
        prog="python -m egw", formatter_class=argparse.RawDescriptionHelpFormatter,
        description="egw: extended Greenwood-Williamson contact of rough spheres.\n"
                    "Use the package from Python (`import egw`) or egw-topo for height maps.")
    parser.add_argument("--version", action="version",
                        version=f"egw {egw.__version__} (libegw {egw.version()}, "
                                f"{egw._capi.lib._name})")
    parser.parse_args(argv)
    parser.print_help()
    return 0


if __name__ == "__main__":
    sys.exit(main())
