// stengmc._core.Surface and sample_surface: a surface's description (surface/surface.hpp),
// read from a study (its [surface], inline or the file it names) or from TOML text the
// package writes from keyword arguments, and one realisation of it as numpy arrays. The
// population is drawn by sample_population, as `stengmc surface` and `stengmc run
// --realisation` draw it, so a sample equals their files' arrays value for value.
#include <pybind11/stl.h>

#include <filesystem>
#include <functional>
#include <memory>

#include "bindings.hpp"
#include "core/error.hpp"
#include "core/toml_reader.hpp"
#include "ensemble/study_file.hpp"
#include "numpy_arrays.hpp"
#include "surface/surface.hpp"

namespace py = pybind11;

namespace stengmc::python {

namespace {

//! A surface the module holds, shared with the study it came from (if any).
struct SurfaceHandle {
  std::shared_ptr<const Surface> surface;
  std::string name;  //!< the file it was read from (or the name given to its text), for messages
};

//! Reads a surface file's root table as `stengmc surface` does: a study is refused (its
//! [surface] is reached through the study), every key nobody read is an error.
SurfaceHandle read_surface_document(TomlDocument& document, const std::string& name) {
  TomlTable root = document.root();
  if (root.has("duration_s") || root.has("model"))
    throw InputError(name + " is a study file, not a surface file: load it with stengmc.load_study and sample "
                            "study.surface");
  auto surface = std::make_shared<const Surface>(Surface::from_toml(root, std::filesystem::path(name).parent_path()));
  document.reject_unknown_keys();
  return {std::move(surface), name};
}

std::vector<double> asperity_column(const Population& p, const std::function<double(const Asperity&)>& field) {
  std::vector<double> out;
  out.reserve(p.asperities.size());
  for (const Asperity& a : p.asperities) out.push_back(field(a));
  return out;
}

//! One realisation as the package's dict (python/stengmc/surface.py documents every key).
py::dict population_dict(const Population& p, std::uint64_t seed, bool random) {
  py::dict summits;
  summits["height_m"] = to_numpy(p.height_m);
  summits["x_m"] = to_numpy(p.x_m);
  summits["y_m"] = to_numpy(p.y_m);
  summits["drive_phase_rad"] = to_numpy(p.drive_phase_rad);
  summits["onset_s"] = to_numpy(p.onset_s);
  summits["normal_load_n"] = to_numpy(p.load_n);
  if (!p.sampled_stiffness_n_per_m.empty()) summits["sampled_stiffness_n_per_m"] = to_numpy(p.sampled_stiffness_n_per_m);
  if (p.contact) {
    summits["interference_m"] = to_numpy(p.contact->interference_m);
    summits["patch_radius_m"] = to_numpy(p.contact->patch_radius_m);
  }

  py::dict asperities;
  asperities["stiffness_n_per_m"] = to_numpy(asperity_column(p, [](const Asperity& a) { return a.stiffness_n_per_m; }));
  asperities["mass_kg"] = to_numpy(asperity_column(p, [](const Asperity& a) { return a.mass_kg; }));
  asperities["normal_load_n"] = to_numpy(asperity_column(p, [](const Asperity& a) { return a.normal_load_n; }));
  asperities["height_m"] = to_numpy(asperity_column(p, [](const Asperity& a) { return a.height_m; }));
  asperities["drive_phase_rad"] = to_numpy(asperity_column(p, [](const Asperity& a) { return a.drive_phase_rad; }));
  asperities["onset_s"] = to_numpy(asperity_column(p, [](const Asperity& a) { return a.onset_s; }));
  asperities["charge_density_c_per_m2"] =
      to_numpy(asperity_column(p, [](const Asperity& a) { return a.element.charge_density_c_per_m2; }));
  asperities["effective_thickness_m"] =
      to_numpy(asperity_column(p, [](const Asperity& a) { return a.element.effective_thickness_m; }));
  asperities["width_m"] = to_numpy(asperity_column(p, [](const Asperity& a) { return a.element.width_m; }));
  asperities["length_m"] = to_numpy(asperity_column(p, [](const Asperity& a) { return a.element.length_m; }));
  // A fixed list's asperities are no summits: no index then.
  if (random) asperities["summit"] = to_numpy_int64(p.summit_of_asperity);

  py::dict out;
  out["realisation"] = p.realisation;
  out["seed"] = seed;
  out["summits"] = summits;
  out["asperities"] = asperities;
  if (p.contact) {
    const PopulationContact& c = *p.contact;
    py::dict contact;
    contact["summit_radius_m"] = c.summit_radius_m;
    contact["separation_m"] = c.separation_m;
    contact["total_load_n"] = c.total_load_n;
    contact["real_area_m2"] = c.real_area_m2;
    contact["contact_density"] = c.contact_density;
    contact["screening_estimate"] = c.screening_estimate;
    contact["hertz_load"] = c.hertz_load;
    contact["load_carried"] = c.load_carried;
    contact["interacting_iterations"] = c.interacting_iterations;
    contact["interacting_converged"] = c.interacting_converged;
    out["contact"] = contact;
  } else {
    out["contact"] = py::none();
  }
  return out;
}

}  // namespace

void bind_surface(py::module_& m) {
  py::class_<SurfaceHandle>(m, "Surface", "A surface's description, read and checked (docs/study-files.md: surface files)")
      .def_readonly("name", &SurfaceHandle::name, "the file it was read from, or the name given to its text")
      .def_property_readonly(
          "is_random", [](const SurfaceHandle& s) { return s.surface->random_surface() != nullptr; },
          "true for a random surface (kind = \"random\"), false for a fixed list of asperities");

  m.def(
      "study_surface",
      [](const StudyFile& study) {
        return SurfaceHandle{study.surface, study.surface_file.empty() ? study.file : study.surface_file};
      },
      py::arg("study"), "The surface a study's realisations draw from (its [surface], inline or the file it names)");
  m.def(
      "read_surface",
      [](const std::string& path) { return read_surface_document(*TomlDocument::from_file(path), path); },
      py::arg("path"), "Reads and checks a surface file; raises stengmc.InputError naming the file, line and key");
  m.def(
      "parse_surface",
      [](const std::string& text, const std::string& name) {
        return read_surface_document(*TomlDocument::from_string(text, name), name);
      },
      py::arg("text"), py::arg("name"),
      "Checks a surface given as TOML text; `name` stands for its file in messages and relative paths");
  m.def(
      "sample_surface",
      [](const SurfaceHandle& s, std::uint64_t seed, std::uint64_t realisation) {
        Population population;
        {
          py::gil_scoped_release release;
          population = s.surface->sample(seed, realisation);
        }
        return population_dict(population, seed, s.surface->random_surface() != nullptr);
      },
      py::arg("surface"), py::arg("seed"), py::arg("realisation"),
      "Realisation `realisation` of the surface under `seed`, as `stengmc surface --seed` draws it");
}

}  // namespace stengmc::python
