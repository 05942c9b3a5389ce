#pragma once
//! /records of a calibration bank (io/calibration_bank_file.hpp): one entry per simulated
//! record (its truth, raw estimate and naive counts), the k lists flat with offsets
//! (true_stiffness / true_offset, stiffness and log_stiffness_se / estimate_offset, orders
//! and log_evidence / order_offset); every table with its checksum.
#include <cstddef>
#include <vector>

#include "core/hdf5_file.hpp"
#include "inverse/calibration_sample.hpp"
#include "io/checksummed_tables.hpp"

namespace stengmc {

//! Writes /records; the naive count of each record at threshold `naive_index` as /records/naive_count.
void write_bank_records(Hdf5Writer& file, const std::vector<CalibrationSample>& samples, std::size_t naive_index);

//! Reads /records back, every checksum verified and the offsets checked against their lists;
//! InputError from `tables` when anything is damaged.
std::vector<CalibrationSample> read_bank_records(const ChecksumReader& tables);

}  // namespace stengmc
