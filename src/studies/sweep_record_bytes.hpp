#pragma once
// A sweep's medium record as bytes, for the MPI ranks of a sweep (sweep_record_bytes.cpp). Private
// to the program.
#include <string>

#include "softdrop/sweep.hpp"

namespace softdrop {

/// A unit's record as bytes, every double to the bit, for sending it between the processes of a
/// job (the byte order of the machine: both ends run the same build on the same kind of node).
std::string encode_sweep_medium(const SweepMedium& medium);
/// The record encode_sweep_medium made; throws std::invalid_argument if `bytes` is not one.
SweepMedium decode_sweep_medium(const std::string& bytes);

}  // namespace softdrop
