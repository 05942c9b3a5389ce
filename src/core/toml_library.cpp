// toml++'s compiled part, once for the whole program (TOML_HEADER_ONLY=0 everywhere else).
#define TOML_IMPLEMENTATION
#include "core/toml_library.hpp"
