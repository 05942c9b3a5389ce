// The journal of finished realisations (ensemble/journal): records come back bitwise after
// reopening; a torn tail is cut back to the last whole record and appending carries on
// after it; a corrupt record costs only itself; a journal of another study, another record format or no journal at
// all is refused (and left untouched) with a message saying how to start afresh;
// concurrent appends never interleave; remove() deletes the file.
//
// What the tests compare against: the records as appended, byte for byte (memcmp of every
// double, so -0.0 vs 0.0 or a changed denormal would fail), and record boundaries measured
// as the file size after each append (append writes and fsyncs before returning), so the
// cuts below need nothing of the format but its framing: u32 length | payload | u64 checksum.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <bit>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <thread>

#include "core/error.hpp"
#include "ensemble/journal.hpp"
#include "support/cli_runner.hpp"

namespace stengmc {
namespace {

const JournalIdentity IDENTITY{fnv1a64("study text"), "stengmc 0.1.0, studies/test.toml"};

//! A record whose every value depends on `id`: id % 5 asperities, traces for every third
//! id, a failure for every fourth.
RealisationRecord make_record(std::uint64_t id) {
  RealisationRecord record;
  record.realisation = id;
  record.valid = id % 4 != 1;
  if (!record.valid) record.failure = "x reached l at t = " + std::to_string(id) + " s";
  for (std::size_t s = 0; s < SCALAR_COUNT; ++s) record.scalars[s] = static_cast<double>(id) + 0.1 * static_cast<double>(s);
  const std::size_t asperities = id % 5;
  for (std::size_t c = 0; c < ASPERITY_COLUMN_COUNT; ++c)
    for (std::size_t a = 0; a < asperities; ++a)
      record.asperities[c].push_back(1e-3 * static_cast<double>(id) / (1.0 + static_cast<double>(c + a)));
  if (id % 3 == 0)
    for (int i = 0; i < 7; ++i) {
      record.time_s.push_back(1e-4 * i);
      record.voltage_v.push_back(-0.5 * i / (1.0 + static_cast<double>(id)));
      record.charge_c.push_back(1e-9 * i * static_cast<double>(id));
    }
  return record;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

void expect_bitwise_equal(const RealisationRecord& expected, const RealisationRecord& actual) {
  EXPECT_EQ(expected.realisation, actual.realisation);
  EXPECT_EQ(expected.valid, actual.valid);
  EXPECT_EQ(expected.failure, actual.failure);
  EXPECT_EQ(std::memcmp(expected.scalars.data(), actual.scalars.data(), sizeof(expected.scalars)), 0)
      << "scalars of realisation " << expected.realisation;
  for (std::size_t c = 0; c < ASPERITY_COLUMN_COUNT; ++c)
    EXPECT_TRUE(same_bits(expected.asperities[c], actual.asperities[c]))
        << "asperity column " << c << " of realisation " << expected.realisation;
  EXPECT_TRUE(same_bits(expected.time_s, actual.time_s)) << expected.realisation;
  EXPECT_TRUE(same_bits(expected.voltage_v, actual.voltage_v)) << expected.realisation;
  EXPECT_TRUE(same_bits(expected.charge_c, actual.charge_c)) << expected.realisation;
}

std::string read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

void write_bytes(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

//! Writes records 0..count-1; returns the file size after the header and after each record,
//! i.e. ends[i] is where record i starts and ends[i + 1] where it ends.
std::vector<std::uint64_t> write_journal(const std::string& path, std::uint64_t count) {
  Journal journal(path, IDENTITY);
  std::vector<std::uint64_t> ends{std::filesystem::file_size(path)};
  for (std::uint64_t id = 0; id < count; ++id) {
    journal.append(make_record(id));
    ends.push_back(std::filesystem::file_size(path));
  }
  return ends;
}

std::string message_of_opening(const std::string& path, const JournalIdentity& identity) {
  try {
    Journal journal(path, identity);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError opening " << path;
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(Journal, RecordsComeBackBitwiseAfterReopening) {
  testing::ScratchDir scratch("journal-roundtrip");
  const std::string path = scratch.file("run.journal");

  RealisationRecord awkward;
  awkward.realisation = std::numeric_limits<std::uint64_t>::max();
  awkward.valid = false;
  awkward.failure = std::string(100'000, 'f') + std::string("\0 nul, é, \n newline", 20);  // long, binary
  const double values[] = {-0.0,
                           5e-324,  // the smallest denormal
                           std::numeric_limits<double>::denorm_min() * 12345,
                           std::numeric_limits<double>::min(),
                           std::numeric_limits<double>::max(),
                           std::numeric_limits<double>::lowest(),
                           1e308,
                           1.0 / 3.0,
                           -2.5e-300};
  for (std::size_t s = 0; s < SCALAR_COUNT; ++s) awkward.scalars[s] = values[s % std::size(values)];
  // zero asperities: every column empty
  awkward.time_s.assign(std::begin(values), std::end(values));
  awkward.voltage_v = {-0.0};
  awkward.charge_c = {};

  RealisationRecord with_asperities = make_record(4);  // 4 asperities, no traces
  for (auto& column : with_asperities.asperities) column[1] = -0.0;
  const std::vector<RealisationRecord> written{awkward, with_asperities, make_record(0), make_record(1)};

  {
    Journal journal(path, IDENTITY);
    EXPECT_TRUE(journal.recovered().empty());
    for (const auto& record : written) journal.append(record);
  }
  const auto size = std::filesystem::file_size(path);
  Journal reopened(path, IDENTITY);
  ASSERT_EQ(reopened.recovered().size(), written.size());
  for (std::size_t i = 0; i < written.size(); ++i) expect_bitwise_equal(written[i], reopened.recovered()[i]);
  EXPECT_EQ(std::filesystem::file_size(path), size);  // an intact journal is not cut
  // The comparison can see a sign: -0.0 and 0.0 differ bitwise.
  EXPECT_NE(std::bit_cast<std::uint64_t>(reopened.recovered()[0].scalars[0]), std::bit_cast<std::uint64_t>(0.0));
}

TEST(Journal, ATornLastRecordIsCutOffAndAppendingCarriesOn) {
  testing::ScratchDir scratch("journal-torn");
  const std::string path = scratch.file("run.journal");
  const auto ends = write_journal(path, 5);
  const std::string whole = read_bytes(path);
  ASSERT_EQ(whole.size(), ends[5]);

  // Every cut inside the 5th record: in its length prefix, payload and checksum.
  for (std::uint64_t cut = ends[4]; cut < ends[5]; ++cut) {
    SCOPED_TRACE("cut at byte " + std::to_string(cut) + " of record 5 spanning [" + std::to_string(ends[4]) + ", " +
                 std::to_string(ends[5]) + ")");
    write_bytes(path, whole.substr(0, cut));
    {
      Journal journal(path, IDENTITY);
      ASSERT_EQ(journal.recovered().size(), 4u);
      for (std::uint64_t id = 0; id < 4; ++id) expect_bitwise_equal(make_record(id), journal.recovered()[id]);
      EXPECT_EQ(std::filesystem::file_size(path), ends[4]);  // cut back to the 4th record's end
      journal.append(make_record(5));
    }
    Journal reopened(path, IDENTITY);
    ASSERT_EQ(reopened.recovered().size(), 5u);
    for (std::uint64_t id = 0; id < 4; ++id) expect_bitwise_equal(make_record(id), reopened.recovered()[id]);
    expect_bitwise_equal(make_record(5), reopened.recovered()[4]);
  }
}

// The real thing: a process appending as fast as it can is SIGKILLed mid-run. What it
// left is compared against the records it was given: a prefix 0..k-1, each bitwise, and
// the lock died with it.
TEST(Journal, AProcessKilledWhileAppendingLeavesAResumableJournal) {
  testing::ScratchDir scratch("journal-kill");
  const std::string path = scratch.file("run.journal");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    try {
      Journal journal(path, IDENTITY);
      for (std::uint64_t id = 0;; ++id) journal.append(make_record(id));
    } catch (...) {
    }
    ::_exit(1);
  }
  int status = 0;
  std::error_code missing;  // until the child has created the file
  while (std::filesystem::file_size(path, missing) < 20'000 || missing)
    if (::waitpid(child, &status, WNOHANG) == child) FAIL() << "the appending process stopped by itself";
  ::kill(child, SIGKILL);
  ::waitpid(child, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);

  std::uint64_t count = 0;
  {
    Journal journal(path, IDENTITY);
    count = journal.recovered().size();
    ASSERT_GE(count, 20u);  // 20 000 bytes hold more than 20 records of < 1000 bytes
    for (std::uint64_t id = 0; id < count; ++id) expect_bitwise_equal(make_record(id), journal.recovered()[id]);
    journal.append(make_record(count));
  }
  Journal resumed(path, IDENTITY);
  ASSERT_EQ(resumed.recovered().size(), count + 1);
  expect_bitwise_equal(make_record(count), resumed.recovered().back());
}

// A corrupt record costs only itself: every other record whose own checksum holds is kept,
// wherever the damage is (journal.hpp, "Recovery"). Before, one bad byte in the first
// record threw away every finished realisation after it.
TEST(Journal, ACorruptRecordLosesOnlyItself) {
  testing::ScratchDir scratch("journal-corrupt");
  const std::string path = scratch.file("run.journal");
  const auto ends = write_journal(path, 5);
  const std::string whole = read_bytes(path);

  const auto expect_all_but = [&](const std::string& damaged, std::uint64_t lost, const std::string& what) {
    SCOPED_TRACE(what);
    write_bytes(path, damaged);
    {
      Journal journal(path, IDENTITY);
      ASSERT_EQ(journal.recovered().size(), 4u);
      std::uint64_t k = 0;
      for (std::uint64_t id = 0; id < 5; ++id)
        if (id != lost) expect_bitwise_equal(make_record(id), journal.recovered()[k++]);
      EXPECT_EQ(std::filesystem::file_size(path), damaged.size());  // nothing whole was cut
      journal.append(make_record(lost));                              // the lost one, run again
    }
    Journal reopened(path, IDENTITY);
    ASSERT_EQ(reopened.recovered().size(), 5u);
    expect_bitwise_equal(make_record(lost), reopened.recovered().back());
  };
  const auto with_length = [&](std::uint64_t record, std::uint32_t length) {
    std::string damaged = whole;
    for (int i = 0; i < 4; ++i) damaged[ends[record] + i] = static_cast<char>(length >> (8 * i));
    return damaged;
  };
  for (const std::uint64_t record : {0u, 2u}) {  // the first record, and one in the middle
    // Each byte of its payload, one at a time (a bit flip the checksum must catch).
    for (std::uint64_t at = ends[record] + 4; at < ends[record + 1] - 8; ++at) {
      std::string damaged = whole;
      damaged[at] = static_cast<char>(damaged[at] ^ 0x10);
      expect_all_but(damaged, record, "record " + std::to_string(record) + " payload byte " + std::to_string(at - ends[record] - 4));
    }
    // Its checksum, and its length prefix: absurd (> 1 GiB), past the end of the file, one short.
    std::string damaged = whole;
    damaged[ends[record + 1] - 1] = static_cast<char>(damaged[ends[record + 1] - 1] ^ 0x01);
    expect_all_but(damaged, record, "checksum flipped");
    expect_all_but(with_length(record, 0xffffffffu), record, "length 4 GiB");
    expect_all_but(with_length(record, static_cast<std::uint32_t>(whole.size())), record, "length past the end");
    expect_all_but(with_length(record, static_cast<std::uint32_t>(ends[record + 1] - ends[record] - 13)), record,
                   "length one short");
  }
}

// What follows the last whole record is a torn append (a kill mid-write): it is cut, even
// after a damaged record, and appending carries on from there.
TEST(Journal, ATornTailAfterACorruptRecordIsCut) {
  testing::ScratchDir scratch("journal-corrupt-torn");
  const std::string path = scratch.file("run.journal");
  const auto ends = write_journal(path, 4);
  std::string damaged = read_bytes(path).substr(0, ends[4] - 5);  // record 3 torn
  damaged[ends[1] + 20] = static_cast<char>(damaged[ends[1] + 20] ^ 0x40);  // record 1 corrupt
  write_bytes(path, damaged);
  {
    Journal journal(path, IDENTITY);
    ASSERT_EQ(journal.recovered().size(), 2u);
    expect_bitwise_equal(make_record(0), journal.recovered()[0]);
    expect_bitwise_equal(make_record(2), journal.recovered()[1]);
    EXPECT_EQ(std::filesystem::file_size(path), ends[3]);
    journal.append(make_record(7));
  }
  Journal reopened(path, IDENTITY);
  ASSERT_EQ(reopened.recovered().size(), 3u);
  expect_bitwise_equal(make_record(7), reopened.recovered()[2]);
}

TEST(Journal, AJournalOfAnotherStudyIsRefusedAndLeftAsItWas) {
  testing::ScratchDir scratch("journal-identity");
  const std::string path = scratch.file("run.journal");
  write_journal(path, 3);
  const std::string before = read_bytes(path);

  const JournalIdentity other{fnv1a64("changed study text"), "stengmc 0.2.0, studies/other.toml"};
  const std::string message = message_of_opening(path, other);
  EXPECT_TRUE(contains(message, path)) << message;
  EXPECT_TRUE(contains(message, IDENTITY.description)) << message;
  EXPECT_TRUE(contains(message, other.description)) << message;
  EXPECT_TRUE(contains(message, "study (or the program) changed")) << message;
  EXPECT_TRUE(contains(message, "delete " + path)) << message;
  EXPECT_TRUE(contains(message, "--restart")) << message;
  EXPECT_EQ(read_bytes(path), before);

  // Only the hash is compared: the description is for messages (e.g. a moved study file).
  Journal same(path, JournalIdentity{IDENTITY.study_hash, "another description"});
  EXPECT_EQ(same.recovered().size(), 3u);
}

TEST(Journal, ARecordOfAnotherFormatIsRefusedNotCut) {
  testing::ScratchDir scratch("journal-format");
  const std::string path = scratch.file("run.journal");
  const auto ends = write_journal(path, 3);  // record 0 is valid: empty failure text
  std::string bytes = read_bytes(path);

  // Record 1 rewritten as by a program with one scalar fewer, its checksum made to match,
  // so only the count can tell: payload = u64 realisation | u8 valid | u32 0 | u32 SCALAR_COUNT ...
  const std::uint64_t payload = ends[0] + 4, length = ends[1] - ends[0] - 12;
  bytes[payload + 13] = static_cast<char>(SCALAR_COUNT - 1);
  const std::uint64_t checksum = fnv1a64(std::string_view(bytes).substr(payload, length));
  for (int i = 0; i < 8; ++i) bytes[payload + length + i] = static_cast<char>(checksum >> (8 * i));
  write_bytes(path, bytes);

  const std::string message = message_of_opening(path, IDENTITY);
  EXPECT_TRUE(contains(message, path)) << message;
  EXPECT_TRUE(contains(message, std::to_string(SCALAR_COUNT - 1) + " scalars")) << message;
  EXPECT_TRUE(contains(message, "--restart")) << message;
  EXPECT_EQ(read_bytes(path), bytes);  // nothing cut
}

TEST(Journal, AFileThatIsNoJournalIsRefusedNotOverwritten) {
  testing::ScratchDir scratch("journal-foreign");
  const std::string path = scratch.write("results.h5", "not a journal at all");
  const std::string message = message_of_opening(path, IDENTITY);
  EXPECT_TRUE(contains(message, "not a stengmc journal")) << message;
  EXPECT_EQ(read_bytes(path), "not a journal at all");
}

TEST(Journal, ConcurrentAppendsAreAllRecoveredWhole) {
  testing::ScratchDir scratch("journal-threads");
  const std::string path = scratch.file("run.journal");
  constexpr std::uint64_t THREADS = 4, PER_THREAD = 50;
  {
    Journal journal(path, IDENTITY);
    std::vector<std::thread> threads;
    for (std::uint64_t t = 0; t < THREADS; ++t)
      threads.emplace_back([&journal, t] {
        for (std::uint64_t i = 0; i < PER_THREAD; ++i) journal.append(make_record(i * THREADS + t));
      });
    for (auto& thread : threads) thread.join();
  }
  const auto size = std::filesystem::file_size(path);
  Journal reopened(path, IDENTITY);
  EXPECT_EQ(std::filesystem::file_size(path), size);  // nothing torn, nothing cut
  ASSERT_EQ(reopened.recovered().size(), THREADS * PER_THREAD);
  std::set<std::uint64_t> ids;
  for (const auto& record : reopened.recovered()) {
    ids.insert(record.realisation);
    expect_bitwise_equal(make_record(record.realisation), record);
  }
  EXPECT_EQ(ids.size(), THREADS * PER_THREAD);
  EXPECT_EQ(*ids.rbegin(), THREADS * PER_THREAD - 1);
}

TEST(Journal, ASecondOpeningOfAJournalInUseIsRefused) {
  testing::ScratchDir scratch("journal-lock");
  const std::string path = scratch.file("run.journal");
  Journal first(path, IDENTITY);
  try {
    Journal second(path, IDENTITY);
    FAIL() << "no exception";
  } catch (const Error& e) {
    EXPECT_TRUE(contains(e.what(), "in use")) << e.what();
  }
}

TEST(Journal, AFailedAppendIsUndoneAndNamesTheFile) {
  testing::ScratchDir scratch("journal-full");
  const std::string path = scratch.file("run.journal");
  {
    Journal journal(path, IDENTITY);
    journal.append(make_record(0));
    const auto size = std::filesystem::file_size(path);

    // A full disk, simulated by a file-size limit 100 bytes past the end: record 3 is
    // ~400 bytes, so part of it is written before the write fails with EFBIG.
    rlimit old_limit{};
    ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old_limit), 0);
    rlimit limit = old_limit;
    limit.rlim_cur = size + 100;
    const auto old_handler = ::signal(SIGXFSZ, SIG_IGN);
    ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &limit), 0);
    std::string message;
    try {
      journal.append(make_record(3));
    } catch (const Error& e) {
      message = e.what();
    }
    ::setrlimit(RLIMIT_FSIZE, &old_limit);
    ::signal(SIGXFSZ, old_handler);

    EXPECT_TRUE(contains(message, path)) << message;
    EXPECT_TRUE(contains(message, std::strerror(EFBIG))) << message;
    EXPECT_EQ(std::filesystem::file_size(path), size);  // the partial record was cut off
    journal.append(make_record(4));                      // and appending carries on
  }
  Journal reopened(path, IDENTITY);
  ASSERT_EQ(reopened.recovered().size(), 2u);
  expect_bitwise_equal(make_record(0), reopened.recovered()[0]);
  expect_bitwise_equal(make_record(4), reopened.recovered()[1]);
}

TEST(Journal, RemoveDeletesTheFile) {
  testing::ScratchDir scratch("journal-remove");
  const std::string path = scratch.file("run.journal");
  Journal journal(path, IDENTITY);
  journal.append(make_record(0));
  ASSERT_TRUE(std::filesystem::exists(path));
  journal.remove();
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_TRUE(std::filesystem::is_empty(scratch.file("")));  // no temporary left behind either
  EXPECT_THROW(journal.append(make_record(1)), Error);
}

}  // namespace
}  // namespace stengmc
