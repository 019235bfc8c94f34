"""Parameter studies: sweep any parameter of any model, run the cases on Dask, get one Dataset.

A study file names a base model, the parameters to vary (dotted paths into the model, each with
a list of values, a range or a distribution), a sampler (grid, Latin hypercube, Sobol, Monte
Carlo) and the outputs to keep. :func:`run_study` runs every case through the same
:func:`drivedyn.run` as a single model, on a local Dask cluster or on a scheduler given by
address, caches each case under the hash of its model, and assembles one ``xarray.Dataset``::

    from drivedyn.study import run_study
    res = run_study("examples/study-pretension.toml", out="study-out")
    res.ds["pulleys.driven.slip"].sel({"belt.pretension": 550.0})

Modules: ``spec`` (the study file), ``design`` (samplers), ``cases`` (resolved models, cache,
the worker task), ``execute`` (Dask), ``collect`` (the Dataset), ``plots``; the ``drivedyn study``
command around them is drivedyn/front/study_command.py.
"""
from .design import Design, make_design
from .execute import StudyRun, run_study
from .plots import plot_key, plot_study
from .spec import Study, load_study, study_from_dict

__all__ = ["run_study", "load_study", "study_from_dict", "make_design", "plot_key", "plot_study",
           "Study", "StudyRun", "Design"]
