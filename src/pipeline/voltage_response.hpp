#pragma once
//! The cheap path from asperities to the load voltage: Model 2 tribology and the circuit of
//! MODEL.md §2 for one asperity (or a few) on a grid, with reusable buffers and no file
//! I/O, for callers that simulate thousands of variants of one device (inverse estimation:
//! the single sliding asperity's response against its stiffness).
#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include "circuit/circuit_solver.hpp"
#include "model/asperity.hpp"
#include "tribology/model2.hpp"
#include "tribology/time_grid.hpp"

namespace stengmc {

//! Everything voltage_response allocates, kept between calls (one per thread: a workspace
//! is not shared). After the first call of a size, later calls of that size allocate
//! nothing.
class VoltageWorkspace {
 public:
  VoltageWorkspace();
  ~VoltageWorkspace();
  VoltageWorkspace(const VoltageWorkspace&) = delete;
  VoltageWorkspace& operator=(const VoltageWorkspace&) = delete;

  struct Buffers;  //!< (internal)
  [[nodiscard]] Buffers& buffers() { return *buffers_; }

 private:
  std::unique_ptr<Buffers> buffers_;
};

//! What voltage_response computed: views into the workspace, valid until its next use.
struct VoltageResponse {
  std::span<const double> time_s;     //!< the grid [s]
  std::span<const double> voltage_v;  //!< V across the load [V]
  std::span<const double> charge_c;   //!< Q = integral of V/R dt, delivered to the load [C]
  std::size_t solver_steps = 0;       //!< tribology steps taken, all asperities
};

//! V(t) and Q(t) on `grid` of `asperities` (Model 2 with `model`; each with its S-TENG
//! element, initial state as given) in parallel on the load of `circuit`: exactly what
//! run_study computes for a Model 2 study with these asperities (same solvers, tolerance
//! and circuit), without validity notes, events, traces, spectra or files.
//! @throws ModelError when an element's x reaches its l (MODEL.md §2: the element formulas
//!         fail there), naming the asperity and time, or when the integrator fails
//! @throws InputError for invalid mechanical or circuit parameters
VoltageResponse voltage_response(std::span<const Asperity> asperities, const Model2Params& model,
                                 const CircuitParams& circuit, const TimeGrid& grid, VoltageWorkspace& workspace);

}  // namespace stengmc
