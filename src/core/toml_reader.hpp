#pragma once
//! Typed, validated access to a TOML document. Every key read is remembered, so once a
//! reader is done, any key nobody asked for is reported as unknown (pbrt's ReportUnused).
//! Every error names the file, the line, the key, the value and what was expected.
//! toml++ stays out of this header: every settings reader includes it, and toml++ is the
//! heaviest header of the build. The tree lives in TomlDocument::Tree (toml_reader.cpp).
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "core/name_table.hpp"

namespace stengmc {

class TomlDocument;

//! One table of a document, read key by key.
class TomlTable {
 public:
  //! A number (integer or float); `fallback` when absent.
  double number(std::string_view key, double fallback);
  //! A number that must be present.
  double required_number(std::string_view key);
  //! A number > 0; `fallback` when absent.
  double positive(std::string_view key, double fallback);
  //! A number >= 0; `fallback` when absent.
  double non_negative(std::string_view key, double fallback);
  //! An integer >= minimum; `fallback` when absent.
  long long integer(std::string_view key, long long fallback, long long minimum);
  //! A boolean; `fallback` when absent.
  bool boolean(std::string_view key, bool fallback);
  //! A string that must be one of `allowed`; `fallback` when absent.
  std::string choice(std::string_view key, std::string_view fallback, const std::vector<std::string_view>& allowed);
  //! A value of an enumeration, by its name in `names`; `fallback` when absent.
  template <class Enum, std::size_t N>
  Enum enumeration(std::string_view key, Enum fallback, const NameTable<Enum, N>& names) {
    return names.value(choice(key, names.name(fallback), names.names()));
  }
  //! An array of finite numbers (integers or floats), empty when absent.
  std::vector<double> number_list(std::string_view key);
  //! An array of arrays of finite numbers, each of `width` entries (`[[1e-6, 0.9], ...]`),
  //! empty when absent.
  std::vector<std::vector<double>> number_rows(std::string_view key, std::size_t width);
  //! An array of strings, each one of `allowed`, or any when `allowed` is empty (empty when absent).
  std::vector<std::string> string_list(std::string_view key, const std::vector<std::string_view>& allowed);
  //! A free string; `fallback` when absent.
  std::string string(std::string_view key, std::string_view fallback);
  //! True when the key is present (and marks it read).
  bool has(std::string_view key);
  //! A sub-table, if present; an error if the key holds something else.
  std::optional<TomlTable> table(std::string_view key);
  //! An array of tables (`[[key]]`), empty if absent.
  std::vector<TomlTable> table_array(std::string_view key);

  //! Throws InputError located at `key` (or at the table if the key is absent).
  [[noreturn]] void fail(std::string_view key, const std::string& what) const;
  //! "[model.solver] key" style name for messages.
  [[nodiscard]] std::string qualified(std::string_view key) const;
  //! Where the table is: "file:line".
  [[nodiscard]] std::string location(std::string_view key) const;

 private:
  friend class TomlDocument;
  //! `table` is a toml::table of `document`'s tree.
  TomlTable(TomlDocument& document, const void* table, std::string path);
  //! The key's toml::node (nullptr when absent), marked read.
  const void* lookup(std::string_view key);

  TomlDocument* document_;
  const void* table_;  //!< a toml::table owned by the document (opaque here: see above)
  std::string path_;
};

//! A parsed TOML file and the record of what was read from it.
class TomlDocument {
 public:
  //! Parses `file`; throws InputError with file:line:column on a syntax error or a missing file.
  static std::unique_ptr<TomlDocument> from_file(const std::string& file);
  //! Parses `text` as if read from `file` (for tests and for studies given as strings).
  static std::unique_ptr<TomlDocument> from_string(const std::string& text, const std::string& file);

  //! The root table.
  TomlTable root();
  //! Sets the number at a dotted path ("model.belt_velocity_m_per_s") before it is read,
  //! as a parameter sweep does: an integral value is stored as an integer (so integer keys
  //! accept it). Every table on the path must exist; the key itself may be new.
  //! Throws InputError naming the file and the path otherwise.
  void set_number(std::string_view dotted_path, double value);
  //! True when the dotted path names an existing table or key.
  [[nodiscard]] bool has_path(std::string_view dotted_path) const;
  //! Throws InputError listing every key that no reader asked for, with its line; with a
  //! `prefix` ("spectrum"), only keys in that table (when a command reads one table of a study).
  void reject_unknown_keys(std::string_view prefix = "") const;
  //! The root table `key` is read (and its keys checked) by another part of the program
  //! (e.g. [inverse] by the inverse commands): reject_unknown_keys leaves it alone.
  void defer_table(std::string_view key);

  [[nodiscard]] const std::string& file() const { return file_; }
  [[nodiscard]] const std::string& text() const { return text_; }

  ~TomlDocument();
  TomlDocument(const TomlDocument&) = delete;
  TomlDocument& operator=(const TomlDocument&) = delete;

 private:
  friend class TomlTable;
  struct Tree;  //!< the parsed toml::table and, per table, the keys read from it
  TomlDocument(std::unique_ptr<Tree> tree, std::string file, std::string text);
  void collect_unknown(const void* table, const std::string& path, std::vector<std::string>& out) const;

  std::unique_ptr<Tree> tree_;
  std::string file_;
  std::string text_;
  std::set<std::string, std::less<>> deferred_;
};

}  // namespace stengmc
