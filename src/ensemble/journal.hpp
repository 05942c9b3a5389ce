#pragma once
//! Crash-safe store of finished realisations, so a killed ensemble run resumes where it
//! stopped. Each record is appended and fsync'ed as its realisation finishes; a run killed
//! (even by SIGKILL or a power cut) loses at most the record being written, which the next
//! opening cuts off. The final HDF5 output is assembled from the records, then the journal
//! is removed.
//!
//! File format, version 2. Integers are little-endian, fixed width, written byte by byte;
//! doubles are their IEEE-754 bit pattern as a u64 (std::bit_cast), so files are portable
//! between machines and values come back bitwise.
//!
//!   header:  "STENGMCJ" (8 bytes) | u32 format version (1)
//!            | u64 study hash | u32 n | n bytes description (JournalIdentity)
//!   records: u32 payload length | payload | u64 fnv1a64(payload)
//!   payload: u64 realisation | u8 valid (0/1) | u32 n | n bytes failure
//!            | u32 SCALAR_COUNT | SCALAR_COUNT doubles, in Scalar order
//!            | u32 ASPERITY_COLUMN_COUNT | u64 asperity count a
//!            | ASPERITY_COLUMN_COUNT × a doubles, column after column (AsperityColumn order)
//!            | u64 n | n doubles time_s | u64 n | n doubles voltage_v | u64 n | n doubles charge_c
//!            | u64 n | n doubles measured_voltage_v
//!            | u32 extras | per extra: u32 n | n bytes name | u64 m | m doubles values
//!
//! Recovery: every record whose own checksum holds is kept. Damage inside the file (a bad
//! block, a stray write) costs only the records it touches: reading resumes at the next
//! offset where a whole frame with a matching checksum begins, and the damaged bytes stay
//! where they are (they are skipped again at the next opening). Whatever follows the last
//! good record is a torn append and is cut off (the file is truncated there); appends only
//! ever write at the end, so a kill can only tear the last record. A record that passes its
//! checksum but does not parse as this program's record (other SCALAR_COUNT or
//! ASPERITY_COLUMN_COUNT) means the format changed: an InputError, never silent loss. The
//! header is written to a temporary file and linked into place, so a journal either does
//! not exist or has a complete header; a damaged header is refused, not guessed at.
//!
//! One run at a time: the file is locked (flock) while open; a second Journal on the same
//! file throws Error. Records are not de-duplicated: the caller skips recovered
//! realisations and appends each remaining one once.
#include <cstdint>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "core/checksum.hpp"  // fnv1a64, the records' checksum
#include "ensemble/realisation_record.hpp"

namespace stengmc {

//! Identity of the computation a journal belongs to; a resume with a different identity is refused.
struct JournalIdentity {
  //! Hash of everything that determines the results (computed by the caller, e.g. with fnv1a64).
  //! The only thing compared on resume.
  std::uint64_t study_hash = 0;
  //! Human text stored in the header (program version, study file) for messages; not compared.
  std::string description;
};

//! Encodes one record as a journal frame (length, payload, checksum): what a journal
//! appends, what a shard file holds and what an MPI worker sends to rank 0. `path` names the
//! destination in messages.
std::string encode_record_frame(const RealisationRecord& record, const std::string& path);

//! Decodes a whole frame from encode_record_frame; InputError naming `source` when the
//! checksum fails or it does not parse as this program's record.
RealisationRecord decode_record_frame(std::string_view frame, const std::string& source);

//! A journal as it is on disk, read without opening it for appending (nothing is cut or
//! locked): what `stengmc merge` reads from a shard file.
struct JournalContents {
  std::uint64_t study_hash = 0;
  std::string description;
  std::vector<RealisationRecord> records;  //!< in file order
};

//! Reads the whole journal at `path`, a regular file (check_input_file; `what` names it:
//! "the shard file"). Unlike a resume, any damage is refused (InputError naming the file
//! and the byte offset, then `advice`: how to make the file again): a finished file written
//! by write_journal_file is never torn, so damage there means the file cannot be trusted.
JournalContents read_journal_file(const std::string& path, const std::string& what, const std::string& advice);

//! A journal read as the resume would read it, but read only (nothing cut, nothing locked:
//! a running job may be appending): what `stengmc status` shows.
struct JournalScan {
  JournalContents contents;
  std::uint64_t skipped_bytes = 0;  //!< damaged bytes between intact records, skipped
  std::uint64_t torn_bytes = 0;     //!< past the last intact record: a torn append, cut off on resume
};

//! Reads the journal at `path` (a regular file; `what` names it) keeping every record whose
//! checksum holds, like a resume. InputError naming the file when it is not a journal, its
//! header is damaged or a record has another record format (then `advice`).
JournalScan scan_journal_file(const std::string& path, const std::string& what, const std::string& advice);

//! Writes a complete journal at `path` in one go (header and every record, under a
//! temporary name, fsync'ed, then renamed into place): a reader sees all of it or nothing.
void write_journal_file(const std::string& path, const JournalIdentity& identity,
                        const std::vector<RealisationRecord>& records);

//! What --restart does: deletes the journal at `path`, if there is one. Anything else there
//! (a device, a FIFO, a folder, a link, a file that does not start as a journal) is refused
//! with an InputError naming it and what it is, and left as it was: --restart deletes only
//! what stengmc wrote. A journal another running stengmc holds is refused too (Error).
void discard_journal(const std::string& path);

//! An open journal file. Errors (disk full, permission) throw Error naming the file and the
//! system's reason; an unusable existing file (another identity, another record format, not
//! a journal) throws InputError saying how to start afresh.
class Journal {
 public:
  //! Opens `path` for appending, creating it (with its header) if it does not exist (a
  //! path where something other than a regular file sits is refused: InputError). An
  //! existing file's intact records are read and a torn or corrupt tail is cut off; if its
  //! study hash differs from `identity.study_hash`, throws InputError naming the file and
  //! both descriptions (the file is left untouched).
  Journal(std::string path, const JournalIdentity& identity);
  //! Closes the file (does not delete it).
  ~Journal();
  Journal(const Journal&) = delete;
  Journal& operator=(const Journal&) = delete;

  //! The records found at opening, in file order.
  [[nodiscard]] const std::vector<RealisationRecord>& recovered() const { return recovered_; }

  //! Appends one record durably (framed record written, then fsync) before returning.
  //! Thread-safe: OpenMP threads call it as they finish. On failure the file is cut back to
  //! its last whole record and Error is thrown.
  void append(const RealisationRecord& record);
  //! Appends several records with one write and one fsync (group commit: rank 0 of an MPI
  //! run journals what arrived together at the cost of one fsync). Same guarantees.
  void append(const std::vector<RealisationRecord>& records);

  //! Deletes the file (after the final output was committed); later appends throw.
  void remove();

  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  void create(const JournalIdentity& identity);
  void load(const JournalIdentity& identity);
  void append_frames(const std::string& frames, const std::string& what);

  std::string path_;
  int fd_ = -1;
  std::uint64_t size_ = 0;  //!< end of the last whole record [bytes]
  bool broken_ = false;     //!< a failed append could not be cut back: refuse further appends
  std::mutex mutex_;
  std::vector<RealisationRecord> recovered_;
};

}  // namespace stengmc
