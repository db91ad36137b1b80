"""Design studies: many variants of a scene, in one process or on a Dask cluster."""

import contextlib
import importlib
import importlib.util
import math
import os
import sys
import time
from typing import TYPE_CHECKING, Any, Iterator, Mapping, Optional, Sequence, Union

import numpy
from numpy.typing import NDArray

from . import _emnet
from ._convert import Integer, Numbers, Texts, input_error, integer, numbers, texts
from ._scene import Scene, SceneLike, as_scene

if TYPE_CHECKING:
    import pandas

#: Variations: "KEY=SPEC" texts, or {KEY: SPEC}, a SPEC being a text or the values themselves.
Vary = Union[str, Sequence[str], Mapping[str, Union[str, Numbers]]]
#: Variants given as they are: a CSV file's path, or a DataFrame (or dict) of keys.
Variants = Union[str, "os.PathLike[str]", "pandas.DataFrame", Mapping[str, Numbers]]

_SIZE_MAX = 2**63 - 1  # what the bindings' std::size_t and std::uint64_t take
_SEED_MAX = 2**64 - 1


def _vary_texts(vary: Optional[Vary]) -> list[str]:
    if isinstance(vary, dict):  # a spec is a text, or the values themselves (any sequence)
        return [f"{key}={spec}" if isinstance(spec, str)
                else f"{key}=" + ",".join(repr(v) for v in numbers(spec, key, "vary"))
                for key, spec in vary.items()]
    return texts(vary, "vary")


def variants(scene: SceneLike, vary: Optional[Vary] = None, samples: Integer = 0,
             seed: Integer = 1, variants: Optional[Variants] = None) -> "pandas.DataFrame":
    """The variants of a study, as a pandas DataFrame (a column per key, SI values).

    Parameters
    ----------
    scene : Scene, str or os.PathLike
        The scene, or a scene file's path.
    vary : str, sequence of str, or dict, optional
        ["KEY=SPEC", ...] or {KEY: SPEC}: values "v1,v2" (or the values themselves, any sequence,
        in a dict) or linspace(a,b,n), logspace(a,b,n) (a grid); uniform(a,b), normal(mean,sd),
        lognormal(median,s) (Monte Carlo). Values in SI, with a unit ("60 mm") or a percentage of
        the scene's value ("95%"); "KEY1+KEY2=SPEC" changes both keys by the same ratio.
    samples : int, default 0
        Monte Carlo draws per grid point.
    seed : int, default 1
        The draws' seed (the same seed, the same variants).
    variants : str, os.PathLike, pandas.DataFrame or dict, optional
        Instead of vary: a CSV file (a header of keys, a variant per line) or a DataFrame of
        keys.

    Returns
    -------
    pandas.DataFrame
        A column per (canonical) key, a row per variant [SI].

    Raises
    ------
    InputError
        A bad keyword value, key or variation (.key names it).
    """
    return _variant_table(scene, vary, samples, seed, variants)


def _variant_table(scene: SceneLike, vary: Optional[Vary], samples: Integer, seed: Integer,
                   variants: Optional[Variants]) -> "pandas.DataFrame":
    import pandas

    handle = as_scene(scene)._handle
    if variants is not None:
        if vary:
            raise input_error("give vary or variants, not both", "variants", "variants")
        if isinstance(variants, (str, os.PathLike)):
            keys, values = _emnet.read_variants(handle, os.fspath(variants))
        else:
            frame = pandas.DataFrame(variants)
            keys = [handle.canonical_key(str(key)) for key in frame.columns]
            values = frame.to_numpy(dtype=float)
    else:
        keys, values = _emnet.make_variants(
            handle, _vary_texts(vary), integer(samples, "samples", low=0, high=_SIZE_MAX),
            integer(seed, "seed", low=0, high=_SEED_MAX))
    return pandas.DataFrame(values, columns=keys)


def _run_chunk(state: dict[str, Any], keys: list[str], values: NDArray[numpy.float64],
               options: dict[str, Any]) -> dict[str, Any]:
    """One chunk of variants on a worker (a Dask task): the study's dict for those rows."""
    scene = Scene.__new__(Scene)
    scene.__setstate__(state)
    return _emnet.run_study(scene._handle, keys, values, **options)


def _frame(keys: list[str], values: NDArray[numpy.float64], first_variant: int,
           part: Mapping[str, Any]) -> "pandas.DataFrame":
    import pandas

    data: dict[str, Any] = {"variant": range(first_variant, first_variant + len(values))}
    for index, key in enumerate(keys):
        data[key] = values[:, index]
    data["status"] = part["status"]
    data["validity"] = part["validity"]
    for index, column in enumerate(part["columns"]):
        data[column] = part["results"][:, index]
    return pandas.DataFrame(data)


@contextlib.contextmanager
def _progress_reporter(progress: Any, total: int, unit: str) -> Iterator[Any]:
    """What a study reports its progress to: for True a tqdm bar (a widget in a notebook with
    ipywidgets, a line on standard error otherwise; without tqdm, the library's own line "emnet
    study: done/total" on standard error), a callable as it is (called as callable(done, total,
    what), at most every 0.1 s and at the end), nothing for False. The bar is closed at the end,
    also when the study is interrupted."""
    if callable(progress) or not progress:
        yield progress if callable(progress) else False
        return
    try:
        import tqdm
    except ImportError:
        yield True
        return
    # tqdm.auto draws a widget in a notebook with ipywidgets, and without it warns.
    widgets = importlib.util.find_spec("ipywidgets") is not None
    bar_class: Any = importlib.import_module("tqdm.auto").tqdm if widgets else tqdm.tqdm
    bar = bar_class(total=total, desc="emnet study", unit=unit, file=sys.stderr)

    def report(done: int, total: int, what: str) -> None:
        bar.total = total
        bar.update(done - bar.n)

    try:
        yield report
    finally:
        bar.close()


def study(scene: SceneLike, vary: Optional[Vary] = None, *, samples: Integer = 0,
          seed: Integer = 1, variants: Optional[Variants] = None,
          analyses: Texts = ("modes",), modes: Integer = 1,
          sweep_frequencies: Optional[Numbers] = None, at: Numbers = (), threads: Integer = 0,
          client: Any = None, chunk_size: Optional[Integer] = None,
          progress: Any = False) -> "pandas.DataFrame":
    """A design study: every variant of `scene` through `analyses`, a row per variant.

    Parameters
    ----------
    scene : Scene, str or os.PathLike
        The scene, or a scene file's path.
    vary, samples, seed, variants
        The variants, as emnet.variants takes them.
    analyses : str or sequence of str, default ("modes",)
        Any of:

        - "modes": f<k>_hz [Hz], zeta<k> [-], f<k>_error_hz [Hz] for the `modes` lowest modes;
        - "static": static.<probe>_<unit> per probe of the scene;
        - "sweep-switching": sweep.peak_hz [Hz], and per output and frequency of `at`
          sweep.<output>.min_at_<f>Hz_<unit>, .max_at_... (the periodic extremes).
    modes : int, default 1
        The modes reported, lowest first.
    sweep_frequencies : sequence of float, optional
        The sweep's switching frequencies [Hz] (default: 1 to 7 Hz in steps of 0.1).
    at : sequence of float, default ()
        The frequencies of the sweep whose extremes are columns [Hz].
    threads : int, default 0
        Worker threads in this process (0: every core).
    client : dask.distributed.Client, optional
        Run chunks of variants on its workers, one thread per task; the rows come back in order,
        equal bit for bit to a local run's.
    chunk_size : int, optional
        Variants per task with a client (default: a quarter of an even share per worker, at
        least 20).
    progress : bool or callable, default False
        True: a progress bar of the variants (of the chunks with a client) done: tqdm's, a
        widget in a notebook where ipywidgets is installed, a line on standard error otherwise.
        A callable is called as progress(done, total, what) instead, at most every 0.1 s and at
        the end (from the study's threads, holding the GIL).

    Returns
    -------
    pandas.DataFrame
        variant, the varied keys [SI], status ("ok" or "failed: why"), validity ("within", or
        "OUTSIDE: " with each violation of the model's limits: deflection against
        model.deflection_limit, DEA fields against breakdown), the result columns (missing,
        NaN, in a failed row). df.attrs holds units {column: unit}, cost (seconds per stage
        summed over the variants, work and wall seconds [s]), segments, unknowns, notes,
        failed and outside_validity (counts).

    Raises
    ------
    InputError
        A bad keyword value (.where and .key name the keyword) or variation.
    """
    started = time.perf_counter()
    scene = as_scene(scene)
    table = _variant_table(scene, vary, samples, seed, variants)
    keys = list(table.columns)
    values = numpy.ascontiguousarray(table.to_numpy(dtype=float))
    options: dict[str, Any] = {
        "analyses": ",".join(texts(analyses, "analyses")), "modes": integer(modes, "modes"),
        "sweep_frequencies": numbers(sweep_frequencies, "sweep_frequencies"),
        "report_frequencies": numbers(at, "at")}
    if client is None:
        with _progress_reporter(progress, len(values), "variant") as report:
            parts = [(0, values, _emnet.run_study(scene._handle, keys, values,
                                                  threads=integer(threads, "threads"),
                                                  progress=report, **options))]
    else:
        workers = client.scheduler_info()["workers"]
        if not workers:
            raise input_error("the Dask cluster has no workers", "client", "client")
        chunk_size = (max(20, math.ceil(len(values) / (4 * len(workers)))) if chunk_size is None
                      else integer(chunk_size, "chunk_size"))
        if chunk_size < 1:
            raise input_error("must be >= 1", "chunk_size", "chunk_size")
        state = scene.__getstate__()
        starts = list(range(0, len(values), chunk_size))
        chunks = [values[start:start + chunk_size] for start in starts]
        task_options = dict(options, threads=1, progress=False)
        futures = client.map(_run_chunk, [state] * len(chunks), [keys] * len(chunks), chunks,
                             [task_options] * len(chunks), pure=False)
        results = []
        with _progress_reporter(progress, len(futures), "chunk") as report:
            for done, future in enumerate(futures, 1):
                results.append(future.result())
                if callable(report):
                    report(done, len(futures), "chunks")
                elif report:
                    print(f"\remnet study: {done}/{len(futures)} chunks",
                          end="\n" if done == len(futures) else "", flush=True, file=sys.stderr)
        parts = list(zip(starts, chunks, results))
    import pandas

    frame = pandas.concat([_frame(keys, chunk, start, part) for start, chunk, part in parts],
                          ignore_index=True)
    first = parts[0][2]
    units = {"variant": ""}
    units.update(dict(zip(first["keys"], first["key_units"])))
    units["status"] = ""
    units["validity"] = ""
    units.update(dict(zip(first["columns"], first["units"])))
    cost = {name: sum(part["cost"][name] for _, _, part in parts)
            for name in first["cost"] if name != "wall_seconds"}
    cost["wall_seconds"] = time.perf_counter() - started
    cost["per_variant_seconds"] = cost["work_seconds"] / max(1, len(frame))
    frame.attrs.update({"units": units, "cost": cost, "segments": first["segments"],
                        "unknowns": first["unknowns"], "notes": list(first["notes"]),
                        "failed": int(sum(part["failed"] for _, _, part in parts)),
                        "outside_validity": int(sum(part["outside_validity"]
                                                    for _, _, part in parts))})
    return frame
