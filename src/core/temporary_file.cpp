#include "core/temporary_file.hpp"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <climits>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <system_error>

#include "core/error.hpp"

namespace stengmc {

namespace {

// The names the signal handler removes. A handler may only touch lock-free atomics and
// memory that is not being written, so each slot is claimed (1), filled, then armed (2);
// the handler reads armed slots only.
constexpr int SLOTS = 64;
constexpr std::size_t NAME_BYTES = PATH_MAX;
std::array<std::array<char, NAME_BYTES>, SLOTS> slot_names{};
std::array<std::atomic<int>, SLOTS> slot_state{};
static_assert(std::atomic<int>::is_always_lock_free);

constexpr int HANDLED_SIGNALS[] = {SIGINT, SIGTERM, SIGHUP};

// The interruption note, guarded like a slot: 0 none, 1 being written, 2 armed.
constexpr std::size_t NOTE_BYTES = 2 * PATH_MAX;
std::array<char, NOTE_BYTES> note_text{};
std::atomic<int> note_state{0};
std::atomic<std::size_t> note_length{0};

//! write(2) until done or failed: the only output a signal handler may make.
void write_all(int fd, const char* data, std::size_t length) {
  while (length > 0) {
    const ssize_t written = ::write(fd, data, length);
    if (written <= 0) {
      if (written < 0 && errno == EINTR) continue;
      return;
    }
    data += written;
    length -= static_cast<std::size_t>(written);
  }
}

extern "C" void remove_temporaries_and_die(int signal_number) {
  const int saved_errno = errno;
  for (int s = 0; s < SLOTS; ++s)
    if (slot_state[s].load() == 2) ::unlink(slot_names[s].data());
  if (note_state.load() == 2) {
    static constexpr char HEAD[] = "\nstengmc: interrupted by ";
    write_all(STDERR_FILENO, HEAD, sizeof HEAD - 1);
    const char* name = signal_number == SIGINT ? "SIGINT (Ctrl-C)" : signal_number == SIGTERM ? "SIGTERM" : "SIGHUP";
    write_all(STDERR_FILENO, name, std::strlen(name));
    write_all(STDERR_FILENO, ". ", 2);
    write_all(STDERR_FILENO, note_text.data(), note_length.load());
    write_all(STDERR_FILENO, "\n", 1);
  }
  errno = saved_errno;
  // Die of the same signal, so the parent (a shell, a batch system) sees what happened.
  struct sigaction default_action {};
  default_action.sa_handler = SIG_DFL;
  ::sigemptyset(&default_action.sa_mask);
  ::sigaction(signal_number, &default_action, nullptr);
  ::raise(signal_number);
}

//! Installs the handler where the signal still has its default action (a signal the user
//! chose to ignore, such as SIGHUP under nohup, stays ignored).
void install_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (const int signal_number : HANDLED_SIGNALS) {
      struct sigaction current {};
      if (::sigaction(signal_number, nullptr, &current) != 0 || current.sa_handler != SIG_DFL) continue;
      struct sigaction action {};
      action.sa_handler = remove_temporaries_and_die;
      ::sigemptyset(&action.sa_mask);
      ::sigaction(signal_number, &action, nullptr);
    }
  });
}

//! Registers `path` for the handler; -1 when it cannot be (too long, too many at once),
//! which costs only the cleanup on a signal, never correctness.
int arm(const std::string& path) {
  install_handlers();
  if (path.size() >= NAME_BYTES) return -1;
  for (int s = 0; s < SLOTS; ++s) {
    int expected = 0;
    if (!slot_state[s].compare_exchange_strong(expected, 1)) continue;
    std::memcpy(slot_names[s].data(), path.c_str(), path.size() + 1);
    slot_state[s].store(2);
    return s;
  }
  return -1;
}

void disarm(int slot) {
  if (slot >= 0) slot_state[slot].store(0);
}

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof name - 1) != 0 || name[0] == '\0') return "localhost";
  for (char& c : name)
    if (c == '/') c = '_';
  return name;
}

//! The pid in `<base>.<host>.<pid>.tmp`, or 0 when `file` is not a temporary of `base` on this host.
long temporary_pid(const std::string& file, const std::string& base, const std::string& host) {
  const std::string prefix = base + "." + host + ".";
  const std::string suffix = ".tmp";
  if (file.size() <= prefix.size() + suffix.size() || file.compare(0, prefix.size(), prefix) != 0 ||
      file.compare(file.size() - suffix.size(), suffix.size(), suffix) != 0)
    return 0;
  const std::string digits = file.substr(prefix.size(), file.size() - prefix.size() - suffix.size());
  if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) return 0;
  return std::stol(digits);
}

}  // namespace

void set_interruption_note(const std::string& note) {
  install_handlers();
  note_state.store(1);  // the handler ignores the note while it changes
  const std::size_t length = std::min(note.size(), NOTE_BYTES);
  std::memcpy(note_text.data(), note.data(), length);
  note_length.store(length);
  if (length > 0) note_state.store(2);
  else note_state.store(0);
}

std::string temporary_name(const std::string& final_path) {
  return final_path + "." + host_name() + "." + std::to_string(::getpid()) + ".tmp";
}

std::size_t remove_stale_temporaries(const std::string& final_path) {
  const std::filesystem::path target(final_path);
  const std::filesystem::path folder = target.parent_path().empty() ? std::filesystem::path(".") : target.parent_path();
  const std::string base = target.filename().string();
  const std::string host = host_name();
  std::size_t removed = 0;
  std::error_code error;  // best effort: an unreadable folder shows up when the output is created
  for (std::filesystem::directory_iterator it(folder, error), end; !error && it != end; it.increment(error)) {
    const long pid = temporary_pid(it->path().filename().string(), base, host);
    if (pid <= 0 || pid == ::getpid()) continue;
    if (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH) continue;  // alive (or not ours to judge)
    std::error_code ignored;
    if (std::filesystem::remove(it->path(), ignored)) ++removed;
  }
  return removed;
}

TemporaryFile::TemporaryFile(std::string final_path) : final_path_(std::move(final_path)) {
  remove_stale_temporaries(final_path_);
  path_ = temporary_name(final_path_);
  std::error_code error;
  const std::filesystem::path absolute = std::filesystem::absolute(path_, error);
  slot_ = arm(error ? path_ : absolute.string());
}

TemporaryFile::~TemporaryFile() {
  if (!committed_) ::unlink(path_.c_str());
  disarm(slot_);
}

void TemporaryFile::commit() {
  std::error_code error;
  std::filesystem::rename(path_, final_path_, error);
  if (error) throw Error(final_path_ + ": cannot move the finished output into place: " + error.message());
  committed_ = true;
  disarm(slot_);
  slot_ = -1;
}

}  // namespace stengmc
