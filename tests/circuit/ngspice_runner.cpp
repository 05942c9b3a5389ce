#include "circuit/ngspice_runner.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace stengmc::test {

namespace {

std::string lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

//! Full double precision, so ngspice sees exactly the samples our solver interpolates.
std::string number(double value) {
  std::array<char, 32> buffer{};
  std::snprintf(buffer.data(), buffer.size(), "%.17g", value);
  return buffer.data();
}

//! Single-quoted for /bin/sh.
std::string shell_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

std::optional<std::filesystem::path> find_ngspice() {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return std::nullopt;
  std::stringstream dirs(path);
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) continue;
    const std::filesystem::path candidate = std::filesystem::path(dir) / "ngspice";
    if (::access(candidate.c_str(), X_OK) == 0 && std::filesystem::is_regular_file(candidate)) return candidate;
  }
  return std::nullopt;
}

std::filesystem::path make_unique_directory(const std::filesystem::path& parent, std::string_view prefix) {
  std::filesystem::create_directories(parent);
  std::string pattern = (parent / (std::string(prefix) + "XXXXXX")).string();
  if (::mkdtemp(pattern.data()) == nullptr)
    throw std::runtime_error("cannot create a temporary directory from " + pattern + ": " + std::strerror(errno));
  return pattern;
}

NgspiceRun run_ngspice(const std::filesystem::path& ngspice, const std::filesystem::path& netlist) {
  const std::string command = "cd " + shell_quote(netlist.parent_path().string()) + " && " +
                              shell_quote(ngspice.string()) + " -b " + shell_quote(netlist.filename().string()) +
                              " 2>&1";
  NgspiceRun run;
  const auto start = std::chrono::steady_clock::now();
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) throw std::runtime_error("cannot start: " + command);
  std::array<char, 4096> buffer{};
  std::size_t read = 0;
  while ((read = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) run.output.append(buffer.data(), read);
  const int status = ::pclose(pipe);
  run.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.exit_status = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
  return run;
}

RawFile RawFile::read_binary(const std::filesystem::path& path) {
  static_assert(std::endian::native == std::endian::little, "the raw file holds little-endian doubles");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open the ngspice raw file " + path.string());
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());

  const std::string marker = "Binary:\n";
  const std::size_t data_start = bytes.find(marker);
  if (data_start == std::string::npos)
    throw std::runtime_error(path.string() + ": no 'Binary:' section (was filetype=binary set?)");
  std::istringstream header(bytes.substr(0, data_start));

  std::size_t variables = 0;
  std::size_t points = 0;
  bool real = false;
  RawFile raw;
  std::string line;
  while (std::getline(header, line)) {
    if (line.rfind("Flags:", 0) == 0) {
      real = line.find("real") != std::string::npos;
    } else if (line.rfind("No. Variables:", 0) == 0) {
      variables = std::stoul(line.substr(14));
    } else if (line.rfind("No. Points:", 0) == 0) {
      points = std::stoul(line.substr(11));
    } else if (line.rfind("Variables:", 0) == 0) {
      for (std::size_t k = 0; k < variables && std::getline(header, line); ++k) {
        std::istringstream fields(line);  // "\t<index>\t<name>\t<type>"
        std::size_t index = 0;
        std::string name;
        fields >> index >> name;
        if (!fields || index != k) throw std::runtime_error(path.string() + ": bad variable line '" + line + "'");
        raw.names_.push_back(lower(name));
      }
    }
  }
  if (!real) throw std::runtime_error(path.string() + ": only real (not complex) raw data is read");
  if (variables == 0 || raw.names_.size() != variables)
    throw std::runtime_error(path.string() + ": the header lists " + std::to_string(raw.names_.size()) +
                             " variables, expected " + std::to_string(variables));
  const std::size_t needed = variables * points * sizeof(double);
  const std::size_t offset = data_start + marker.size();
  if (bytes.size() < offset + needed)
    throw std::runtime_error(path.string() + ": truncated, " + std::to_string(bytes.size() - offset) +
                             " data bytes for " + std::to_string(points) + " points of " + std::to_string(variables) +
                             " variables");
  raw.columns_.assign(variables, std::vector<double>(points));
  for (std::size_t p = 0; p < points; ++p)
    for (std::size_t v = 0; v < variables; ++v)
      std::memcpy(&raw.columns_[v][p], bytes.data() + offset + (p * variables + v) * sizeof(double), sizeof(double));
  return raw;
}

const std::vector<double>& RawFile::column(std::string_view name) const {
  const std::string key = lower(name);
  const auto it = std::find(names_.begin(), names_.end(), key);
  if (it == names_.end()) {
    std::string known;
    for (const std::string& n : names_) known += " " + n;
    throw std::runtime_error("raw file has no vector '" + key + "'; it has:" + known);
  }
  return columns_[static_cast<std::size_t>(it - names_.begin())];
}

void write_parallel_steng_netlist(const std::filesystem::path& netlist, const std::filesystem::path& raw_file,
                                  std::span<const StengElement> elements, std::span<const double> times_s,
                                  std::span<const std::vector<double>> displacement_m, double load_resistance_ohm,
                                  double epsilon0, const SpiceTransient& transient) {
  if (displacement_m.size() != elements.size()) throw std::invalid_argument("one displacement series per element");
  std::ofstream out(netlist);
  if (!out) throw std::runtime_error("cannot write " + netlist.string());
  out << "* S-TENG elements in parallel on a load (stengmc test_ngspice)\n";

  // The paper's appendix subcircuit, second model (Fig. 10). Parameters travel as node
  // voltages in SI units, as in the paper. Bv is the open-circuit voltage (Eq. 6); Bc
  // writes the charge C(x) (V(vp) - V(n003)) of the element's capacitor (Eq. 7) onto
  // the 1 F capacitor Cc, so the current through the 0 V sense source Vc is that
  // charge's time derivative, which Fc copies into the branch vp -> n003.
  out << ".subckt steng x sigma d0 w l vp vn\n"
         "Rx x 0 10G\n"
         "Bv n003 vn V=V(sigma)*V(d0)*V(x)/{epsilon0}/(V(l)-V(x))\n"
         "Fc vp n003 Vc 1\n"
         "Bc n001 0 V={epsilon0}*V(w)*(V(l)-V(x))/V(d0)*(V(vp)-V(n003))\n"
         "Vc n001 n002 0V\n"
         "Cc n002 0 1\n"
         ".param epsilon0=" << number(epsilon0) << "\n"
         ".ends steng\n\n";

  for (std::size_t i = 0; i < elements.size(); ++i) {
    const StengElement& e = elements[i];
    const std::vector<double>& x = displacement_m[i];
    if (x.size() != times_s.size()) throw std::invalid_argument("displacement and time samples differ in length");
    out << "Vsig" << i << " sig" << i << " 0 " << number(e.charge_density_c_per_m2) << "\n"
        << "Vd" << i << " d" << i << " 0 " << number(e.effective_thickness_m) << "\n"
        << "Vw" << i << " w" << i << " 0 " << number(e.width_m) << "\n"
        << "Vl" << i << " l" << i << " 0 " << number(e.length_m) << "\n"
        << "Vx" << i << " x" << i << " 0 PWL(\n";
    for (std::size_t k = 0; k < x.size(); ++k) {
      out << (k % 4 == 0 ? "+ " : " ") << number(times_s[k]) << " " << number(x[k]);
      if (k % 4 == 3 || k + 1 == x.size()) out << "\n";
    }
    out << "+ )\n"
        << "X" << i << " x" << i << " sig" << i << " d" << i << " w" << i << " l" << i << " out 0 steng\n\n";
  }

  out << "Rload out 0 " << number(load_resistance_ohm) << "\n"
      // Delivered charge, integrated by ngspice: I = V(out)/R into 1 F, so V(q) = Q [C].
      << "Bq 0 q I=V(out)/" << number(load_resistance_ohm) << "\n"
      << "Cq q 0 1\n"
      // q has no DC path; pin it to 0 for the operating point only (no `uic`).
      << ".ic v(q)=0\n\n";

  out << ".options reltol=" << number(transient.reltol) << " abstol=" << number(transient.abstol_a)
      << " chgtol=" << number(transient.chgtol_c) << " vntol=" << number(transient.vntol_v)
      << " method=" << transient.method << "\n"
      << ".control\n"
      << "set filetype=binary\n"
      << "tran " << number(transient.print_step_s) << " " << number(transient.stop_time_s) << " 0 "
      << number(transient.max_step_s) << "\n"
      << "write " << raw_file.filename().string() << " v(out) v(q)";
  for (std::size_t i = 0; i < elements.size(); ++i) out << " i(v.x" << i << ".vc)";
  out << "\n"
      << ".endc\n"
      << ".end\n";
  if (!out) throw std::runtime_error("error writing " + netlist.string());
}

}  // namespace stengmc::test
