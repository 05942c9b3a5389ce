// stengmc._core.Study: a study read and validated by the library (io/study.hpp), without
// a realisation drawn; run() and run_ensemble() draw what they need from it.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "io/study.hpp"

namespace py = pybind11;

namespace stengmc::python {

void bind_study(py::module_& m) {
  py::class_<Study, std::shared_ptr<Study>>(m, "Study", "A study file read and checked (README: study files)")
      .def_readonly("file", &Study::file, "the path it was read from (or the name given to its text)")
      .def_readonly("text", &Study::text, "the study text, verbatim")
      .def_readonly("title", &Study::title)
      .def_readonly("seed", &Study::seed, "master seed")
      .def_readonly("duration_s", &Study::duration_s, "simulated time [s]")
      .def_readonly("sample_rate_hz", &Study::sample_rate_hz, "output sample rate [Hz]")
      .def_readonly("surface_file", &Study::surface_file, "the surface file it names, or '' when inline")
      .def_readonly("output_file", &Study::output_file, "where `stengmc run` would write")
      .def_property_readonly("model", [](const Study& s) { return std::string(model_name(s.model)); })
      .def_property_readonly("random_surface", [](const Study& s) { return s.surface->random_surface(); },
                             "true when every realisation draws its own asperities")
      .def_property_readonly("is_ensemble", [](const Study& s) { return s.ensemble.has_value(); },
                             "true when the study has an [ensemble] table")
      .def_property_readonly(
          "realisations",
          [](const Study& s) -> std::optional<std::uint64_t> {
            if (!s.ensemble) return std::nullopt;
            return s.ensemble->realisations;
          },
          "[ensemble] realisations, or None");

  m.def(
      "read_study", [](const std::string& path) { return std::make_shared<Study>(read_study(path, std::nullopt)); },
      py::arg("path"), "Reads and checks a study file; raises stengmc.InputError naming the file, line and key");
  m.def(
      "parse_study",
      [](const std::string& text, const std::string& file) {
        return std::make_shared<Study>(parse_study(text, file, std::nullopt));
      },
      py::arg("text"), py::arg("file"),
      "Checks a study given as TOML text; `file` names it in messages and relative surface paths start at its folder");
}

}  // namespace stengmc::python
