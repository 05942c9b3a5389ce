#include "io/calibration_bank_file.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>

#include "core/checksum.hpp"
#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "core/input_file.hpp"
#include "inverse/naive_count.hpp"
#include "io/calibration_bank_codec.hpp"
#include "io/calibration_bank_records.hpp"
#include "io/checksummed_tables.hpp"
#include "io/guarded_read.hpp"
#include "io/output_vocabulary.hpp"
#include "io/run_file.hpp"

namespace stengmc {

namespace {

constexpr const char* FILE_TYPE = "stengmc-calibration-bank";
// 5: the fit classes' second boundary, /maps@line_se_bound (a line the record does not pin).
// 4: the maps learnt apart for the two fit classes (/maps/fits, /maps/misfits; issue 23).
// 3: the atoms as a shape family (issue 23; inverse/atom_shapes.hpp), every table and the
// numeric attributes of /atoms and /maps with their checksum (io/checksummed_tables.hpp).
// 2 held the old atom table (with checksums), 1 that table without checksums: a damaged
// bank was used silently.
constexpr std::int64_t FORMAT_VERSION = 5;
const std::string REMAKE = "make the bank again with stengmc calibrate";

//! The numeric attributes of /atoms and /maps, in the order their checksum covers them.
const std::vector<std::string> ATOM_ATTRIBUTES = {"min_pi", "max_pi", "min_zeta", "max_zeta", "onset_samples",
                                                  "breakaway_samples", "check_error", "log_pi_step", "zeta_node_count",
                                                  "theta_step", "after_breakaway", "before_breakaway", "split_pi", "blend",
                                                  "tail_fit_span"};
const std::vector<std::string> MAP_ATTRIBUTES = {"count_min", "count_max", "misfit_ratio", "line_se_bound", "naive_threshold_index",
                                                 "naive_threshold", "records", "bank_count_rmse", "bank_exact_rate",
                                                 "bank_naive_rmse", "bank_naive_exact_rate"};
const std::vector<std::string> CLASS_ATTRIBUTES = {"line_error_scale", "records", "pooled"};
//! The fit classes' groups, in FitClass order.
const std::array<std::string, FIT_CLASSES> CLASS_GROUPS = {"/maps/fits", "/maps/misfits"};

//! An InputError saying the bank at `path` is damaged, and what to do.
InputError damaged(const std::string& path, const std::string& what) {
  return ChecksumReader::damaged(path, "the calibration bank", what, REMAKE);
}

//! The bank's tables, each read with its checksum verified.
ChecksumReader bank_tables(const Hdf5Reader& f, const std::string& path) {
  return {f, path, "the calibration bank", REMAKE};
}

//! The atoms' shape family (atom_shapes.hpp): the nodes, each representation's rows for the
//! nodes that have it, the tails' parameters, each with its checksum; the range and settings
//! as attributes, with theirs (in ATOM_ATTRIBUTES' order).
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
  write_checked(f, "/atoms/pi_nodes", a.pi_nodes);
  write_checked(f, "/atoms/zeta_nodes", a.zeta_nodes);
  write_checked(f, "/atoms/onset_nodes", onset_nodes);
  write_checked(f, "/atoms/onset_values", onset_values);
  write_checked(f, "/atoms/onset_slopes", onset_slopes);
  write_checked(f, "/atoms/breakaway_nodes", breakaway_nodes);
  write_checked(f, "/atoms/breakaway_values", breakaway_values);
  write_checked(f, "/atoms/breakaway_slopes", breakaway_slopes);
  write_checked(f, "/atoms/breakaway_share", a.breakaway_share);
  write_checked(f, "/atoms/tail_log_amplitude", a.tail_log_amplitude);
  write_checked(f, "/atoms/tail_phase", a.tail_phase);
  const auto count = [](std::size_t n) { return static_cast<double>(n); };
  // In ATOM_ATTRIBUTES' order.
  write_checked_attributes(f, "/atoms",
                           {{"min_pi", a.range.min_pi},
                            {"max_pi", a.range.max_pi},
                            {"min_zeta", a.range.min_zeta},
                            {"max_zeta", a.range.max_zeta},
                            {"onset_samples", count(a.onset_samples), true},
                            {"breakaway_samples", count(a.breakaway_samples), true},
                            {"check_error", a.check_error},
                            {"log_pi_step", a.settings.log_pi_step},
                            {"zeta_node_count", count(a.settings.zeta_nodes), true},
                            {"theta_step", a.settings.theta_step},
                            {"after_breakaway", a.settings.after_breakaway},
                            {"before_breakaway", a.settings.before_breakaway},
                            {"split_pi", a.settings.split_pi},
                            {"blend", a.settings.blend},
                            {"tail_fit_span", a.settings.tail_fit_span}});
}

//! The shape family, every table and attribute verified against its checksum, and its
//! tables against one another (a bank written with matching checksums but tables of other
//! sizes would otherwise be read past their ends).
AtomShapeData read_atom_shapes(const ChecksumReader& tables) {
  const auto number = tables.attributes("/atoms", ATOM_ATTRIBUTES);
  // Sample and node counts of a few thousand at most; the bound keeps a damaged one from sizing anything.
  const auto whole = [&](const char* name) {
    const double v = number.at(name);
    if (!(v >= 0.0 && v <= 1e9) || v != std::floor(v)) throw tables.damaged(std::string("/atoms@") + name + " is not a count");
    return static_cast<std::size_t>(v);
  };
  AtomShapeData a;
  a.range = {number.at("min_pi"), number.at("max_pi"), number.at("min_zeta"), number.at("max_zeta")};
  a.onset_samples = whole("onset_samples");
  a.breakaway_samples = whole("breakaway_samples");
  a.check_error = number.at("check_error");
  a.settings.log_pi_step = number.at("log_pi_step");
  a.settings.zeta_nodes = whole("zeta_node_count");
  a.settings.theta_step = number.at("theta_step");
  a.settings.after_breakaway = number.at("after_breakaway");
  a.settings.before_breakaway = number.at("before_breakaway");
  a.settings.split_pi = number.at("split_pi");
  a.settings.blend = number.at("blend");
  a.settings.tail_fit_span = number.at("tail_fit_span");

  a.pi_nodes = tables.vector("/atoms/pi_nodes");
  a.zeta_nodes = tables.vector("/atoms/zeta_nodes");
  const std::size_t nodes = a.pi_nodes.size() * a.zeta_nodes.size();
  for (auto* v : {&a.onset_values, &a.onset_slopes, &a.breakaway_values, &a.breakaway_slopes}) v->assign(nodes, {});
  const auto rows = [&](const std::string& index, const std::string& values, const std::string& slopes, std::size_t samples,
                        std::vector<std::vector<double>>& v, std::vector<std::vector<double>>& g) {
    const std::vector<double> which = tables.vector(index);
    const auto vals = tables.matrix(values), slps = tables.matrix(slopes);
    if (vals.size() != which.size() || slps.size() != which.size())
      throw tables.damaged(values + " or " + slopes + " does not match " + index);
    for (std::size_t r = 0; r < which.size(); ++r) {
      const double w = which[r];
      if (!(w >= 0.0 && w < static_cast<double>(nodes)) || w != std::floor(w))
        throw tables.damaged(index + " names a node that is not one of its " + std::to_string(nodes));
      if (vals[r].size() != samples || slps[r].size() != samples)
        throw tables.damaged(values + " or " + slopes + " does not hold " + std::to_string(samples) + " samples a row");
      const auto n = static_cast<std::size_t>(w);
      v[n] = vals[r];
      g[n] = slps[r];
    }
  };
  rows("/atoms/onset_nodes", "/atoms/onset_values", "/atoms/onset_slopes", a.onset_samples, a.onset_values, a.onset_slopes);
  rows("/atoms/breakaway_nodes", "/atoms/breakaway_values", "/atoms/breakaway_slopes", a.breakaway_samples,
       a.breakaway_values, a.breakaway_slopes);
  a.breakaway_share = tables.vector("/atoms/breakaway_share");
  a.tail_log_amplitude = tables.vector("/atoms/tail_log_amplitude");
  a.tail_phase = tables.vector("/atoms/tail_phase");
  if (a.breakaway_share.size() != nodes || a.tail_log_amplitude.size() != nodes || a.tail_phase.size() != nodes)
    throw tables.damaged("its atoms' per-node tables do not match its " + std::to_string(nodes) + " nodes");
  return a;
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
  f.attribute("/", "identity_hash", checksum_text(id.hash));
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
  const auto count = [](std::size_t n) { return static_cast<double>(n); };

  const CalibrationMaps& m = bank.maps;
  for (std::size_t c = 0; c < FIT_CLASSES; ++c) {
    const ClassMaps& own = m.classes[c];
    const std::string& group = CLASS_GROUPS[c];
    write_checked(f, group + "/confusion", own.confusion);
    write_checked(f, group + "/median_score_quantile", own.median_score_quantile);
    write_checked(f, group + "/sd_score_quantile", own.sd_score_quantile);
    // In CLASS_ATTRIBUTES' order.
    write_checked_attributes(f, group,
                             {{"line_error_scale", own.line_error_scale},
                              {"records", count(own.records), true},
                              {"pooled", own.pooled ? 1.0 : 0.0, true}});
  }
  write_checked(f, "/maps/naive_thresholds", naive_count_thresholds());
  // In MAP_ATTRIBUTES' order.
  write_checked_attributes(f, "/maps",
                           {{"count_min", count(m.count_min), true},
                            {"count_max", count(m.count_max), true},
                            {"misfit_ratio", m.misfit_ratio},
                            {"line_se_bound", m.line_se_bound},
                            {"naive_threshold_index", count(m.naive_threshold_index), true},
                            {"naive_threshold", naive_count_thresholds()[m.naive_threshold_index]},
                            {"records", count(m.records), true},
                            {"bank_count_rmse", m.bank_count_rmse},
                            {"bank_exact_rate", m.bank_exact_rate},
                            {"bank_naive_rmse", m.bank_naive_rmse},
                            {"bank_naive_exact_rate", m.bank_naive_exact_rate}});
  write_bank_records(f, bank.samples, m.naive_threshold_index);
  f.commit();
}

namespace {

//! Refuses a file that is not a bank of this format: another file type, a format version
//! that is not a valid one, a newer one, format 1, which carries no checksums, or format 2,
//! whose atoms are the old table.
void check_bank_format(const std::string& path, const Hdf5Reader& f) {
  const std::string type = f.string_attribute("/", "file_type");
  if (type != FILE_TYPE)
    throw InputError(path + ": not a calibration bank (file_type \"" + type + "\"; make one with stengmc calibrate)");
  check_format_version(f, path, RUN_FILE_FORMAT_VERSION);
  const auto version = f.integer_attribute("/", "bank_format_version");
  if (!version || *version < 1)
    throw damaged(path, "bank_format_version " + (version ? std::to_string(*version) : std::string("missing")) +
                            " is not a valid version (>= 1)");
  if (*version == 1)
    throw InputError(path + ": calibration bank format 1 carries no checksums of its tables, so damage to it cannot be "
                     "detected; this stengmc reads format " + std::to_string(FORMAT_VERSION) + ": " + REMAKE);
  if (*version == 2)
    throw InputError(path + ": calibration bank format 2 holds the atoms as a table of stiffnesses, which this stengmc "
                     "no longer uses (its atoms are a family of shapes); this stengmc reads format " +
                     std::to_string(FORMAT_VERSION) + ": " + REMAKE);
  if (*version == 3)
    throw InputError(path + ": calibration bank format 3 holds one set of maps for every record, which this stengmc "
                     "learns apart for records that fit their noise and records that do not; this stengmc reads format " +
                     std::to_string(FORMAT_VERSION) + ": " + REMAKE);
  if (*version == 4)
    throw InputError(path + ": calibration bank format 4 sorts records into fit classes by their residual alone, and "
                     "this stengmc also by how well the record pins each line; this stengmc reads format " +
                     std::to_string(FORMAT_VERSION) + ": " + REMAKE);
  if (*version > FORMAT_VERSION)
    throw InputError(path + ": calibration bank format " + std::to_string(*version) + " is newer than this stengmc reads (" +
                     std::to_string(FORMAT_VERSION) + "); update stengmc, or " + REMAKE);
}

//! A bank's identity and atoms (everything but the maps), after checking its format.
StoredBank read_identity_and_atoms(const std::string& path, const Hdf5Reader& f) {
  check_bank_format(path, f);
  StoredBank bank;
  bank.path = path;
  bank.identity.device = f.string_attribute("/", "identity_device");
  bank.identity.prior = f.string_attribute("/", "identity_prior");
  bank.identity.grid = f.string_attribute("/", "identity_grid");
  bank.identity.estimator = f.string_attribute("/", "identity_estimator");
  const std::string hash = f.string_attribute("/", "identity_hash");
  const auto [end, error] = std::from_chars(hash.data(), hash.data() + hash.size(), bank.identity.hash, 16);
  if (hash.empty() || error != std::errc() || end != hash.data() + hash.size())
    throw damaged(path, "its identity_hash \"" + hash + "\" is not a hexadecimal number");
  bank.git_revision = f.string_attribute("/", "git_revision");
  bank.created_utc = f.string_attribute("/", "created_utc");

  bank.atoms = read_atom_shapes(bank_tables(f, path));
  return bank;
}

//! The maps, checked against their count range.
CalibrationMaps read_maps(const ChecksumReader& tables) {
  CalibrationMaps m;
  (void)tables.vector("/maps/naive_thresholds");  // verified: every table of a bank is
  const auto number = tables.attributes("/maps", MAP_ATTRIBUTES);
  // Counts of a few dozen at most; the bound keeps a damaged count from sizing anything.
  const auto whole = [&](const char* name) {
    const double v = number.at(name);
    if (!(v >= 0.0 && v <= 1e9) || v != std::floor(v)) throw tables.damaged(std::string("/maps@") + name + " is not a count");
    return static_cast<std::size_t>(v);
  };
  m.count_min = whole("count_min");
  m.count_max = whole("count_max");
  m.misfit_ratio = number.at("misfit_ratio");
  m.line_se_bound = number.at("line_se_bound");
  m.naive_threshold_index = whole("naive_threshold_index");
  m.naive_threshold = number.at("naive_threshold");
  m.records = whole("records");
  m.bank_count_rmse = number.at("bank_count_rmse");
  m.bank_exact_rate = number.at("bank_exact_rate");
  m.bank_naive_rmse = number.at("bank_naive_rmse");
  m.bank_naive_exact_rate = number.at("bank_naive_exact_rate");
  if (m.count_max < m.count_min) throw tables.damaged("its maps' count range is empty");
  const std::size_t counts = m.count_max - m.count_min + 1;
  const std::size_t bins = (counts + POPULATION_BIN_COUNTS - 1) / POPULATION_BIN_COUNTS;
  for (std::size_t c = 0; c < FIT_CLASSES; ++c) {
    ClassMaps& own = m.classes[c];
    const std::string& group = CLASS_GROUPS[c];
    own.confusion = tables.matrix(group + "/confusion");
    own.median_score_quantile = tables.vector(group + "/median_score_quantile");
    own.sd_score_quantile = tables.vector(group + "/sd_score_quantile");
    const auto own_number = tables.attributes(group, CLASS_ATTRIBUTES);
    own.line_error_scale = own_number.at("line_error_scale");
    const double records = own_number.at("records");
    if (!(records >= 0.0 && records <= 1e9) || records != std::floor(records))
      throw tables.damaged(group + "@records is not a count");
    own.records = static_cast<std::size_t>(records);
    own.pooled = own_number.at("pooled") != 0.0;
    if (own.confusion.size() != counts || own.median_score_quantile.size() != bins || own.sd_score_quantile.size() != bins)
      throw tables.damaged("its maps (" + group + ") do not match its count range");
  }
  return m;
}

//! Reads the bank at `path` with `read` (given the open file). HDF5 failing on it (a
//! damaged bank) is said as such, without the library's words.
template <class Read>
auto read_bank(const std::string& path, Read read) -> decltype(read(std::declval<const Hdf5Reader&>())) {
  try {
    const Hdf5Reader f(path);
    return read(f);
  } catch (const Hdf5ReadFailure& e) {
    throw damaged(path, "its " + e.object() + " cannot be read");
  }
}

StoredBank read_stored_bank(const std::string& path, const Hdf5Reader& f) {
  StoredBank bank = read_identity_and_atoms(path, f);
  const ChecksumReader tables = bank_tables(f, path);
  bank.maps = read_maps(tables);
  // `invert` does not use the records, but a bank whose records are damaged is damaged.
  (void)read_bank_records(tables);
  return bank;
}

}  // namespace

// A bank is read by a child process only (io/guarded_read.hpp), which hands what it read
// back as bytes (io/calibration_bank_codec.hpp): HDF5 may crash, loop or - on a damaged
// global heap, found by the bank's fuzz - corrupt memory without crashing on a damaged file,
// and none of that may reach the command.

StoredBank read_calibration_bank(const std::string& path) {
  check_input_file(path, "the calibration bank");
  return decode_stored_bank(read_in_child(
      path, [&] { return encode_stored_bank(read_bank(path, [&](const Hdf5Reader& f) { return read_stored_bank(path, f); })); }));
}

BankIdentity bank_identity_of(const std::string& path) { return read_calibration_bank(path).identity; }

CalibrationBank read_calibration_bank_records(const std::string& path, const InverseSetup& setup) {
  check_input_file(path, "the calibration bank");
  CalibrationBank bank = decode_bank_with_records(read_in_child(path, [&] {
    return encode_bank_with_records(read_bank(path, [&](const Hdf5Reader& f) {
      const StoredBank stored = read_stored_bank(path, f);
      CalibrationBank read;
      read.device_study_file = f.string_attribute("/", "input_file");
      read.device_study_text = f.string_attribute("/", "input_text");
      read.prior_study_text = f.string_attribute("/", "prior_study_text");
      read.atoms = stored.atoms;
      read.threads = static_cast<int>(f.integer_attribute("/", "threads").value_or(1));
      read.seconds = f.number_attribute("/", "seconds").value_or(0.0);
      read.atom_seconds = f.number_attribute("/", "atom_seconds").value_or(0.0);
      read.samples = read_bank_records(bank_tables(f, path));
      for (const CalibrationSample& s : read.samples) read.estimation_cpu_seconds += s.seconds;
      return read;
    }));
  }));
  bank.setup = setup;
  return bank;
}

}  // namespace stengmc
