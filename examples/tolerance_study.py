#!/usr/bin/python3
"""Tolerance study of the paper's fish fin: how much do f1 and the P4 swing at 5 Hz scatter when
each part is made to ±5 %?

Varies, each uniformly within ±5 % of the scene's value and independently per DEA: the bending
stiffness EI, each DEA's film thickness (its dielectric and force thickness together: one film),
electrode width and lever arm. Per variant: the modes (f1) and the periodic steady state of the 4 kV switching at
5 Hz (the P4 peak: dx4's largest |deflection| over the period). Writes a histogram of each.

    PYTHONPATH=build/python python3 examples/tolerance_study.py                 # 1000 variants
    PYTHONPATH=build/python python3 examples/tolerance_study.py --samples 200 --plot fin.png
    PYTHONPATH=build/python python3 examples/tolerance_study.py --scheduler tcp://host:8786

Run from the repository's root (or give --scene).
"""

import argparse
import os
import sys

import numpy

import emnet

# "KEY1+KEY2": varied together by the same relative change (one film's two thicknesses).
KEYS = ["beam.bending_stiffness"]
for dea in ("A", "B"):
    KEYS += [f"dea.{dea}.dielectric_thickness+dea.{dea}.force_thickness",
             f"dea.{dea}.electrode_width", f"dea.{dea}.lever_arm"]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default="netlists/fishfin.toml")
    parser.add_argument("--samples", type=int, default=1000)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--tolerance", type=float, default=5.0, help="± percent (default 5)")
    parser.add_argument("--plot", default="tolerance_study.png", help="PNG to write")
    parser.add_argument("--csv", default="", help="also write the table here")
    parser.add_argument("--scheduler", default="",
                        help="a Dask scheduler's address: run the variants on its workers")
    args = parser.parse_args()

    fin = emnet.Scene(args.scene)
    low, high = 100 - args.tolerance, 100 + args.tolerance
    vary = [f"{key}=uniform({low}%,{high}%)" for key in KEYS]
    client = None
    if args.scheduler:
        from dask.distributed import Client
        client = Client(args.scheduler)
    frame = emnet.study(fin, vary=vary, samples=args.samples, seed=args.seed,
                        analyses=["modes", "sweep-switching"], at=[5.0],
                        sweep_frequencies=[5.0], client=client, progress=True)
    ok = frame[frame["status"] == "ok"]
    peak = numpy.maximum(ok["sweep.dx4.max_at_5Hz_m"].abs(), ok["sweep.dx4.min_at_5Hz_m"].abs())
    cost = frame.attrs["cost"]
    print(f"{len(frame)} variants ({frame.attrs['failed']} failed) in {cost['wall_seconds']:.2f} s;"
          f" {1e3 * cost['per_variant_seconds']:.2f} ms of work per variant")
    print(f"f1: {ok['f1_hz'].mean():.4f} Hz ± {ok['f1_hz'].std():.4f} Hz (1 sd), "
          f"range {ok['f1_hz'].min():.4f}..{ok['f1_hz'].max():.4f} Hz")
    print(f"P4 peak at 5 Hz: {1e3 * peak.mean():.3f} mm ± {1e3 * peak.std():.3f} mm (1 sd)")
    if args.csv:
        frame.to_csv(args.csv, index=False)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    figure, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    left.hist(ok["f1_hz"], bins=40, color="#1f77b4")
    left.axvline(emnet.modes(fin, count=1).modes["frequency_hz"][0], color="k", linestyle="--",
                 label="nominal")
    left.set_xlabel("first resonance f1 [Hz]")
    left.set_ylabel("variants")
    left.legend()
    right.hist(1e3 * peak, bins=40, color="#d62728")
    nominal = emnet.sweep_switching(fin, frequencies=[5.0]).outputs.row("dx4")
    right.axvline(1e3 * max(abs(nominal["left"][0]), abs(nominal["right"][0])), color="k",
                  linestyle="--", label="nominal")
    right.legend()
    right.set_xlabel("P4 peak deflection, 4 kV switched at 5 Hz [mm]")
    right.set_ylabel("variants")
    figure.suptitle(f"{fin.name}: ±{args.tolerance:g} % on EI, film thickness, electrode width, "
                    f"lever arm ({len(ok)} variants)")
    figure.tight_layout()
    figure.savefig(args.plot, dpi=110)
    print(f"plot: {os.path.abspath(args.plot)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
