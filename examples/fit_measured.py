#!/usr/bin/python3
"""Identify a scene's parameters from a measured amplitude-versus-frequency curve.

The curve is a CSV file of two columns: the switching frequency [Hz] and the measured amplitude
[m] of one output (half its periodic peak-to-peak, as a camera tracking a point sees it). The
fit is least squares over the whole curve (Levenberg-Marquardt on the relative residuals, the
parameters in log scale), not a match of two numbers; each model curve is emnet's periodic steady
state of the scene's drive (sweep_switching). Prints the fitted values, their standard errors
from the Jacobian, and writes a plot of the data against the fitted curve.

    PYTHONPATH=build/python python3 examples/fit_measured.py examples/data/fin-amplitude-demo.csv
    PYTHONPATH=build/python python3 examples/fit_measured.py CURVE.csv --scene S.toml \
        --output dx4 --fit beam.bending_stiffness --fit damping.loss_factor

examples/data/fin-amplitude-demo.csv is a demonstration curve, not a measurement: made by
`--make-demo` from netlists/fishfin-measured.toml (EI 1.337608e-3 N*m^2, loss factor 0.03935
at 5 Hz, i.e. a Kelvin-Voigt time of 1.2526 ms) with 2 % noise (seed 1), so that the fit can be
seen to recover known values. The default start, netlists/fishfin.toml, refers its loss factor
to 6.385 Hz: compare the Kelvin-Voigt time the fit prints.
"""

import argparse
import sys

import numpy

import emnet


def amplitude(scene, output, frequencies):
    sweep = emnet.sweep_switching(scene, frequencies=list(frequencies))
    series = sweep.outputs.row(output)
    return 0.5 * (series["right"] - series["left"])


def read_curve(path):
    """Two columns, frequency [Hz] and amplitude [m]; '#' comments and one header line skipped."""
    rows = []
    with open(path) as lines:
        for number, line in enumerate(lines, 1):
            text = line.strip()
            if not text or text.startswith("#"):
                continue
            fields = text.replace(";", ",").split(",")
            try:
                rows.append((float(fields[0]), float(fields[1])))
            except (ValueError, IndexError):
                if rows:
                    raise SystemExit(f"{path}:{number}: expected two numbers, got '{text}'")
    if not rows:
        raise SystemExit(f"{path}: no data")
    data = numpy.array(rows)
    return data[:, 0], data[:, 1]


def fit(scene, output, keys, frequencies, measured, iterations=30):
    """Levenberg-Marquardt on r(p) = model/measured - 1 over log p."""
    log_p = numpy.log([scene.get(key) for key in keys])

    def residual(log_values):
        changed = scene.with_values(dict(zip(keys, numpy.exp(log_values))))
        return amplitude(changed, output, frequencies) / measured - 1.0

    r = residual(log_p)
    damping = 1e-3
    for _ in range(iterations):
        jacobian = numpy.empty((len(r), len(keys)))
        for k in range(len(keys)):
            step = numpy.zeros(len(keys))
            step[k] = 1e-6
            jacobian[:, k] = (residual(log_p + step) - residual(log_p - step)) / 2e-6
        normal = jacobian.T @ jacobian
        gradient = jacobian.T @ r
        while True:
            delta = numpy.linalg.solve(normal + damping * numpy.diag(numpy.diag(normal)),
                                       -gradient)
            trial = residual(log_p + delta)
            if trial @ trial < r @ r:
                log_p, r, damping = log_p + delta, trial, damping / 3
                break
            damping *= 4
            if damping > 1e8:
                break
        if numpy.max(numpy.abs(delta)) < 1e-9 or damping > 1e8:
            break
    dof = max(1, len(r) - len(keys))
    covariance = numpy.linalg.inv(jacobian.T @ jacobian) * (r @ r) / dof
    values = numpy.exp(log_p)
    return values, values * numpy.sqrt(numpy.diag(covariance)), r


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("curve", help="CSV: frequency [Hz], amplitude [m] (a header line allowed)")
    parser.add_argument("--scene", default="netlists/fishfin.toml",
                        help="the scene whose parameters are fitted (start values)")
    parser.add_argument("--output", default="dx4", help="the output measured (default dx4)")
    parser.add_argument("--fit", action="append", default=None,
                        help="a key to fit (repeatable; default EI and the loss factor)")
    parser.add_argument("--plot", default="fit_measured.png")
    parser.add_argument("--make-demo", action="store_true",
                        help="write the demonstration curve to CURVE instead of fitting")
    args = parser.parse_args()
    keys = args.fit or ["beam.bending_stiffness", "damping.loss_factor"]

    if args.make_demo:
        truth = emnet.Scene("netlists/fishfin-measured.toml")
        frequencies = numpy.round(numpy.arange(3.0, 7.01, 0.25), 2)
        clean = amplitude(truth, args.output, frequencies)
        noisy = clean * (1 + 0.02 * numpy.random.default_rng(1).standard_normal(len(clean)))
        with open(args.curve, "w") as out:
            out.write("# demonstration curve, not a measurement: emnet sweep_switching of "
                      "netlists/fishfin-measured.toml, output dx4, 2 % noise (seed 1); "
                      "made by examples/fit_measured.py --make-demo\n")
            out.write("frequency_hz,amplitude_m\n")
            for f, a in zip(frequencies, noisy):
                out.write(f"{f:.6g},{a:.6e}\n")
        print(f"wrote {args.curve}")
        return 0

    frequencies, measured = read_curve(args.curve)
    if len(frequencies) < len(keys) + 1 or not numpy.all(measured > 0):
        raise SystemExit(f"{args.curve}: need more points than parameters, amplitudes > 0")
    scene = emnet.Scene(args.scene)
    values, errors, r = fit(scene, args.output, keys, frequencies, measured)
    print(f"fitted to {len(frequencies)} points of {args.curve} (output {args.output}):")
    for key, value, error in zip(keys, values, errors):
        print(f"  {key} = {value:.6g} ± {error:.2g} {scene.unit(key)}")
    print(f"  rms relative residual {numpy.sqrt(numpy.mean(r ** 2)):.3g}")
    if "damping.loss_factor" in keys:
        # The loss factor holds at damping.loss_factor_frequency: the Kelvin-Voigt time
        # tau = eta / (2 pi f_ref) is what the curve fixes, whatever the reference frequency.
        eta = values[keys.index("damping.loss_factor")]
        reference = scene.get("damping.loss_factor_frequency")
        print(f"  Kelvin-Voigt time tau = eta/(2 pi {reference:g} Hz) = "
              f"{eta / (2 * numpy.pi * reference):.4g} s")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fitted = scene.with_values(dict(zip(keys, values)))
    fine = numpy.linspace(frequencies.min(), frequencies.max(), 200)
    figure, axis = plt.subplots(figsize=(6, 4))
    axis.plot(frequencies, 1e3 * measured, "o", color="k", label="measured")
    axis.plot(fine, 1e3 * amplitude(fitted, args.output, fine), "-", color="#1f77b4",
              label="fitted model")
    axis.set_xlabel("switching frequency [Hz]")
    axis.set_ylabel(f"{args.output} amplitude [mm]")
    axis.legend()
    figure.tight_layout()
    figure.savefig(args.plot, dpi=110)
    print(f"plot: {args.plot}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
