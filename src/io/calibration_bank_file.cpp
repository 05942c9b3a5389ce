#include "io/calibration_bank_file.hpp"

#include <cstdio>
#include <sstream>

#include "core/error.hpp"
#include "inverse/naive_count.hpp"
#include "core/hdf5_file.hpp"
#include "io/run_file.hpp"
#include "io/output_vocabulary.hpp"

namespace stengmc {

namespace {

constexpr const char* FILE_TYPE = "stengmc-calibration-bank";
constexpr std::int64_t FORMAT_VERSION = 2;  // 2: the atoms as a shape family (issue 23)

std::string hex(std::uint64_t value) {
  char text[32];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
  return text;
}

//! The atoms' shape family (atom_shapes.hpp): the nodes, each representation's rows for the
//! nodes that have it, the tails' parameters, the range and settings as attributes.
void write_atom_shapes(Hdf5Writer& f, const AtomShapeData& a) {
  std::vector<std::int64_t> onset_nodes, breakaway_nodes;
  std::vector<std::vector<double>> onset_values, onset_slopes, breakaway_values, breakaway_slopes;
  for (std::size_t n = 0; n < a.onset_values.size(); ++n) {
    if (!a.onset_values[n].empty()) {
      onset_nodes.push_back(static_cast<std::int64_t>(n));
      onset_values.push_back(a.onset_values[n]);
      onset_slopes.push_back(a.onset_slopes[n]);
    }
    if (!a.breakaway_values[n].empty()) {
      breakaway_nodes.push_back(static_cast<std::int64_t>(n));
      breakaway_values.push_back(a.breakaway_values[n]);
      breakaway_slopes.push_back(a.breakaway_slopes[n]);
    }
  }
  f.write("/atoms/pi_nodes", a.pi_nodes);
  f.write("/atoms/zeta_nodes", a.zeta_nodes);
  f.write("/atoms/onset_nodes", onset_nodes);
  f.write("/atoms/onset_values", onset_values);
  f.write("/atoms/onset_slopes", onset_slopes);
  f.write("/atoms/breakaway_nodes", breakaway_nodes);
  f.write("/atoms/breakaway_values", breakaway_values);
  f.write("/atoms/breakaway_slopes", breakaway_slopes);
  f.write("/atoms/breakaway_share", a.breakaway_share);
  f.write("/atoms/tail_log_amplitude", a.tail_log_amplitude);
  f.write("/atoms/tail_phase", a.tail_phase);
  f.attribute("/atoms", "min_pi", a.range.min_pi);
  f.attribute("/atoms", "max_pi", a.range.max_pi);
  f.attribute("/atoms", "min_zeta", a.range.min_zeta);
  f.attribute("/atoms", "max_zeta", a.range.max_zeta);
  f.attribute("/atoms", "onset_samples", static_cast<std::int64_t>(a.onset_samples));
  f.attribute("/atoms", "breakaway_samples", static_cast<std::int64_t>(a.breakaway_samples));
  f.attribute("/atoms", "check_error", a.check_error);
  f.attribute("/atoms", "log_pi_step", a.settings.log_pi_step);
  f.attribute("/atoms", "zeta_node_count", static_cast<std::int64_t>(a.settings.zeta_nodes));
  f.attribute("/atoms", "theta_step", a.settings.theta_step);
  f.attribute("/atoms", "after_breakaway", a.settings.after_breakaway);
  f.attribute("/atoms", "before_breakaway", a.settings.before_breakaway);
  f.attribute("/atoms", "split_pi", a.settings.split_pi);
  f.attribute("/atoms", "blend", a.settings.blend);
  f.attribute("/atoms", "tail_fit_span", a.settings.tail_fit_span);
}

AtomShapeData read_atom_shapes(const std::string& path, const Hdf5Reader& f) {
  auto number = [&](const std::string& name) {
    const auto v = f.number_attribute("/atoms", name);
    if (!v) throw InputError(path + ": attribute /atoms@" + name + " is missing (a damaged bank?)");
    return *v;
  };
  AtomShapeData a;
  a.pi_nodes = f.vector("/atoms/pi_nodes");
  a.zeta_nodes = f.vector("/atoms/zeta_nodes");
  const std::size_t nodes = a.pi_nodes.size() * a.zeta_nodes.size();
  for (auto* v : {&a.onset_values, &a.onset_slopes, &a.breakaway_values, &a.breakaway_slopes}) v->assign(nodes, {});
  auto rows = [&](const char* index, const char* values, const char* slopes, std::vector<std::vector<double>>& v,
                  std::vector<std::vector<double>>& g) {
    const std::vector<double> which = f.vector(index);
    const auto vals = f.matrix(values), slps = f.matrix(slopes);
    if (vals.size() != which.size() || slps.size() != which.size())
      throw InputError(path + ": " + values + " does not match " + index + " (a damaged bank?)");
    for (std::size_t r = 0; r < which.size(); ++r) {
      const auto n = static_cast<std::size_t>(which[r]);
      if (n >= nodes) throw InputError(path + ": " + index + " names node " + std::to_string(n) + " of " + std::to_string(nodes));
      v[n] = vals[r];
      g[n] = slps[r];
    }
  };
  rows("/atoms/onset_nodes", "/atoms/onset_values", "/atoms/onset_slopes", a.onset_values, a.onset_slopes);
  rows("/atoms/breakaway_nodes", "/atoms/breakaway_values", "/atoms/breakaway_slopes", a.breakaway_values, a.breakaway_slopes);
  a.breakaway_share = f.vector("/atoms/breakaway_share");
  a.tail_log_amplitude = f.vector("/atoms/tail_log_amplitude");
  a.tail_phase = f.vector("/atoms/tail_phase");
  a.range = {number("min_pi"), number("max_pi"), number("min_zeta"), number("max_zeta")};
  a.onset_samples = static_cast<std::size_t>(number("onset_samples"));
  a.breakaway_samples = static_cast<std::size_t>(number("breakaway_samples"));
  a.check_error = number("check_error");
  a.settings.log_pi_step = number("log_pi_step");
  a.settings.zeta_nodes = static_cast<std::size_t>(number("zeta_node_count"));
  a.settings.theta_step = number("theta_step");
  a.settings.after_breakaway = number("after_breakaway");
  a.settings.before_breakaway = number("before_breakaway");
  a.settings.split_pi = number("split_pi");
  a.settings.blend = number("blend");
  a.settings.tail_fit_span = number("tail_fit_span");
  return a;
}

void write_records(Hdf5Writer& f, const std::vector<CalibrationSample>& samples, std::size_t naive_index) {
  std::vector<std::int64_t> ids, valid, true_count, count, true_offset{0}, estimate_offset{0}, order_offset{0};
  std::vector<double> snr, first, second, true_median, median, true_sd, sd, noise, residual, band, snr_estimate, seconds, naive;
  std::vector<double> true_k, k, se, orders, evidence;
  std::vector<std::vector<double>> naive_counts;
  for (const CalibrationSample& s : samples) {
    ids.push_back(static_cast<std::int64_t>(s.realisation));
    valid.push_back(s.valid ? 1 : 0);
    true_count.push_back(static_cast<std::int64_t>(s.true_count()));
    count.push_back(static_cast<std::int64_t>(s.count));
    snr.push_back(s.snr_db);
    first.push_back(s.law_first);
    second.push_back(s.law_second);
    true_median.push_back(s.true_median());
    median.push_back(s.median);
    true_sd.push_back(s.true_sd_log());
    sd.push_back(s.sd_log);
    noise.push_back(s.noise_sigma_v);
    residual.push_back(s.residual_sigma_v);
    band.push_back(s.band_power_ratio);
    snr_estimate.push_back(s.snr_estimate_db);
    seconds.push_back(s.seconds);
    naive.push_back(naive_index < s.naive_counts.size() ? s.naive_counts[naive_index] : 0.0);
    std::vector<double> row = s.naive_counts;
    row.resize(naive_count_thresholds().size(), 0.0);
    naive_counts.push_back(row);
    true_k.insert(true_k.end(), s.true_stiffness.begin(), s.true_stiffness.end());
    true_offset.push_back(static_cast<std::int64_t>(true_k.size()));
    k.insert(k.end(), s.stiffness.begin(), s.stiffness.end());
    se.insert(se.end(), s.log_stiffness_se.begin(), s.log_stiffness_se.end());
    estimate_offset.push_back(static_cast<std::int64_t>(k.size()));
    orders.insert(orders.end(), s.counts.begin(), s.counts.end());
    evidence.insert(evidence.end(), s.log_evidence.begin(), s.log_evidence.end());
    order_offset.push_back(static_cast<std::int64_t>(orders.size()));
  }
  f.write("/records/realisation", ids);
  f.write("/records/valid", valid);
  f.write("/records/true_count", true_count);
  f.write("/records/count", count);
  f.write("/records/snr_db", snr);
  f.write("/records/law_first", first);
  f.write("/records/law_second", second);
  f.write("/records/true_median", true_median);
  f.write("/records/median", median);
  f.write("/records/true_sd_log", true_sd);
  f.write("/records/sd_log", sd);
  f.write("/records/noise_sigma", noise);
  f.write("/records/residual_sigma", residual);
  f.write("/records/band_power_ratio", band);
  f.write("/records/snr_estimate_db", snr_estimate);
  f.write("/records/seconds", seconds);
  f.write("/records/naive_count", naive);
  f.write("/records/naive_counts", naive_counts);
  f.write("/records/true_stiffness", true_k);
  f.write("/records/true_offset", true_offset);
  f.write("/records/stiffness", k);
  f.write("/records/log_stiffness_se", se);
  f.write("/records/estimate_offset", estimate_offset);
  f.write("/records/orders", orders);
  f.write("/records/log_evidence", evidence);
  f.write("/records/order_offset", order_offset);
}

}  // namespace

void write_calibration_bank(const std::string& path, const CalibrationBank& bank) {
  Hdf5Writer f(path, describe_output);
  write_provenance(f, {.file_type = FILE_TYPE,
                       .input_file = bank.device_study_file,
                       .input_text = bank.device_study_text,
                       .seed = bank.setup.prior.seed,
                       .surface_file = "",
                       .surface_text = "",
                       .auxiliary_inputs = ""});
  f.attribute("/", "bank_format_version", FORMAT_VERSION);
  const BankIdentity& id = bank.setup.identity;
  f.attribute("/", "identity_hash", hex(id.hash));
  f.attribute("/", "identity_device", id.device);
  f.attribute("/", "identity_prior", id.prior);
  f.attribute("/", "identity_grid", id.grid);
  f.attribute("/", "identity_estimator", id.estimator);
  f.attribute("/", "prior_study_text", bank.prior_study_text);
  f.attribute("/", "records_requested", static_cast<std::int64_t>(bank.setup.prior.calibration_records));
  f.attribute("/", "records_valid", static_cast<std::int64_t>(bank.maps.records));
  f.attribute("/", "seconds", bank.seconds);
  f.attribute("/", "atom_seconds", bank.atom_seconds);
  f.attribute("/", "threads", static_cast<std::int64_t>(bank.threads));

  write_atom_shapes(f, bank.atoms);

  const CalibrationMaps& m = bank.maps;
  f.write("/maps/confusion", m.confusion);
  f.write("/maps/median_score_quantile", m.median_score_quantile);
  f.write("/maps/sd_score_quantile", m.sd_score_quantile);
  f.write("/maps/naive_thresholds", naive_count_thresholds());
  f.attribute("/maps", "count_min", static_cast<std::int64_t>(m.count_min));
  f.attribute("/maps", "count_max", static_cast<std::int64_t>(m.count_max));
  f.attribute("/maps", "line_error_scale", m.line_error_scale);
  f.attribute("/maps", "naive_threshold_index", static_cast<std::int64_t>(m.naive_threshold_index));
  f.attribute("/maps", "naive_threshold", naive_count_thresholds()[m.naive_threshold_index]);
  f.attribute("/maps", "records", static_cast<std::int64_t>(m.records));
  f.attribute("/maps", "bank_count_rmse", m.bank_count_rmse);
  f.attribute("/maps", "bank_exact_rate", m.bank_exact_rate);
  f.attribute("/maps", "bank_naive_rmse", m.bank_naive_rmse);
  f.attribute("/maps", "bank_naive_exact_rate", m.bank_naive_exact_rate);
  write_records(f, bank.samples, m.naive_threshold_index);
  f.commit();
}

namespace {

//! A bank's identity and atoms (everything but the maps), after checking the file type.
StoredBank read_identity_and_atoms(const std::string& path, const Hdf5Reader& f) {
  const std::string type = f.string_attribute("/", "file_type");
  if (type != FILE_TYPE)
    throw InputError(path + ": not a calibration bank (file_type \"" + type + "\"; make one with stengmc calibrate)");
  check_format_version(f, path, RUN_FILE_FORMAT_VERSION);
  const auto version = f.integer_attribute("/", "bank_format_version");
  if (version && *version < 1)
    throw InputError(path + ": bank_format_version " + std::to_string(*version) + " is not a valid version (>= 1); damaged file?");
  if (!version || *version > FORMAT_VERSION)
    throw InputError(path + ": calibration bank format " + (version ? std::to_string(*version) : std::string("?")) +
                     " is not one this stengmc reads (" + std::to_string(FORMAT_VERSION) + "); make the bank again");
  StoredBank bank;
  bank.path = path;
  bank.identity.device = f.string_attribute("/", "identity_device");
  bank.identity.prior = f.string_attribute("/", "identity_prior");
  bank.identity.grid = f.string_attribute("/", "identity_grid");
  bank.identity.estimator = f.string_attribute("/", "identity_estimator");
  bank.identity.hash = std::stoull(f.string_attribute("/", "identity_hash"), nullptr, 16);
  bank.git_revision = f.string_attribute("/", "git_revision");
  bank.created_utc = f.string_attribute("/", "created_utc");

  bank.atoms = read_atom_shapes(path, f);
  return bank;
}

}  // namespace

StoredBank read_calibration_bank(const std::string& path) {
  Hdf5Reader f(path);
  StoredBank bank = read_identity_and_atoms(path, f);
  auto number = [&](const std::string& object, const std::string& name) {
    const auto v = f.number_attribute(object, name);
    if (!v) throw InputError(path + ": attribute " + object + "@" + name + " is missing (a damaged bank?)");
    return *v;
  };
  CalibrationMaps& m = bank.maps;
  m.confusion = f.matrix("/maps/confusion");
  m.median_score_quantile = f.vector("/maps/median_score_quantile");
  m.sd_score_quantile = f.vector("/maps/sd_score_quantile");
  m.count_min = static_cast<std::size_t>(number("/maps", "count_min"));
  m.count_max = static_cast<std::size_t>(number("/maps", "count_max"));
  m.line_error_scale = number("/maps", "line_error_scale");
  m.naive_threshold_index = static_cast<std::size_t>(number("/maps", "naive_threshold_index"));
  m.naive_threshold = number("/maps", "naive_threshold");
  m.records = static_cast<std::size_t>(number("/maps", "records"));
  m.bank_count_rmse = number("/maps", "bank_count_rmse");
  m.bank_exact_rate = number("/maps", "bank_exact_rate");
  m.bank_naive_rmse = number("/maps", "bank_naive_rmse");
  m.bank_naive_exact_rate = number("/maps", "bank_naive_exact_rate");
  const std::size_t counts = m.count_max - m.count_min + 1;
  const std::size_t bins = (counts + POPULATION_BIN_COUNTS - 1) / POPULATION_BIN_COUNTS;
  if (m.confusion.size() != counts || m.median_score_quantile.size() != bins || m.sd_score_quantile.size() != bins)
    throw InputError(path + ": the bank's maps do not match its count range (a damaged bank?)");
  return bank;
}

BankIdentity bank_identity_of(const std::string& path) {
  Hdf5Reader f(path);
  return read_identity_and_atoms(path, f).identity;
}

CalibrationBank read_calibration_bank_records(const std::string& path, const InverseSetup& setup) {
  Hdf5Reader f(path);
  const StoredBank stored = read_identity_and_atoms(path, f);
  CalibrationBank bank;
  bank.setup = setup;
  bank.device_study_file = f.string_attribute("/", "input_file");
  bank.device_study_text = f.string_attribute("/", "input_text");
  bank.prior_study_text = f.string_attribute("/", "prior_study_text");
  bank.atoms = stored.atoms;
  bank.threads = static_cast<int>(f.integer_attribute("/", "threads").value_or(1));
  bank.seconds = f.number_attribute("/", "seconds").value_or(0.0);
  bank.atom_seconds = f.number_attribute("/", "atom_seconds").value_or(0.0);
  const auto ids = f.vector("/records/realisation");
  const auto valid = f.vector("/records/valid");
  const auto count = f.vector("/records/count");
  const auto snr = f.vector("/records/snr_db");
  const auto first = f.vector("/records/law_first"), second = f.vector("/records/law_second");
  const auto median = f.vector("/records/median"), sd = f.vector("/records/sd_log");
  const auto noise = f.vector("/records/noise_sigma"), residual = f.vector("/records/residual_sigma");
  const auto band = f.vector("/records/band_power_ratio"), snr_estimate = f.vector("/records/snr_estimate_db");
  const auto seconds = f.vector("/records/seconds");
  const auto naive = f.matrix("/records/naive_counts");
  const auto true_k = f.vector("/records/true_stiffness"), true_offset = f.vector("/records/true_offset");
  const auto k = f.vector("/records/stiffness"), se = f.vector("/records/log_stiffness_se");
  const auto estimate_offset = f.vector("/records/estimate_offset");
  const auto orders = f.vector("/records/orders"), evidence = f.vector("/records/log_evidence");
  const auto order_offset = f.vector("/records/order_offset");
  auto slice = [](const std::vector<double>& v, const std::vector<double>& offset, std::size_t j) {
    return std::vector<double>(v.begin() + static_cast<std::ptrdiff_t>(offset[j]), v.begin() + static_cast<std::ptrdiff_t>(offset[j + 1]));
  };
  for (std::size_t j = 0; j < ids.size(); ++j) {
    CalibrationSample s;
    s.realisation = static_cast<std::uint64_t>(ids[j]);
    s.valid = valid[j] != 0.0;
    s.snr_db = snr[j];
    s.law_first = first[j];
    s.law_second = second[j];
    s.true_stiffness = slice(true_k, true_offset, j);
    s.count = static_cast<std::size_t>(count[j]);
    s.stiffness = slice(k, estimate_offset, j);
    s.log_stiffness_se = slice(se, estimate_offset, j);
    s.counts = slice(orders, order_offset, j);
    s.log_evidence = slice(evidence, order_offset, j);
    s.median = median[j];
    s.sd_log = sd[j];
    s.noise_sigma_v = noise[j];
    s.residual_sigma_v = residual[j];
    s.band_power_ratio = band[j];
    s.snr_estimate_db = snr_estimate[j];
    s.seconds = seconds[j];
    s.naive_counts = naive[j];
    bank.estimation_cpu_seconds += s.seconds;
    bank.samples.push_back(std::move(s));
  }
  return bank;
}

}  // namespace stengmc
