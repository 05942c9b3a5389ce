#include "io/calibration_bank_file.hpp"

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
// 2: every table, and the numeric attributes of /atoms and /maps, carry a checksum
// (io/checksummed_tables.hpp). Format 1 had none: a damaged bank was used silently.
constexpr std::int64_t FORMAT_VERSION = 2;
const std::string REMAKE = "make the bank again with stengmc calibrate";

//! The numeric attributes of /atoms and /maps, in the order their checksum covers them.
const std::vector<std::string> ATOM_ATTRIBUTES = {"min_stiffness_n_per_m", "max_stiffness_n_per_m", "head_samples",
                                                  "check_error", "head_log_step", "tail_log_step",
                                                  "head_after_breakaway_s", "blend_s", "checks"};
const std::vector<std::string> MAP_ATTRIBUTES = {"count_min", "count_max", "line_error_scale", "naive_threshold_index",
                                                 "naive_threshold", "records", "bank_count_rmse", "bank_exact_rate",
                                                 "bank_naive_rmse", "bank_naive_exact_rate"};

//! A flat array of rows (row after row) as a 2-D dataset.
std::vector<std::vector<double>> rows_of(const std::vector<double>& flat, std::size_t columns) {
  std::vector<std::vector<double>> rows;
  for (std::size_t i = 0; columns > 0 && i + columns <= flat.size(); i += columns)
    rows.emplace_back(flat.begin() + static_cast<std::ptrdiff_t>(i), flat.begin() + static_cast<std::ptrdiff_t>(i + columns));
  return rows;
}

std::vector<double> flat_of(const std::vector<std::vector<double>>& rows) {
  std::vector<double> flat;
  for (const auto& r : rows) flat.insert(flat.end(), r.begin(), r.end());
  return flat;
}

//! An InputError saying the bank at `path` is damaged, and what to do.
InputError damaged(const std::string& path, const std::string& what) {
  return ChecksumReader::damaged(path, "the calibration bank", what, REMAKE);
}

//! The bank's tables, each read with its checksum verified.
ChecksumReader bank_tables(const Hdf5Reader& f, const std::string& path) {
  return {f, path, "the calibration bank", REMAKE};
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

  const AtomTableData& a = bank.atoms;
  write_checked(f, "/atoms/heads", rows_of(a.heads, a.head_samples));
  write_checked(f, "/atoms/head_slopes", rows_of(a.head_slopes, a.head_samples));
  write_checked(f, "/atoms/tail_shift_s", a.tail_shift_s);
  write_checked(f, "/atoms/tail_phase_rad", a.tail_phase_rad);
  write_checked(f, "/atoms/tail_fit_error", a.tail_fit_error);
  const auto count = [](std::size_t n) { return static_cast<double>(n); };
  // In ATOM_ATTRIBUTES' order.
  write_checked_attributes(f, "/atoms",
                           {{"min_stiffness_n_per_m", a.min_stiffness_n_per_m},
                            {"max_stiffness_n_per_m", a.max_stiffness_n_per_m},
                            {"head_samples", count(a.head_samples), true},
                            {"check_error", a.check_error},
                            {"head_log_step", a.settings.head_log_step},
                            {"tail_log_step", a.settings.tail_log_step},
                            {"head_after_breakaway_s", a.settings.head_after_breakaway_s},
                            {"blend_s", a.settings.blend_s},
                            {"checks", count(a.settings.checks), true}});

  const CalibrationMaps& m = bank.maps;
  write_checked(f, "/maps/confusion", m.confusion);
  write_checked(f, "/maps/median_score_quantile", m.median_score_quantile);
  write_checked(f, "/maps/sd_score_quantile", m.sd_score_quantile);
  write_checked(f, "/maps/naive_thresholds", naive_count_thresholds());
  // In MAP_ATTRIBUTES' order.
  write_checked_attributes(f, "/maps",
                           {{"count_min", count(m.count_min), true},
                            {"count_max", count(m.count_max), true},
                            {"line_error_scale", m.line_error_scale},
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
//! that is not a valid one, a newer one, or format 1, which carries no checksums.
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

  const ChecksumReader tables = bank_tables(f, path);
  AtomTableData& a = bank.atoms;
  a.heads = flat_of(tables.matrix("/atoms/heads"));
  a.head_slopes = flat_of(tables.matrix("/atoms/head_slopes"));
  a.tail_shift_s = tables.vector("/atoms/tail_shift_s");
  a.tail_phase_rad = tables.vector("/atoms/tail_phase_rad");
  a.tail_fit_error = tables.vector("/atoms/tail_fit_error");
  const auto number = tables.attributes("/atoms", ATOM_ATTRIBUTES);
  a.min_stiffness_n_per_m = number.at("min_stiffness_n_per_m");
  a.max_stiffness_n_per_m = number.at("max_stiffness_n_per_m");
  a.head_samples = static_cast<std::size_t>(number.at("head_samples"));
  a.check_error = number.at("check_error");
  a.settings.head_log_step = number.at("head_log_step");
  a.settings.tail_log_step = number.at("tail_log_step");
  a.settings.head_after_breakaway_s = number.at("head_after_breakaway_s");
  a.settings.blend_s = number.at("blend_s");
  a.settings.checks = static_cast<std::size_t>(number.at("checks"));
  return bank;
}

//! The maps, checked against their count range.
CalibrationMaps read_maps(const ChecksumReader& tables) {
  CalibrationMaps m;
  m.confusion = tables.matrix("/maps/confusion");
  m.median_score_quantile = tables.vector("/maps/median_score_quantile");
  m.sd_score_quantile = tables.vector("/maps/sd_score_quantile");
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
  m.line_error_scale = number.at("line_error_scale");
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
  if (m.confusion.size() != counts || m.median_score_quantile.size() != bins || m.sd_score_quantile.size() != bins)
    throw tables.damaged("its maps do not match its count range");
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
