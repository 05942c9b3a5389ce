#include "io/displacement_input.hpp"

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/error.hpp"
#include "io/guarded_read.hpp"
#include "core/hdf5_file.hpp"
#include "core/input_file.hpp"
#include "core/text_excerpt.hpp"
#include "io/run_file.hpp"

namespace stengmc {

namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream stream(line);
  std::string field;
  while (std::getline(stream, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

}  // namespace

namespace {

DisplacementInput read_hdf5(const std::string& path) {
  Hdf5Reader file(path);
  check_format_version(file, path, RUN_FILE_FORMAT_VERSION);
  DisplacementInput input;
  input.times_s = file.vector("/time");
  input.x_m = file.matrix("/asperity/x");
  const auto sigma = file.vector("/asperity/sigma");
  const auto d0 = file.vector("/asperity/d0");
  const auto w = file.vector("/asperity/w");
  const auto l = file.vector("/asperity/l");
  const std::size_t n = input.x_m.size();
  for (const auto* v : {&sigma, &d0, &w, &l})
    if (v->size() != n)
      throw InputError(path + ": /asperity/sigma, d0, w and l must each have one value per row of /asperity/x (" +
                       std::to_string(n) + ")");
  for (std::size_t i = 0; i < n; ++i) input.elements.push_back({sigma[i], d0[i], w[i], l[i]});
  validate(input, path);
  return input;
}

}  // namespace

DisplacementInput read_displacement_hdf5(const std::string& path) {
  check_input_file(path, "an HDF5 file");
  read_in_child_first(path, [&] { (void)read_hdf5(path); });
  return read_hdf5(path);
}

DisplacementInput read_displacement_csv(const std::string& path, const StengElement& element) {
  std::ifstream in = open_input_file(path, "the displacement CSV file");
  std::string line;
  if (!std::getline(in, line)) throw InputError(path + ":1: empty file; expected a header `t,x1,...`");
  const auto header = split(line);
  if (header.size() < 2 || trim_blanks(header[0]) != "t")
    throw InputError(path + ":1: header must be `t,x1,...,xn` (time in s, displacements in m)");
  DisplacementInput input;
  input.x_m.resize(header.size() - 1);
  std::size_t line_number = 1;
  while (std::getline(in, line)) {
    ++line_number;
    if (trim_blanks(line).empty()) continue;
    const auto fields = split(line);
    if (fields.size() != header.size())
      throw InputError(path + ":" + std::to_string(line_number) + ": " + std::to_string(fields.size()) +
                       " fields; the header has " + std::to_string(header.size()));
    for (std::size_t k = 0; k < fields.size(); ++k) {
      const std::string text = trim_blanks(fields[k]);
      std::string why;
      const auto value = parse_number(text, &why);
      if (!value)
        throw InputError(path + ":" + std::to_string(line_number) + ": column '" + text_excerpt(trim_blanks(header[k])) +
                         "' = '" + text_excerpt(text) +
                         "' " + (why == "is not a number" ? "is not a finite number" : why));
      (k == 0 ? input.times_s : input.x_m[k - 1]).push_back(*value);
    }
  }
  input.elements.assign(input.x_m.size(), element);
  validate(input, path);
  return input;
}

void validate(const DisplacementInput& input, const std::string& path) {
  const std::size_t m = input.times_s.size();
  if (input.x_m.empty()) throw InputError(path + ": no displacement series (need at least one element)");
  if (m < 2) throw InputError(path + ": need at least 2 samples, got " + std::to_string(m));
  for (std::size_t j = 0; j < m; ++j) {
    if (!std::isfinite(input.times_s[j])) throw InputError(path + ": time sample " + std::to_string(j) + " is not finite");
    if (j > 0 && !(input.times_s[j] > input.times_s[j - 1]))
      throw InputError(path + ": times must be strictly increasing (sample " + std::to_string(j) + ")");
  }
  for (std::size_t i = 0; i < input.x_m.size(); ++i) {
    const StengElement& e = input.elements[i];
    if (!(e.effective_thickness_m > 0) || !(e.width_m > 0) || !(e.length_m > 0) || !std::isfinite(e.charge_density_c_per_m2))
      throw InputError(path + ": element " + std::to_string(i + 1) + ": d0, w and l must be > 0 and sigma finite");
    if (input.x_m[i].size() != m)
      throw InputError(path + ": element " + std::to_string(i + 1) + " has " + std::to_string(input.x_m[i].size()) +
                       " samples; /time has " + std::to_string(m));
    for (std::size_t j = 0; j < m; ++j) {
      const double x = input.x_m[i][j];
      if (!std::isfinite(x))
        throw InputError(path + ": element " + std::to_string(i + 1) + ", sample " + std::to_string(j) + ": x is not finite");
      if (x >= e.length_m) {
        std::ostringstream what;
        what << path << ": element " << i + 1 << ": x = " << x << " m reaches l = " << e.length_m << " m at t = "
             << input.times_s[j] << " s; the S-TENG element formulas (MODEL.md §2) hold only for x < l";
        throw InputError(what.str());
      }
    }
  }
}

}  // namespace stengmc
