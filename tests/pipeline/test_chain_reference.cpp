// The whole chain (tribology -> circuit) of the paper's four asperities against an
// independent solution of the same physics: the coupled system of MODEL.md §1 and §2
// integrated at once by Boost.Odeint's rosenbrock4 (support/coupled_chain_reference.hpp:
// ten equations written out again from MODEL.md, no stengmc code shared) at a tolerance
// 1e4 times tighter than the default. The accuracy bars for the chain are relative
// L2 errors over the whole record of <= 1e-4 in V and <= 1e-5 in Q.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "pipeline/study.hpp"
#include "pipeline/run_study.hpp"
#include "support/coupled_chain_reference.hpp"

namespace stengmc {
namespace {

test::ChainSolution reference_for(const Study& study, const std::vector<double>& times_s, double tolerance) {
  std::vector<test::ChainAsperity> asperities;
  for (const Asperity& a : study.asperities)
    asperities.push_back({a.stiffness_n_per_m, a.mass_kg, a.normal_load_n, a.initial_displacement_m,
                          a.initial_velocity_m_per_s, a.element.charge_density_c_per_m2,
                          a.element.effective_thickness_m, a.element.width_m, a.element.length_m});
  const Model2Params& m = study.model2;
  const test::ChainParameters params{m.friction.static_coefficient, m.friction.kinetic_coefficient,
                                     m.belt_velocity_m_per_s, m.damping_n_s_per_m, m.stribeck_decay_s_per_m,
                                     m.atan_sharpness_s_per_m, study.circuit.load_resistance_ohm,
                                     study.circuit.load_capacitance_f};
  return test::coupled_chain_reference(asperities, params, times_s, tolerance);
}

double relative_l2(const std::vector<double>& reference, const std::vector<double>& value) {
  double difference = 0.0, norm = 0.0;
  for (std::size_t j = 0; j < reference.size(); ++j) {
    difference += (reference[j] - value[j]) * (reference[j] - value[j]);
    norm += reference[j] * reference[j];
  }
  return std::sqrt(difference / norm);
}

Study paper_chain(double belt_velocity) {
  const std::string name = belt_velocity == 1.0 ? "fig6_vb1_l50" : "fig6_vb10_l50";
  Study study = read_study(std::string(STENGMC_SOURCE_DIR) + "/studies/paper/" + name + ".toml");
  study.spectrum.reset();  // the chain only
  return study;
}

// The reference's own error is far below the bars: rosenbrock4 at 1e-12 and at 1e-13
// agree to 2e-11 in V and 6e-13 in Q (measured; 1e-11 against 1e-13: 2.5e-10, 7e-12), so
// what this measures is ours (before issue 12: V 3.3e-6 / 1.9e-6, Q 3.7e-6 / 2.6e-7 at
// v_b = 1 / 10 m/s, the Q error at v_b = 1 from the circuit stepping over the belt catch).
TEST(ChainReference, FourAsperitiesVoltageAndChargeAgreeWithCoupledRosenbrock) {
  for (const double belt_velocity : {1.0, 10.0}) {
    const Study study = paper_chain(belt_velocity);
    ASSERT_EQ(study.model, ModelKind::model2);
    ASSERT_EQ(study.model2.friction_law->name, "consistent");  // the form the reference writes out
    const RunResult run = run_study(study, RunOptions{.show_progress = false});
    ASSERT_TRUE(run.valid);
    const test::ChainSolution ref = reference_for(study, run.times_s, 1e-12);
    ASSERT_EQ(ref.voltage_v.size(), run.circuit.voltage_v.size());
    const double error_v = relative_l2(ref.voltage_v, run.circuit.voltage_v);
    const double error_q = relative_l2(ref.charge_c, run.circuit.charge_c);
    std::printf("v_b = %g m/s: relative L2 error vs coupled rosenbrock4: V %.3e, Q %.3e\n", belt_velocity, error_v,
                error_q);
    RecordProperty("error_v_vb" + std::to_string(static_cast<int>(belt_velocity)), std::to_string(error_v));
    RecordProperty("error_q_vb" + std::to_string(static_cast<int>(belt_velocity)), std::to_string(error_q));
    EXPECT_LE(error_v, 1e-4) << "v_b = " << belt_velocity;
    EXPECT_LE(error_q, 1e-5) << "v_b = " << belt_velocity;
  }
}

}  // namespace
}  // namespace stengmc
