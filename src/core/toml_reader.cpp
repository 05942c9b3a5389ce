#include "core/toml_reader.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <map>
#include <string>

#include "core/error.hpp"
#include "core/format.hpp"
#include "core/input_file.hpp"
#include "core/toml_library.hpp"

namespace stengmc {

struct TomlDocument::Tree {
  toml::table root;
  std::map<const toml::table*, std::set<std::string, std::less<>>> read;  //!< keys asked for, per table

  void note_read(const toml::table& table, std::string_view key) { read[&table].emplace(key); }
};

namespace {

const toml::table& table_of(const void* table) { return *static_cast<const toml::table*>(table); }
const toml::node* node_of(const void* node) { return static_cast<const toml::node*>(node); }

std::string describe(const toml::node& node) {
  switch (node.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::table: return "a table";
    case toml::node_type::array: return "an array";
    default: return "a date or time";
  }
}

std::string join(const std::vector<std::string_view>& items) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? ", \"" : "\"") + std::string(items[i]) + "\"";
  return out;
}

}  // namespace

// ---------------------------------------------------------------- TomlDocument

TomlDocument::TomlDocument(std::unique_ptr<Tree> tree, std::string file, std::string text)
    : tree_(std::move(tree)), file_(std::move(file)), text_(std::move(text)) {}

TomlDocument::~TomlDocument() = default;

std::unique_ptr<TomlDocument> TomlDocument::from_file(const std::string& file) {
  return from_string(read_text_file(file, "a TOML file (study, surface or settings)"), file);
}

std::unique_ptr<TomlDocument> TomlDocument::from_string(const std::string& text, const std::string& file) {
  try {
    auto tree = std::make_unique<Tree>();
    tree->root = toml::parse(text, file);
    return std::unique_ptr<TomlDocument>(new TomlDocument(std::move(tree), file, text));
  } catch (const toml::parse_error& e) {
    const auto& where = e.source().begin;
    throw InputError(file + ":" + std::to_string(where.line) + ":" + std::to_string(where.column) +
                     ": not valid TOML: " + std::string(e.description()));
  }
}

TomlTable TomlDocument::root() { return TomlTable(*this, &tree_->root, ""); }

namespace {

std::vector<std::string> split_path(std::string_view dotted) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = dotted.find('.', start);
    parts.emplace_back(dotted.substr(start, dot == std::string_view::npos ? std::string_view::npos : dot - start));
    if (dot == std::string_view::npos) break;
    start = dot + 1;
  }
  return parts;
}

}  // namespace

void TomlDocument::set_number(std::string_view dotted_path, double value) {
  const std::vector<std::string> parts = split_path(dotted_path);
  toml::table* table = &tree_->root;
  std::string walked;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    walked += (walked.empty() ? "" : ".") + parts[i];
    toml::table* next = table->get_as<toml::table>(parts[i]);
    if (!next)
      throw InputError(file_ + ": cannot set " + std::string(dotted_path) + ": there is no table [" + walked +
                       "] in the file (a swept parameter must name a key of an existing table)");
    table = next;
  }
  if (parts.back().empty()) throw InputError(file_ + ": cannot set '" + std::string(dotted_path) + "': empty key");
  if (std::isfinite(value) && value == std::floor(value) && std::abs(value) < 9.0e15)
    table->insert_or_assign(parts.back(), static_cast<std::int64_t>(value));
  else
    table->insert_or_assign(parts.back(), value);
}

bool TomlDocument::has_path(std::string_view dotted_path) const {
  const std::vector<std::string> parts = split_path(dotted_path);
  const toml::table* table = &tree_->root;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const toml::node* node = table->get(parts[i]);
    if (!node) return false;
    if (i + 1 == parts.size()) return true;
    table = node->as_table();
    if (!table) return false;
  }
  return true;
}

void TomlDocument::defer_table(std::string_view key) {
  tree_->note_read(tree_->root, key);
  deferred_.emplace(key);
}

void TomlDocument::collect_unknown(const void* opaque, const std::string& path, std::vector<std::string>& out) const {
  const toml::table& table = table_of(opaque);
  const auto& read = tree_->read;
  const auto found = read.find(&table);
  for (const auto& [key, node] : table) {
    const std::string name(key.str());
    const bool was_read = found != read.end() && found->second.count(name) > 0;
    const std::string qualified = path.empty() ? name : path + "." + name;
    if (!was_read) {
      std::string allowed;
      if (found != read.end())
        for (const auto& k : found->second) allowed += (allowed.empty() ? "" : ", ") + k;
      out.push_back(file_ + ":" + std::to_string(node.source().begin.line) + ": unknown key '" + qualified +
                    "'" + (allowed.empty() ? "" : "; allowed here: " + allowed));
      continue;
    }
    if (&table == &tree_->root && deferred_.count(name) > 0) continue;
    if (const auto* sub = node.as_table()) collect_unknown(sub, qualified, out);
    if (const auto* array = node.as_array())
      for (std::size_t i = 0; i < array->size(); ++i)
        if (const auto* sub = (*array)[i].as_table())
          collect_unknown(sub, qualified + "[" + std::to_string(i) + "]", out);
  }
}

void TomlDocument::reject_unknown_keys(std::string_view prefix) const {
  std::vector<std::string> all;
  collect_unknown(&tree_->root, "", all);
  std::vector<std::string> unknown;
  const std::string marker = "unknown key '" + std::string(prefix) + (prefix.empty() ? "" : ".");
  for (auto& line : all)
    if (line.find(marker) != std::string::npos) unknown.push_back(std::move(line));
  if (unknown.empty()) return;
  std::string message;
  for (const auto& line : unknown) message += (message.empty() ? "" : "\n") + line;
  throw InputError(message);
}

// ---------------------------------------------------------------- TomlTable

TomlTable::TomlTable(TomlDocument& document, const void* table, std::string path)
    : document_(&document), table_(table), path_(std::move(path)) {}

const void* TomlTable::lookup(std::string_view key) {
  document_->tree_->note_read(table_of(table_), key);
  return table_of(table_).get(key);
}

std::string TomlTable::qualified(std::string_view key) const {
  return path_.empty() ? std::string(key) : "[" + path_ + "] " + std::string(key);
}

std::string TomlTable::location(std::string_view key) const {
  const toml::node* node = table_of(table_).get(key);
  // A value set by a parameter sweep has no line in the file.
  if (node && node->source().begin.line == 0) return document_->file() + " (value set by the sweep)";
  const auto line = node ? node->source().begin.line : table_of(table_).source().begin.line;
  return document_->file() + ":" + std::to_string(line);
}

void TomlTable::fail(std::string_view key, const std::string& what) const {
  throw InputError(location(key) + ": " + qualified(key) + " " + what);
}

bool TomlTable::has(std::string_view key) { return lookup(key) != nullptr; }

double TomlTable::number(std::string_view key, double fallback) {
  const toml::node* node = node_of(lookup(key));
  if (!node) return fallback;
  double value = 0.0;
  if (const auto* i = node->as_integer()) {
    value = static_cast<double>(i->get());
  } else if (const auto* f = node->as_floating_point()) {
    value = f->get();
  } else {
    fail(key, "is " + describe(*node) + "; expected a number");
  }
  if (!std::isfinite(value)) fail(key, "= " + format_number(value) + " is not a finite number");
  return value;
}

double TomlTable::required_number(std::string_view key) {
  if (!lookup(key)) fail(key, "is missing; a number is required");
  return number(key, 0.0);
}

double TomlTable::positive(std::string_view key, double fallback) {
  const double value = number(key, fallback);
  if (!(value > 0.0)) fail(key, "= " + format_number(value) + " must be > 0");
  return value;
}

double TomlTable::non_negative(std::string_view key, double fallback) {
  const double value = number(key, fallback);
  if (!(value >= 0.0)) fail(key, "= " + format_number(value) + " must be >= 0");
  return value;
}

long long TomlTable::integer(std::string_view key, long long fallback, long long minimum) {
  const toml::node* node = node_of(lookup(key));
  if (!node) return fallback;
  const auto* i = node->as_integer();
  if (!i) fail(key, "is " + describe(*node) + "; expected an integer");
  if (i->get() < minimum) fail(key, "= " + std::to_string(i->get()) + " must be >= " + std::to_string(minimum));
  return i->get();
}

bool TomlTable::boolean(std::string_view key, bool fallback) {
  const toml::node* node = node_of(lookup(key));
  if (!node) return fallback;
  const auto* b = node->as_boolean();
  if (!b) fail(key, "is " + describe(*node) + "; expected true or false");
  return b->get();
}

std::string TomlTable::string(std::string_view key, std::string_view fallback) {
  const toml::node* node = node_of(lookup(key));
  if (!node) return std::string(fallback);
  const auto* s = node->as_string();
  if (!s) fail(key, "is " + describe(*node) + "; expected a string");
  return s->get();
}

std::string TomlTable::choice(std::string_view key, std::string_view fallback,
                              const std::vector<std::string_view>& allowed) {
  std::string value = string(key, fallback);
  for (auto a : allowed)
    if (value == a) return value;
  fail(key, "= \"" + value + "\" is not one of " + join(allowed));
}

namespace {
//! "[i][j]...": where an item lies in nested arrays (built by appending: GCC 12 warns,
//! wrongly, of -Wrestrict on a chained concatenation of temporaries).
std::string index_path(std::initializer_list<std::size_t> indices) {
  std::string path;
  for (std::size_t index : indices) {
    path += '[';
    path += std::to_string(index);
    path += ']';
  }
  return path;
}

//! The number at `where` (an index path such as "[2][1]") of array `key`: an integer or a
//! float, finite; anything else fails naming the key and the index.
double finite_number(const TomlTable& table, std::string_view key, const toml::node& item, const std::string& where) {
  double value = 0.0;
  if (const auto* integer = item.as_integer()) {
    value = static_cast<double>(integer->get());
  } else if (const auto* floating = item.as_floating_point()) {
    value = floating->get();
  } else {
    table.fail(key, where + " is " + describe(item) + "; expected a number");
  }
  if (!std::isfinite(value)) table.fail(key, where + " is not a finite number");
  return value;
}
}  // namespace

std::vector<double> TomlTable::number_list(std::string_view key) {
  std::vector<double> out;
  const toml::node* node = node_of(lookup(key));
  if (!node) return out;
  const auto* array = node->as_array();
  if (!array) fail(key, "is " + describe(*node) + "; expected an array of numbers");
  for (std::size_t i = 0; i < array->size(); ++i) {
    out.push_back(finite_number(*this, key, (*array)[i], index_path({i})));
  }
  return out;
}

std::vector<std::vector<double>> TomlTable::number_rows(std::string_view key, std::size_t width) {
  std::vector<std::vector<double>> out;
  const toml::node* node = node_of(lookup(key));
  if (!node) return out;
  const auto* array = node->as_array();
  const std::string expected = "expected an array of [" + std::to_string(width) + " numbers] arrays";
  if (!array) fail(key, "is " + describe(*node) + "; " + expected);
  for (std::size_t i = 0; i < array->size(); ++i) {
    const auto* row = (*array)[i].as_array();
    if (!row || row->size() != width)
      fail(key, "[" + std::to_string(i) + "] is " + describe((*array)[i]) + (row ? " of " + std::to_string(row->size()) + " entries" : "") +
                    "; " + expected);
    std::vector<double> values;
    for (std::size_t j = 0; j < width; ++j) {
      const double value = finite_number(*this, key, (*row)[j], index_path({i, j}));
      values.push_back(value);
    }
    out.push_back(std::move(values));
  }
  return out;
}

std::vector<std::string> TomlTable::string_list(std::string_view key, const std::vector<std::string_view>& allowed) {
  std::vector<std::string> out;
  const toml::node* node = node_of(lookup(key));
  if (!node) return out;
  const auto* array = node->as_array();
  if (!array)
    fail(key, "is " + describe(*node) + "; expected an array of strings" +
                  (allowed.empty() ? std::string() : ", each one of " + join(allowed)));
  for (std::size_t i = 0; i < array->size(); ++i) {
    const auto* text = (*array)[i].as_string();
    if (!text) fail(key, std::string("[") + std::to_string(i) + "] is " + describe((*array)[i]) + "; expected a string");
    if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), text->get()) == allowed.end())
      fail(key, std::string("[") + std::to_string(i) + "] = \"" + text->get() + "\" is not one of " + join(allowed));
    out.push_back(text->get());
  }
  return out;
}

std::optional<TomlTable> TomlTable::table(std::string_view key) {
  const toml::node* node = node_of(lookup(key));
  if (!node) return std::nullopt;
  const auto* sub = node->as_table();
  if (!sub) fail(key, "is " + describe(*node) + "; expected a table");
  return TomlTable(*document_, sub, path_.empty() ? std::string(key) : path_ + "." + std::string(key));
}

std::vector<TomlTable> TomlTable::table_array(std::string_view key) {
  std::vector<TomlTable> out;
  const toml::node* node = node_of(lookup(key));
  if (!node) return out;
  const auto* array = node->as_array();
  if (!array) fail(key, "is " + describe(*node) + "; expected an array of tables ([[" + std::string(key) + "]])");
  for (std::size_t i = 0; i < array->size(); ++i) {
    const auto* sub = (*array)[i].as_table();
    if (!sub) fail(key, std::string("[") + std::to_string(i) + "] is " + describe((*array)[i]) + "; expected a table");
    out.push_back(TomlTable(*document_, sub, (path_.empty() ? "" : path_ + ".") + std::string(key) + "[" + std::to_string(i) + "]"));
  }
  return out;
}

}  // namespace stengmc
