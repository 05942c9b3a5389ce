#pragma once
//! Where the installed (or built) program finds the files it ships beside itself.

#include <filesystem>

namespace stengmc::app {

//! Folder of the plotting scripts (plot_run.py and the modules it imports): found
//! relative to the running executable, so an installed tree works wherever it is moved.
//! In an install that is <prefix>/share/stengmc/scripts beside <prefix>/bin/stengmc; in
//! the build tree the build makes the same relative path a link to the source scripts.
//! Throws stengmc::Error naming the folder it looked for when it is not there.
[[nodiscard]] std::filesystem::path scripts_dir();

}  // namespace stengmc::app
