"""The examples run and do what they say (small sizes)."""

import re
import subprocess
import sys

from conftest import ROOT


def run(script, *arguments):
    done = subprocess.run([sys.executable, str(ROOT / "examples" / script), *arguments],
                          capture_output=True, text=True, cwd=ROOT, check=False)
    assert done.returncode == 0, done.stderr
    return done.stdout


def test_tolerance_study(tmp_path):
    out = run("tolerance_study.py", "--samples", "20", "--plot", str(tmp_path / "t.png"))
    assert "20 variants (0 failed)" in out
    assert (tmp_path / "t.png").stat().st_size > 10000


def test_fit_recovers_the_demo_curves_parameters(tmp_path):
    # The demonstration curve was made from netlists/fishfin-measured.toml (EI 1.337608e-3 N*m^2,
    # Kelvin-Voigt time 0.03935/(2 pi 5 Hz) = 1.2526 ms) with 2 % noise: the fit must find both
    # within 3 of its own standard errors.
    out = run("fit_measured.py", "examples/data/fin-amplitude-demo.csv", "--plot",
              str(tmp_path / "f.png"))
    stiffness, error = map(float, re.search(r"bending_stiffness = (\S+) ± (\S+)", out).groups())
    assert abs(stiffness - 1.337608e-3) < 3 * error
    eta, eta_error = map(float, re.search(r"loss_factor = (\S+) ± (\S+)", out).groups())
    tau = float(re.search(r"tau = .* = (\S+) s", out).group(1))
    assert abs(tau - 0.03935468 / (2 * 3.141592653589793 * 5.0)) < 3 * tau * eta_error / eta
