#pragma once
//! Reading a file the HDF5 library may not survive. HDF5 1.10 can crash or loop for ever on
//! a damaged file (the fuzz tests found a loop in H5C_protect reading a corrupt global
//! heap), and no exception can report that. So such a file is first read by a child
//! process: if the child dies of a signal or does not finish in time, the file is refused
//! with an InputError naming it, and this process never touches it (README: "Rejected
//! inputs and faults").
#include <functional>
#include <string>

namespace stengmc {

//! Runs `read` in a child process first (its result and exceptions are discarded there);
//! returns when the child finished normally, so the caller can then read for real. Throws
//! InputError naming `path` when the child crashed or took longer than 10 s + 1 s per 20 MB.
//! Damage that makes HDF5 corrupt memory without crashing may pass the child and then harm
//! this process's own read: read_in_child below leaves this process out altogether.
void read_in_child_first(const std::string& path, const std::function<void()>& read);

//! Runs `read` in a child process only and returns the bytes it returned (through a pipe;
//! core/byte_codec.hpp encodes a reader's result): the file never meets HDF5 in this
//! process. An InputError thrown by `read` is thrown here with its message, any other
//! exception as Error; a crash or a timeout (as above) is an InputError naming `path`.
std::string read_in_child(const std::string& path, const std::function<std::string()>& read);

//! Reads every attribute and dataset of the HDF5 file at `path` (what a figure script may
//! touch); throws InputError on an HDF5 failure.
void read_every_hdf5_object(const std::string& path);

}  // namespace stengmc
