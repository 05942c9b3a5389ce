#pragma once
//! Where a command may write (docs/faults.md): never over one of its
//! own inputs, never onto something that is not a regular file.
#include <string>
#include <vector>

namespace stengmc {

//! A file a command reads, with what it is for messages ("the study", "a histogram file").
struct NamedInput {
  std::string path;
  std::string role;
};

//! Throws InputError (exit 2), before anything runs, when `out`
//!  - is empty;
//!  - is, after resolving links, the same file as one of `inputs` (the output would
//!    replace it);
//!  - exists and is not a regular file: a device (as root, /dev/null would be renamed
//!    over), a FIFO (writing would block), a folder. No command writes to stdout-like sinks.
//! `option` says where `out` came from ("--out", "study.toml: [output] file").
void check_output_path(const std::string& out, const std::vector<NamedInput>& inputs,
                       const std::string& option = "--out");

}  // namespace stengmc
