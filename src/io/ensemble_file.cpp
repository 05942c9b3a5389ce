#include "io/ensemble_file.hpp"

#include <cstdint>

#include "io/hdf5_file.hpp"
#include "io/run_file.hpp"

namespace stengmc {

namespace {

void write_realisations(Hdf5Writer& f, const EnsembleRun& run) {
  std::vector<std::int64_t> ids, valid, offsets{0};
  std::vector<std::string> failures;
  for (const RealisationRecord& r : run.records) {
    ids.push_back(static_cast<std::int64_t>(r.realisation));
    valid.push_back(r.valid ? 1 : 0);
    failures.push_back(r.failure);
    offsets.push_back(offsets.back() + static_cast<std::int64_t>(r.asperity_count()));
  }
  f.write("/realisations/realisation", ids, "index");
  f.write("/realisations/valid", valid, "1");
  f.write("/realisations/failure", failures, "text");
  f.write("/realisations/asperity_offset", offsets, "index");
  for (std::size_t k = 0; k < SCALAR_COUNT; ++k) {
    std::vector<double> values;
    for (const RealisationRecord& r : run.records) values.push_back(r.scalars[k]);
    const ScalarInfo& info = scalar_info(static_cast<Scalar>(k));
    f.write("/realisations/" + std::string(info.name), values, info.unit);
  }
  for (std::size_t c = 0; c < ASPERITY_COLUMN_COUNT; ++c) {
    std::vector<double> values;
    for (const RealisationRecord& r : run.records) values.insert(values.end(), r.asperities[c].begin(), r.asperities[c].end());
    const ScalarInfo& info = column_info(static_cast<AsperityColumn>(c));
    f.write("/asperities/" + std::string(info.name), values, info.unit);
  }
}

void write_traces(Hdf5Writer& f, const EnsembleRun& run) {
  for (const RealisationRecord& r : run.records) {
    if (r.time_s.empty()) continue;
    const std::string g = "/traces/realisation_" + std::to_string(r.realisation);
    f.write(g + "/time", r.time_s, "s");
    f.write(g + "/voltage", r.voltage_v, "V");
    f.write(g + "/charge", r.charge_c, "C");
  }
}

void write_interval(Hdf5Writer& f, const std::string& group, const std::string& name, const Interval& i,
                    std::string_view unit) {
  f.write(group + "/" + name, std::vector<double>{i.estimate}, unit);
  f.write(group + "/" + name + "_low", std::vector<double>{i.low}, unit);
  f.write(group + "/" + name + "_high", std::vector<double>{i.high}, unit);
  f.attribute(group, name + "_method", i.method);
  f.attribute(group, name + "_known", static_cast<std::int64_t>(i.known ? 1 : 0));
}

void write_summary(Hdf5Writer& f, const EnsembleSummary& s) {
  for (std::size_t k = 0; k < SCALAR_COUNT; ++k) {
    const ScalarInfo& info = scalar_info(static_cast<Scalar>(k));
    const ScalarSummary& v = s.scalars[k];
    const std::string g = "/summary/" + std::string(info.name);
    f.write(g + "/count", std::vector<std::int64_t>{static_cast<std::int64_t>(v.count)}, "1");
    write_interval(f, g, "mean", v.mean, info.unit);
    write_interval(f, g, "std", v.standard_deviation, info.unit);
    write_interval(f, g, "median", v.median, info.unit);
    write_interval(f, g, "p05", v.p05, info.unit);
    write_interval(f, g, "p95", v.p95, info.unit);
    f.write(g + "/min", std::vector<double>{v.min}, info.unit);
    f.write(g + "/max", std::vector<double>{v.max}, info.unit);
  }
  write_interval(f, "/summary/pooled", "fft_ratio", s.fft_pooled_ratio, "1");
  write_interval(f, "/summary/pooled", "hr_ratio", s.hr_pooled_ratio, "1");
  write_interval(f, "/summary/pooled", "valid_fraction", s.valid_fraction, "1");
}

}  // namespace

void write_ensemble_file(const std::string& path, const Study& study, const EnsembleRun& run,
                         const EnsembleSummary& summary) {
  Hdf5Writer file(path);
  write_provenance(file, {.file_type = "stengmc-ensemble",
                          .input_file = study.file,
                          .input_text = study.text,
                          .seed = study.seed,
                          .surface_file = study.surface_file,
                          .surface_text = study.surface_text});
  const EnsembleSettings& e = *study.ensemble;
  file.attribute("/", "title", study.title);
  file.attribute("/", "realisations_requested", static_cast<std::int64_t>(e.realisations));
  file.attribute("/", "realisations_run", static_cast<std::int64_t>(run.records.size()));
  file.attribute("/", "valid_realisations", static_cast<std::int64_t>(summary.valid));
  file.attribute("/", "stopped_at_target", static_cast<std::int64_t>(run.stopped_at_target ? 1 : 0));
  file.attribute("/", "target_statistic", e.target ? scalar_info(*e.target).name : "");
  file.attribute("/", "target_half_width", e.target_half_width);
  write_realisations(file, run);
  write_traces(file, run);
  write_summary(file, summary);
  file.commit();
}

}  // namespace stengmc
