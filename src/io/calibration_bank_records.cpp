#include "io/calibration_bank_records.hpp"

#include <cmath>
#include <initializer_list>
#include <map>
#include <set>
#include <string>

#include "inverse/naive_count.hpp"

namespace stengmc {

namespace {

//! Every 1-D table of /records (the one 2-D table is /records/naive_counts).
const std::vector<std::string> RECORD_TABLES = {
    "/records/realisation", "/records/valid", "/records/true_count", "/records/count", "/records/snr_db",
    "/records/law_first", "/records/law_second", "/records/true_median", "/records/median", "/records/true_sd_log",
    "/records/sd_log", "/records/noise_sigma", "/records/residual_sigma", "/records/band_power_ratio",
    "/records/snr_estimate_db", "/records/seconds", "/records/naive_count", "/records/true_stiffness",
    "/records/true_offset", "/records/stiffness", "/records/log_stiffness_se", "/records/estimate_offset",
    "/records/orders", "/records/log_evidence", "/records/order_offset"};
//! The tables of /records that are lists of all records' values, cut by offsets.
const std::set<std::string> FLAT_LISTS = {"/records/true_stiffness", "/records/stiffness", "/records/log_stiffness_se",
                                          "/records/orders", "/records/log_evidence"};

}  // namespace

void write_bank_records(Hdf5Writer& f, const std::vector<CalibrationSample>& samples, std::size_t naive_index) {
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
  write_checked(f, "/records/realisation", ids);
  write_checked(f, "/records/valid", valid);
  write_checked(f, "/records/true_count", true_count);
  write_checked(f, "/records/count", count);
  write_checked(f, "/records/snr_db", snr);
  write_checked(f, "/records/law_first", first);
  write_checked(f, "/records/law_second", second);
  write_checked(f, "/records/true_median", true_median);
  write_checked(f, "/records/median", median);
  write_checked(f, "/records/true_sd_log", true_sd);
  write_checked(f, "/records/sd_log", sd);
  write_checked(f, "/records/noise_sigma", noise);
  write_checked(f, "/records/residual_sigma", residual);
  write_checked(f, "/records/band_power_ratio", band);
  write_checked(f, "/records/snr_estimate_db", snr_estimate);
  write_checked(f, "/records/seconds", seconds);
  write_checked(f, "/records/naive_count", naive);
  write_checked(f, "/records/naive_counts", naive_counts);
  write_checked(f, "/records/true_stiffness", true_k);
  write_checked(f, "/records/true_offset", true_offset);
  write_checked(f, "/records/stiffness", k);
  write_checked(f, "/records/log_stiffness_se", se);
  write_checked(f, "/records/estimate_offset", estimate_offset);
  write_checked(f, "/records/orders", orders);
  write_checked(f, "/records/log_evidence", evidence);
  write_checked(f, "/records/order_offset", order_offset);
}

std::vector<CalibrationSample> read_bank_records(const ChecksumReader& tables) {
  std::map<std::string, std::vector<double>> columns;
  for (const std::string& name : RECORD_TABLES) columns[name] = tables.vector(name);
  const auto column = [&](const std::string& name) -> const std::vector<double>& { return columns.at(name); };
  const auto naive = tables.matrix("/records/naive_counts");
  const std::vector<double>& ids = column("/records/realisation");
  const std::size_t records = ids.size();
  // A table per record has an entry per record, an offset table one more; the flat lists'
  // lengths are where their offsets end.
  for (const std::string& name : RECORD_TABLES) {
    if (FLAT_LISTS.contains(name)) continue;
    const std::size_t expected = name.ends_with("_offset") ? records + 1 : records;
    if (column(name).size() != expected)
      throw tables.damaged("table " + name + " has " + std::to_string(column(name).size()) + " entries for " +
                           std::to_string(records) + " records");
  }
  if (naive.size() != records) throw tables.damaged("table /records/naive_counts does not have a row per record");
  const auto check_offsets = [&](const std::string& offsets, std::initializer_list<std::string> lists) {
    const std::vector<double>& o = column(offsets);
    for (std::size_t j = 0; j < o.size(); ++j)
      if (o[j] != std::floor(o[j]) || (j == 0 ? o[j] != 0.0 : o[j] < o[j - 1]))
        throw tables.damaged("table " + offsets + " is not a list of offsets from 0");
    for (const std::string& list : lists)
      if (o.back() != static_cast<double>(column(list).size()))
        throw tables.damaged("table " + offsets + " does not end at the length of " + list);
  };
  check_offsets("/records/true_offset", {"/records/true_stiffness"});
  check_offsets("/records/estimate_offset", {"/records/stiffness", "/records/log_stiffness_se"});
  check_offsets("/records/order_offset", {"/records/orders", "/records/log_evidence"});
  const auto slice = [](const std::vector<double>& v, const std::vector<double>& offset, std::size_t j) {
    return std::vector<double>(v.begin() + static_cast<std::ptrdiff_t>(offset[j]),
                               v.begin() + static_cast<std::ptrdiff_t>(offset[j + 1]));
  };
  std::vector<CalibrationSample> samples;
  for (std::size_t j = 0; j < records; ++j) {
    CalibrationSample s;
    s.realisation = static_cast<std::uint64_t>(ids[j]);
    s.valid = column("/records/valid")[j] != 0.0;
    s.snr_db = column("/records/snr_db")[j];
    s.law_first = column("/records/law_first")[j];
    s.law_second = column("/records/law_second")[j];
    s.true_stiffness = slice(column("/records/true_stiffness"), column("/records/true_offset"), j);
    s.count = static_cast<std::size_t>(column("/records/count")[j]);
    s.stiffness = slice(column("/records/stiffness"), column("/records/estimate_offset"), j);
    s.log_stiffness_se = slice(column("/records/log_stiffness_se"), column("/records/estimate_offset"), j);
    s.counts = slice(column("/records/orders"), column("/records/order_offset"), j);
    s.log_evidence = slice(column("/records/log_evidence"), column("/records/order_offset"), j);
    s.median = column("/records/median")[j];
    s.sd_log = column("/records/sd_log")[j];
    s.noise_sigma_v = column("/records/noise_sigma")[j];
    s.residual_sigma_v = column("/records/residual_sigma")[j];
    s.band_power_ratio = column("/records/band_power_ratio")[j];
    s.snr_estimate_db = column("/records/snr_estimate_db")[j];
    s.seconds = column("/records/seconds")[j];
    s.naive_counts = naive[j];
    samples.push_back(std::move(s));
  }
  return samples;
}

}  // namespace stengmc
