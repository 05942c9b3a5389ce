#pragma once
//! A calibration bank as read, as bytes (core/byte_codec.hpp): what the child process that
//! reads a bank file hands back to the command (io/calibration_bank_file.cpp), so that a
//! damaged bank never meets HDF5 in the command's own process.
#include <string>
#include <string_view>

#include "io/calibration_bank_file.hpp"

namespace stengmc {

std::string encode_stored_bank(const StoredBank& bank);
//! @throws Error when `bytes` are not what encode_stored_bank wrote (a program error).
StoredBank decode_stored_bank(std::string_view bytes);

//! A bank read back with its records (read_calibration_bank_records), but its setup, which
//! the reader's caller gives.
std::string encode_bank_with_records(const CalibrationBank& bank);
//! @throws Error when `bytes` are not what encode_bank_with_records wrote.
CalibrationBank decode_bank_with_records(std::string_view bytes);

}  // namespace stengmc
