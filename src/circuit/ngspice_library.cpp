#include "circuit/ngspice_library.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>
#include <optional>
#include <type_traits>

#include "core/error.hpp"
#include "core/progress.hpp"

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

// ------------------------------------------------------------------ the child's side

//! libngspice's functions, from the library opened on first use: linked instead, the loader
//! mapped and relocated its ~30 000 pointers at every start of stengmc, netlist or not
//! (0.5 ms of the 4 ms a start costs). The name is the library's soname (Debian libngspice0).
//! Opened in the parent, once, so that every child finds it mapped; initialised only in the
//! children, so each starts from a fresh simulator.
constexpr const char* NGSPICE_LIBRARY = "libngspice.so.0";
struct NgspiceFunctions {
  decltype(&ngSpice_Init) init = nullptr;
  decltype(&ngSpice_Init_Sync) init_sync = nullptr;
  decltype(&ngSpice_Command) command = nullptr;
  decltype(&ngSpice_Circ) circ = nullptr;
  decltype(&ngGet_Vec_Info) vector_info = nullptr;
};
NgspiceFunctions ngspice;

//! What the child sends its parent, in frames of (kind, 8-byte length, payload).
enum Frame : char {
  FRAME_MESSAGE = 'm',   //!< a line ngspice wrote to stderr
  FRAME_PROGRESS = 'p',  //!< the transient's progress, a double in [0, 1]
  FRAME_RESULT = 'r',    //!< the vectors: count, then per vector its length and values
  FRAME_ERROR = 'e',     //!< stengmc's own message when the netlist was refused (bad input)
  FRAME_SOLVER = 's',    //!< stengmc's own message when ngspice could not finish a valid netlist
};

std::string frame(Frame kind, std::string_view payload) {
  std::string out(1, static_cast<char>(kind));
  const std::uint64_t size = payload.size();
  out.append(reinterpret_cast<const char*>(&size), sizeof size);
  out.append(payload);
  return out;
}

//! Everything the child's callbacks touch (one child, one run: no locking).
struct Session {
  const NgspiceTransient* transient = nullptr;
  int parent_fd = -1;
  std::string errors;          // ngspice's stderr lines of this run
  std::string callback_error;  // an exception thrown inside a callback, reported after the run
  bool exit_requested = false;
  double last_progress = -1.0;
};
Session session;

std::string lower(std::string_view text) {
  std::string out(text);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

// The callbacks are C functions called from inside ngspice: no exception may cross them.
// stderr lines go to the parent as they come, so a crash still leaves ngspice's last words.
int on_output(char* text, int, void*) {
  const std::string_view line(text != nullptr ? text : "");
  constexpr std::string_view err = "stderr ";
  if (line.substr(0, err.size()) == err) {
    const std::string_view message = line.substr(err.size());
    if (session.errors.size() < (1u << 20)) session.errors.append(message).append("\n");
    write_to_pipe(session.parent_fd, frame(FRAME_MESSAGE, message));
  }
  return 0;
}
//! "tran: 34.5%": the progress, sent at most once per 0.5 %.
int on_status(char* text, int, void*) {
  const char* percent = text != nullptr ? std::strchr(text, '%') : nullptr;
  const char* colon = text != nullptr ? std::strchr(text, ':') : nullptr;
  if (percent == nullptr || colon == nullptr || colon > percent) return 0;
  const double fraction = std::atof(colon + 1) / 100.0;
  if (fraction >= session.last_progress + 0.005) {
    session.last_progress = fraction;
    write_to_pipe(session.parent_fd, frame(FRAME_PROGRESS, std::string_view(reinterpret_cast<const char*>(&fraction), sizeof fraction)));
  }
  return 0;
}
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
std::string error_origin(const NgspiceTransient& transient, const std::string& errors) {
  constexpr std::string_view marker = "Error on line ";
  const std::size_t at = errors.find(marker);
  if (at == std::string::npos) return "";
  std::size_t line = 0;
  for (std::size_t k = at + marker.size(); k < errors.size() && k < at + marker.size() + 9 &&
                                           std::isdigit(static_cast<unsigned char>(errors[k])); ++k)
    line = line * 10 + static_cast<std::size_t>(errors[k] - '0');
  return line >= 1 && line <= transient.card_origins.size() ? transient.card_origins[line - 1] : "";
}

//! The message of a failed run, with ngspice's own last lines.
std::string failure(const NgspiceTransient& transient, const std::string& what, const std::string& errors) {
  const std::string origin = error_origin(transient, errors);
  std::string message = (origin.empty() ? transient.origin : origin) + ": ngspice: " + what;
  if (!errors.empty()) message += "\nngspice said:\n" + last_lines(errors, 12);
  return message;
}

[[noreturn]] void fail(const NgspiceTransient& transient, const std::string& what) {
  throw InputError(failure(transient, what, session.errors));
}

//! A netlist ngspice took but could not integrate to its end ("timestep too small"): the
//! solver failed, not the input (exit 1, not 2).
struct SolverFailure : Error {
  using Error::Error;
};

[[noreturn]] void fail_to_finish(const NgspiceTransient& transient, const std::string& what) {
  throw SolverFailure(failure(transient, what, session.errors) +
                      "\n(a solver failure: ngspice took the netlist but could not integrate it to the end; stiff "
                      "switches such as diodes without junction capacitance are the usual cause, docs/faults.md)");
}

std::vector<double> read_vector(const NgspiceTransient& transient, const std::string& name) {
  std::string buffer(name);
  const pvector_info info = ngspice.vector_info(buffer.data());
  if (info == nullptr || info->v_realdata == nullptr || info->v_length <= 0)
    fail(transient, "the run has no vector '" + name + "'");
  return {info->v_realdata, info->v_realdata + info->v_length};
}

//! The whole run, in the child: a fresh ngspice, the cards, the transient, the vectors.
std::vector<std::vector<double>> run_in_this_child(const NgspiceTransient& transient) {
  // ngspice runs the `.spiceinit` of its current folder as commands (shell included) when
  // it starts: start it where no user put one.
  if (::chdir("/") != 0) fail(transient, "cannot leave the current folder");
  ::unsetenv("HOME");
  ngspice.init(on_output, on_status, on_exit, nullptr, nullptr, on_thread, nullptr);
  int ident = 0;
  ngspice.init_sync(on_external_voltage, on_external_current, nullptr, &ident, nullptr);
  session.errors.clear();  // the start's notes ("no compatibility mode") are not the netlist's

  // Only the wanted vectors are kept: without `.save` ngspice keeps every node voltage and
  // branch current at every step (20 000 resistors: 20 000 vectors).
  std::vector<std::string> cards = transient.cards;
  std::string save = ".save";
  for (const std::string& name : transient.vectors) {
    const std::size_t branch = name.find("#branch");
    save += " " + (branch == std::string::npos ? name : "i(" + name.substr(0, branch) + ")");
  }
  cards.insert(!cards.empty() && lower(cards.back()) == ".end" ? cards.end() - 1 : cards.end(), save);
  std::vector<char*> pointers;
  for (std::string& card : cards) pointers.push_back(card.data());
  pointers.push_back(nullptr);
  if (ngspice.circ(pointers.data()) != 0 || session.exit_requested) fail(transient, "the netlist does not load");
  if (session.errors.find("rror") != std::string::npos) fail(transient, "the netlist does not load");
  command("run");
  if (!session.callback_error.empty()) fail(transient, session.callback_error);
  if (session.exit_requested) fail_to_finish(transient, "the simulator stopped");
  std::vector<std::vector<double>> out{read_vector(transient, "time")};
  // ngspice reports success even when the transient aborts ("timestep too small"): what
  // counts is the time it reached.
  const double reached = out[0].back();
  if (!(std::abs(reached - transient.stop_time_s) <= 1e-9 * transient.stop_time_s))
    fail_to_finish(transient, "the transient stopped at t = " + std::to_string(reached) + " s before its end " +
                        std::to_string(transient.stop_time_s) + " s");
  for (const std::string& name : transient.vectors) {
    out.push_back(read_vector(transient, name));
    if (out.back().size() != out[0].size())
      fail(transient, "vector '" + name + "' has " + std::to_string(out.back().size()) + " points, time " +
                          std::to_string(out[0].size()));
  }
  return out;
}

void child_work(const NgspiceTransient& transient, int parent_fd) {
  session = Session{};
  session.transient = &transient;
  session.parent_fd = parent_fd;
  try {
    const std::vector<std::vector<double>> vectors = run_in_this_child(transient);
    std::string payload;
    const std::uint64_t count = vectors.size();
    payload.append(reinterpret_cast<const char*>(&count), sizeof count);
    for (const std::vector<double>& v : vectors) {
      const std::uint64_t length = v.size();
      payload.append(reinterpret_cast<const char*>(&length), sizeof length);
      payload.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(double));
    }
    write_to_pipe(parent_fd, frame(FRAME_RESULT, payload));
  } catch (const SolverFailure& error) {
    write_to_pipe(parent_fd, frame(FRAME_SOLVER, error.what()));
  } catch (const std::exception& error) {
    write_to_pipe(parent_fd, frame(FRAME_ERROR, error.what()));
  }
}

// ------------------------------------------------------------------ the parent's side

//! Opens libngspice (once; it stays loaded) and finds its functions.
void load_library(const NgspiceTransient& transient) {
  static std::mutex mutex;
  static bool loaded = false;
  const std::lock_guard<std::mutex> lock(mutex);
  if (loaded) return;
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
  loaded = true;
}

//! Reads the child's frames as they arrive: messages kept, progress shown, the result or
//! error kept for the end.
class FrameReader {
 public:
  explicit FrameReader(bool show_progress) {
    if (show_progress) progress_.emplace("circuit (ngspice)", 1000);
  }
  void take(std::string_view bytes) {
    pending_.append(bytes);
    constexpr std::size_t HEADER = 1 + sizeof(std::uint64_t);
    std::size_t at = 0;
    while (pending_.size() - at >= HEADER) {
      std::uint64_t size = 0;
      std::memcpy(&size, pending_.data() + at + 1, sizeof size);
      if (pending_.size() - at - HEADER < size) break;
      handle(static_cast<Frame>(pending_[at]), std::string_view(pending_).substr(at + HEADER, size));
      at += HEADER + size;
    }
    pending_.erase(0, at);
  }
  std::string messages;
  std::optional<std::string> result, error, solver_failure;

 private:
  void handle(Frame kind, std::string_view payload) {
    switch (kind) {
      case FRAME_MESSAGE:
        if (messages.size() < (1u << 20)) messages.append(payload).append("\n");
        break;
      case FRAME_PROGRESS:
        if (progress_ && payload.size() == sizeof(double)) {
          double fraction = 0.0;
          std::memcpy(&fraction, payload.data(), sizeof fraction);
          const auto target = static_cast<std::size_t>(std::clamp(fraction, 0.0, 1.0) * 1000.0);
          if (target > shown_) progress_->advance(target - shown_), shown_ = target;
        }
        break;
      case FRAME_RESULT: result.emplace(payload); break;
      case FRAME_ERROR: error.emplace(payload); break;
      case FRAME_SOLVER: solver_failure.emplace(payload); break;
    }
  }
  std::string pending_;
  std::optional<Progress> progress_;
  std::size_t shown_ = 0;
};

NgspiceVectors decode_vectors(const NgspiceTransient& transient, const std::string& payload) {
  std::size_t at = 0;
  auto take_count = [&] {
    std::uint64_t value = 0;
    if (payload.size() - at < sizeof value) throw Error(transient.origin + ": ngspice's child sent a short result");
    std::memcpy(&value, payload.data() + at, sizeof value);
    at += sizeof value;
    return value;
  };
  const std::uint64_t count = take_count();
  if (count != transient.vectors.size() + 1) throw Error(transient.origin + ": ngspice's child sent a malformed result");
  NgspiceVectors out;
  for (std::uint64_t v = 0; v < count; ++v) {
    const std::uint64_t length = take_count();
    if ((payload.size() - at) / sizeof(double) < length) throw Error(transient.origin + ": ngspice's child sent a short result");
    std::vector<double> values(length);
    std::memcpy(values.data(), payload.data() + at, length * sizeof(double));
    at += length * sizeof(double);
    if (v == 0) out.time_s = std::move(values);
    else out.values.push_back(std::move(values));
  }
  return out;
}

}  // namespace

NgspiceVectors run_ngspice_transient(const NgspiceTransient& transient) {
  load_library(transient);
  FrameReader reader(transient.show_progress);
  const ChildOutcome outcome = run_in_child([&](int parent_fd) { child_work(transient, parent_fd); }, transient.budget,
                                            [&](std::string_view bytes) { reader.take(bytes); });
  if (reader.error) throw InputError(*reader.error);
  if (reader.solver_failure) throw Error(*reader.solver_failure);
  if (outcome.end == ChildOutcome::End::finished && reader.result) return decode_vectors(transient, *reader.result);
  std::string what = outcome.describe(transient.budget) + " on this netlist";
  if (outcome.end == ChildOutcome::End::out_of_time || outcome.end == ChildOutcome::End::out_of_memory)
    what += ": the run is larger than its estimate, or the netlist keeps ngspice from finishing";
  throw InputError(failure(transient, what, reader.messages));
}

#endif

}  // namespace stengmc
