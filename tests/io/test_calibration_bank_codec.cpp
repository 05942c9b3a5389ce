// The bytes a bank's reading child hands back (io/calibration_bank_codec.hpp) decode to
// what was encoded, bitwise: the atoms' shape family (issue 23) with its empty rows (nodes
// without that representation), signed zeros, NaNs and infinities, the maps and the records.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/error.hpp"
#include "io/calibration_bank_codec.hpp"

namespace stengmc {
namespace {

std::vector<std::uint64_t> bits(const std::vector<double>& values) {
  std::vector<std::uint64_t> b;
  for (double v : values) b.push_back(std::bit_cast<std::uint64_t>(v));
  return b;
}

std::vector<std::vector<std::uint64_t>> bits(const std::vector<std::vector<double>>& rows) {
  std::vector<std::vector<std::uint64_t>> b;
  for (const auto& row : rows) b.push_back(bits(row));
  return b;
}

std::uint64_t bits(double v) { return std::bit_cast<std::uint64_t>(v); }

//! A shape family of 4 x 2 nodes: small Pi ones with onset rows, large ones with breakaway
//! rows, two in the overlap with both; awkward values in every table.
AtomShapeData shapes() {
  AtomShapeData a;
  a.range = {0.2, 31.5, 1e-12, 0.07};
  a.settings.log_pi_step = 0.021;
  a.settings.zeta_nodes = 2;
  a.settings.theta_step = 0.05;
  a.settings.after_breakaway = 30.0;
  a.settings.before_breakaway = 8.0;
  a.settings.split_pi = 12.0;
  a.settings.blend = 5.0;
  a.settings.tail_fit_span = 80.0;
  a.pi_nodes = {0.2, 3.0, 12.0, 31.5};
  a.zeta_nodes = {1e-12, 0.07};
  a.onset_samples = 3;
  a.breakaway_samples = 2;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (auto* v : {&a.onset_values, &a.onset_slopes, &a.breakaway_values, &a.breakaway_slopes}) v->assign(8, {});
  for (std::size_t n = 0; n < 8; ++n) {
    const double x = 0.1 * static_cast<double>(n) + 1.0 / 3.0;
    if (n < 6) {
      a.onset_values[n] = {x, -0.0, std::nextafter(x, 2.0)};
      a.onset_slopes[n] = {-x, 0.0, 1e-308};
    }
    if (n >= 4) {
      a.breakaway_values[n] = {x * x, n == 5 ? nan : -x};
      a.breakaway_slopes[n] = {5e-324, n == 7 ? -inf : x};
    }
    a.breakaway_share.push_back(n >= 4 ? x / 7.0 : 0.0);
    a.tail_log_amplitude.push_back(std::log(x));
    a.tail_phase.push_back(-x * 3.0);
  }
  a.check_error = 2.5e-4;
  return a;
}

void expect_same(const AtomShapeData& a, const AtomShapeData& b) {
  EXPECT_EQ(bits(a.range.min_pi), bits(b.range.min_pi));
  EXPECT_EQ(bits(a.range.max_pi), bits(b.range.max_pi));
  EXPECT_EQ(bits(a.range.min_zeta), bits(b.range.min_zeta));
  EXPECT_EQ(bits(a.range.max_zeta), bits(b.range.max_zeta));
  EXPECT_EQ(bits(a.settings.log_pi_step), bits(b.settings.log_pi_step));
  EXPECT_EQ(a.settings.zeta_nodes, b.settings.zeta_nodes);
  EXPECT_EQ(bits(a.settings.theta_step), bits(b.settings.theta_step));
  EXPECT_EQ(bits(a.settings.after_breakaway), bits(b.settings.after_breakaway));
  EXPECT_EQ(bits(a.settings.before_breakaway), bits(b.settings.before_breakaway));
  EXPECT_EQ(bits(a.settings.split_pi), bits(b.settings.split_pi));
  EXPECT_EQ(bits(a.settings.blend), bits(b.settings.blend));
  EXPECT_EQ(bits(a.settings.tail_fit_span), bits(b.settings.tail_fit_span));
  EXPECT_EQ(bits(a.pi_nodes), bits(b.pi_nodes));
  EXPECT_EQ(bits(a.zeta_nodes), bits(b.zeta_nodes));
  EXPECT_EQ(a.onset_samples, b.onset_samples);
  EXPECT_EQ(a.breakaway_samples, b.breakaway_samples);
  EXPECT_EQ(bits(a.onset_values), bits(b.onset_values));
  EXPECT_EQ(bits(a.onset_slopes), bits(b.onset_slopes));
  EXPECT_EQ(bits(a.breakaway_values), bits(b.breakaway_values));
  EXPECT_EQ(bits(a.breakaway_slopes), bits(b.breakaway_slopes));
  EXPECT_EQ(bits(a.breakaway_share), bits(b.breakaway_share));
  EXPECT_EQ(bits(a.tail_log_amplitude), bits(b.tail_log_amplitude));
  EXPECT_EQ(bits(a.tail_phase), bits(b.tail_phase));
  EXPECT_EQ(bits(a.check_error), bits(b.check_error));
}

TEST(BankCodec, AStoredBankRoundTripsBitwise) {
  StoredBank bank;
  bank.path = "bank.h5";
  bank.identity.device = "device";
  bank.identity.prior = "prior";
  bank.identity.grid = "grid";
  bank.identity.estimator = "estimator";
  bank.identity.hash = 0x9ff2dcb812345678ULL;
  bank.git_revision = "40dbdfa";
  bank.created_utc = "2026-11-26T19:00:00Z";
  bank.atoms = shapes();
  bank.maps.count_min = 1;
  bank.maps.count_max = 2;
  bank.maps.misfit_ratio = 1.375;
  bank.maps.line_se_bound = 2.5e-3;
  bank.maps.classes[0].confusion = {{0.75, 0.25}, {-0.0, 1.0}};
  bank.maps.classes[0].median_score_quantile = {1.5};
  bank.maps.classes[0].sd_score_quantile = {2.5};
  bank.maps.classes[0].line_error_scale = 1.25;
  bank.maps.classes[0].records = 41;
  bank.maps.classes[1].confusion = {{0.5, 0.5}, {0.125, 0.875}};
  bank.maps.classes[1].median_score_quantile = {3.5};
  bank.maps.classes[1].sd_score_quantile = {4.5};
  bank.maps.classes[1].line_error_scale = 2.25;
  bank.maps.classes[1].records = 9;
  bank.maps.classes[1].pooled = true;
  bank.maps.naive_threshold_index = 3;
  bank.maps.naive_threshold = 4.0;
  bank.maps.records = 50;
  bank.maps.bank_count_rmse = 0.3;
  const StoredBank back = decode_stored_bank(encode_stored_bank(bank));
  EXPECT_EQ(back.path, bank.path);
  EXPECT_EQ(back.identity.device, bank.identity.device);
  EXPECT_EQ(back.identity.estimator, bank.identity.estimator);
  EXPECT_EQ(back.identity.hash, bank.identity.hash);
  EXPECT_EQ(back.created_utc, bank.created_utc);
  expect_same(back.atoms, bank.atoms);
  EXPECT_EQ(back.maps.records, bank.maps.records);
  EXPECT_EQ(bits(back.maps.misfit_ratio), bits(bank.maps.misfit_ratio));
  EXPECT_EQ(bits(back.maps.line_se_bound), bits(bank.maps.line_se_bound));
  for (std::size_t c = 0; c < FIT_CLASSES; ++c) {
    SCOPED_TRACE(c);
    const ClassMaps &was = bank.maps.classes[c], &is = back.maps.classes[c];
    EXPECT_EQ(bits(is.confusion), bits(was.confusion));
    EXPECT_EQ(bits(is.median_score_quantile), bits(was.median_score_quantile));
    EXPECT_EQ(bits(is.sd_score_quantile), bits(was.sd_score_quantile));
    EXPECT_EQ(bits(is.line_error_scale), bits(was.line_error_scale));
    EXPECT_EQ(is.records, was.records);
    EXPECT_EQ(is.pooled, was.pooled);
  }
}

TEST(BankCodec, ABankWithRecordsRoundTripsBitwise) {
  CalibrationBank bank;
  bank.device_study_file = "device.toml";
  bank.device_study_text = "[device]\n";
  bank.prior_study_text = "[ensemble]\n";
  bank.atoms = shapes();
  bank.threads = 2;
  bank.seconds = 1.5;
  bank.atom_seconds = 0.25;
  bank.estimation_cpu_seconds = 0.75;
  CalibrationSample s;
  s.realisation = 7;
  s.valid = true;
  s.true_stiffness = {45.0, 130.0};
  s.stiffness = {44.0};
  s.log_stiffness_se = {0.1};
  s.counts = {1.0, 2.0};
  s.log_evidence = {-3.0, -std::numeric_limits<double>::infinity()};
  s.naive_counts = {1.0, 2.0, 3.0};
  bank.samples = {s, CalibrationSample{}};
  const CalibrationBank back = decode_bank_with_records(encode_bank_with_records(bank));
  expect_same(back.atoms, bank.atoms);
  EXPECT_EQ(back.device_study_text, bank.device_study_text);
  EXPECT_EQ(back.threads, 2);
  ASSERT_EQ(back.samples.size(), 2u);
  EXPECT_EQ(bits(back.samples[0].log_evidence), bits(s.log_evidence));
  EXPECT_EQ(bits(back.samples[0].true_stiffness), bits(s.true_stiffness));
}

TEST(BankCodec, BytesCutShortAreAProgramError) {
  StoredBank bank;
  bank.atoms = shapes();
  const std::string bytes = encode_stored_bank(bank);
  EXPECT_THROW((void)decode_stored_bank(std::string_view(bytes).substr(0, bytes.size() - 1)), Error);
  EXPECT_THROW((void)decode_stored_bank(bytes + '\0'), Error);
}

}  // namespace
}  // namespace stengmc
