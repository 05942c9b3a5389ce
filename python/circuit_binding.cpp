// stengmc._core.circuit: the S-TENG elements and their load driven by displacements given as
// numpy arrays, as `stengmc circuit` drives them from a displacement file (its CSV: one
// element row each, the same element parameters for all, or per element here): the same
// checks (io/displacement_input.hpp), interpolation and solver (circuit/element_sums.hpp).
#include <pybind11/stl.h>

#include <memory>

#include "bindings.hpp"
#include "circuit/element_sums.hpp"
#include "core/error.hpp"
#include "io/displacement_input.hpp"
#include "numpy_arrays.hpp"
#include "tribology/domain_check.hpp"
#include "tribology/sampled_motion.hpp"

namespace py = pybind11;

namespace stengmc::python {

namespace {

//! An element parameter given once for all elements or once per element.
std::vector<double> per_element(const py::array_t<double, py::array::forcecast>& values, std::size_t elements,
                                const std::string& what) {
  std::vector<double> out = from_numpy(values, what);  // stengmc.circuit passes a scalar as one value
  if (out.size() == 1) out.assign(elements, out.front());
  if (out.size() != elements)
    throw InputError(what + ": " + std::to_string(out.size()) + " values for " + std::to_string(elements) +
                     " elements: expected one, or one per element");
  return out;
}

py::dict circuit(const py::array_t<double, py::array::forcecast>& x_m, const py::array_t<double, py::array::forcecast>& time_s,
                 const py::array_t<double, py::array::forcecast>& sigma, const py::array_t<double, py::array::forcecast>& d0,
                 const py::array_t<double, py::array::forcecast>& width, const py::array_t<double, py::array::forcecast>& length,
                 double load_resistance_ohm, double load_capacitance_f, const std::string& interpolation,
                 std::size_t substeps, const std::string& name) {
  DisplacementInput input;
  input.times_s = from_numpy(time_s, name + ": time_s");
  if (x_m.ndim() == 1) {
    input.x_m.push_back(from_numpy(x_m, name + ": x_m"));
  } else if (x_m.ndim() == 2) {
    const auto view = x_m.unchecked<2>();
    for (py::ssize_t i = 0; i < view.shape(0); ++i) {
      std::vector<double> row(static_cast<std::size_t>(view.shape(1)));
      for (py::ssize_t j = 0; j < view.shape(1); ++j) row[static_cast<std::size_t>(j)] = view(i, j);
      input.x_m.push_back(std::move(row));
    }
  } else {
    throw InputError(name + ": x_m: expected one displacement per sample (1-D) or elements x samples (2-D), got " +
                     std::to_string(x_m.ndim()) + " dimensions");
  }
  const std::size_t n = input.x_m.size();
  const auto s = per_element(sigma, n, name + ": charge_density_c_per_m2");
  const auto d = per_element(d0, n, name + ": effective_thickness_m");
  const auto w = per_element(width, n, name + ": width_m");
  const auto l = per_element(length, n, name + ": length_m");
  for (std::size_t i = 0; i < n; ++i) input.elements.push_back(StengElement{s[i], d[i], w[i], l[i]});
  validate(input, name);
  const Interpolation kind = parse_interpolation(interpolation, "interpolation");
  const CircuitParams params{load_resistance_ohm, load_capacitance_f, substeps};
  if (!(load_resistance_ohm > 0.0)) throw InputError(name + ": load_resistance_ohm must be > 0 [Ohm]");
  if (!(load_capacitance_f >= 0.0)) throw InputError(name + ": load_capacitance_f must be >= 0 [F]");
  if (substeps < 1) throw InputError(name + ": substeps must be >= 1");
  CircuitResult result;
  {
    py::gil_scoped_release release;
    std::vector<std::unique_ptr<Motion>> motions;
    std::vector<const Motion*> pointers;
    for (std::size_t i = 0; i < n; ++i) {
      const std::string element = name + ": element " + std::to_string(i + 1) + ": ";  // 1-based, as validate()
      try {
        motions.push_back(std::make_unique<SampledMotion>(input.times_s, input.x_m[i], kind));
        // A spline can overshoot l between samples that all stay below it (as `stengmc circuit`).
        if (const auto exit = first_domain_exit(*motions.back(), input.times_s, input.x_m[i], input.elements[i].length_m))
          throw InputError("x reaches l between samples, at t = " + std::to_string(*exit) +
                           " s; the S-TENG element formulas hold only for x < l");
      } catch (const InputError& e) {
        throw InputError(element + e.what());
      } catch (const ModelError& e) {
        throw InputError(element + e.what());
      }
      pointers.push_back(motions.back().get());
    }
    result = solve_circuit_streamed(input.elements, pointers, input.times_s, params);
  }
  py::dict out;
  out["time_s"] = to_numpy(input.times_s);
  out["voltage_v"] = to_numpy(result.voltage_v);
  out["charge_c"] = to_numpy(result.charge_c);
  out["current_a"] = rows_to_numpy(result.current_a);
  out["element_charge_c"] = rows_to_numpy(result.element_charge_c);
  return out;
}

}  // namespace

void bind_circuit(py::module_& m) {
  m.def("circuit", &circuit, py::arg("x_m"), py::arg("time_s"), py::arg("charge_density_c_per_m2"),
        py::arg("effective_thickness_m"), py::arg("width_m"), py::arg("length_m"), py::arg("load_resistance_ohm"),
        py::arg("load_capacitance_f"), py::arg("interpolation"), py::arg("substeps"), py::arg("name"),
        "The elements' voltage, charge and currents for displacements x_m [m] (elements x samples) at time_s [s]");
}

}  // namespace stengmc::python
