#include "ensemble/ensemble_runner.hpp"

#include <omp.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <map>
#include <mutex>

#include "core/build_info.hpp"
#include "core/error.hpp"
#include "core/format.hpp"
#include "core/progress.hpp"
#include "core/random_stream.hpp"
#include "core/temporary_file.hpp"
#include "ensemble/journal.hpp"
#include "ensemble/process_world.hpp"
#include "ensemble/run_realisation.hpp"
#include "ensemble/work_distribution.hpp"
#include "stats/ensemble_statistics.hpp"

namespace stengmc {

namespace {

bool keeps_traces(const EnsembleSettings& settings, std::uint64_t realisation) {
  if (settings.trace_all) return true;
  const auto& t = settings.trace_realisations;
  return std::find(t.begin(), t.end(), realisation) != t.end();
}

//! The running means the progress line shows, over the valid records so far.
class RunningStatus {
 public:
  void add(const RealisationRecord& r) {
    ++done_;
    if (!r.valid) return;
    ++valid_;
    voltage_rms_ += r.scalar(Scalar::voltage_rms_v);
    fft_identifiable_ += r.scalar(Scalar::fft_identifiable);
    sliding_ += r.scalar(Scalar::n_sliding);
  }
  [[nodiscard]] std::string line() const {
    if (valid_ == 0) return "valid 0/" + std::to_string(done_);
    std::string out = "valid " + std::to_string(valid_) + "/" + std::to_string(done_) +
                      "  mean V_rms " + format_number(voltage_rms_ / static_cast<double>(valid_)) + " V";
    if (sliding_ > 0) out += "  FFT identified " + format_number(fft_identifiable_ / sliding_);
    return out;
  }

 private:
  std::size_t done_ = 0, valid_ = 0;
  double voltage_rms_ = 0.0, fft_identifiable_ = 0.0, sliding_ = 0.0;
};

//! The 95 % CI half-width of the target's mean over the valid records with ids below
//! `end` (only those: a resumed journal may hold later ids, which an uninterrupted run
//! would not have seen at this point); nothing with fewer than the minimum count.
std::optional<double> target_half_width(const StudyFile& study, const std::map<std::uint64_t, RealisationRecord>& done,
                                        std::uint64_t end) {
  const EnsembleSettings& settings = *study.ensemble;
  std::vector<double> values;
  for (auto it = done.begin(); it != done.end() && it->first < end; ++it)
    if (it->second.valid) values.push_back(it->second.scalar(*settings.target));
  if (values.size() < MIN_REALISATIONS_FOR_TARGET) return std::nullopt;
  RandomEngine engine =
      random_stream(study.seed, 0, StreamKind::bootstrap, static_cast<std::uint64_t>(*settings.target));
  const Interval ci = mean_interval(values, engine);
  if (!ci.known) return std::nullopt;
  return ci.half_width();
}

//! One realisation's record, with the caller's hook applied.
RealisationRecord compute_record(const StudyFile& study, std::uint64_t id, const WorkLimits& limits,
                                 const RealisationHook& hook) {
  RealisationRecord record = run_realisation(study, id, hook.needs_traces || keeps_traces(*study.ensemble, id), limits);
  if (hook.apply) hook.apply(record);
  return record;
}

//! Runs `ids` on `threads` threads of this process.
void run_locally(const std::vector<std::uint64_t>& ids, int threads, const ComputeRecord& compute,
                 const DeliverRecords& deliver) {
  std::mutex mutex;
  std::exception_ptr failure;
  const auto count = static_cast<std::int64_t>(ids.size());
  // Dynamic schedule: realisations differ in cost (contact count, stick phases).
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
  for (std::int64_t k = 0; k < count; ++k) {
    {
      std::lock_guard lock(mutex);
      if (failure) continue;
    }
    try {
      std::vector<RealisationRecord> one;
      one.push_back(compute(ids[static_cast<std::size_t>(k)]));
      deliver(std::move(one));
    } catch (...) {
      std::lock_guard lock(mutex);
      if (!failure) failure = std::current_exception();
    }
  }
  if (failure) std::rethrow_exception(failure);
}

//! Runs `ids` in parallel (over the ranks with `distributor`); records go to the journal
//! (if any) and `done`.
void run_batch(const StudyFile& study, const std::vector<std::uint64_t>& ids, int threads, const WorkLimits& limits,
               Journal* journal, std::map<std::uint64_t, RealisationRecord>& done, Progress* progress,
               RunningStatus& status, const RealisationHook& hook, WorkDistributor* distributor,
               const std::function<void()>& on_record = {}) {
  std::vector<RealisationRecord> results;
  results.reserve(ids.size());
  std::mutex mutex;
  const ComputeRecord compute = [&](std::uint64_t id) { return compute_record(study, id, limits, hook); };
  const DeliverRecords deliver = [&](std::vector<RealisationRecord>&& records) {
    if (journal) journal->append(records);
    std::lock_guard lock(mutex);
    for (RealisationRecord& record : records) {
      status.add(record);
      if (progress) {
        progress->set_status(status.line());
        progress->advance();
      }
      if (on_record) on_record();
      results.push_back(std::move(record));
    }
  };
  if (distributor) distributor->run(ids, threads, compute, deliver);
  else run_locally(ids, threads, compute, deliver);
  for (RealisationRecord& r : results) {
    const std::uint64_t id = r.realisation;
    done.emplace(id, std::move(r));
  }
}

}  // namespace

std::uint64_t ensemble_identity_hash(const Study& study) {
  std::uint64_t h = fnv1a64(study.text);
  h = fnv1a64(std::string_view("\0surface\0", 9), h);
  h = fnv1a64(study.surface_text, h);
  h = fnv1a64(study.surface->auxiliary_inputs(), h);
  for (const ParameterOverride& o : study.overrides) {
    h = fnv1a64(std::string_view("\0override\0", 10), h);
    h = fnv1a64(o.parameter, h);
    const auto bits = std::bit_cast<std::uint64_t>(o.value);
    h = fnv1a64(std::string_view(reinterpret_cast<const char*>(&bits), sizeof bits), h);
  }
  h = fnv1a64(std::string_view("\0program\0", 9), h);
  h = fnv1a64(program_version(), h);
  return fnv1a64(git_revision(), h);
}

namespace {
constexpr std::string_view JOURNAL_STUDY_PREFIX = "), study ";
constexpr std::string_view JOURNAL_SHARD_PREFIX = "; shard ";
}

JournalIdentity ensemble_journal_identity(const StudyFile& study, const RealisationHook& hook,
                                          const std::optional<ShardSpec>& shard) {
  const std::uint64_t identity =
      hook.identity.empty() ? ensemble_identity_hash(study) : fnv1a64(hook.identity, ensemble_identity_hash(study));
  return {identity, std::string("stengmc ") + program_version() + " (git " + git_revision() +
                        (shard ? std::string(JOURNAL_SHARD_PREFIX) + shard->text() : std::string()) +
                        std::string(JOURNAL_STUDY_PREFIX) + study.file};
}

std::string journal_study_file(const std::string& description) {
  const auto at = description.find(JOURNAL_STUDY_PREFIX);
  return at == std::string::npos ? std::string() : description.substr(at + JOURNAL_STUDY_PREFIX.size());
}

std::optional<ShardSpec> journal_shard(const std::string& description) {
  // Only the part before ", study ": a study path may contain anything.
  const std::string head = description.substr(0, description.find(JOURNAL_STUDY_PREFIX));
  const auto at = head.find(JOURNAL_SHARD_PREFIX);
  if (at == std::string::npos) return std::nullopt;
  const std::string text = head.substr(at + JOURNAL_SHARD_PREFIX.size());
  try {
    return parse_shard_spec(text);
  } catch (const InputError&) {
    std::string message = "its header names shard \"";
    message.append(text).append("\": expected i/n, two whole numbers with 0 <= i < n");
    throw InputError(message);
  }
}

EnsembleRun run_ensemble(const StudyFile& study, const std::string& journal_path, const EnsembleOptions& options,
                         const RealisationHook& hook) {
  if (!study.ensemble) throw InputError(study.file + ": the study has no [ensemble] table");
  const EnsembleSettings& settings = *study.ensemble;
  const auto start = std::chrono::steady_clock::now();
  EnsembleRun run;
  run.requested = settings.realisations;
  run.only = options.only;
  run.threads = options.threads > 0 ? options.threads : omp_get_max_threads();
  std::map<std::uint64_t, RealisationRecord> done;
  RunningStatus status;

  if (settings.target && options.shard)
    throw InputError(study.file + ": [ensemble] target_statistic: a study that stops at a target cannot run in "
                     "shards (a slice cannot know where the whole run would stop); run it whole, or over MPI");
  const ProcessWorld world = process_world();
  std::optional<WorkDistributor> distributor;
  if (world.distributed() && !options.only) {
    if (!world.root()) {
      serve_realisations(run.threads, [&](std::uint64_t id) { return compute_record(study, id, options.limits, hook); });
      run.worker = true;
      return run;
    }
    distributor.emplace();
  }
  const auto in_slice = [&](std::uint64_t id) { return !options.shard || options.shard->contains(id); };
  std::uint64_t to_run = 0;
  for (std::uint64_t id = 0; id < settings.realisations; ++id) to_run += in_slice(id) ? 1 : 0;

  if (options.only) {
    run_batch(study, {*options.only}, 1, options.limits, nullptr, done, nullptr, status, hook, nullptr);
  } else {
    if (options.restart) discard_journal(journal_path);
    Journal journal(journal_path, ensemble_journal_identity(study, hook, options.shard));
    // A realisation refused by the work limits is run again: this run's limits may differ.
    for (const RealisationRecord& r : journal.recovered())
      if (r.realisation < settings.realisations && in_slice(r.realisation) &&
          r.failure.rfind(WORK_LIMIT_FAILURE, 0) != 0)
        done.emplace(r.realisation, r);
    run.resumed = done.size();
    for (const auto& [id, r] : done) status.add(r);
    if (options.show_progress && run.resumed > 0)
      std::fprintf(stderr, "  resuming: %zu realisations taken from %s (--restart starts over)\n", run.resumed,
                   journal_path.c_str());
    // A Ctrl-C or a batch system's SIGTERM ends the run where it is; say what is kept.
    const InterruptionNote note("The finished realisations are kept in " + journal_path +
                                ": the same command resumes from them (--restart starts over).");
    std::optional<Progress> progress;
    if (options.show_progress) {
      // Only what is left: counting resumed realisations as done now would make the ETA
      // optimistic.
      progress.emplace(options.progress_label, to_run - done.size());
      if (options.job_start) progress->set_job_share(*options.job_start, options.job_before, options.job_share);
    }
    std::size_t delivered = 0;  // counted under run_batch's lock, so one call at a time
    const std::size_t total = to_run - done.size();
    std::function<void()> on_record;
    if (options.on_record) on_record = [&] { options.on_record(++delivered, total); };
    // Without a target, one batch of everything balances the threads best.
    const std::uint64_t batch = settings.target ? settings.batch : settings.realisations;
    for (std::uint64_t first = 0; first < settings.realisations; first += batch) {
      const std::uint64_t end = std::min(settings.realisations, first + batch);
      std::vector<std::uint64_t> ids;
      for (std::uint64_t id = first; id < end; ++id)
        if (!done.count(id) && in_slice(id)) ids.push_back(id);
      run_batch(study, ids, run.threads, options.limits, &journal, done, progress ? &*progress : nullptr, status, hook,
                distributor ? &*distributor : nullptr, on_record);
      const auto width = settings.target ? target_half_width(study, done, end) : std::nullopt;
      if (width && *width <= settings.target_half_width && end < settings.realisations) {
        run.stopped_at_target = true;
        // Records of later batches (recovered from a journal) are not part of this run.
        done.erase(done.lower_bound(end), done.end());
        break;
      }
    }
    if (distributor) distributor->finish();
  }
  if (settings.target && !options.only) {
    const auto width = target_half_width(study, done, settings.realisations);
    run.target_half_width_reached = width.value_or(0.0);
    run.target_met = width && *width <= settings.target_half_width;
  }
  for (auto& [id, r] : done) run.records.push_back(std::move(r));
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

}  // namespace stengmc
