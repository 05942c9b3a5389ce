#include "circuit/netlist_load.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <system_error>

#include "circuit/netlist_policy.hpp"
#include "circuit/netlist_structure.hpp"
#include "circuit/spice_cards.hpp"
#include "core/error.hpp"
#include "core/input_file.hpp"

namespace stengmc {

namespace fs = std::filesystem;

namespace {

//! Whether a card (lower case) names the port node as one of its fields. A field is split
//! at blanks, parentheses, commas and '='; good enough to catch a netlist that forgot the
//! port, while ngspice itself judges everything else.
bool names_port(const std::string& card) {
  std::string field;
  for (std::size_t k = 0; k <= card.size(); ++k) {
    const char c = k < card.size() ? card[k] : ' ';
    if (std::isspace(static_cast<unsigned char>(c)) || c == '(' || c == ')' || c == ',' || c == '=') {
      if (field == STENG_PORT_NODE) return true;
      field.clear();
    } else {
      field += c;
    }
  }
  return false;
}

//! `path` with links resolved, or the reason it cannot be.
fs::path resolved(const fs::path& path, const std::string& origin) {
  std::error_code error;
  const fs::path real = fs::canonical(path, error);
  if (error) throw InputError(origin + ": cannot read " + path.string() + ": " + error.message());
  return real;
}

bool is_inside(const fs::path& path, const fs::path& folder) {
  const auto [end, unused] = std::mismatch(folder.begin(), folder.end(), path.begin(), path.end());
  return end == folder.end();
}

//! The fields after a card's head: a quoted first one whole.
std::vector<std::string> arguments(const std::string& card) {
  std::vector<std::string> out;
  std::size_t k = card.find_first_of(" \t");
  while (k < card.size()) {
    while (k < card.size() && (card[k] == ' ' || card[k] == '\t')) ++k;
    if (k >= card.size()) break;
    if (card[k] == '"' || card[k] == '\'') {
      const std::size_t close = card.find(card[k], k + 1);
      out.push_back(card.substr(k + 1, (close == std::string::npos ? card.size() : close) - k - 1));
      k = close == std::string::npos ? card.size() : close + 1;
    } else {
      const std::size_t start = k;
      while (k < card.size() && card[k] != ' ' && card[k] != '\t') ++k;
      out.push_back(card.substr(start, k - start));
    }
  }
  return out;
}

//! Reads a netlist and the files it includes, checks every card, inlines the includes.
class NetlistReader {
 public:
  NetlistReader(NetlistLoad& load, fs::path allowed_folder) : load_(load), allowed_folder_(std::move(allowed_folder)) {}

  //! Expands `cards` (read from one file) into the load's cards. `chain`: the files being
  //! expanded, outermost first (cycles, depth).
  void expand(const std::vector<SpiceCard>& cards, std::vector<fs::path>& chain) {
    for (const SpiceCard& card : cards) {
      switch (classify_card(card)) {
        case CardKind::end: return;
        case CardKind::include: {
          const std::vector<std::string> args = arguments(card.text);
          if (args.size() != 1) throw InputError(card.origin() + ": write .include FILE (one file name)");
          expand_file(card, args[0], "", chain);
          break;
        }
        case CardKind::library: {
          const std::vector<std::string> args = arguments(card.text);
          if (args.size() != 2)
            throw InputError(card.origin() + ": write .lib FILE ENTRY (a library section of a file; '.lib ENTRY' "
                                             "... '.endl' sections belong in the library file)");
          expand_file(card, args[0], spice_lower(args[1]), chain);
          break;
        }
        case CardKind::library_end:
          throw InputError(card.origin() + ": '.endl' outside a library section read by .lib FILE ENTRY");
        default:
          cards_.push_back(card);
      }
    }
  }

  std::vector<SpiceCard>& cards() { return cards_; }

  //! Reads a file named by the study or an include: a regular file inside the folder.
  std::string read(const fs::path& path, const std::string& origin, const std::string& what) {
    const fs::path real = resolved(path, origin);
    if (!is_inside(real, allowed_folder_))
      throw InputError(origin + ": " + what + " " + path.string() + " lies outside the study's folder " +
                       allowed_folder_.string() +
                       ": a study reads netlists only from its own folder and the folders below it (copy the file there)");
    std::string text;
    try {
      text = read_text_file(path.string(), what, MAX_NETLIST_FILE_BYTES);
    } catch (const InputError& error) {
      throw InputError(origin + ": " + error.what());
    }
    bytes_ += text.size();
    if (bytes_ > 4 * MAX_NETLIST_FILE_BYTES)
      throw InputError(origin + ": the netlist and its includes exceed " + std::to_string(4 * MAX_NETLIST_FILE_BYTES) +
                       " bytes together");
    return text;
  }

 private:
  void expand_file(const SpiceCard& card, const std::string& name, const std::string& entry, std::vector<fs::path>& chain) {
    if (name.empty()) throw InputError(card.origin() + ": an include without a file name");
    const fs::path path = fs::path(name).is_absolute() ? fs::path(name) : fs::path(card.file).parent_path() / name;
    const std::string text = read(path, card.origin(), "the included file");
    const fs::path real = resolved(path, card.origin());
    if (std::find(chain.begin(), chain.end(), real) != chain.end() && entry.empty())
      throw InputError(card.origin() + ": " + path.string() + " includes itself (directly or through others)");
    if (chain.size() >= MAX_INCLUDE_DEPTH)
      throw InputError(card.origin() + ": includes nest deeper than " + std::to_string(MAX_INCLUDE_DEPTH) + " files");
    load_.included.push_back({path.string(), text});
    std::vector<SpiceCard> cards = split_spice_cards(text, path.string(), false);
    if (!entry.empty()) cards = library_section(cards, entry, card, path.string());
    chain.push_back(real);
    expand(cards, chain);
    chain.pop_back();
  }

  //! The cards between `.lib ENTRY` and its `.endl` in a library file.
  static std::vector<SpiceCard> library_section(const std::vector<SpiceCard>& cards, const std::string& entry,
                                                const SpiceCard& call, const std::string& file) {
    std::vector<SpiceCard> section;
    bool inside = false;
    for (const SpiceCard& card : cards) {
      const std::string head = spice_card_head(card.text);
      if (head == ".lib") {
        const std::vector<std::string> args = arguments(card.text);
        if (args.size() == 1) {  // a section starts
          if (inside) throw InputError(card.origin() + ": a library section inside another (no '.endl' before it)");
          inside = spice_lower(args[0]) == entry;
          continue;
        }
      }
      if (head == ".endl") {
        if (inside) return section;
        continue;  // the end of another section
      }
      if (inside) section.push_back(card);
    }
    if (inside) throw InputError(file + ": library section '" + entry + "' has no '.endl'");
    throw InputError(call.origin() + ": " + file + " has no library section '" + entry + "'");
  }

  NetlistLoad& load_;
  fs::path allowed_folder_;
  std::vector<SpiceCard> cards_;
  std::uint64_t bytes_ = 0;
};

fs::path folder_of(const std::string& file, const std::string& allowed_folder) {
  if (!allowed_folder.empty()) return allowed_folder;
  const fs::path parent = fs::path(file).parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

NetlistLoad parse_with(NetlistReader& reader, NetlistLoad& load) {
  std::vector<fs::path> chain;
  std::error_code ignored;
  if (const fs::path real = fs::canonical(load.file, ignored); !ignored) chain.push_back(real);
  reader.expand(split_spice_cards(load.text, load.file, true), chain);
  const std::vector<SpiceCard>& cards = reader.cards();
  if (cards.empty())
    throw InputError(load.file + ": the netlist holds no card (the first line is its title, as in every SPICE file)");
  bool port = false;
  for (const SpiceCard& card : cards) {
    port = port || names_port(spice_lower(card.text));
    load.lines.push_back(card.text);
    load.origins.push_back(card.origin());
  }
  if (!port)
    throw InputError(load.file + ": no element connects to the S-TENG port node '" + std::string(STENG_PORT_NODE) +
                     "': the load must sit between node " + std::string(STENG_PORT_NODE) + " and ground 0");
  load.devices = examine_netlist_structure(cards).devices;
  return load;
}

}  // namespace

NetlistLoad parse_netlist_load(const std::string& text, const std::string& file, const std::string& allowed_folder) {
  NetlistLoad load{file, text, {}, {}, {}, 0.0};
  std::error_code ignored;
  fs::path folder = folder_of(file, allowed_folder);
  if (fs::path real = fs::canonical(folder, ignored); !ignored) folder = real;
  NetlistReader reader(load, folder);
  return parse_with(reader, load);
}

NetlistLoad read_netlist_load(const std::string& path, const std::string& allowed_folder, const std::string& origin) {
  NetlistLoad load{path, "", {}, {}, {}, 0.0};
  const fs::path folder = resolved(folder_of(path, allowed_folder), origin);
  NetlistReader reader(load, folder);
  load.text = reader.read(path, origin, "the netlist");
  return parse_with(reader, load);
}

std::string netlist_cards_text(const NetlistLoad& load) {
  std::string text;
  for (const std::string& line : load.lines) text += line + "\n";
  return text;
}

}  // namespace stengmc
