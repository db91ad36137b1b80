#!/usr/bin/python3
"""The Python module's part of benchmark section 6 (run by build/emnet_bench, or alone):

- its overhead on one `modes` call: the call's wall time in Python against the time the library
  measured inside it (cost.total_seconds), medians of repeated calls;
- the tolerance study through emnet.study: in this process on 2 threads, and on a Dask
  LocalCluster of 1 and of 2 worker processes (one thread each), with the task overhead
  (workers × wall − the variants' work) / (workers × wall), and whether the DataFrames equal
  the local run's bit for bit.

Prints a markdown fragment. Usage:
  PYTHONPATH=build/python /usr/bin/python3 tools/benchmark/python_study.py \\
      --scene netlists/fishfin.toml --variants 1000
"""

import argparse
import statistics
import time

import emnet

VARY = ["beam.bending_stiffness=uniform(95%,105%)"]
for _dea in ("A", "B"):
    VARY += [f"dea.{_dea}.dielectric_thickness+dea.{_dea}.force_thickness=uniform(95%,105%)",
             f"dea.{_dea}.electrode_width=uniform(95%,105%)",
             f"dea.{_dea}.lever_arm=uniform(95%,105%)"]


def overhead(scene, repetitions=200):
    emnet.modes(scene)  # warm-up
    walls, inside = [], []
    for _ in range(repetitions):
        started = time.perf_counter()
        result = emnet.modes(scene)
        walls.append(time.perf_counter() - started)
        inside.append(result.cost["total_seconds"])
    return statistics.median(walls), statistics.median(inside)


def study(scene, variants, **options):
    started = time.perf_counter()
    frame = emnet.study(scene, vary=VARY, samples=variants, seed=1,
                        analyses=["modes", "static", "sweep-switching"], at=[5.0], **options)
    return frame, time.perf_counter() - started


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--scene", default="netlists/fishfin.toml")
    parser.add_argument("--variants", type=int, default=1000)
    args = parser.parse_args()
    fin = emnet.Scene(args.scene)

    wall, inside = overhead(fin)
    print("Python module (`tools/benchmark/python_study.py`):\n")
    print(f"- One `emnet.modes(fin)` call: {1e3 * wall:.3f} ms in Python, {1e3 * inside:.3f} ms "
          f"measured by the library inside it: the module adds {1e6 * (wall - inside):.0f} µs, "
          f"{100 * (wall - inside) / wall:.1f} % of the call (goal: under 5 %; medians of 200 "
          f"calls).")

    local, local_wall = study(fin, args.variants, threads=2)
    work = local.attrs["cost"]["work_seconds"]
    print(f"- `emnet.study` of {args.variants} variants in this process, 2 threads: "
          f"{local_wall:.2f} s ({1e3 * local_wall / args.variants:.2f} ms per variant; "
          f"{1e3 * work / args.variants:.2f} ms of work per variant).")

    try:
        from dask.distributed import Client, LocalCluster
    except ImportError:
        print("- Dask: not installed (python3-distributed), not measured.\n")
        return
    rows = []
    for workers in (1, 2):
        with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                          dashboard_address=None) as cluster, Client(cluster) as client:
            study(fin, min(40, args.variants), client=client)  # warm-up: imports on the workers
            frame, seconds = study(fin, args.variants, client=client)
        same = frame.equals(local) and list(frame.columns) == list(local.columns)
        task_work = frame.attrs["cost"]["work_seconds"]
        rows.append((workers, seconds, task_work, same))
    print("\n| Dask workers (processes, 1 thread each) | wall | speed-up | task overhead | equal "
          "to the local run |\n|---|---|---|---|---|")
    for workers, seconds, task_work, same in rows:
        overhead_share = max(0.0, (workers * seconds - task_work) / (workers * seconds))
        print(f"| {workers} | {seconds:.2f} s | {rows[0][1] / seconds:.2f} | "
              f"{100 * overhead_share:.1f} % | {'bit for bit' if same else '**no**'} |")
    print("\nTask overhead: the share of the workers' wall time not spent on variants "
          "(scheduling, pickling the scene and the chunks, the results' way back).")


if __name__ == "__main__":
    main()
