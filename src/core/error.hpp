#pragma once
#include <stdexcept>
#include <string>

namespace stengmc {

//! Base of every exception the library throws; only the CLI catches it.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

//! Bad input: a study, surface or displacement file that cannot be used.
//! The message names the file, the line where known, the key and what was expected.
class InputError : public Error {
 public:
  using Error::Error;
};

//! The model left its domain of validity (x reaching l under policy `error`,
//! an integrator that could not meet its tolerance).
class ModelError : public Error {
 public:
  using Error::Error;
};

}  // namespace stengmc
