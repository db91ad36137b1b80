"""A study on a real Dask LocalCluster (a scheduler and two worker processes on localhost) gives
the local run's DataFrame bit for bit."""

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
