// Atoms and the record model of the inverse estimation against the forward model itself
// (an independent path: the tribology's RODAS4 and the circuit's Radau IIA on every
// asperity, the shared circuit solved with all elements at once), and the friction's
// averaged damping against its small-amplitude closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "inverse/atom_library.hpp"
#include "inverse/friction_ratios.hpp"
#include "inverse/record_model.hpp"
#include "inverse/simulated_record.hpp"
#include "tribology/model2.hpp"

namespace stengmc {
namespace {

KnownDevice regime_device(double belt_velocity) {
  KnownDevice d;  // MODEL.md Table 1-2 values
  d.model.belt_velocity_m_per_s = belt_velocity;
  d.asperity.element.length_m = 50e-6;
  return d;
}

double relative_l2(const std::vector<double>& a, const std::vector<double>& b) {
  double e = 0.0, n = 0.0;
  for (std::size_t m = 0; m < a.size(); ++m) e += (a[m] - b[m]) * (a[m] - b[m]), n += b[m] * b[m];
  return std::sqrt(e / n);
}

// 30 us at 100 MHz: long enough for the tail to matter (the heads end ~5 us in), short
// enough for quick shapes.
const RecordGrid GRID{0.0, 1e-8, 3001};

//! Atoms for stiffnesses 30-300 N/m, loads 0.3-3 x the device's, its own damping.
AtomCoverage coverage_of(const KnownDevice& device) {
  AtomCoverage c;
  c.min_stiffness_n_per_m = 30.0;
  c.max_stiffness_n_per_m = 300.0;
  c.min_load_ratio = 0.3;
  c.max_load_ratio = 3.0;
  c.min_damping_rate = c.max_damping_rate = device.damping_rate_per_s();
  return c;
}

std::vector<double> model_voltage(const RecordModel& model, const std::vector<AtomParameters>& atoms, double d) {
  FitState state;
  state.atoms = atoms;
  state.damping_rate_per_s = d;
  std::vector<double> v(GRID.samples);
  model.voltage(state, v);
  return v;
}

TEST(InverseAtoms, MatchTheForwardModelForAnyStiffnessLoadAndOnset) {
  for (double v_b : {10.0, 5.0}) {
    const KnownDevice device = regime_device(v_b);
    const AtomLibrary library(device, GRID, coverage_of(device));
    const RecordModel model(library);
    // The shapes' own check (midpoints of their node grid); 1e-3 is what the record model
    // promises (MODEL_RELATIVE_ACCURACY) and what the evidence's noise floor assumes.
    EXPECT_LT(library.check_error(), 1e-3) << "v_b = " << v_b;
    const double n0 = device.asperity.normal_load_n;
    for (const SimulatedAsperity& a : {SimulatedAsperity{31.7, n0, 0.0}, SimulatedAsperity{98.2, 0.37 * n0, 3.3e-6},
                                       SimulatedAsperity{171.3, 2.6 * n0, 11.05e-6}, SimulatedAsperity{288.8, n0, 19.9e-6},
                                       SimulatedAsperity{55.55, 1.7 * n0, 0.0}}) {
      const std::vector<SimulatedAsperity> one = {a};
      const std::vector<double> exact = simulate_record(device, one, GRID);
      const std::vector<double> approx =
          model_voltage(model, {{a.stiffness_n_per_m, a.normal_load_n, a.onset_s}}, device.damping_rate_per_s());
      EXPECT_LT(relative_l2(approx, exact), 1e-3) << "v_b = " << v_b << ", k = " << a.stiffness_n_per_m << ", N = "
                                                  << a.normal_load_n << ", onset " << a.onset_s;
    }
  }
}

TEST(InverseAtoms, DerivativesMatchDifferences) {
  const KnownDevice device = regime_device(10.0);
  const AtomLibrary library(device, GRID, coverage_of(device));
  const AtomModel& model = library.model();
  const double d = device.damping_rate_per_s();
  // Central differences with h = 1e-5 (ln k, ln N) and 1e-13 s (onset, 1e-5 of a sample):
  // truncation ~h^2, round-off ~eps / h of the atom; the interpolants' derivatives are
  // those of the functions the values come from, so what is left is their smoothness.
  auto values = [&](const AtomParameters& a) {
    AtomValues v;
    model.evaluate(a, d, v, false);
    std::vector<double> full(GRID.samples, 0.0);
    for (std::size_t j = 0; j < v.u.size(); ++j) full[v.first + j] = v.u[j];
    return full;
  };
  for (const AtomParameters& a : {AtomParameters{45.0, 1e-3, 0.0}, AtomParameters{130.0, 0.6e-3, 4.321e-6}}) {
    AtomValues v;
    model.evaluate(a, d, v, true);
    auto analytic = [&](const std::vector<double>& part) {
      std::vector<double> full(GRID.samples, 0.0);
      for (std::size_t j = 0; j < part.size(); ++j) full[v.first + j] = part[j];
      return full;
    };
    auto central = [&](AtomParameters plus, AtomParameters minus, double h) {
      const std::vector<double> p = values(plus), m = values(minus);
      std::vector<double> fd(GRID.samples);
      for (std::size_t i = 0; i < GRID.samples; ++i) fd[i] = (p[i] - m[i]) / (2.0 * h);
      return fd;
    };
    const double h = 1e-5, ht = 1e-13;
    AtomParameters kp = a, km = a, np = a, nm = a, tp = a, tm = a;
    kp.stiffness_n_per_m *= std::exp(h), km.stiffness_n_per_m *= std::exp(-h);
    np.load_n *= std::exp(h), nm.load_n *= std::exp(-h);
    tp.onset_s += ht, tm.onset_s -= ht;
    EXPECT_LT(relative_l2(analytic(v.d_lnk), central(kp, km, h)), 1e-4) << "k = " << a.stiffness_n_per_m;
    EXPECT_LT(relative_l2(analytic(v.d_lnn), central(np, nm, h)), 1e-4) << "k = " << a.stiffness_n_per_m;
    // An onset on a sample (t = 0) puts the pick-up's kink there: a one-sided derivative at
    // that sample, which no difference matches. Off the samples it is smooth.
    if (a.onset_s > 0.0) {
      EXPECT_LT(relative_l2(analytic(v.d_onset), central(tp, tm, ht)), 1e-4) << "k = " << a.stiffness_n_per_m;
    }
  }
}

TEST(InverseAtoms, FrictionDampsLikeItsLinearisationForSmallAmplitudes) {
  // For A << 1, phi(A cos t) ~ 1 - F'(v_b) v_b A cos t / (N f_ref): G(A) = -F'(v_b) v_b A /
  // (2 N f_ref) (the cos^2 average). F' by a central difference of the law itself (h = 1e-3
  // m/s: F is smooth there, truncation ~1e-8 relative). At A = 1e-3 the neglected terms are
  // ~A^2 relative, far inside the 1e-3 tolerance.
  const KnownDevice device = regime_device(10.0);
  const FrictionRatios ratios(device);
  const double v_b = device.model.belt_velocity_m_per_s, h = 1e-3, load = device.asperity.normal_load_n;
  const double slope = (model2_friction(device.model, load, v_b + h) - model2_friction(device.model, load, v_b - h)) / (2.0 * h);
  const double f_ref = model2_friction(device.model, load, v_b) / load;
  EXPECT_NEAR(ratios.reference(), f_ref, 1e-12 * f_ref);
  const double a = 1e-3, expected = -slope * v_b * a / (2.0 * load * f_ref);
  EXPECT_NEAR(ratios.averaged_by_quadrature(a), expected, 1e-3 * std::abs(expected));
  EXPECT_NEAR(ratios.averaged(a), expected, 1e-3 * std::abs(expected));
  EXPECT_NEAR(ratios.linear_damping(), -expected / a, 1e-3 * std::abs(expected / a));
}

TEST(InverseRecordModel, MatchesTheSharedCircuitAndNeedsItsCoupling) {
  const KnownDevice device = regime_device(10.0);
  const AtomLibrary library(device, GRID, coverage_of(device));
  const RecordModel model(library);
  const double n0 = device.asperity.normal_load_n, d = device.damping_rate_per_s();
  // Six asperities of the device's load, all from t = 0; then of unequal loads and onsets.
  const std::vector<std::vector<SimulatedAsperity>> cases = {
      {{35.0, n0, 0.0}, {52.0, n0, 0.0}, {77.0, n0, 0.0}, {80.0, n0, 0.0}, {140.0, n0, 0.0}, {260.0, n0, 0.0}},
      {{35.0, n0, 0.0}, {52.0, 0.5 * n0, 2e-6}, {77.0, 1.4 * n0, 0.0}, {80.0, n0, 7.5e-6}, {140.0, 2.0 * n0, 0.0},
       {260.0, 0.8 * n0, 1e-6}}};
  for (const std::vector<SimulatedAsperity>& asperities : cases) {
    const std::vector<double> truth = simulate_record(device, asperities, GRID);
    std::vector<AtomParameters> atoms;
    for (const SimulatedAsperity& a : asperities) atoms.push_back({a.stiffness_n_per_m, a.normal_load_n, a.onset_s});
    const std::vector<double> v = model_voltage(model, atoms, d);
    std::vector<double> plain(GRID.samples, 0.0);
    for (const AtomParameters& a : atoms) {
      const std::vector<double> one = model_voltage(model, {a}, d);
      for (std::size_t m = 0; m < GRID.samples; ++m) plain[m] += one[m];
    }
    // Measured 1e-4 (equal loads) and 2e-4 (unequal, staggered); the plain sum of atoms,
    // without the elements' coupling through the shared load, is off by several times more.
    const double error = relative_l2(v, truth);
    EXPECT_LT(error, 1e-3);
    EXPECT_GT(relative_l2(plain, truth), 3.0 * error) << "the coupling terms should matter at n = 6";
  }
}

}  // namespace
}  // namespace stengmc
