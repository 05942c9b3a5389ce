#include "ensemble/work_distribution.hpp"

#include <omp.h>

#include <chrono>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <string>
#include <thread>
#include <utility>

#include "core/error.hpp"
#include "ensemble/journal.hpp"
#include "ensemble/process_transport.hpp"
#include "ensemble/process_world.hpp"

namespace stengmc {

namespace {

// Worker -> rank 0, one tag for all: [u8 kind][u32 slot][payload].
constexpr int TAG_TO_ROOT = 1;
// Rank 0 -> the worker thread `slot`: [u8 kind][u64 id]. One tag per thread, so each
// thread of a worker receives only its own replies.
constexpr int TAG_REPLY_BASE = 100;
enum class ToRoot : char { request = 0, result = 1, failure = 2 };
enum class ToWorker : char { work = 0, stop = 1 };
enum class FailureKind : char { other = 0, input = 1, model = 2 };

// Waiting threads poll (ProcessTransport::try_receive) and sleep in between instead of
// blocking in a receive: OpenMPI busy-polls inside a blocking receive, which would take a
// core from the realisations. A realisation takes 10 ms-1 s, so a 0.2 ms reaction time
// costs nothing.
constexpr auto POLL_INTERVAL = std::chrono::microseconds(200);
// Most records rank 0 takes in before journalling them together.
constexpr std::size_t MAX_GROUP = 1024;

void put_u64(std::string& bytes, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) bytes.push_back(static_cast<char>(v >> (8 * i)));
}

std::uint64_t get_u64(std::string_view bytes) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < 8; ++i) v |= std::uint64_t{static_cast<unsigned char>(bytes[i])} << (8 * i);
  return v;
}

std::string message_to_root(ToRoot kind, int slot) {
  std::string bytes(1, static_cast<char>(kind));
  for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<char>(static_cast<std::uint32_t>(slot) >> (8 * i)));
  return bytes;
}

void send(std::string_view bytes, int destination, int tag) { process_transport().send(bytes, destination, tag); }

//! A waiting message from `source` with `tag` (ANY_PROCESS allowed), if any.
bool try_receive(int source, int tag, std::string& bytes, int& from) {
  return process_transport().try_receive(source, tag, bytes, from);
}

std::string receive(int source, int tag) {
  std::string bytes;
  int from = 0;
  while (!try_receive(source, tag, bytes, from)) std::this_thread::sleep_for(POLL_INTERVAL);
  return bytes;
}

std::exception_ptr remote_failure(std::string_view payload, int rank) {
  const std::string what = "rank " + std::to_string(rank) + ": " + std::string(payload.substr(1));
  switch (static_cast<FailureKind>(payload[0])) {
    case FailureKind::input: return std::make_exception_ptr(InputError(what));
    case FailureKind::model: return std::make_exception_ptr(ModelError(what));
    default: return std::make_exception_ptr(Error(what));
  }
}

}  // namespace

struct WorkDistributor::State {
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<std::uint64_t> queue;           //!< ids of the batch not handed out yet
  std::size_t remaining = 0;                 //!< ids of the batch not delivered yet
  std::exception_ptr failure;
  std::vector<std::pair<int, int>> waiting;  //!< remote (rank, thread slot) asking for work
  std::vector<RealisationRecord> local;      //!< records of rank 0's own threads, to deliver
  int remote_threads = 0;
  bool finishing = false, stop = false;

  std::mutex deliver_mutex;                  //!< held while records are delivered
  const DeliverRecords* deliver = nullptr;    //!< the current batch's, null between batches
  std::thread service;

  void serve();
  //! Sends an id to every waiting remote thread while the queue lasts, and when the
  //! ensemble is finishing and every remote thread waits, tells them to stop (true then).
  bool answer_requests();
  void handle(const std::string& bytes, int rank, std::vector<RealisationRecord>& arrived);
  void deliver_arrived(std::vector<RealisationRecord>& arrived);
};

void WorkDistributor::State::handle(const std::string& bytes, int rank, std::vector<RealisationRecord>& arrived) {
  if (bytes.size() < 5) throw Error("rank " + std::to_string(rank) + " sent a malformed message");
  const auto kind = static_cast<ToRoot>(bytes[0]);
  int slot = 0;
  for (std::size_t i = 0; i < 4; ++i) slot |= static_cast<int>(static_cast<unsigned char>(bytes[1 + i])) << (8 * i);
  const std::string_view payload = std::string_view(bytes).substr(5);
  if (kind == ToRoot::failure) {
    const std::lock_guard lock(mutex);
    if (!failure) failure = remote_failure(payload, rank);
    changed.notify_all();
    return;
  }
  if (kind == ToRoot::result) {
    try {
      arrived.push_back(decode_record_frame(payload, "the record sent by rank " + std::to_string(rank)));
    } catch (...) {
      const std::lock_guard lock(mutex);
      if (!failure) failure = std::current_exception();
    }
  }
  const std::lock_guard lock(mutex);
  waiting.emplace_back(rank, slot);  // a result also asks for the next id
}

void WorkDistributor::State::deliver_arrived(std::vector<RealisationRecord>& arrived) {
  if (arrived.empty()) return;
  const std::size_t count = arrived.size();
  try {
    const std::lock_guard deliver_lock(deliver_mutex);
    if (deliver) (*deliver)(std::move(arrived));
  } catch (...) {
    const std::lock_guard lock(mutex);
    if (!failure) failure = std::current_exception();
  }
  arrived.clear();
  const std::lock_guard lock(mutex);
  remaining -= std::min(remaining, count);
  changed.notify_all();
}

bool WorkDistributor::State::answer_requests() {
  std::vector<std::pair<std::pair<int, int>, std::string>> replies;
  bool released = false;
  {
    const std::lock_guard lock(mutex);
    while (!waiting.empty() && !queue.empty() && !failure) {
      std::string reply(1, static_cast<char>(ToWorker::work));
      put_u64(reply, queue.front());
      queue.pop_front();
      replies.emplace_back(waiting.back(), std::move(reply));
      waiting.pop_back();
    }
    if (finishing && queue.empty() && static_cast<int>(waiting.size()) == remote_threads) {
      for (const auto& w : waiting) replies.emplace_back(w, std::string(1, static_cast<char>(ToWorker::stop)));
      waiting.clear();
      released = true;
    }
  }
  for (const auto& [to, reply] : replies) send(reply, to.first, TAG_REPLY_BASE + to.second);
  return released;
}

void WorkDistributor::State::serve() {
  std::string bytes;
  std::vector<RealisationRecord> arrived;
  for (;;) {
    {
      const std::lock_guard lock(mutex);
      if (stop) return;
    }
    if (answer_requests()) return;
    // Take everything that has arrived (up to a bound), answer the requests it carries
    // before the fsync (the workers compute while rank 0 writes), then journal the records
    // together with one fsync (group commit): the busier rank 0 gets, the less a record costs.
    int from = 0;
    std::size_t received = 0;
    while (received < MAX_GROUP && try_receive(ANY_PROCESS, TAG_TO_ROOT, bytes, from)) {
      handle(bytes, from, arrived);
      ++received;
    }
    {
      const std::lock_guard lock(mutex);
      for (RealisationRecord& r : local) arrived.push_back(std::move(r));
      local.clear();
    }
    if (arrived.empty() && received == 0) {
      std::this_thread::sleep_for(POLL_INTERVAL);
      continue;
    }
    const bool released = answer_requests();
    deliver_arrived(arrived);
    if (released) return;
  }
}

WorkDistributor::WorkDistributor() : state_(std::make_unique<State>()) {
  const ProcessWorld world = process_world();
  std::vector<int> threads(static_cast<std::size_t>(world.size), 0);
  process_transport().gather_to_root(0, threads.data());
  for (int t : threads) state_->remote_threads += t;
  state_->service = std::thread([state = state_.get()] {
    try {
      state->serve();
    } catch (...) {  // a malformed message, a failed send: run() rethrows it
      const std::lock_guard lock(state->mutex);
      if (!state->failure) state->failure = std::current_exception();
      state->changed.notify_all();
    }
  });
}

WorkDistributor::~WorkDistributor() {
  if (!state_->service.joinable()) return;
  {
    const std::lock_guard lock(state_->mutex);
    state_->stop = true;
  }
  state_->service.join();
}

void WorkDistributor::run(const std::vector<std::uint64_t>& ids, int threads, const ComputeRecord& compute,
                          const DeliverRecords& deliver) {
  State& s = *state_;
  {
    const std::lock_guard deliver_lock(s.deliver_mutex);
    s.deliver = &deliver;
  }
  {
    const std::lock_guard lock(s.mutex);
    s.queue.assign(ids.begin(), ids.end());
    s.remaining = ids.size();
  }
#pragma omp parallel num_threads(threads)
  for (;;) {
    std::uint64_t id = 0;
    {
      const std::lock_guard lock(s.mutex);
      if (s.failure || s.queue.empty()) break;
      id = s.queue.front();
      s.queue.pop_front();
    }
    try {
      // Journalled by the service thread with whatever else has arrived (one fsync).
      RealisationRecord record = compute(id);
      const std::lock_guard lock(s.mutex);
      s.local.push_back(std::move(record));
    } catch (...) {
      const std::lock_guard lock(s.mutex);
      if (!s.failure) s.failure = std::current_exception();
      s.changed.notify_all();
      break;
    }
  }
  std::exception_ptr failure;
  {
    std::unique_lock lock(s.mutex);
    s.changed.wait(lock, [&] { return s.remaining == 0 || s.failure; });
    failure = s.failure;
  }
  {
    const std::lock_guard deliver_lock(s.deliver_mutex);
    s.deliver = nullptr;
  }
  if (failure) std::rethrow_exception(failure);
}

void WorkDistributor::finish() {
  {
    const std::lock_guard lock(state_->mutex);
    state_->finishing = true;
  }
  state_->service.join();
  if (state_->failure) std::rethrow_exception(state_->failure);  // the other ranks may still wait: end the job
}

void serve_realisations(int threads, const ComputeRecord& compute) {
  process_transport().gather_to_root(threads, nullptr);
  const std::string source = "rank " + std::to_string(process_world().rank);
#pragma omp parallel num_threads(threads)
  {
    const int slot = omp_get_thread_num();
    std::string message = message_to_root(ToRoot::request, slot);
    for (;;) {
      send(message, 0, TAG_TO_ROOT);
      const std::string reply = receive(0, TAG_REPLY_BASE + slot);
      if (reply.empty() || static_cast<ToWorker>(reply[0]) != ToWorker::work) break;
      const std::uint64_t id = get_u64(std::string_view(reply).substr(1));
      FailureKind kind = FailureKind::other;
      std::string what;
      try {
        message = message_to_root(ToRoot::result, slot) + encode_record_frame(compute(id), source);
        continue;
      } catch (const InputError& e) {
        kind = FailureKind::input, what = e.what();
      } catch (const ModelError& e) {
        kind = FailureKind::model, what = e.what();
      } catch (const std::exception& e) {
        what = e.what();
      } catch (...) {
        what = "unknown failure in realisation " + std::to_string(id);
      }
      // Rank 0 rethrows it and ends the job; this thread asks for nothing more.
      send(message_to_root(ToRoot::failure, slot) + static_cast<char>(kind) + what, 0, TAG_TO_ROOT);
      break;
    }
  }
}

}  // namespace stengmc
