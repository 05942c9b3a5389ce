#pragma once
//! Model 2's keys of a study's [model] table, read and listed beside its parameters
//! (docs/study-files.md): the reader checks them, and the list is what run files record as
//! /model attributes and what generated studies write back.
#include <vector>

#include "core/setting.hpp"
#include "core/toml_reader.hpp"
#include "tribology/model2.hpp"

namespace stengmc {

//! Model 2's keys of `model` (its `kind` is the caller's); InputError names the key.
Model2Params read_model2_params(TomlTable& model);

//! Every key with its value, in the order study files list them.
std::vector<Setting> model2_settings(const Model2Params& params);

//! A study's `[counterface]` table (docs/study-files.md): InputError names the key.
//! `belt_velocity_m_per_s` is Model 2's: a modulation needs a moving belt.
CounterfaceParams read_counterface(TomlTable& counterface, double belt_velocity_m_per_s);

//! `[counterface]`'s keys with their values.
std::vector<Setting> counterface_settings(const CounterfaceParams& counterface);

}  // namespace stengmc
