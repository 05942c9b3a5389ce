#pragma once
// Small surface files the command-line tests write into their scratch folders.

namespace stengmc::testing {

//! Three summits whose heights come from the histogram file h.csv beside it (an empirical
//! law), stiffnesses uniform on [50, 150] N/m, 1 mN each.
inline const char* HISTOGRAM_SURFACE = R"(kind = "random"
nominal_area_m2 = 1e-6
[summits]
count_rule = "fixed"
count = 3
[heights]
kind = "empirical"
file = "h.csv"
[stiffness]
kind = "uniform"
min = 50
max = 150
[load]
rule = "fixed"
normal_load_n = 1e-3
)";

}  // namespace stengmc::testing
