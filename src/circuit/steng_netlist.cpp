#include "circuit/steng_netlist.hpp"

#include <algorithm>
#include <array>
#include <charconv>

namespace stengmc {

std::string spice_number(double value) {
  // The shortest text that reads back as the same double.
  std::array<char, 32> buffer{};
  const auto end = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value).ptr;
  return std::string(buffer.data(), end);
}

std::vector<std::string> steng_subcircuit_cards(double epsilon0_f_per_m) {
  // Parameters travel as node voltages in SI units, as in the paper. Bv is the open-circuit
  // voltage (paper Eq. 6); Bc writes the charge C(x) (V(vp) - V(n003)) of the element's
  // capacitor (Eq. 7) onto the 1 F capacitor Cc, so the current through the 0 V sense
  // source Vc is that charge's time derivative, which Fc copies into the branch vp -> n003.
  return {".subckt stengmc_element x sigma d0 w l vp vn",
          "Rx x 0 10G",
          "Bv n003 vn V=V(sigma)*V(d0)*V(x)/{epsilon0}/(V(l)-V(x))",
          "Fc vp n003 Vc 1",
          "Bc n001 0 V={epsilon0}*V(w)*(V(l)-V(x))/V(d0)*(V(vp)-V(n003))",
          "Vc n001 n002 0V",
          "Cc n002 0 1",
          ".param epsilon0=" + spice_number(epsilon0_f_per_m),
          ".ends stengmc_element"};
}

std::string steng_displacement_source_name(std::size_t index) { return "vstengmc_x" + std::to_string(index); }

std::vector<std::string> steng_port_cards(const std::string& port_node) {
  return {std::string("Vstengmc_port ") + STENG_ELEMENT_NODE + " " + port_node + " 0"};
}

std::string steng_element_current_vector(std::size_t index) {
  return "v.xstengmc_" + std::to_string(index) + ".vc#branch";
}

std::vector<std::string> steng_element_cards(std::size_t index, const StengElement& element,
                                             const std::string& displacement_source) {
  const std::string i = std::to_string(index);
  return {"Vstengmc_sig" + i + " stengmc_sig" + i + " 0 " + spice_number(element.charge_density_c_per_m2),
          "Vstengmc_d" + i + " stengmc_d" + i + " 0 " + spice_number(element.effective_thickness_m),
          "Vstengmc_w" + i + " stengmc_w" + i + " 0 " + spice_number(element.width_m),
          "Vstengmc_l" + i + " stengmc_l" + i + " 0 " + spice_number(element.length_m),
          "Vstengmc_x" + i + " stengmc_x" + i + " 0 " + displacement_source,
          "Xstengmc_" + i + " stengmc_x" + i + " stengmc_sig" + i + " stengmc_d" + i + " stengmc_w" + i + " stengmc_l" +
              i + " " + STENG_ELEMENT_NODE + " 0 stengmc_element"};
}

SpiceTransientSettings choose_transient(std::span<const StengElement> elements, double max_speed_m_per_s,
                                        double sample_step_s, double stop_time_s, double time_constant_s) {
  double current_scale = 0.0;  // sum sigma w |x'|max [A]
  double charge_scale = 0.0;   // largest sigma w l [C]
  for (const StengElement& e : elements) {
    current_scale += e.charge_density_c_per_m2 * e.width_m * max_speed_m_per_s;
    charge_scale = std::max(charge_scale, e.charge_density_c_per_m2 * e.width_m * e.length_m);
  }
  SpiceTransientSettings s;
  s.stop_time_s = stop_time_s;
  // ngspice's first step is a tenth of the print step, taken with backward Euler: below the
  // circuit's time constant R sum C or V starts ~8 % off (NGSPICE-NOTES). A tiny first step
  // costs a few dozen steps (the step at most doubles per step); every accepted step is
  // stored whatever the print step.
  s.print_step_s = std::min(1e-5 * sample_step_s, 0.1 * time_constant_s);
  // The print step would also be the maximum step. A tenth of the sample step: measured on
  // the paper's subcircuit against the built-in solver (tests/circuit/test_ngspice.cpp),
  // 1 sample step gives 1.2e-3 relative error on V, 1/10 3.4e-7.
  s.max_step_s = 0.1 * sample_step_s;
  // reltol 1e-6 (1e-8 aborts with "timestep too small"); the absolute tolerances scaled
  // to these femtocoulomb elements, or a defaults-only run is silently inaccurate. The
  // current's: reltol times the current scale. A thousandth of that (NGSPICE-NOTES) gives
  // the same V on the paper's resistor (relative L2 to the built-in 6.92e-6 against
  // 6.93e-6 at ngspice's 1e-12 A) but stops Newton at the diodes of a bridge rectifier
  // ("timestep too small", studies/circuits/bridge_rectifier.toml).
  s.reltol = 1e-6;
  s.abstol_a = std::max(s.reltol * current_scale, 1e-30);
  s.chgtol_c = std::max(1e-3 * s.reltol * charge_scale, 1e-35);
  // vntol stays ngspice's 1 uV. The subcircuit carries each element's charge as a node
  // voltage (~1e-15 V), which it waves through Newton's convergence test; but the
  // elements are linear once x(t) is known, so V does not depend on it (measured: vntol
  // 1 uV and 4e-23 V give the same V on the paper's resistor), while a charge-sized
  // vntol on a real node stops Newton at a diode (a bridge rectifier aborted with
  // "timestep too small").
  s.vntol_v = 1e-6;
  return s;
}

std::vector<std::string> transient_cards(const SpiceTransientSettings& s) {
  return {".options reltol=" + spice_number(s.reltol) + " abstol=" + spice_number(s.abstol_a) + " chgtol=" +
              spice_number(s.chgtol_c) + " vntol=" + spice_number(s.vntol_v) + " method=trap",
          ".tran " + spice_number(s.print_step_s) + " " + spice_number(s.stop_time_s) + " 0 " +
              spice_number(s.max_step_s)};
}

}  // namespace stengmc
