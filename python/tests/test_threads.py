"""Calls from several threads at once: the GIL is released during solves and the library keeps no
global state, so two threads give the results one thread gives, exactly."""

import threading

import emnet


def test_two_threads_give_identical_results(fishfin):
    expected_modes = emnet.modes(fishfin, count=3).modes["frequency_hz"]
    expected_sweep = emnet.sweep_switching(fishfin, from_hz=4, to_hz=6, step_hz=0.25)
    results = {}

    def work(name):
        for _ in range(3):
            modes = emnet.modes(fishfin, count=3).modes["frequency_hz"]
            sweep = emnet.sweep_switching(fishfin, from_hz=4, to_hz=6, step_hz=0.25)
            results.setdefault(name, []).append((modes, sweep))

    threads = [threading.Thread(target=work, args=(n,)) for n in ("a", "b")]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    for runs in results.values():
        assert len(runs) == 3
        for modes, sweep in runs:
            assert list(modes) == list(expected_modes)
            for mine, expected in zip(sweep.outputs["right"], expected_sweep.outputs["right"]):
                assert list(mine) == list(expected)
