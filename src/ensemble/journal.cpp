#include "ensemble/journal.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <optional>
#include <sstream>
#include <system_error>
#include <utility>

#include "core/byte_codec.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"
#include "core/posix_file.hpp"
#include "core/temporary_file.hpp"

namespace stengmc {

namespace {

constexpr std::string_view MAGIC = "STENGMCJ";
constexpr std::uint32_t FORMAT_VERSION = 2;  // 2: measured voltage trace and named extras
// Any length above this is corruption: a record is kilobytes, a traced one megabytes. Also
// bounds what a damaged length can make us allocate.
constexpr std::uint64_t MAX_PAYLOAD_BYTES = std::uint64_t{1} << 30;
constexpr std::uint64_t LENGTH_BYTES = 4;
constexpr std::uint64_t CHECKSUM_BYTES = 8;

std::string system_message(int error) { return std::generic_category().message(error); }

[[noreturn]] void throw_system(const std::string& path, const std::string& what, int error) {
  throw Error(path + ": " + what + ": " + system_message(error));
}

std::string how_to_start_afresh(const std::string& path) {
  return "To start afresh, delete " + path + " or run again with --restart.";
}

bool starts_with_magic(std::string_view file) { return file.substr(0, MAGIC.size()) == MAGIC; }

[[noreturn]] void refuse_foreign(const std::string& path, const std::string& advice) {
  throw InputError(path + ": not a stengmc journal (it does not start with " + std::string(MAGIC) + "). " + advice);
}

//! What to do about a file of something else where a journal should be: --restart would
//! refuse it too (discard_journal), so it is not the advice.
std::string how_to_get_past(const std::string& path) {
  return "Refusing to overwrite it: move " + path + " away, or choose another output name (--out).";
}

std::string hex(std::uint64_t value) {
  std::ostringstream out;
  out << "0x" << std::hex << value;
  return out.str();
}

std::string quoted(const std::string& description) {
  return description.empty() ? std::string("(no description)") : "\"" + description + "\"";
}

//! The framed record: length, payload, checksum.
std::string encode_frame(const RealisationRecord& record, const std::string& path) {
  const std::size_t asperities = record.asperity_count();
  for (const auto& column : record.asperities)
    if (column.size() != asperities)
      throw Error(path + ": realisation " + std::to_string(record.realisation) +
                  ": asperity columns of different lengths cannot be journalled");
  ByteEncoder out;
  out.u32(0);  // payload length, filled in below
  out.u64(record.realisation);
  out.u8(record.valid ? 1 : 0);
  out.text(record.failure);
  out.u32(static_cast<std::uint32_t>(SCALAR_COUNT));
  out.doubles(record.scalars);
  out.u32(static_cast<std::uint32_t>(ASPERITY_COLUMN_COUNT));
  out.u64(asperities);
  for (const auto& column : record.asperities) out.doubles(column);
  out.vector(record.time_s);
  out.vector(record.voltage_v);
  out.vector(record.charge_c);
  out.vector(record.measured_voltage_v);
  out.u32(static_cast<std::uint32_t>(record.extras.size()));
  for (const RecordExtra& e : record.extras) {
    out.text(e.name);
    out.vector(e.values);
  }

  std::string& bytes = out.bytes();
  const std::uint64_t payload = bytes.size() - LENGTH_BYTES;
  if (payload > MAX_PAYLOAD_BYTES)
    throw Error(path + ": the record of realisation " + std::to_string(record.realisation) + " is " +
                std::to_string(payload) + " bytes, more than the journal's limit of 1 GiB per record");
  for (std::size_t i = 0; i < LENGTH_BYTES; ++i) bytes[i] = static_cast<char>(payload >> (8 * i));
  out.u64(fnv1a64(std::string_view(bytes).substr(LENGTH_BYTES)));
  return bytes;
}

//! `advice` says what to do about a file written by another record format (how to start
//! afresh, or how to make the file again).
RealisationRecord decode_payload(std::string_view payload, const std::string& path, std::size_t index,
                                 const std::string& advice) {
  const auto malformed = [&](const std::string& what) {
    return InputError(path + ": record " + std::to_string(index + 1) + " " + what +
                      ": the file was written by a program with another record format. The program changed "
                      "since it was written, so its finished realisations cannot be reused. " + advice);
  };
  ByteDecoder in(payload);
  RealisationRecord record;
  std::uint8_t valid = 0;
  std::uint32_t scalars = 0, columns = 0;
  std::uint64_t asperities = 0;
  if (!in.u64(record.realisation) || !in.u8(valid) || valid > 1 || !in.text(record.failure) || !in.u32(scalars))
    throw malformed("does not parse");
  record.valid = valid == 1;
  if (scalars != SCALAR_COUNT)
    throw malformed("holds " + std::to_string(scalars) + " scalars where this program has " +
                    std::to_string(SCALAR_COUNT));
  if (!in.doubles(SCALAR_COUNT, record.scalars.data()) || !in.u32(columns)) throw malformed("does not parse");
  if (columns != ASPERITY_COLUMN_COUNT)
    throw malformed("holds " + std::to_string(columns) + " asperity columns where this program has " +
                    std::to_string(ASPERITY_COLUMN_COUNT));
  if (!in.u64(asperities) || in.left() / 8 / ASPERITY_COLUMN_COUNT < asperities) throw malformed("does not parse");
  for (auto& column : record.asperities) {
    column.resize(asperities);
    in.doubles(asperities, column.data());
  }
  std::uint32_t extras = 0;
  if (!in.vector(record.time_s) || !in.vector(record.voltage_v) || !in.vector(record.charge_c) ||
      !in.vector(record.measured_voltage_v) || !in.u32(extras))
    throw malformed("does not parse");
  for (std::uint32_t i = 0; i < extras; ++i) {
    RecordExtra e;
    if (!in.text(e.name) || !in.vector(e.values)) throw malformed("does not parse");
    record.extras.push_back(std::move(e));
  }
  if (in.left() != 0) throw malformed("does not parse");
  return record;
}

// ---------------------------------------------------------------- file access

//! Reads exactly `size` bytes at `offset` (the caller checked the file is long enough).
std::string read_at(int fd, std::uint64_t offset, std::uint64_t size, const std::string& path) {
  std::string bytes(size, '\0');
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::pread(fd, bytes.data() + done, size - done, static_cast<off_t>(offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw_system(path, "cannot read the journal", errno);
    if (n == 0) throw Error(path + ": the journal shrank while being read (is another program writing it?)");
    done += static_cast<std::size_t>(n);
  }
  return bytes;
}

std::uint64_t little_endian(std::string_view bytes) {
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < bytes.size(); ++i) v |= std::uint64_t{static_cast<unsigned char>(bytes[i])} << (8 * i);
  return v;
}


//! True when a whole frame whose checksum holds starts at `offset` of `body`.
bool frame_at(std::string_view body, std::uint64_t offset) {
  if (body.size() - offset < LENGTH_BYTES + CHECKSUM_BYTES) return false;
  const std::uint64_t length = little_endian(body.substr(offset, LENGTH_BYTES));
  if (length > MAX_PAYLOAD_BYTES || body.size() - offset - LENGTH_BYTES - CHECKSUM_BYTES < length) return false;
  return fnv1a64(body.substr(offset + LENGTH_BYTES, length)) ==
         little_endian(body.substr(offset + LENGTH_BYTES + length, CHECKSUM_BYTES));
}

//! The first offset >= `from` where a whole frame with a matching checksum begins. A cheap
//! look at the payload's fixed fields (valid is 0 or 1, the failure text fits, the scalar
//! count is this program's) spares the checksum at almost every offset; a random offset
//! then passes the 64-bit checksum with probability 2^-64.
std::optional<std::uint64_t> next_frame(std::string_view body, std::uint64_t from) {
  constexpr std::uint64_t FIXED_PAYLOAD = 8 + 1 + 4 + 4;  // realisation, valid, failure length, scalar count
  for (std::uint64_t offset = from; body.size() - offset >= LENGTH_BYTES + FIXED_PAYLOAD + CHECKSUM_BYTES; ++offset) {
    const std::uint64_t length = little_endian(body.substr(offset, LENGTH_BYTES));
    if (length < FIXED_PAYLOAD || body.size() - offset - LENGTH_BYTES - CHECKSUM_BYTES < length) continue;
    const std::string_view payload = body.substr(offset + LENGTH_BYTES, length);
    if (static_cast<unsigned char>(payload[8]) > 1) continue;
    const std::uint64_t failure = little_endian(payload.substr(9, 4));
    if (failure > length - FIXED_PAYLOAD || little_endian(payload.substr(13 + failure, 4)) != SCALAR_COUNT) continue;
    if (frame_at(body, offset)) return offset;
  }
  return std::nullopt;
}

//! The header: magic, format version, study hash, description.
std::string encode_header(const JournalIdentity& identity) {
  ByteEncoder header;
  header.bytes().append(MAGIC);
  header.u32(FORMAT_VERSION);
  header.u64(identity.study_hash);
  header.text(identity.description);
  return header.bytes();
}

struct Header {
  std::uint64_t study_hash = 0;
  std::string description;
  std::uint64_t body_start = 0;  //!< offset of the first record [bytes]
};

//! The header at the start of `file` (the whole file), whose magic the caller checked. It
//! was complete before the file got its name, so anything wrong with it is not a torn
//! write: refuse rather than overwrite what may be someone else's file. `advice` says what
//! to do about it (how to start afresh, or how to make the file again).
Header parse_header(std::string_view file, const std::string& path, const std::string& advice) {
  const std::uint64_t fixed = MAGIC.size() + 4 + 8 + 4;
  if (file.size() < fixed) throw InputError(path + ": the journal header is damaged. " + advice);
  const auto version = little_endian(file.substr(MAGIC.size(), 4));
  Header header;
  header.study_hash = little_endian(file.substr(MAGIC.size() + 4, 8));
  const auto description_size = little_endian(file.substr(MAGIC.size() + 12, 4));
  if (version != FORMAT_VERSION)
    throw InputError(path + ": journal format version " + std::to_string(version) + ", this program reads version " +
                     std::to_string(FORMAT_VERSION) + ". " + advice);
  if (file.size() - fixed < description_size) throw InputError(path + ": the journal header is damaged. " + advice);
  header.description.assign(file.substr(fixed, description_size));
  header.body_start = fixed + description_size;
  return header;
}


struct ScanEnd {
  std::uint64_t end_of_good = 0;  //!< offset in the body just past the last good frame
  std::uint64_t skipped = 0;      //!< damaged bytes between good frames, skipped
};

//! The records of a journal's `body`: every frame whose checksum holds, in file order. The
//! scan resumes at the next offset where a whole frame with a matching checksum begins, so
//! damage costs only the frames it touches. What follows the last good frame (from
//! end_of_good on) is a torn append.
ScanEnd scan_records(std::string_view body, const std::string& path, const std::string& advice,
                     std::vector<RealisationRecord>& records) {
  ScanEnd end;
  std::uint64_t offset = 0;
  while (offset < body.size()) {
    if (!frame_at(body, offset)) {
      const auto next = next_frame(body, offset + 1);
      if (!next) break;
      end.skipped += *next - offset;
      offset = *next;
    }
    const std::uint64_t length = little_endian(body.substr(offset, LENGTH_BYTES));
    records.push_back(decode_payload(body.substr(offset + LENGTH_BYTES, length), path, records.size(), advice));
    offset += LENGTH_BYTES + length + CHECKSUM_BYTES;
    end.end_of_good = offset;
  }
  return end;
}
}  // namespace

std::string encode_record_frame(const RealisationRecord& record, const std::string& path) {
  return encode_frame(record, path);
}

RealisationRecord decode_record_frame(std::string_view frame, const std::string& source) {
  if (!frame_at(frame, 0) || frame.size() != LENGTH_BYTES + little_endian(frame.substr(0, LENGTH_BYTES)) + CHECKSUM_BYTES)
    throw InputError(source + ": a record's checksum does not hold (damaged in transit or on disk)");
  return decode_payload(frame.substr(LENGTH_BYTES, frame.size() - LENGTH_BYTES - CHECKSUM_BYTES), source, 0,
                        "Run every process of the job with the same stengmc.");
}

namespace {

//! The whole of the journal file at `path`, a regular file starting with the magic.
std::string read_whole_journal(const std::string& path, const std::string& what, const std::string& advice) {
  // A FIFO would block the read for ever, a device feed it without end: a regular file only.
  check_input_file(path, what);
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) throw InputError(path + ": cannot open: " + system_message(errno));
  std::string file;
  try {
    struct stat status {};
    if (::fstat(fd, &status) != 0) throw_system(path, "cannot read", errno);
    // The magic before the whole file: a large file of something else is not read into memory.
    if (!starts_with_magic(read_at(fd, 0, std::min<std::uint64_t>(MAGIC.size(), status.st_size), path)))
      refuse_foreign(path, advice);
    file = read_at(fd, 0, static_cast<std::uint64_t>(status.st_size), path);
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
  return file;
}

}  // namespace

JournalScan scan_journal_file(const std::string& path, const std::string& what, const std::string& advice) {
  const std::string file = read_whole_journal(path, what, advice);
  Header header = parse_header(file, path, advice);
  JournalScan scan;
  scan.contents = {header.study_hash, std::move(header.description), {}};
  const std::string_view body = std::string_view(file).substr(header.body_start);
  const ScanEnd end = scan_records(body, path, advice, scan.contents.records);
  scan.skipped_bytes = end.skipped;
  scan.torn_bytes = body.size() - end.end_of_good;
  return scan;
}

JournalContents read_journal_file(const std::string& path, const std::string& what, const std::string& advice) {
  const std::string file = read_whole_journal(path, what, advice);
  Header header = parse_header(file, path, advice);
  JournalContents contents{header.study_hash, std::move(header.description), {}};
  const std::string_view body = std::string_view(file).substr(header.body_start);
  for (std::uint64_t offset = 0; offset < body.size();) {
    if (!frame_at(body, offset))
      throw InputError(path + ": damaged at byte " + std::to_string(header.body_start + offset) +
                       " (a record whose checksum does not hold): the file cannot be trusted. " + advice);
    const std::uint64_t length = little_endian(body.substr(offset, LENGTH_BYTES));
    contents.records.push_back(
        decode_payload(body.substr(offset + LENGTH_BYTES, length), path, contents.records.size(), advice));
    offset += LENGTH_BYTES + length + CHECKSUM_BYTES;
  }
  return contents;
}

void write_journal_file(const std::string& path, const JournalIdentity& identity,
                        const std::vector<RealisationRecord>& records) {
  std::string bytes = encode_header(identity);
  for (const RealisationRecord& r : records) bytes += encode_frame(r, path);
  TemporaryFile temporary(path);
  write_file_durably(temporary.path(), bytes, path, "the file");
  temporary.commit();
  sync_directory_of(path);
}

void discard_journal(const std::string& path) {
  const std::string nothing_removed =
      ": --restart removes only a journal stengmc wrote, and removed nothing. Move it away, or choose another output "
      "name (--out).";
  std::error_code error;
  const auto type = std::filesystem::symlink_status(path, error).type();  // a link is not followed: not ours
  if (type == std::filesystem::file_type::not_found) return;
  if (error) throw_system(path, "cannot examine the journal", error.value());
  if (type != std::filesystem::file_type::regular)
    throw InputError(path + " is " + describe_file_type(type) + ", not a stengmc journal" + nothing_removed);
  const int fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) throw_system(path, "cannot open the journal", errno);
  try {
    struct stat status {};
    if (::fstat(fd, &status) != 0) throw_system(path, "cannot read the journal", errno);
    if (!S_ISREG(status.st_mode) ||
        !starts_with_magic(read_at(fd, 0, std::min<std::uint64_t>(MAGIC.size(), status.st_size), path)))
      throw InputError(path + " is a file that is not a stengmc journal (it does not start with " + std::string(MAGIC) +
                       ")" + nothing_removed);
    // A journal another run holds is that run's: removing it would lose what it appends.
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK)
      throw Error(path + ": the journal is in use by another running stengmc; --restart removed nothing");
    if (::unlink(path.c_str()) != 0 && errno != ENOENT) throw_system(path, "cannot delete the journal", errno);
  } catch (...) {
    ::close(fd);
    throw;
  }
  ::close(fd);
}

// ---------------------------------------------------------------- Journal

Journal::Journal(std::string path, const JournalIdentity& identity) : path_(std::move(path)) {
  const auto parent = std::filesystem::path(path_).parent_path();
  std::error_code ignored;  // a folder that cannot be made shows up as the open failing
  if (!parent.empty()) std::filesystem::create_directories(parent, ignored);

  // A FIFO would block the read for ever, a device feed it without end, a folder is no
  // file: a journal is a regular file or nothing yet.
  std::error_code error;
  const auto type = std::filesystem::status(path_, error).type();
  if (!error && type != std::filesystem::file_type::not_found && type != std::filesystem::file_type::regular)
    throw InputError(path_ + " is " + describe_file_type(type) + ", not a journal. " + how_to_get_past(path_));
  fd_ = ::open(path_.c_str(), O_RDWR | O_CLOEXEC);
  if (fd_ < 0 && errno == ENOENT) {
    create(identity);
    fd_ = ::open(path_.c_str(), O_RDWR | O_CLOEXEC);
  }
  if (fd_ < 0) throw_system(path_, "cannot open the journal", errno);
  try {
    // The lock goes with the process, so a killed run never leaves a stale one. Only a live
    // holder is refused; a filesystem without locks is used unlocked.
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0 && errno == EWOULDBLOCK)
      throw Error(path_ + ": the journal is in use by another running stengmc (one run per journal)");
    load(identity);
  } catch (...) {
    ::close(fd_);
    throw;
  }
}

Journal::~Journal() {
  if (fd_ >= 0) ::close(fd_);
}

void Journal::create(const JournalIdentity& identity) {
  if (identity.description.size() > MAX_PAYLOAD_BYTES)
    throw Error(path_ + ": the journal description is longer than 1 GiB");
  const std::string header = encode_header(identity);

  // Written and synced under a temporary name, then linked into place: the journal appears
  // with its whole header or not at all. link() (unlike rename) never replaces a journal
  // another run created meanwhile; that one is then opened and its identity checked.
  // The temporary is removed however this ends, also by a SIGTERM, and a stale one of a
  // killed run by the next (core/temporary_file.hpp).
  const TemporaryFile temporary(path_);
  write_file_durably(temporary.path(), header, path_, "the journal header");
  if (::link(temporary.path().c_str(), path_.c_str()) != 0 && errno != EEXIST &&
      ::rename(temporary.path().c_str(), path_.c_str()) != 0)  // a filesystem without hard links
    throw_system(path_, "cannot create the journal", errno);
  sync_directory_of(path_);
}

void Journal::load(const JournalIdentity& identity) {
  struct stat status {};
  if (::fstat(fd_, &status) != 0) throw_system(path_, "cannot read the journal", errno);
  const auto file_size = static_cast<std::uint64_t>(status.st_size);
  // The magic before the whole file: a large file of something else is not read into memory.
  if (!starts_with_magic(read_at(fd_, 0, std::min<std::uint64_t>(MAGIC.size(), file_size), path_)))
    refuse_foreign(path_, how_to_get_past(path_));
  const std::string file = read_at(fd_, 0, file_size, path_);
  const Header header = parse_header(file, path_, how_to_start_afresh(path_));
  if (header.study_hash != identity.study_hash)
    throw InputError(path_ + ": this journal belongs to another computation: it was written for " +
                     quoted(header.description) + " (study hash " + hex(header.study_hash) + "), this run is " +
                     quoted(identity.description) + " (study hash " + hex(identity.study_hash) +
                     "). The study (or the program) changed since the interrupted run, so its finished "
                     "realisations cannot be reused. " + how_to_start_afresh(path_));

  // Records. Every frame whose checksum holds is kept; damage (a bad disk block, a stray
  // write) costs only the frames it touches (scan_records). Whatever follows the last good
  // frame is a torn append (a kill mid-write) and is cut off, so appends continue after a
  // whole record.
  const std::uint64_t start = header.body_start;
  const std::string_view body = std::string_view(file).substr(start);
  const std::uint64_t end_of_good = scan_records(body, path_, how_to_start_afresh(path_), recovered_).end_of_good;
  // Cut only after every check passed, so a refused journal is left as it was.
  const std::uint64_t end = start + end_of_good;
  if (end < file_size && (::ftruncate(fd_, static_cast<off_t>(end)) != 0 || ::fsync(fd_) != 0))
    throw_system(path_, "cannot cut the torn record off the journal", errno);
  size_ = end;
}

void Journal::append(const RealisationRecord& record) {
  // Encoded outside the lock: threads encode in parallel.
  append_frames(encode_record_frame(record, path_), "realisation " + std::to_string(record.realisation));
}

void Journal::append(const std::vector<RealisationRecord>& records) {
  if (records.empty()) return;
  std::string frames;
  for (const RealisationRecord& r : records) frames += encode_record_frame(r, path_);
  append_frames(frames, records.size() == 1 ? "realisation " + std::to_string(records.front().realisation)
                                            : std::to_string(records.size()) + " realisations (" +
                                                  std::to_string(records.front().realisation) + ", ...)");
}

void Journal::append_frames(const std::string& frames, const std::string& what) {
  const std::lock_guard lock(mutex_);
  if (fd_ < 0) throw Error(path_ + ": the journal was removed; cannot append " + what);
  if (broken_) throw Error(path_ + ": an earlier append failed and could not be undone; not appending " + what);
  if (!write_all(fd_, size_, frames) || ::fsync(fd_) != 0) {
    const int error = errno;
    // Cut the partial record so the file ends on a whole one again. If even that fails,
    // what lies past the last whole record is unknown (after a failed fsync the kernel may
    // have dropped pages), so stop appending; the next opening cuts the tail.
    if (::ftruncate(fd_, static_cast<off_t>(size_)) != 0) broken_ = true;
    throw_system(path_, "cannot append " + what + " to the journal", error);
  }
  size_ += frames.size();
}

void Journal::remove() {
  const std::lock_guard lock(mutex_);
  if (fd_ < 0) return;
  // Unlinked while still locked, so no other run opens it half-way through.
  if (::unlink(path_.c_str()) != 0 && errno != ENOENT) throw_system(path_, "cannot delete the journal", errno);
  ::close(fd_);
  fd_ = -1;
}

}  // namespace stengmc
