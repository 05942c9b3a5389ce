#pragma once
//! Model 1's keys of a study's [model] table, read and listed beside its parameters
//! (docs/study-files.md). The list is what run files record as /model attributes; the
//! drive's frequency is recorded as the angular frequency the solver uses.
#include <vector>

#include "core/setting.hpp"
#include "core/toml_reader.hpp"
#include "tribology/model1.hpp"

namespace stengmc {

//! Model 1's keys of `model` (its `kind` is the caller's); InputError names the key.
Model1Params read_model1_params(TomlTable& model);

//! Every setting with its value, as run files record them.
std::vector<Setting> model1_settings(const Model1Params& params);

}  // namespace stengmc
