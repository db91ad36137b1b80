"""A study on a real Dask LocalCluster (a scheduler and two worker processes on localhost) gives
the local run's DataFrame bit for bit, even when a worker process is killed mid-study."""

import importlib
import os
import signal
import threading
import time

import pandas
import pytest

import emnet


def test_local_cluster_equals_local_run(fishfin):
    distributed = pytest.importorskip("distributed")
    vary = ["beam.bending_stiffness=normal(100%,5%)", "dea.A.electrode_width=uniform(95%,105%)"]
    local = emnet.study(fishfin, vary=vary, samples=40, seed=3, analyses=["modes", "static"])
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        remote = emnet.study(fishfin, vary=vary, samples=40, seed=3,
                             analyses=["modes", "static"], client=client, chunk_size=10)
    pandas.testing.assert_frame_equal(local, remote, check_exact=True)
    assert remote.attrs["units"] == local.attrs["units"]


CHUNKS, CHUNK_SIZE = 40, 75
VARY = ["beam.bending_stiffness=normal(100%,5%)", "dea.A.electrode_width=uniform(95%,105%)"]


def _chunks_in_memory(dask_scheduler):
    return sum(ts.state == "memory" for key, ts in dask_scheduler.tasks.items()
               if str(key).startswith("_run_chunk"))


def _suspicious_and_workers(dask_scheduler):
    """Tasks rescheduled because a worker died while they were on it; the workers' addresses."""
    return (sum(ts.suspicious for ts in dask_scheduler.tasks.values()),
            list(dask_scheduler.workers))


def _study_on_a_fresh_cluster(scene, kill):
    """The study on a new LocalCluster of 2 nanny-managed worker processes (1 thread each), timed
    from the call to its DataFrame; with kill, one worker is SIGKILLed once a quarter of the
    chunks are done. Returns the DataFrame, the wall time and what the killing thread saw."""
    distributed = pytest.importorskip("distributed")
    seen = {}
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        client.run(importlib.import_module, "emnet")  # both runs start from imported workers
        pids = client.run(os.getpid)

        def kill_a_busy_worker():
            until = time.monotonic() + 120
            while time.monotonic() < until:
                done = client.run_on_scheduler(_chunks_in_memory)
                if done >= CHUNKS // 4:
                    break
                time.sleep(0.02)
            busy = {address: keys for address, keys in client.processing().items() if keys}
            address = sorted(busy)[0]
            os.kill(pids[address], signal.SIGKILL)
            seen.update(done=done, busy=len(busy[address]), pid=pids[address],
                        killed_at=time.monotonic())
            while time.monotonic() < until:  # until the scheduler has taken the worker out
                suspicious, workers = client.run_on_scheduler(_suspicious_and_workers)
                if address not in workers:
                    seen["suspicious"] = suspicious
                    break
                time.sleep(0.02)
            while time.monotonic() < until:  # until the nanny's new worker has joined
                if len(client.run_on_scheduler(_suspicious_and_workers)[1]) == 2:
                    seen["restart_seconds"] = time.monotonic() - seen["killed_at"]
                    break
                time.sleep(0.02)

        killer = threading.Thread(target=kill_a_busy_worker)
        started = time.monotonic()
        if kill:
            killer.start()
        frame = emnet.study(scene, vary=VARY, samples=CHUNKS * CHUNK_SIZE, seed=5,
                            analyses=["modes", "static"], client=client, chunk_size=CHUNK_SIZE)
        wall = time.monotonic() - started
        if kill:
            killer.join()
            client.wait_for_workers(2, timeout=60)
            seen["pids_after"] = sorted(client.run(os.getpid).values())
    return frame, wall, seen


def test_a_killed_worker_costs_time_not_results(fishfin):
    """A worker process SIGKILLed mid-study (a quarter of the 40 chunks done, one chunk or more
    running on it) is restarted by its nanny, Dask runs its lost chunks again, and the DataFrame
    equals the local run's bit for bit. The kill is shown to have hit running work: the
    scheduler marks the chunks it held as suspicious (rescheduled after their worker died). The
    time lost (the same study on the same cluster set-up without a kill, subtracted) is
    printed, not bounded: it depends on how fast this machine starts a worker."""
    local = emnet.study(fishfin, vary=VARY, samples=CHUNKS * CHUNK_SIZE, seed=5,
                        analyses=["modes", "static"])
    undisturbed, clean_wall, _ = _study_on_a_fresh_cluster(fishfin, kill=False)
    killed, killed_wall, seen = _study_on_a_fresh_cluster(fishfin, kill=True)

    assert 0 < seen["done"] < CHUNKS, seen
    assert seen["busy"] >= 1 and seen["suspicious"] >= 1, seen
    assert seen["pid"] not in seen["pids_after"] and len(seen["pids_after"]) == 2, seen
    for remote in (undisturbed, killed):
        pandas.testing.assert_frame_equal(local, remote, check_exact=True)
        for name in ("units", "segments", "unknowns", "notes", "failed", "outside_validity"):
            assert remote.attrs[name] == local.attrs[name], name
    print(f"\n{CHUNKS} chunks of {CHUNK_SIZE} variants on 2 workers: {clean_wall:.2f} s; with a "
          f"worker killed at {seen['done']}/{CHUNKS} chunks ({seen['busy']} on it): "
          f"{killed_wall:.2f} s, {killed_wall - clean_wall:+.2f} s lost; the nanny's new worker "
          f"joined {seen.get('restart_seconds', float('nan')):.2f} s after the kill")
