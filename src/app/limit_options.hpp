#pragma once
//! --max-memory-gb and --max-steps, the limits every command checks its work estimate
//! against before it starts (pipeline/work_estimate.hpp; docs/faults.md, "Limits").
#include <CLI/CLI.hpp>

#include "app/validators.hpp"
#include "pipeline/work_estimate.hpp"

namespace stengmc::app {

struct LimitOptions {
  double memory_gb = WorkLimits{}.memory_bytes / 1e9;
  double steps = WorkLimits{}.steps;

  [[nodiscard]] WorkLimits limits() const { return {memory_gb * 1e9, steps}; }
};

inline void add_limit_options(CLI::App* command, LimitOptions& options) {
  command->add_option("--max-memory-gb", options.memory_gb,
                      "Refuse, before starting, work estimated to need more memory than this [GB]")
      ->capture_default_str()
      ->check(finite_number(false));
  command->add_option("--max-steps", options.steps,
                      "Refuse, before starting, work estimated to take more solver steps than this (~100 ns each)")
      ->capture_default_str()
      ->check(finite_number(false));
}

}  // namespace stengmc::app
