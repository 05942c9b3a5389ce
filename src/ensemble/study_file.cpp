#include "ensemble/study_file.hpp"

#include "core/toml_reader.hpp"

namespace stengmc {

namespace {

StudyFile parse(TomlDocument& document, std::optional<std::uint64_t> realisation,
                const std::vector<ParameterOverride>& overrides) {
  std::optional<EnsembleSettings> ensemble;
  auto read_ensemble = [&](TomlTable& root) {
    if (auto table = root.table("ensemble")) ensemble = read_ensemble_settings(*table);
  };
  StudyFile study;
  static_cast<Study&>(study) = parse_study_document(document, realisation, overrides, read_ensemble);
  study.ensemble = std::move(ensemble);
  return study;
}

}  // namespace

StudyFile read_study_file(const std::string& file, std::optional<std::uint64_t> realisation,
                          const std::vector<ParameterOverride>& overrides) {
  auto document = TomlDocument::from_file(file);
  return parse(*document, realisation, overrides);
}

StudyFile parse_study_file(const std::string& text, const std::string& file, std::optional<std::uint64_t> realisation,
                           const std::vector<ParameterOverride>& overrides) {
  auto document = TomlDocument::from_string(text, file);
  return parse(*document, realisation, overrides);
}

}  // namespace stengmc
