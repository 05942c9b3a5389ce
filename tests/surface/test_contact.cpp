// Contact mechanics of a sampled surface (MODEL.md §4): effective moduli and Mindlin
// stiffness against hand values, the Hertz load solve against its 1e-12 target and the
// Greenwood–Williamson closed form, Goryacheva-style spot interaction against Boussinesq.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "core/error.hpp"
#include "surface/hertz_contact.hpp"
#include "surface/interaction.hpp"
#include "surface/materials.hpp"

namespace stengmc {
namespace {

constexpr double pi = std::numbers::pi;
const ElasticBody PET{2.8e9, 0.4};
const ElasticBody STEEL{210e9, 0.3};
constexpr double E_STAR = 3.285870755750274e9;  // PET on steel, hand value below
constexpr double R_S = 50e-6;                   // summit radius [m]

std::vector<double> exponential_heights(std::size_t n, double sigma, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::exponential_distribution<double> dist(1.0 / sigma);
  std::vector<double> z(n);
  for (double& v : z) v = dist(rng);
  return z;
}

// Least-squares slope and intercept of y on x.
std::pair<double, double> fit_line(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i]; sy += y[i]; sxx += x[i] * x[i]; sxy += x[i] * y[i];
  }
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  return {slope, (sy - slope * sx) / n};
}

TEST(Materials, PetOnSteelAgainstHandValues) {
  // 1/E* = (1 - 0.16)/2.8e9 + (1 - 0.09)/210e9 = 3.0e-10 + 4.3333e-12 Pa^-1.
  // G_PET = 2.8e9/2.8 = 1e9, G_steel = 210e9/2.6; 1/G* = 1.6/G_PET + 1.7/G_steel.
  // Same formulas evaluated by hand (Python, double): only rounding can differ -> 1e-14.
  EXPECT_NEAR(effective_modulus(PET, STEEL) / 3.285870755750274e9, 1.0, 1e-14);
  EXPECT_NEAR(effective_modulus(STEEL, PET) / 3.285870755750274e9, 1.0, 1e-14);  // symmetric
  const double g_star = effective_shear_modulus(PET, STEEL);
  EXPECT_NEAR(g_star / 616885024.3816463, 1.0, 1e-14);
  EXPECT_NEAR(shear_modulus(PET), 1e9, 1e-5);
  // Mindlin k = 8 G* a at a = 10 um: 49350.80 N/m.
  EXPECT_NEAR(mindlin_stiffness(g_star, 10e-6) / 49350.801950531706, 1.0, 1e-14);
  EXPECT_EQ(mindlin_stiffness(g_star, 0.0), 0.0);
}

TEST(HertzContact, ExponentialHeightsFollowGreenwoodWilliamson) {
  // GW 1966 with phi(z) = exp(-z/s)/s: E[W(d)] = n (4/3) E* R^(1/2) Gamma(5/2) s^(3/2) exp(-d/s),
  // so log W is linear in d with slope -1/s. Sampling error, derived: per asperity
  // X = c (z - d)_+^(3/2) has E X = c s^1.5 Gamma(5/2) e^(-d/s), E X^2 = 6 c^2 s^3 e^(-d/s), so
  // W(d) has relative sd sqrt(6/(Gamma(5/2)^2 m) - 1/n), m = n e^(-d/s) expected contacts.
  // The fitted slope's error (correlated points) is taken from the spread over seeds.
  const std::size_t n = 20000;
  const double sigma = 1e-6;
  const int seeds = 16;
  const double c = (4.0 / 3.0) * E_STAR * std::sqrt(R_S);
  const double prefactor = static_cast<double>(n) * c * std::tgamma(2.5) * std::pow(sigma, 1.5);
  std::vector<double> d;
  for (int k = 0; k <= 8; ++k) d.push_back(0.5 * k * sigma);  // deepest d = 4 s: m ~ 366 contacts
  double slope_sum = 0, slope_sum2 = 0, pref_sum = 0, pref_sum2 = 0, w0_sum = 0;
  for (int s = 0; s < seeds; ++s) {
    const auto z = exponential_heights(n, sigma, 1000 + static_cast<std::uint64_t>(s));
    std::vector<double> log_w;
    for (double dk : d) log_w.push_back(std::log(hertz_contact_at_separation(z, R_S, E_STAR, dk).total_load_n));
    const auto [slope, intercept] = fit_line(d, log_w);
    slope_sum += slope * sigma; slope_sum2 += slope * sigma * slope * sigma;
    const double ratio = std::exp(intercept) / prefactor;
    pref_sum += ratio; pref_sum2 += ratio * ratio;
    w0_sum += std::exp(log_w[0]) / prefactor;
  }
  const double k = seeds;
  const double slope_mean = slope_sum / k;
  const double slope_se = std::sqrt((slope_sum2 / k - slope_mean * slope_mean) / (k - 1));
  const double pref_mean = pref_sum / k;
  const double pref_se = std::sqrt((pref_sum2 / k - pref_mean * pref_mean) / (k - 1));
  RecordProperty("slope_times_sigma", std::to_string(slope_mean) + " +- " + std::to_string(slope_se));
  RecordProperty("prefactor_ratio", std::to_string(pref_mean) + " +- " + std::to_string(pref_se));
  std::printf("GW fit: slope*sigma = %.4f +- %.4f, prefactor ratio = %.4f +- %.4f (%d seeds)\n", slope_mean,
              slope_se, pref_mean, pref_se, seeds);
  // 4 standard errors: a false failure has probability ~1e-3 even with t(15) tails.
  EXPECT_NEAR(slope_mean, -1.0, 4.0 * slope_se) << "se " << slope_se;
  EXPECT_NEAR(pref_mean, 1.0, 4.0 * pref_se) << "se " << pref_se;
  // The error bars must be the size the derivation says, else 4 se proves nothing:
  // at d = 0 (m = n) the pooled W has relative sd sqrt(6/Gamma(5/2)^2 - 1)/sqrt(k n).
  const double w0_sd = std::sqrt(6.0 / (std::tgamma(2.5) * std::tgamma(2.5)) - 1.0) / std::sqrt(k * n);
  EXPECT_NEAR(w0_sum / k, 1.0, 4.0 * w0_sd);
  EXPECT_LT(slope_se, 0.02);
  EXPECT_LT(pref_se, 0.03);
}

TEST(HertzContact, LoadSolveMeetsTargetOverSixDecades) {
  // Heights carry a 1 mm offset over 1 um roughness so d must be resolved to ~1e-19 m
  // relative to it: the solve works in depth below the top summit, which keeps that.
  auto z = exponential_heights(10000, 1e-6, 7);
  for (double& v : z) v += 1e-3;
  for (double w : {1e-3, 1e-2, 1e-1, 1.0, 1e1, 1e2, 1e3}) {
    const HertzContact c = solve_hertz_contact(z, R_S, E_STAR, w);
    // Independent check: rebuild every N_i from its delta_i and sum in long double.
    long double sum = 0;
    for (std::size_t i = 0; i < z.size(); ++i) {
      EXPECT_NEAR(c.load_n[i], hertz_load(c.interference_m[i], R_S, E_STAR), 1e-15 * w);
      sum += c.load_n[i];
    }
    EXPECT_LE(std::abs(static_cast<double>(sum) - w) / w, 1e-12) << "W = " << w;
    EXPECT_LE(c.load_relative_error, 1e-12);
    EXPECT_GE(c.contact_count, 1u);
    double area = 0;
    for (double a : c.patch_radius_m) area += pi * a * a;
    EXPECT_NEAR(c.real_area_m2 / area, 1.0, 1e-12);
    std::printf("W = %-6g N: %5zu contacts, %2d iterations, relative load error %.2e\n", w, c.contact_count,
                c.solver_iterations, c.load_relative_error);
  }
}

TEST(HertzContact, SingleSummitMatchesHertz) {
  // One sphere: delta = (3W / (4 E* R^1/2))^(2/3) (Johnson 1985, §4.2).
  const double w = 0.01;
  const HertzContact c = solve_hertz_contact({2e-6}, R_S, E_STAR, w);
  const double delta = std::pow(3.0 * w / (4.0 * E_STAR * std::sqrt(R_S)), 2.0 / 3.0);
  EXPECT_NEAR(c.interference_m[0] / delta, 1.0, 1e-12);
  EXPECT_NEAR(c.separation_m, 2e-6 - delta, 1e-12 * delta);
}

TEST(SpotInteraction, TwoSpotsGiveBoussinesq) {
  // Far field switched off (R_loc = 10 r > R_out = 5 r): each spot is displaced by the
  // other's point load only, N_other / (pi E* r); same arithmetic -> rounding (1e-14).
  const double r = 40e-6, n1 = 2e-3, n2 = 5e-3;
  const double a1 = 1e-6, a2 = 1.5e-6;
  InteractionSettings settings;
  settings.kernel = InteractionKernel::point_load;
  settings.localisation_radius_m = 10 * r;
  const auto s = spot_interaction({0.0, r}, {0.0, 0.0}, {n1, n2}, {a1, a2}, {2e-8, 4e-8}, E_STAR,
                                  pi * 25 * r * r, settings);
  EXPECT_EQ(s.far_field_m, 0.0);
  EXPECT_NEAR(s.extra_displacement_m[0] / (n2 / (pi * E_STAR * r)), 1.0, 1e-14);
  EXPECT_NEAR(s.extra_displacement_m[1] / (n1 / (pi * E_STAR * r)), 1.0, 1e-14);
  EXPECT_NEAR(s.relative[1], n1 / (pi * E_STAR * r) / 4e-8, 1e-14);
  EXPECT_EQ(s.overlapping_pairs, 0u);
  // Beyond R_loc the neighbour is not summed; it is part of the nominal pressure.
  settings.localisation_radius_m = 0.5 * r;
  EXPECT_EQ(spot_interaction({0.0, r}, {0.0, 0.0}, {n1, n2}, {a1, a2}, {2e-8, 4e-8}, E_STAR, pi * 0.04 * r * r,
                             settings).near_field_m[0], 0.0);
  // Hertz-pressure kernel: tends to the point load as 1 + x^2/10 + 9 x^4/280, x = a/r (series
  // of Johnson's §3.4 closed form); at x = 1/27 the omitted x^6 term is < 1e-9.
  settings.localisation_radius_m = 10 * r;
  settings.kernel = InteractionKernel::hertz_pressure;
  const double x2 = a2 / r;
  const auto h = spot_interaction({0.0, r}, {0.0, 0.0}, {n1, n2}, {a1, a2}, {2e-8, 4e-8}, E_STAR,
                                  pi * 25 * r * r, settings);
  EXPECT_NEAR(h.extra_displacement_m[0] / (n2 / (pi * E_STAR * r)), 1.0 + x2 * x2 * (0.1 + 9.0 / 280.0 * x2 * x2), 1e-9);
}

TEST(SpotInteraction, LoadRedistributionOfTwoSpotsMatchesItsClosedForm) {
  // Two spots, point loads, far field off: u_1 = N_2/(pi E* r), u_2 = N_1/(pi E* r). With
  // s_i = 2 E* a_i and u_bar = (s_1 u_1 + s_2 u_2)/(s_1 + s_2), the load moved is
  // s_1 |u_1 - u_bar| + s_2 |u_2 - u_bar| = 2 s_1 s_2 |u_1 - u_2| / (s_1 + s_2), over N_1 + N_2.
  // Equal spots push each other equally: nothing moves.
  const double r = 40e-6, n1 = 2e-3, n2 = 5e-3, a1 = 1e-6, a2 = 1.5e-6;
  InteractionSettings settings;
  settings.kernel = InteractionKernel::point_load;
  settings.localisation_radius_m = 10 * r;
  const auto s = spot_interaction({0.0, r}, {0.0, 0.0}, {n1, n2}, {a1, a2}, {2e-8, 4e-8}, E_STAR, pi * 25 * r * r, settings);
  const double s1 = 2 * E_STAR * a1, s2 = 2 * E_STAR * a2;
  const double u1 = n2 / (pi * E_STAR * r), u2 = n1 / (pi * E_STAR * r);
  const double expected = 2 * s1 * s2 * std::abs(u1 - u2) / (s1 + s2) / (n1 + n2);
  EXPECT_NEAR(s.load_redistribution / expected, 1.0, 1e-13);
  const auto equal = spot_interaction({0.0, r}, {0.0, 0.0}, {n1, n1}, {a1, a1}, {2e-8, 2e-8}, E_STAR, pi * 25 * r * r, settings);
  EXPECT_EQ(equal.load_redistribution, 0.0);
}

TEST(SpotInteraction, FarFieldEqualsUniformPressureOnAnnulus) {
  // Check of the far-field derivation: a square lattice of point loads p h^2 filling the
  // annulus R_loc < r < R_out, summed here exactly with the Boussinesq kernel, must give the
  // code's far-field term 2 p (R_out - R_loc) / E* (one spot carrying W = p A0, A0 = pi R_out^2).
  // Lattice error is O(h / R_loc) from the ragged circles: 0.5 % tolerance at R_loc = 50 h.
  const double h = 1e-6, r_loc = 50 * h, r_out = 250 * h, p = 1e4;
  double lattice = 0.0;
  for (int i = -250; i <= 250; ++i)
    for (int j = -250; j <= 250; ++j) {
      const double r = h * std::hypot(i, j);
      if (r > r_loc && r < r_out) lattice += p * h * h / (pi * E_STAR * r);
    }
  InteractionSettings settings;
  settings.localisation_radius_m = r_loc;
  const double area = pi * r_out * r_out;
  const auto s = spot_interaction({0.0}, {0.0}, {p * area}, {0.0}, {1e-9}, E_STAR, area, settings);
  EXPECT_NEAR(s.nominal_pressure_pa, p, 1e-12 * p);
  EXPECT_NEAR(s.far_field_m / lattice, 1.0, 5e-3);
  std::printf("far field %.6e m, lattice sum %.6e m (ratio - 1 = %.1e)\n", s.far_field_m, lattice,
              s.far_field_m / lattice - 1.0);
}

TEST(SpotInteraction, MagnitudeFallsAsSqrtOfContactDensity) {
  // Same load and interference per spot, same count n, nominal area growing 1000-fold.
  // Derivation: near field ~ 2 p R_loc / E*, far field 2 p (R_out - R_loc) / E*, with
  // N/(E* delta) = (4/3) a and R_loc, R_out both proportional to sqrt(A0) at fixed n,
  // give extra/delta = (8 / 3 pi) sqrt(n) sqrt(A_r/A0): slope 1/2 in log-log.
  // Positions are drawn afresh at each density, so only sampling noise perturbs it;
  // band 0.5 +- 0.05 (the uniform far-field part, ~7x the near one here, is deterministic).
  const std::size_t n = 2000;
  const double delta = 2e-8, a = std::sqrt(R_S * delta);
  const double load = hertz_load(delta, R_S, E_STAR);
  std::vector<double> log_density, log_mag, log_redistribution;
  double previous = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= 6; ++k) {
    const double density = 1e-1 * std::pow(10.0, -0.5 * k);  // A_r/A0 from 1e-1 to 1e-4
    const double area = static_cast<double>(n) * pi * a * a / density, side = std::sqrt(area);
    std::mt19937_64 rng(42 + static_cast<std::uint64_t>(k));
    std::uniform_real_distribution<double> u(0.0, side);
    std::vector<double> x(n), y(n);
    for (std::size_t i = 0; i < n; ++i) { x[i] = u(rng); y[i] = u(rng); }
    const auto s = spot_interaction(x, y, std::vector<double>(n, load), std::vector<double>(n, a),
                                    std::vector<double>(n, delta), E_STAR, area);
    EXPECT_LT(s.rms_relative, previous) << "A_r/A0 = " << density;
    previous = s.rms_relative;
    log_density.push_back(std::log(density));
    log_mag.push_back(std::log(s.rms_relative));
    log_redistribution.push_back(std::log(s.load_redistribution));
    const double predicted = 8.0 / (3.0 * pi) * std::sqrt(double(n)) * std::sqrt(density);
    std::printf("A_r/A0 = %.1e: interaction rms %.4f (homogeneous prediction %.4f), max %.3f, "
                "load redistribution %.4f, screening %.2e\n", density, s.rms_relative, predicted, s.max_relative,
                s.load_redistribution, screening_interaction_estimate(density));
  }
  const double slope = fit_line(log_density, log_mag).first;
  RecordProperty("magnitude_slope", std::to_string(slope));
  EXPECT_NEAR(slope, 0.5, 0.05);
  // The load redistribution (the non-uniform part, which a fixed W cannot absorb into d)
  // scales the same way but is set by the random close pairs, hence the wider band.
  const double slope_redistribution = fit_line(log_density, log_redistribution).first;
  std::printf("log-log slopes: rms %.4f, load redistribution %.4f\n", slope, slope_redistribution);
  EXPECT_NEAR(slope_redistribution, 0.5, 0.1);
}

TEST(SpotInteraction, InteractingModeShiftsLoadFromCrowdedSpots) {
  // Three equal summits: two 20 um apart, one far away. Interaction depresses the pair,
  // so at fixed W the lone summit must carry more than either of the pair; W stays met.
  const std::vector<double> z{1e-6, 1e-6, 1e-6}, x{0.0, 20e-6, 5e-3}, y{0.0, 0.0, 0.0};
  const double w = 0.02;
  InteractionSettings settings;
  settings.localisation_radius_m = 100e-6;
  const auto r = solve_interacting_contact(z, x, y, R_S, E_STAR, w, 1e-4, settings);
  EXPECT_TRUE(r.converged);
  EXPECT_LT(r.last_change, 1e-10);
  EXPECT_NEAR(r.contact.load_n[0], r.contact.load_n[1], 1e-12 * w);  // symmetric pair
  EXPECT_GT(r.contact.load_n[2], r.contact.load_n[0] * 1.001);
  EXPECT_LE(r.contact.load_relative_error, 1e-12);
  std::printf("interacting: %d iterations, loads %.6g %.6g %.6g N\n", r.iterations, r.contact.load_n[0],
              r.contact.load_n[1], r.contact.load_n[2]);
}

TEST(ContactBadInput, RejectedWithDocumentedErrors) {
  const std::vector<double> z{1e-6, 2e-6};
  EXPECT_THROW(solve_hertz_contact(z, R_S, E_STAR, 0.0), ModelError);
  EXPECT_THROW(solve_hertz_contact(z, R_S, E_STAR, -1.0), ModelError);
  EXPECT_THROW(solve_hertz_contact(z, R_S, E_STAR, std::numeric_limits<double>::infinity()), ModelError);
  EXPECT_THROW(solve_hertz_contact(z, R_S, E_STAR, std::nan("")), ModelError);
  EXPECT_THROW(solve_hertz_contact({}, R_S, E_STAR, 1.0), ModelError);
  EXPECT_THROW(solve_hertz_contact(z, 0.0, E_STAR, 1.0), InputError);
  EXPECT_THROW(solve_hertz_contact(z, R_S, -1.0, 1.0), InputError);
  EXPECT_THROW(effective_modulus({0.0, 0.3}, STEEL), InputError);
  EXPECT_THROW(effective_modulus({-2e9, 0.3}, STEEL), InputError);
  EXPECT_THROW(effective_modulus(PET, {210e9, 0.5}), InputError);
  EXPECT_THROW(effective_shear_modulus(PET, {210e9, -1.0}), InputError);
  EXPECT_THROW(effective_shear_modulus({2.8e9, 5.0}, STEEL), InputError);
  EXPECT_THROW(mindlin_stiffness(1e9, -1e-6), InputError);
  try {
    solve_hertz_contact({}, R_S, E_STAR, 1.0);
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("no asperities"), std::string::npos) << e.what();
  }
  try {
    effective_modulus(PET, {210e9, 0.7});
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("poisson_ratio = 0.7"), std::string::npos) << e.what();
  }
  EXPECT_THROW(spot_interaction({0.0, 0.0}, {0.0, 0.0}, {1.0, 1.0}, {0.0, 0.0}, {1e-9, 1e-9}, E_STAR, 1e-6),
               ModelError);  // coincident loaded spots, point-load kernel
}

}  // namespace
}  // namespace stengmc
