"""The console script `emnet` of an installed package: runs the command line program the wheel
holds (emnet/bin/emnet) with the same arguments, in place of this Python process."""

import os
import sys
from typing import Optional


def program(name: str = "emnet") -> Optional[str]:
    """The path of a program the installed package holds (emnet, emnet-ngspice-worker), or None
    where there is none (the package run from build/python: the programs are in build/)."""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bin", name)
    return path if os.access(path, os.X_OK) else None


def main() -> None:
    path = program()
    if path is None:
        sys.exit("emnet: this emnet package holds no command line program (emnet/bin/emnet); "
                 "run build/emnet, or install the package with pip")
    os.execv(path, [path, *sys.argv[1:]])
