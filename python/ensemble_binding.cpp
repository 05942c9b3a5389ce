// stengmc._core.run_ensemble: an [ensemble] study's realisations (ensemble/ensemble_runner.hpp)
// on threads, with the records and statistics `stengmc run` writes to the ensemble file
// (io/ensemble_file.hpp), as nested dicts of numpy arrays named as the file's datasets.
#include <pybind11/stl.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <type_traits>
#include <variant>

#include "bindings.hpp"
#include "ensemble/ensemble_runner.hpp"
#include "ensemble/ensemble_summary.hpp"
#include "ensemble/record_table.hpp"
#include "ensemble/sweep.hpp"
#include "numpy_arrays.hpp"

namespace py = pybind11;

namespace stengmc::python {

namespace {

//! A private folder for the runner's journals, removed with everything in it: the module
//! returns its results instead of writing a file, so nothing is kept to resume from.
class JournalFolder {
 public:
  JournalFolder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "stengmc-python-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw Error("cannot create a folder for the ensemble journal in " + pattern);
    path_ = pattern;
  }
  ~JournalFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  JournalFolder(const JournalFolder&) = delete;
  JournalFolder& operator=(const JournalFolder&) = delete;
  [[nodiscard]] std::string journal(std::size_t point, std::size_t count) const {
    return journal_path((path_ / "ensemble.h5").string(), point, count);
  }

 private:
  std::filesystem::path path_;
};

//! /realisations/ and /asperities/ of the ensemble file: one entry per realisation (by
//! grid point, then id) and the per-asperity columns flat over them.
void add_records(py::dict& out, const std::vector<GridPoint>& grid) {
  RecordTable t = tabulate_records(grid);
  py::dict realisations;
  realisations["grid_point"] = to_numpy(std::move(t.grid_point));
  realisations["realisation"] = to_numpy(std::move(t.realisation));
  realisations["valid"] = to_numpy(std::move(t.valid));
  realisations["failure"] = t.failure;
  realisations["asperity_offset"] = to_numpy(std::move(t.asperity_offset));
  for (std::size_t k = 0; k < SCALAR_COUNT; ++k)
    realisations[py::str(std::string(scalar_info(static_cast<Scalar>(k)).name))] = to_numpy(std::move(t.scalars[k]));
  py::dict asperities;
  for (std::size_t c = 0; c < ASPERITY_COLUMN_COUNT; ++c)
    asperities[py::str(std::string(column_info(static_cast<AsperityColumn>(c)).name))] =
        to_numpy(std::move(t.asperities[c]));
  out["realisations"] = realisations;
  out["asperities"] = asperities;
}

//! /traces/: the kept traces, keyed "realisation_<r>" (under "point_<g>" in a sweep).
void add_traces(py::dict& out, const std::vector<GridPoint>& grid) {
  py::dict traces;
  for (std::size_t g = 0; g < grid.size(); ++g) {
    py::dict point;
    for (const RealisationRecord& r : grid[g].run.records) {
      if (r.time_s.empty()) continue;
      py::dict trace;
      trace["time_s"] = to_numpy(r.time_s);
      trace["voltage_v"] = to_numpy(r.voltage_v);
      trace["charge_c"] = to_numpy(r.charge_c);
      if (!r.measured_voltage_v.empty()) trace["measured_voltage_v"] = to_numpy(r.measured_voltage_v);
      point[py::str("realisation_" + std::to_string(r.realisation))] = trace;
    }
    if (grid.size() == 1) traces = point;
    else traces[py::str("point_" + std::to_string(g))] = point;
  }
  out["traces"] = traces;
}

//! /summary/: every scalar's statistics, the pooled ratios and the target, per grid point.
void add_summary(py::dict& out, const std::vector<GridPoint>& grid) {
  py::dict summary;
  for (SummaryColumn& c : tabulate_summary(grid)) {
    const py::str group(c.group);
    if (!summary.contains(group)) summary[group] = py::dict();
    py::dict columns = summary[group];
    std::visit(
        [&](auto& values) {
          if constexpr (std::is_same_v<std::decay_t<decltype(values)>, std::vector<std::string>>)
            columns[py::str(c.name)] = values;
          else
            columns[py::str(c.name)] = to_numpy(std::move(values));
        },
        c.values);
  }
  out["summary"] = summary;
}

//! /grid/ of a sweep, and the table `stengmc run` prints for each point.
void add_grid(py::dict& out, const StudyFile& base, const std::vector<GridPoint>& grid) {
  std::string text;
  std::size_t run = 0, valid = 0;
  double seconds = 0.0;
  for (const GridPoint& point : grid) {
    if (grid.size() > 1) text += "point " + describe_grid_point(point) + ":\n";
    text += format_ensemble_summary(point.summary, point.run);
    run += point.run.records.size();
    valid += point.summary.valid;
    seconds += point.run.seconds;
  }
  if (!base.ensemble->sweep.empty()) {
    py::list names;
    for (const SweepAxis& axis : base.ensemble->sweep) names.append(axis.parameter);
    py::dict g;
    g["parameter"] = names;
    g["values"] = rows_to_numpy(tabulate_grid(grid));
    out["grid"] = g;
  }
  if (!base.ensemble->draws.empty()) {
    // /draws/: each [[ensemble.draw]]'s value per realisation, in the order of "realisations".
    py::list names;
    for (const DrawAxis& d : base.ensemble->draws) names.append(d.parameter);
    py::dict d;
    d["parameter"] = names;
    d["values"] = rows_to_numpy(tabulate_draws(base.ensemble->draws, grid));
    out["draws"] = d;
  }
  out["realisations_requested"] = base.ensemble->realisations;
  out["realisations_run"] = run;
  out["valid_realisations"] = valid;
  out["threads"] = grid.front().run.threads;
  out["seconds"] = seconds;
  out["text"] = text;
}

//! The Python callable `on_progress(done, total)` over the whole job (every grid point of a
//! sweep, each of the study's realisations), called from the worker that delivers a record:
//! it takes the interpreter's lock for the call (the computing thread released it). An
//! exception it raises stops the ensemble and comes out of run_ensemble.
//! A handle, not an object: copying the std::function (without the lock) must not touch the
//! callable's reference count; run_ensemble's caller holds the callable until it returns.
std::function<void(std::size_t, std::size_t)> python_progress(py::handle on_progress, std::size_t before,
                                                               std::size_t job_total) {
  if (on_progress.is_none()) return {};
  return [on_progress, before, job_total](std::size_t done, std::size_t) {
    py::gil_scoped_acquire acquire;
    on_progress(before + done, job_total);
  };
}

py::dict run_ensemble_study(const StudyFile& base, int threads, bool progress, const py::object& on_progress) {
  if (!base.ensemble)
    throw InputError(base.file + ": has no [ensemble] table: run one realisation with run(), or add [ensemble]");
  if (threads < 0 || threads > MAX_THREADS)
    throw InputError("threads = " + std::to_string(threads) + ": expected 0 (every core) to " + std::to_string(MAX_THREADS));
  std::vector<GridPoint> grid;
  {
    py::gil_scoped_release release;
    const JournalFolder journals;
    grid = prepare_grid(base);
    for (std::size_t g = 0; g < grid.size(); ++g) {
      EnsembleOptions options{.threads = threads, .restart = true, .show_progress = progress,
                              .limits = WorkLimits{}};
      const std::size_t per_point = base.ensemble->realisations;
      options.on_record = python_progress(on_progress, g * per_point, grid.size() * per_point);
      if (grid.size() > 1) options.progress_label = "point " + std::to_string(g + 1) + "/" + std::to_string(grid.size());
      grid[g].run = run_ensemble(grid[g].study, journals.journal(g, grid.size()), options);
      grid[g].summary = summarise_ensemble(grid[g].run.records, base.seed);
    }
  }
  py::dict out;
  add_records(out, grid);
  add_traces(out, grid);
  add_summary(out, grid);
  add_grid(out, base, grid);
  return out;
}

}  // namespace

void bind_ensemble(py::module_& m) {
  m.attr("MAX_THREADS") = MAX_THREADS;  // stengmc.Study.run_ensemble checks `threads` against it
  m.def("run_ensemble", &run_ensemble_study, py::arg("study"), py::arg("threads") = 0, py::arg("progress") = false,
        py::arg("on_progress") = py::none(),
        "Runs every realisation of an [ensemble] study (each grid point of a sweep) on `threads` threads "
        "(0: OMP_NUM_THREADS or every core); the ensemble file's records and statistics as dicts. progress: the "
        "library's bar on stderr; on_progress: a callable (done, total) over the whole job");
}

}  // namespace stengmc::python
