// stengmc._core.Study: a study read and validated by the library (ensemble/study_file.hpp), without
// a realisation drawn; run() and run_ensemble() draw what they need from it.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "ensemble/study_file.hpp"

namespace py = pybind11;

namespace stengmc::python {

void bind_study(py::module_& m) {
  py::class_<StudyFile, std::shared_ptr<StudyFile>>(m, "Study", "A study file read and checked (README: study files)")
      .def_readonly("file", &StudyFile::file, "the path it was read from (or the name given to its text)")
      .def_readonly("text", &StudyFile::text, "the study text, verbatim")
      .def_readonly("title", &StudyFile::title)
      .def_readonly("seed", &StudyFile::seed, "master seed")
      .def_readonly("duration_s", &StudyFile::duration_s, "simulated time [s]")
      .def_readonly("sample_rate_hz", &StudyFile::sample_rate_hz, "output sample rate [Hz]")
      .def_readonly("surface_file", &StudyFile::surface_file, "the surface file it names, or '' when inline")
      .def_property_readonly("output_file", [](const StudyFile& s) { return s.output.file; }, "where `stengmc run` would write")
      .def_property_readonly("model", [](const StudyFile& s) { return std::string(model_name(s.model)); })
      // A bool, as documented: the library's accessor returns the surface's description
      // (a RandomSurface pointer), a type the module does not expose.
      .def_property_readonly("random_surface", [](const StudyFile& s) { return s.surface->random_surface() != nullptr; },
                             "true when every realisation draws its own asperities")
      .def_property_readonly("is_ensemble", [](const StudyFile& s) { return s.ensemble.has_value(); },
                             "true when the study has an [ensemble] table")
      .def_property_readonly(
          "realisations",
          [](const StudyFile& s) -> std::optional<std::uint64_t> {
            if (!s.ensemble) return std::nullopt;
            return s.ensemble->realisations;
          },
          "[ensemble] realisations, or None");

  m.def(
      "read_study", [](const std::string& path) { return std::make_shared<StudyFile>(read_study_file(path, std::nullopt)); },
      py::arg("path"), "Reads and checks a study file; raises stengmc.InputError naming the file, line and key");
  m.def(
      "parse_study",
      [](const std::string& text, const std::string& file) {
        return std::make_shared<StudyFile>(parse_study_file(text, file, std::nullopt));
      },
      py::arg("text"), py::arg("file"),
      "Checks a study given as TOML text; `file` names it in messages and relative surface paths start at its folder");
}

}  // namespace stengmc::python
