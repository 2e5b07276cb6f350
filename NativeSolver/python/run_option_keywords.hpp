#pragma once
// The run options' Python keywords and Scene properties, made from the run options table
// (lightsolver/run_options.hpp): names, defaults, ranges and help in one place.
#include <pybind11/pybind11.h>

#include <functional>
#include <initializer_list>
#include <string>

#include "lightsolver/run_options.hpp"

/// Which rows a function takes as keywords.
using KeywordFilter = std::function<bool(const lightsolver::RunOptionInfo&)>;

/// Every row with a Python keyword (solve()).
bool every_keyword(const lightsolver::RunOptionInfo& row);
/// The rows a Simulation's run() takes (not those fixed when it is built: threads, backend).
bool per_run_keyword(const lightsolver::RunOptionInfo& row);
/// The rows cost() and study() take (seed, confidence, threads, backend).
bool checkpointed_keyword(const lightsolver::RunOptionInfo& row);

/// How a Python call started a run, for the results' provenance: "python: lightsolver.solve"
/// ("Simulation.<function>" for `run`, `refine` and `combine`), then " in " and sys.argv where
/// it is not empty.
std::string python_command(const char* function);

/// Sets `options` from the keywords of a call: each must be a row `take` accepts or one of
/// `own` (the caller's own, skipped here); None leaves the option at its default. A value out
/// of the row's range raises InputError naming the keyword with the scene reader's message;
/// an unknown keyword raises TypeError as Python does.
/// Also sets `options.command` to python_command(function).
void set_run_options(const pybind11::kwargs& keywords, lightsolver::SolveOptions& options,
                     const KeywordFilter& take, std::initializer_list<const char*> own,
                     const char* function);

/// The keywords `take` accepts as docstring lines: "photons=None: Photon paths ...".
std::string keywords_doc(const KeywordFilter& take);

/// Scene properties for every scene setting (photons, seed, confidence, ...), range-checked.
void bind_scene_settings(pybind11::class_<lightsolver::Scene>& scene);

/// `lightsolver.run_options()`: the table as a list of dicts.
pybind11::list run_options_list();
