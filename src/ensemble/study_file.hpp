#pragma once
//! Everything a study file says: the run's settings (Study, the pipeline's) and the
//! [ensemble] table when it has one. The ensemble layer reads the file because [ensemble]
//! is its table; the pipeline reads only the run's (pipeline/study.hpp).
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ensemble/ensemble_settings.hpp"
#include "pipeline/study.hpp"

namespace stengmc {

//! A Study is-a run's settings: every realisation of an ensemble is a Study, so the
//! ensemble's functions hand this to the pipeline's unchanged.
struct StudyFile : Study {
  std::optional<EnsembleSettings> ensemble;  //!< when the study is an ensemble ([ensemble])
};

//! read_study (pipeline/study.hpp) that also reads and checks [ensemble].
StudyFile read_study_file(const std::string& file, std::optional<std::uint64_t> realisation = 0,
                          const std::vector<ParameterOverride>& overrides = {});

//! parse_study (pipeline/study.hpp) that also reads and checks [ensemble].
StudyFile parse_study_file(const std::string& text, const std::string& file,
                           std::optional<std::uint64_t> realisation = 0,
                           const std::vector<ParameterOverride>& overrides = {});

}  // namespace stengmc
