#include "circuit/ngspice_library.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <mutex>
#include <type_traits>

#include "core/error.hpp"

#ifdef STENGMC_WITH_NGSPICE
#include <dlfcn.h>
#include <ngspice/sharedspice.h>
#endif

namespace stengmc {

#ifndef STENGMC_WITH_NGSPICE

bool ngspice_library_available() { return false; }

NgspiceVectors run_ngspice_transient(const NgspiceTransient& transient) {
  throw InputError(transient.origin + ": this stengmc was built without ngspice (STENGMC_WITH_NGSPICE=OFF); install "
                   "libngspice0-dev (scripts/setup.sh) and rebuild, or use the built-in load ([circuit] "
                   "load_resistance_ohm, load_capacitance_f)");
}

#else

bool ngspice_library_available() { return true; }

namespace {

//! Everything the callbacks touch; guarded by `library_mutex` (held for a whole run).
struct Session {
  const NgspiceTransient* transient = nullptr;
  std::string errors;       // ngspice's stderr lines of this run
  std::string last_output;  // its last stdout lines, for context
  std::string callback_error;  // an exception thrown inside a callback, reported after the run
  bool exit_requested = false;
};

std::mutex library_mutex;
Session session;
bool initialised = false;

//! libngspice's functions, from the library opened on first use: linked instead, the loader
//! mapped and relocated its ~30 000 pointers at every start of stengmc, netlist or not
//! (0.5 ms of the 4 ms a start costs). The name is the library's soname (Debian libngspice0).
constexpr const char* NGSPICE_LIBRARY = "libngspice.so.0";
struct NgspiceFunctions {
  decltype(&ngSpice_Init) init = nullptr;
  decltype(&ngSpice_Init_Sync) init_sync = nullptr;
  decltype(&ngSpice_Command) command = nullptr;
  decltype(&ngSpice_Circ) circ = nullptr;
  decltype(&ngGet_Vec_Info) vector_info = nullptr;
};
NgspiceFunctions ngspice;

std::string lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

// The callbacks are C functions called from inside ngspice: no exception may cross them.
int on_output(char* text, int, void*) {
  const std::string_view line(text != nullptr ? text : "");
  constexpr std::string_view err = "stderr ";
  if (line.substr(0, err.size()) == err) {
    session.errors += std::string(line.substr(err.size())) + "\n";
  } else {
    session.last_output += std::string(line.substr(std::min(line.size(), std::string_view("stdout ").size()))) + "\n";
    if (session.last_output.size() > 4000) session.last_output.erase(0, session.last_output.size() - 2000);
  }
  return 0;
}
int on_status(char*, int, void*) { return 0; }
int on_exit(int, NG_BOOL, NG_BOOL, int, void*) {
  session.exit_requested = true;
  return 0;
}
int on_thread(NG_BOOL, int, void*) { return 0; }
int on_external_voltage(double* value, double t_s, char* name, int, void*) {
  try {
    *value = session.transient->external_voltage(lower(name != nullptr ? name : ""), t_s);
  } catch (const std::exception& e) {
    if (session.callback_error.empty()) session.callback_error = e.what();
    *value = 0.0;
  }
  return 0;
}
// A current source marked EXTERNAL in a user's netlist: stengmc supplies none.
int on_external_current(double* value, double, char* name, int, void*) {
  if (session.callback_error.empty())
    session.callback_error = std::string("current source ") + (name != nullptr ? name : "?") +
                             " is EXTERNAL: stengmc supplies no external current sources";
  *value = 0.0;
  return 0;
}

void command(const char* text) {
  std::string buffer(text);
  ngspice.command(buffer.data());
}

std::string last_lines(const std::string& text, std::size_t count) {
  std::size_t start = text.size();
  for (std::size_t k = 0; k < count && start > 0; ++k) {
    start = text.rfind('\n', start - 1);
    if (start == std::string::npos) return text;
  }
  return text.substr(start + 1);
}

//! "file:line" of the card ngspice's first "Error on line N" is about, or "".
std::string error_origin(const NgspiceTransient& transient) {
  constexpr std::string_view marker = "Error on line ";
  const std::size_t at = session.errors.find(marker);
  if (at == std::string::npos) return "";
  std::size_t line = 0;
  for (std::size_t k = at + marker.size(); k < session.errors.size() && std::isdigit(static_cast<unsigned char>(session.errors[k])); ++k)
    line = line * 10 + static_cast<std::size_t>(session.errors[k] - '0');
  return line >= 1 && line <= transient.card_origins.size() ? transient.card_origins[line - 1] : "";
}

[[noreturn]] void fail(const NgspiceTransient& transient, const std::string& what) {
  const std::string origin = error_origin(transient);
  std::string message = (origin.empty() ? transient.origin : origin) + ": ngspice: " + what;
  if (!session.errors.empty()) message += "\nngspice said:\n" + last_lines(session.errors, 12);
  throw InputError(message);
}

std::vector<double> read_vector(const NgspiceTransient& transient, const std::string& name) {
  std::string buffer(name);
  // ngGet_Vec_Info returns a pointer to one static struct: copy before the next call.
  const pvector_info info = ngspice.vector_info(buffer.data());
  if (info == nullptr || info->v_realdata == nullptr || info->v_length <= 0)
    fail(transient, "the run has no vector '" + name + "'");
  return {info->v_realdata, info->v_realdata + info->v_length};
}

//! Opens libngspice (once; it stays loaded) and finds its functions.
void load_library(const NgspiceTransient& transient) {
  void* library = dlopen(NGSPICE_LIBRARY, RTLD_NOW | RTLD_LOCAL);
  if (library == nullptr)
    throw InputError(transient.origin + ": cannot load " + NGSPICE_LIBRARY + " (" + dlerror() +
                     "); install libngspice0 (scripts/setup.sh) or use the built-in load ([circuit] "
                     "load_resistance_ohm, load_capacitance_f)");
  auto find = [&](auto& function, const char* name) {
    function = reinterpret_cast<std::remove_reference_t<decltype(function)>>(dlsym(library, name));
    if (function == nullptr) throw InputError(transient.origin + ": " + NGSPICE_LIBRARY + " has no function " + name);
  };
  find(ngspice.init, "ngSpice_Init");
  find(ngspice.init_sync, "ngSpice_Init_Sync");
  find(ngspice.command, "ngSpice_Command");
  find(ngspice.circ, "ngSpice_Circ");
  find(ngspice.vector_info, "ngGet_Vec_Info");
}

NgspiceVectors run_locked(const NgspiceTransient& transient) {
  if (!initialised) {
    load_library(transient);
    ngspice.init(on_output, on_status, on_exit, nullptr, nullptr, on_thread, nullptr);
    int ident = 0;
    ngspice.init_sync(on_external_voltage, on_external_current, nullptr, &ident, nullptr);
    initialised = true;
  }
  session = Session{};
  session.transient = &transient;
  // Leftovers of an earlier run (its circuit and plots) would be found by name otherwise.
  command("destroy all");
  command("remcirc");
  session.errors.clear();

  std::vector<std::string> cards = transient.cards;
  std::vector<char*> pointers;
  for (std::string& card : cards) pointers.push_back(card.data());
  pointers.push_back(nullptr);
  if (ngspice.circ(pointers.data()) != 0 || session.exit_requested) fail(transient, "the netlist does not load");
  if (session.errors.find("rror") != std::string::npos) fail(transient, "the netlist does not load");
  command("run");
  if (!session.callback_error.empty()) fail(transient, session.callback_error);
  if (session.exit_requested) fail(transient, "the simulator stopped");
  NgspiceVectors out;
  out.time_s = read_vector(transient, "time");
  // ngspice reports success even when the transient aborts ("timestep too small"): what
  // counts is the time it reached.
  const double reached = out.time_s.back();
  if (!(std::abs(reached - transient.stop_time_s) <= 1e-9 * transient.stop_time_s))
    fail(transient, "the transient stopped at t = " + std::to_string(reached) + " s before its end " +
                        std::to_string(transient.stop_time_s) + " s");
  for (const std::string& name : transient.vectors) {
    out.values.push_back(read_vector(transient, name));
    if (out.values.back().size() != out.time_s.size())
      fail(transient, "vector '" + name + "' has " + std::to_string(out.values.back().size()) + " points, time " +
                          std::to_string(out.time_s.size()));
  }
  command("destroy all");
  command("remcirc");
  return out;
}

}  // namespace

NgspiceVectors run_ngspice_transient(const NgspiceTransient& transient) {
  const std::lock_guard<std::mutex> lock(library_mutex);
  try {
    return run_locked(transient);
  } catch (...) {
    command("destroy all");
    command("remcirc");
    session = Session{};
    throw;
  }
}

#endif

}  // namespace stengmc
