#include "io/calibration_bank_codec.hpp"

#include "core/byte_codec.hpp"
#include "core/error.hpp"

namespace stengmc {

namespace {

//! Reads what the matching encoder wrote, in the same order; any shortfall is a program
//! error (the bytes come from this program's own child process, not from a file).
class BankDecoder {
 public:
  explicit BankDecoder(std::string_view bytes) : in_(bytes) {}
  std::string text() {
    std::string s;
    check(in_.text(s));
    return s;
  }
  std::uint64_t whole() {
    std::uint64_t v = 0;
    check(in_.u64(v));
    return v;
  }
  double number() {
    double v = 0.0;
    check(in_.doubles(1, &v));
    return v;
  }
  std::vector<double> vector() {
    std::vector<double> v;
    check(in_.vector(v));
    return v;
  }
  std::vector<std::vector<double>> rows() {
    std::vector<std::vector<double>> v;
    check(in_.rows(v));
    return v;
  }
  void finish() const { check(in_.left() == 0); }

 private:
  static void check(bool read) {
    if (!read) throw Error("a calibration bank handed over by the process that read it does not decode (a program error)");
  }
  ByteDecoder in_;
};

void encode_atoms(ByteEncoder& out, const AtomShapeData& a) {
  out.f64(a.range.min_pi);
  out.f64(a.range.max_pi);
  out.f64(a.range.min_zeta);
  out.f64(a.range.max_zeta);
  out.f64(a.settings.log_pi_step);
  out.u64(a.settings.zeta_nodes);
  out.f64(a.settings.theta_step);
  out.f64(a.settings.after_breakaway);
  out.f64(a.settings.before_breakaway);
  out.f64(a.settings.split_pi);
  out.f64(a.settings.blend);
  out.f64(a.settings.tail_fit_span);
  out.vector(a.pi_nodes);
  out.vector(a.zeta_nodes);
  out.u64(a.onset_samples);
  out.u64(a.breakaway_samples);
  out.rows(a.onset_values);
  out.rows(a.onset_slopes);
  out.rows(a.breakaway_values);
  out.rows(a.breakaway_slopes);
  out.vector(a.breakaway_share);
  out.vector(a.tail_log_amplitude);
  out.vector(a.tail_phase);
  out.f64(a.check_error);
}

AtomShapeData decode_atoms(BankDecoder& in) {
  AtomShapeData a;
  a.range.min_pi = in.number();
  a.range.max_pi = in.number();
  a.range.min_zeta = in.number();
  a.range.max_zeta = in.number();
  a.settings.log_pi_step = in.number();
  a.settings.zeta_nodes = in.whole();
  a.settings.theta_step = in.number();
  a.settings.after_breakaway = in.number();
  a.settings.before_breakaway = in.number();
  a.settings.split_pi = in.number();
  a.settings.blend = in.number();
  a.settings.tail_fit_span = in.number();
  a.pi_nodes = in.vector();
  a.zeta_nodes = in.vector();
  a.onset_samples = in.whole();
  a.breakaway_samples = in.whole();
  a.onset_values = in.rows();
  a.onset_slopes = in.rows();
  a.breakaway_values = in.rows();
  a.breakaway_slopes = in.rows();
  a.breakaway_share = in.vector();
  a.tail_log_amplitude = in.vector();
  a.tail_phase = in.vector();
  a.check_error = in.number();
  return a;
}

void encode_maps(ByteEncoder& out, const CalibrationMaps& m) {
  out.u64(m.count_min);
  out.u64(m.count_max);
  out.f64(m.misfit_ratio);
  out.f64(m.line_se_bound);
  for (const ClassMaps& c : m.classes) {
    out.rows(c.confusion);
    out.vector(c.median_score_quantile);
    out.vector(c.sd_score_quantile);
    out.f64(c.line_error_scale);
    out.u64(c.records);
    out.u64(c.pooled ? 1 : 0);
  }
  out.u64(m.naive_threshold_index);
  out.f64(m.naive_threshold);
  out.u64(m.records);
  out.f64(m.bank_count_rmse);
  out.f64(m.bank_exact_rate);
  out.f64(m.bank_naive_rmse);
  out.f64(m.bank_naive_exact_rate);
}

CalibrationMaps decode_maps(BankDecoder& in) {
  CalibrationMaps m;
  m.count_min = in.whole();
  m.count_max = in.whole();
  m.misfit_ratio = in.number();
  m.line_se_bound = in.number();
  for (ClassMaps& c : m.classes) {
    c.confusion = in.rows();
    c.median_score_quantile = in.vector();
    c.sd_score_quantile = in.vector();
    c.line_error_scale = in.number();
    c.records = in.whole();
    c.pooled = in.whole() != 0;
  }
  m.naive_threshold_index = in.whole();
  m.naive_threshold = in.number();
  m.records = in.whole();
  m.bank_count_rmse = in.number();
  m.bank_exact_rate = in.number();
  m.bank_naive_rmse = in.number();
  m.bank_naive_exact_rate = in.number();
  return m;
}

void encode_sample(ByteEncoder& out, const CalibrationSample& s) {
  out.u64(s.realisation);
  out.u64(s.valid ? 1 : 0);
  out.vector(s.true_stiffness);
  out.f64(s.snr_db);
  out.f64(s.law_first);
  out.f64(s.law_second);
  out.u64(s.count);
  out.vector(s.counts);
  out.vector(s.log_evidence);
  out.vector(s.stiffness);
  out.vector(s.log_stiffness_se);
  out.f64(s.median);
  out.f64(s.sd_log);
  out.f64(s.noise_sigma_v);
  out.f64(s.residual_sigma_v);
  out.f64(s.band_power_ratio);
  out.f64(s.snr_estimate_db);
  out.f64(s.seconds);
  out.vector(s.naive_counts);
}

CalibrationSample decode_sample(BankDecoder& in) {
  CalibrationSample s;
  s.realisation = in.whole();
  s.valid = in.whole() != 0;
  s.true_stiffness = in.vector();
  s.snr_db = in.number();
  s.law_first = in.number();
  s.law_second = in.number();
  s.count = in.whole();
  s.counts = in.vector();
  s.log_evidence = in.vector();
  s.stiffness = in.vector();
  s.log_stiffness_se = in.vector();
  s.median = in.number();
  s.sd_log = in.number();
  s.noise_sigma_v = in.number();
  s.residual_sigma_v = in.number();
  s.band_power_ratio = in.number();
  s.snr_estimate_db = in.number();
  s.seconds = in.number();
  s.naive_counts = in.vector();
  return s;
}

}  // namespace

std::string encode_stored_bank(const StoredBank& bank) {
  ByteEncoder out;
  out.text(bank.path);
  out.text(bank.identity.device);
  out.text(bank.identity.prior);
  out.text(bank.identity.grid);
  out.text(bank.identity.estimator);
  out.u64(bank.identity.hash);
  out.text(bank.git_revision);
  out.text(bank.created_utc);
  encode_atoms(out, bank.atoms);
  encode_maps(out, bank.maps);
  return std::move(out.bytes());
}

StoredBank decode_stored_bank(std::string_view bytes) {
  BankDecoder in(bytes);
  StoredBank bank;
  bank.path = in.text();
  bank.identity.device = in.text();
  bank.identity.prior = in.text();
  bank.identity.grid = in.text();
  bank.identity.estimator = in.text();
  bank.identity.hash = in.whole();
  bank.git_revision = in.text();
  bank.created_utc = in.text();
  bank.atoms = decode_atoms(in);
  bank.maps = decode_maps(in);
  in.finish();
  return bank;
}

std::string encode_bank_with_records(const CalibrationBank& bank) {
  ByteEncoder out;
  out.text(bank.device_study_file);
  out.text(bank.device_study_text);
  out.text(bank.prior_study_text);
  encode_atoms(out, bank.atoms);
  out.u64(static_cast<std::uint64_t>(bank.threads));
  out.f64(bank.seconds);
  out.f64(bank.atom_seconds);
  out.f64(bank.estimation_cpu_seconds);
  out.u64(bank.samples.size());
  for (const CalibrationSample& s : bank.samples) encode_sample(out, s);
  return std::move(out.bytes());
}

CalibrationBank decode_bank_with_records(std::string_view bytes) {
  BankDecoder in(bytes);
  CalibrationBank bank;
  bank.device_study_file = in.text();
  bank.device_study_text = in.text();
  bank.prior_study_text = in.text();
  bank.atoms = decode_atoms(in);
  bank.threads = static_cast<int>(in.whole());
  bank.seconds = in.number();
  bank.atom_seconds = in.number();
  bank.estimation_cpu_seconds = in.number();
  const std::uint64_t samples = in.whole();
  for (std::uint64_t i = 0; i < samples; ++i) bank.samples.push_back(decode_sample(in));
  in.finish();
  return bank;
}

}  // namespace stengmc
