#include "core/format.hpp"
#include "surface/interaction.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <string>

#include "core/constants.hpp"
#include "core/error.hpp"

namespace stengmc {

namespace {

//! Normal displacement (both bodies, modulus E*) at distance r from a spot of load N and
//! patch radius a.
double kernel_displacement(InteractionKernel kernel, double load, double patch_radius, double r, double e_star) {
  if (kernel == InteractionKernel::point_load || patch_radius <= 0.0) {
    if (r <= 0.0) throw ModelError("spot interaction: two loaded spots at the same position (point-load kernel is singular)");
    return load / (PI * e_star * r);
  }
  // Hertz pressure p0 (1 - r^2/a^2)^(1/2), p0 = 3N / (2 pi a^2) (Johnson 1985, §3.4).
  const double a = patch_radius;
  const double p0 = 3.0 * load / (2.0 * PI * a * a);
  if (r <= a) return PI * p0 * (2.0 * a * a - r * r) / (4.0 * a * e_star);
  const double x = a / r;
  // Far from the patch the closed form cancels to O(x^3); its series avoids losing
  // eps/x^2 of relative accuracy: u = N/(pi E* r) (1 + x^2/10 + 9 x^4/280 + O(x^6)).
  if (x < 1e-2) return load / (PI * e_star * r) * (1.0 + x * x * (0.1 + 9.0 / 280.0 * x * x));
  return p0 / (2.0 * a * e_star) * ((2.0 * a * a - r * r) * std::asin(x) + a * std::sqrt(r * r - a * a));
}

//! Normal contact stiffness of a Hertz spot, dN/d delta = 2 E* a (Johnson 1985, §4.2).
double contact_stiffness(double effective_modulus_pa, double patch_radius_m) {
  return 2.0 * effective_modulus_pa * patch_radius_m;
}

//! Uniform cell list over the loaded spots, cell side >= R_loc so a query scans 3 x 3 cells.
class CellList {
 public:
  CellList(const std::vector<double>& x, const std::vector<double>& y, const std::vector<std::size_t>& sources,
           double radius) {
    x_min_ = y_min_ = HUGE_VAL;
    double x_max = -HUGE_VAL, y_max = -HUGE_VAL;
    for (std::size_t j : sources) {
      x_min_ = std::min(x_min_, x[j]);
      y_min_ = std::min(y_min_, y[j]);
      x_max = std::max(x_max, x[j]);
      y_max = std::max(y_max, y[j]);
    }
    const double ns = static_cast<double>(sources.size());
    const double lx = x_max - x_min_, ly = y_max - y_min_;
    // Cell side at least R_loc (3 x 3 scan suffices) and large enough that the cell
    // count stays O(n) even for a tiny R_loc or spots on a line.
    side_ = std::max({radius, std::sqrt(lx * ly / ns), std::max(lx, ly) / ns, 1e-300});
    nx_ = static_cast<std::size_t>(lx / side_) + 1;
    ny_ = static_cast<std::size_t>(ly / side_) + 1;
    start_.assign(nx_ * ny_ + 1, 0);
    for (std::size_t j : sources) ++start_[cell(x[j], y[j]) + 1];
    for (std::size_t c = 0; c < nx_ * ny_; ++c) start_[c + 1] += start_[c];
    members_.resize(sources.size());
    std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t j : sources) members_[fill[cell(x[j], y[j])]++] = j;
  }

  //! Calls visit(j) for every source in the 3 x 3 block of cells around (x, y).
  template <class Visit>
  void for_neighbours(double x, double y, Visit&& visit) const {
    const long cx = static_cast<long>(std::floor((x - x_min_) / side_));
    const long cy = static_cast<long>(std::floor((y - y_min_) / side_));
    for (long ix = std::max(cx - 1, 0L); ix <= std::min(cx + 1, static_cast<long>(nx_) - 1); ++ix)
      for (long iy = std::max(cy - 1, 0L); iy <= std::min(cy + 1, static_cast<long>(ny_) - 1); ++iy) {
        const std::size_t c = static_cast<std::size_t>(ix) * ny_ + static_cast<std::size_t>(iy);
        for (std::size_t k = start_[c]; k < start_[c + 1]; ++k) visit(members_[k]);
      }
  }

 private:
  std::size_t cell(double x, double y) const {
    const auto ix = std::min(static_cast<std::size_t>((x - x_min_) / side_), nx_ - 1);
    const auto iy = std::min(static_cast<std::size_t>((y - y_min_) / side_), ny_ - 1);
    return ix * ny_ + iy;
  }
  double x_min_, y_min_, side_;
  std::size_t nx_, ny_;
  std::vector<std::size_t> start_, members_;
};

}  // namespace

SpotInteraction spot_interaction(const std::vector<double>& x_m, const std::vector<double>& y_m,
                                 const std::vector<double>& load_n, const std::vector<double>& patch_radius_m,
                                 const std::vector<double>& interference_m, double effective_modulus_pa,
                                 double nominal_area_m2, const InteractionSettings& settings) {
  const std::size_t n = x_m.size();
  if (y_m.size() != n || load_n.size() != n || patch_radius_m.size() != n || interference_m.size() != n)
    throw InputError("spot interaction: positions, loads, patch radii and interferences must have equal lengths");
  if (!std::isfinite(effective_modulus_pa) || effective_modulus_pa <= 0.0)
    throw InputError("spot interaction: effective modulus E* = " + format_number(effective_modulus_pa) + " Pa must be > 0");
  if (!std::isfinite(nominal_area_m2) || nominal_area_m2 <= 0.0)
    throw InputError("spot interaction: nominal area A0 = " + format_number(nominal_area_m2) + " m^2 must be > 0");
  if (!(settings.localisation_radius_m >= 0.0) || !(settings.localisation_spacings > 0.0))
    throw InputError("spot interaction: localisation_radius_m must be >= 0 and localisation_spacings > 0");

  SpotInteraction s;
  s.near_field_m.assign(n, 0.0);
  s.extra_displacement_m.assign(n, 0.0);
  s.relative.assign(n, 0.0);
  s.outer_radius_m = std::sqrt(nominal_area_m2 / PI);
  std::vector<std::size_t> sources;
  double total_load = 0.0;
  for (std::size_t j = 0; j < n; ++j)
    if (load_n[j] > 0.0) {
      sources.push_back(j);
      total_load += load_n[j];
    }
  s.contact_count = sources.size();
  if (sources.empty()) return s;
  s.nominal_pressure_pa = total_load / nominal_area_m2;
  s.localisation_radius_m = settings.localisation_radius_m > 0.0
                                ? settings.localisation_radius_m
                                : settings.localisation_spacings * std::sqrt(nominal_area_m2 / static_cast<double>(sources.size()));
  const double r_loc = s.localisation_radius_m;

  // Far field (localisation principle): every spot is treated as the centre of a
  // homogeneous field, so the load outside R_loc acts as the nominal pressure p on the
  // annulus R_loc < r < R_out, R_out = sqrt(A0/pi). Integrating the point-load kernel,
  // int_0^2pi int_Rloc^Rout p / (pi E* r) r dr dtheta = 2 p (R_out - R_loc) / E*,
  // i.e. Johnson's uniform-pressure centre displacement 2 (1 - nu^2) p a / E (§3.4)
  // for the disc R_out minus the disc R_loc, both bodies combined through E*.
  s.far_field_m = 2.0 * s.nominal_pressure_pa * std::max(s.outer_radius_m - r_loc, 0.0) / effective_modulus_pa;

  const CellList cells(x_m, y_m, sources, r_loc);
  const double r_loc2 = r_loc * r_loc;
  for (std::size_t i = 0; i < n; ++i) {
    double u = 0.0;
    cells.for_neighbours(x_m[i], y_m[i], [&](std::size_t j) {
      if (j == i) return;
      const double dx = x_m[i] - x_m[j], dy = y_m[i] - y_m[j];
      const double r2 = dx * dx + dy * dy;
      if (r2 > r_loc2) return;
      const double r = std::sqrt(r2);
      u += kernel_displacement(settings.kernel, load_n[j], patch_radius_m[j], r, effective_modulus_pa);
      // Count each pair once (from its lower index) when both are loaded.
      if (load_n[i] > 0.0 && i < j && r < patch_radius_m[i] + patch_radius_m[j]) ++s.overlapping_pairs;
    });
    s.near_field_m[i] = u;
    s.extra_displacement_m[i] = u + s.far_field_m;
  }

  // Summaries over the spots in contact only: a free asperity has no interference to compare with.
  double sum2 = 0.0;
  for (std::size_t j : sources) {
    s.relative[j] = s.extra_displacement_m[j] / interference_m[j];
    s.max_relative = std::max(s.max_relative, s.relative[j]);
    sum2 += s.relative[j] * s.relative[j];
  }
  const double ns = static_cast<double>(sources.size());
  double stiffness_sum = 0.0, weighted_extra = 0.0, load_sum = 0.0;
  for (std::size_t j : sources) {
    const double s_j = contact_stiffness(effective_modulus_pa, patch_radius_m[j]);
    stiffness_sum += s_j;
    weighted_extra += s_j * s.extra_displacement_m[j];
    load_sum += load_n[j];
  }
  const double uniform_part = weighted_extra / stiffness_sum;
  double moved = 0.0;
  for (std::size_t j : sources)
    moved += contact_stiffness(effective_modulus_pa, patch_radius_m[j]) * std::abs(s.extra_displacement_m[j] - uniform_part);
  s.load_redistribution = moved / load_sum;
  s.rms_relative = std::sqrt(sum2 / ns);
  return s;
}

InteractingContact solve_interacting_contact(const std::vector<double>& heights_m, const std::vector<double>& x_m,
                                             const std::vector<double>& y_m, double summit_radius_m,
                                             double effective_modulus_pa, double nominal_load_n,
                                             double nominal_area_m2, const InteractionSettings& settings,
                                             int max_iterations, double tolerance) {
  if (x_m.size() != heights_m.size() || y_m.size() != heights_m.size())
    throw InputError("interacting contact: heights and positions must have equal lengths");
  if (max_iterations < 1 || !(tolerance > 0.0))
    throw InputError("interacting contact: max_iterations must be >= 1 and tolerance > 0");
  InteractingContact out;
  const std::size_t n = heights_m.size();
  // Fixed point of the displacement field, u = G(u) = extra displacement of the loads
  // N(z - u) (Hertz at load W). Plain iteration has the gain 2 a / (pi r) between two
  // spots r apart, above 1 once their patches overlap, so dense contacts diverge or creep.
  // Anderson acceleration (Walker & Ni 2011, SIAM J. Numer. Anal. 49(4), type II, depth 5)
  // solves the linearised problem in the span of the last residuals and converges where
  // the plain iteration cannot. Converged: the load error the residual implies,
  // max_i s_i |G(u)_i - u_i| with s_i = dN_i/d delta_i = 2 E* a_i, is below tolerance W.
  constexpr std::size_t depth = 5;
  Eigen::VectorXd u = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n)), g_prev, f_prev;
  std::deque<Eigen::VectorXd> delta_f, delta_g;
  std::vector<double> effective(n);
  double best_residual = INFINITY;
  // The default R_loc follows the contact count; frozen at the independent solution's,
  // so a grazing summit entering or leaving contact cannot make G jump.
  InteractionSettings frozen = settings;
  if (frozen.localisation_radius_m <= 0.0) {
    const HertzContact independent = solve_hertz_contact(heights_m, summit_radius_m, effective_modulus_pa, nominal_load_n);
    frozen.localisation_radius_m =
        frozen.localisation_spacings * std::sqrt(nominal_area_m2 / static_cast<double>(independent.contact_count));
  }
  for (out.iterations = 1; out.iterations <= max_iterations; ++out.iterations) {
    for (std::size_t i = 0; i < n; ++i) effective[i] = heights_m[i] - u[static_cast<Eigen::Index>(i)];
    out.contact = solve_hertz_contact(effective, summit_radius_m, effective_modulus_pa, nominal_load_n);
    out.interaction = spot_interaction(x_m, y_m, out.contact.load_n, out.contact.patch_radius_m,
                                       out.contact.interference_m, effective_modulus_pa, nominal_area_m2, frozen);
    const Eigen::VectorXd g = Eigen::Map<const Eigen::VectorXd>(out.interaction.extra_displacement_m.data(),
                                                                static_cast<Eigen::Index>(n));
    const Eigen::VectorXd f = g - u;
    double residual = 0.0;
    for (std::size_t i = 0; i < n; ++i)
      residual = std::max(residual, contact_stiffness(effective_modulus_pa, out.contact.patch_radius_m[i]) *
                                        std::abs(f[static_cast<Eigen::Index>(i)]));
    out.last_change = residual / nominal_load_n;
    if (out.last_change < tolerance) {
      out.converged = true;
      return out;
    }
    // A residual far above the best seen means the history misleads: start it afresh.
    if (out.last_change > 10.0 * best_residual) {
      delta_f.clear();
      delta_g.clear();
    }
    best_residual = std::min(best_residual, out.last_change);
    if (f_prev.size() > 0) {
      delta_f.push_back(f - f_prev);
      delta_g.push_back(g - g_prev);
      if (delta_f.size() > depth) {
        delta_f.pop_front();
        delta_g.pop_front();
      }
    }
    f_prev = f;
    g_prev = g;
    if (delta_f.empty()) {
      u = g;
      continue;
    }
    Eigen::MatrixXd df(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(delta_f.size()));
    Eigen::MatrixXd dg(df.rows(), df.cols());
    for (std::size_t c = 0; c < delta_f.size(); ++c) {
      df.col(static_cast<Eigen::Index>(c)) = delta_f[c];
      dg.col(static_cast<Eigen::Index>(c)) = delta_g[c];
    }
    const Eigen::VectorXd gamma = df.colPivHouseholderQr().solve(f);
    u = g - dg * gamma;
  }
  // Not converged: the last contact state and its own interaction are returned, flagged.
  out.iterations = max_iterations;
  return out;
}

}  // namespace stengmc
