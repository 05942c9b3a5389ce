// A deterministic mutation fuzzer of the readers a user's files go through (README:
// "Rejected inputs and faults"): study files (read, estimated and run within tight
// limits), surface files (read and sampled), CSV files (displacements, signals,
// histograms), HDF5 files (run files read by `circuit`, `spectrum` and `plot`), the
// records `invert` reads (CSV `t,V`, run and ensemble files, read and checked as invert
// checks them before it computes anything), load netlists (`[circuit] netlist`: read,
// checked against the policy, includes inlined; every 50th accepted one also run by ngspice
// in its child process) and calibration banks (read by `invert` and `calibrate --refit`,
// then rebuilt into atoms).
//
//   fuzz_readers READER RUNS [SEED]     READER: study | surface | csv | hdf5 | record | netlist | bank
//
// Each execution takes a valid seed input (the repository's studies and surfaces, CSV and
// HDF5 files made here), mutates it with a generator seeded by (SEED, execution) — bit
// flips, byte changes, insertions, deletions, duplicated chunks, numbers replaced by
// awkward ones (1e308, -1, 1e-310, nan, 2^63, "") — writes it to a scratch file and reads
// it in this process. The only acceptable outcomes are those of a documented exit code: a
// result (0), an InputError (2) or a ModelError (3). Anything else — another exception, a
// non-finite number in a result, a signal, a sanitizer report (the sanitizer build runs
// this too), more than 60 s on one input — is a finding: the input is kept as
// fuzz-findings/<reader>-<execution>.bin (a crash leaves fuzz-findings/current.<reader>)
// and the program exits 1. The same SEED and RUNS give the same inputs on every machine.
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "circuit/netlist_load.hpp"
#include "circuit/ngspice_library.hpp"
#include "core/error.hpp"
#include "inverse/record_input.hpp"
#include "inverse/atom_library.hpp"
#include "inverse/calibration_run.hpp"
#include "io/calibration_bank_file.hpp"
#include "io/displacement_input.hpp"
#include "io/inverse_signals.hpp"
#include "core/hdf5_file.hpp"
#include "io/run_file.hpp"
#include "io/signal_input.hpp"
#include "pipeline/study.hpp"
#include "ensemble/study_file.hpp"
#include "core/toml_reader.hpp"
#include "pipeline/run_study.hpp"
#include "pipeline/run_summary.hpp"
#include "pipeline/surface_examination.hpp"
#include "pipeline/work_estimate.hpp"
#include "surface/distribution.hpp"
#include "surface/surface.hpp"

namespace fs = std::filesystem;
using namespace stengmc;

namespace {

// Tight limits: a mutated study may ask for anything; the fuzz wants many inputs, and the
// limits themselves are under test (an estimate that lets a slow input through shows up
// as the alarm below).
const WorkLimits LIMITS{.memory_bytes = 0.3e9, .steps = 2e6};
// Longer than any input within the limits takes (the Model 2 integrator's own step budget
// can take tens of seconds to exhaust); shorter than "for ever".
constexpr unsigned SECONDS_PER_INPUT = 60;

//! What the alarm handler prints (prepared before each input: a handler may only write).
char hang_message[512] = "";

extern "C" void on_alarm(int) {
  const ssize_t ignored = ::write(STDERR_FILENO, hang_message, std::strlen(hang_message));
  (void)ignored;
  ::_exit(1);
}

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void write_file(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// ---------------------------------------------------------------- mutations

const std::vector<std::string> AWKWARD_TEXT = {
    "0", "-0", "-1", "1e308", "-1e308", "1e309", "1e-310", "4.9e-324", "nan", "inf", "-inf", "1e300", "1e-300",
    "9223372036854775807", "18446744073709551616", "4294967296", "2147483648", "\"\"", "[]", "{}", "1e15", "1e-15",
    "0.5", "3", "\"/dev/zero\"", "\"random\"", "\"model1\"", "true", "1_000", "0x10", ",", "\n", "#", "=", "[", "]"};

//! One random mutation of `bytes`; text inputs also get number replacements and line splices.
void mutate_once(std::string& bytes, std::mt19937_64& rng, bool text, const std::vector<std::string>& others) {
  const auto pick = [&](std::size_t n) { return n == 0 ? std::size_t{0} : static_cast<std::size_t>(rng() % n); };
  if (bytes.empty()) {
    bytes = AWKWARD_TEXT[pick(AWKWARD_TEXT.size())];
    return;
  }
  const std::size_t at = pick(bytes.size());
  // Text inputs mostly get token-level changes (an awkward value where a number was, a line
  // from another input): byte-level damage mostly tests the TOML parser, not stengmc.
  const std::size_t kind = text ? std::array<std::size_t, 10>{0, 1, 2, 3, 5, 6, 6, 6, 6, 7}[rng() % 10] : rng() % 6;
  switch (kind) {
    case 0:  // flip a bit
      bytes[at] = static_cast<char>(bytes[at] ^ (1 << (rng() % 8)));
      break;
    case 1:  // any byte
      bytes[at] = static_cast<char>(rng() % 256);
      break;
    case 2:  // delete a run
      bytes.erase(at, 1 + pick(std::min<std::size_t>(64, bytes.size() - at)));
      break;
    case 3:  // duplicate a chunk somewhere
    {
      const std::string chunk = bytes.substr(at, 1 + pick(256));
      bytes.insert(pick(bytes.size() + 1), chunk);
      break;
    }
    case 4:  // truncate
      bytes.resize(at);
      break;
    case 5:  // an awkward 32- or 64-bit integer in place (lengths, offsets, counts)
    {
      const std::uint64_t values[] = {0, 1, 0xff, 0xffff, 0x7fffffff, 0xffffffff, 0x7fffffffffffffff, ~0ull};
      const std::uint64_t v = values[pick(8)];
      const std::size_t width = rng() % 2 ? 4 : 8;
      for (std::size_t i = 0; i < width && at + i < bytes.size(); ++i) bytes[at + i] = static_cast<char>(v >> (8 * i));
      break;
    }
    case 6:  // a number (or any token) replaced by an awkward one
    {
      std::size_t start = at;
      while (start > 0 && (std::isalnum(static_cast<unsigned char>(bytes[start - 1])) || bytes[start - 1] == '.' ||
                           bytes[start - 1] == '-' || bytes[start - 1] == '+'))
        --start;
      std::size_t end = at;
      while (end < bytes.size() && (std::isalnum(static_cast<unsigned char>(bytes[end])) || bytes[end] == '.' ||
                                    bytes[end] == '-' || bytes[end] == '+'))
        ++end;
      bytes.replace(start, end - start, AWKWARD_TEXT[pick(AWKWARD_TEXT.size())]);
      break;
    }
    default:  // a line of another seed input
    {
      if (others.empty()) break;
      const std::string& other = others[pick(others.size())];
      const std::size_t from = other.rfind('\n', pick(other.size()));
      const std::size_t begin = from == std::string::npos ? 0 : from + 1;
      const std::size_t stop = other.find('\n', begin);
      const std::string line = other.substr(begin, stop == std::string::npos ? std::string::npos : stop - begin + 1);
      const std::size_t where = bytes.rfind('\n', at);
      bytes.insert(where == std::string::npos ? 0 : where + 1, line);
      break;
    }
  }
}

std::string mutate(const std::string& seed_input, std::mt19937_64& rng, bool text, const std::vector<std::string>& others) {
  std::string bytes = seed_input;
  const int count = 1 + static_cast<int>(rng() % (text ? 2 : 4));
  for (int i = 0; i < count; ++i) mutate_once(bytes, rng, text, others);
  return bytes;
}

//! The same within one region of the input, spliced back: a bank is ~3.7 MB of atom shape
//! values whose damage its checksums catch at once, around ~60 kB of structure (HDF5's
//! superblock, object headers, attributes, the small tables) where damage tests the reader;
//! so half the inputs are mutated in the first 16 kB, a quarter in the last 64 kB.
std::string mutate_structure(const std::string& seed_input, std::mt19937_64& rng) {
  const std::size_t size = seed_input.size(), head = std::min<std::size_t>(size, 16 << 10),
                    tail = std::min<std::size_t>(size, 64 << 10);
  const std::size_t region = rng() % 4;
  const std::size_t begin = region < 2 ? 0 : region == 2 ? size - tail : 0;
  const std::size_t end = region < 2 ? head : size;
  return seed_input.substr(0, begin) + mutate(seed_input.substr(begin, end - begin), rng, false, {}) + seed_input.substr(end);
}

// ---------------------------------------------------------------- seed inputs

struct Corpus {
  std::vector<std::string> inputs;
  bool text = true;
};

std::vector<std::string> toml_files(const fs::path& folder) {
  std::vector<fs::path> paths;
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.path().extension() == ".toml") paths.push_back(entry.path());
  std::sort(paths.begin(), paths.end());  // directory order differs between machines
  std::vector<std::string> texts;
  for (const auto& p : paths) texts.push_back(read_file(p));
  return texts;
}

std::string csv_of(const std::string& header, int rows, double (*value)(int, int), int columns) {
  std::ostringstream out;
  out.precision(17);
  out << header << "\n";
  for (int j = 0; j < rows; ++j) {
    out << j * 1e-8;
    for (int c = 1; c < columns; ++c) out << "," << value(j, c);
    out << "\n";
  }
  return out.str();
}

//! A small run file of each model, written by this program, as the HDF5 seeds: `duration`
//! at 50 MHz.
std::vector<std::string> hdf5_seeds(const fs::path& scratch, const std::string& duration = "1e-6") {
  std::vector<std::string> seeds;
  for (const char* model : {"kind = \"model1\"", "kind = \"model2\"\nbelt_velocity_m_per_s = 10"}) {
    const std::string text = "duration_s = " + duration + "\nsample_rate_hz = 50e6\n[model]\n" + model +
                             "\n[surface]\n[surface.defaults]\nlength_m = 50e-6\n[[surface.asperity]]\n"
                             "stiffness_n_per_m = 75\n[[surface.asperity]]\nstiffness_n_per_m = 155\n"
                             "[spectrum]\nhigh_resolution = false\n";
    const StudyFile study = parse_study_file(text, (scratch / "seed.toml").string());
    const RunResult result = run_study(study, RunOptions{.show_progress = false});
    const fs::path file = scratch / "seed.h5";
    write_run_file(file.string(), study, result, summarise(study, result));
    seeds.push_back(read_file(file));
  }
  return seeds;
}

//! A record file of another program: /time as doubles, /circuit/voltage as int64 (in uV).
std::string integer_voltage_record(const fs::path& scratch) {
  const fs::path file = scratch / "integer.h5";
  {
    H5::H5File out(file.string(), H5F_ACC_TRUNC);
    const hsize_t n = 100;
    std::vector<double> t(n);
    std::vector<std::int64_t> v(n);
    for (hsize_t j = 0; j < n; ++j) {
      const double x = static_cast<double>(j);
      t[j] = x * 1e-8;
      v[j] = static_cast<std::int64_t>(3000.0 * std::sin(0.7 * x));
    }
    const H5::DataSpace space(1, &n);
    out.createDataSet("/time", H5::PredType::NATIVE_DOUBLE, space).write(t.data(), H5::PredType::NATIVE_DOUBLE);
    out.createGroup("/circuit");
    out.createDataSet("/circuit/voltage", H5::PredType::STD_I64LE, space).write(v.data(), H5::PredType::NATIVE_INT64);
  }
  return read_file(file);
}

//! The known device of the inverse tests with 20 us records and the quick prior (a bank of
//! 50 records in seconds: tests/support/known_device*.toml).
Study bank_device(const fs::path& source, const fs::path& scratch) {
  const std::string text = "duration_s = 20e-6\n" + read_file(source / "tests/support/known_device.toml") + "[inverse]\n" +
                           read_file(source / "tests/support/known_device_quick_prior.toml");
  return parse_study(text, (scratch / "device.toml").string(), std::nullopt);
}

//! A bank of that device, made here once (a few seconds), as the seed input.
std::string bank_seed(const fs::path& source, const fs::path& scratch) {
  const Study device = bank_device(source, scratch);
  const fs::path journal = scratch / "bank.h5.journal", bank = scratch / "bank.h5";
  CalibrationOptions quiet;
  quiet.show_progress = false;
  write_calibration_bank(bank.string(), run_calibration(device, journal.string(), quiet));
  fs::remove(journal);
  return read_file(bank);
}

Corpus corpus_for(const std::string& reader, const fs::path& source, const fs::path& scratch) {
  Corpus c;
  if (reader == "study") {
    for (const char* folder : {"studies/paper", "studies/surfaces", "studies/ensembles"})
      for (std::string text : toml_files(source / folder)) {
        // Surface files by absolute path, so the study reads them from the scratch folder.
        const std::string relative = "\"../../surfaces/";
        std::string absolute = "\"";  // not `"\"" + path`: GCC 12 warns falsely there (-Wrestrict, PR 105651)
        absolute += (source / "surfaces/").string();
        std::string rewritten;
        std::size_t from = 0;
        for (std::size_t at = text.find(relative); at != std::string::npos; at = text.find(relative, from)) {
          rewritten.append(text, from, at - from).append(absolute);
          from = at + relative.size();
        }
        text = rewritten.append(text, from, std::string::npos);
        c.inputs.push_back(text);
      }
  } else if (reader == "surface") {
    c.inputs = toml_files(source / "surfaces");
  } else if (reader == "csv") {
    c.inputs.push_back(csv_of("t,x1,x2", 40, [](int j, int column) { return 1e-7 * column * std::sin(0.3 * j); }, 3));
    c.inputs.push_back(csv_of("t,V", 64, [](int j, int) { return std::sin(0.7 * j) + 0.1 * std::cos(2.3 * j); }, 2));
    c.inputs.push_back("lower,upper,weight\n100e-6,105e-6,1\n105e-6,110e-6,3\n110e-6,120e-6,0.5\n");
  } else if (reader == "hdf5") {
    c.inputs = hdf5_seeds(scratch);
    c.text = false;
  } else if (reader == "netlist") {
    for (const char* name : {"bridge_rectifier.cir", "resistor_1meg.cir"})
      c.inputs.push_back(read_file(source / "studies/circuits" / name));
    // Every construct the policy knows, accepted and refused, for mutations to cross.
    c.inputs.push_back(
        "* rich load\n.param r0=1e6 c0={1p*2}\n.func half(x) {x/2}\n.subckt rc p n params: r=1k\nR1 p m {r}\n"
        "C1 m n 1p ; comment\n+ ic=0\n.ends rc\nX1 steng 0 rc params: r={half(r0)}\n.include parts.cir\n"
        ".lib models.lib fast\nD1 steng 0 dfast\nB1 steng 0 I=v(steng)/1e9 $ behavioural\n.end\n");
    c.inputs.push_back("* refused\nRload steng 0 1e6\n.control\nshell touch ran-this\n.endc\n*#echo\n"
                       "A1 %v(steng) f\n.model f filesource(file=\"/dev/zero\")\n.options reltol=1\n");
    write_file(scratch / "parts.cir", "Rpart steng 0 1e9\n");
    write_file(scratch / "models.lib", ".lib fast\n.model dfast d(is=1e-15 rs=10 cjo=0)\n.endl\n");
  } else if (reader == "record") {
    // Records as invert takes them: a CSV `t,V` (100 MHz, 64 samples and more) and run files;
    // one with its voltage stored as 64-bit integers, as another program may write it.
    c.inputs.push_back(csv_of("t,V", 80, [](int j, int) { return 1e-3 * std::sin(0.7 * j) + 1e-4 * std::cos(2.3 * j); }, 2));
    for (std::string& seed : hdf5_seeds(scratch, "2e-6")) c.inputs.push_back(std::move(seed));  // 101 samples
    c.inputs.push_back(integer_voltage_record(scratch));
  } else if (reader == "bank") {
    c.inputs = {bank_seed(source, scratch)};
    c.text = false;
  }
  return c;
}

//! HDF5 files start with this signature (the HDF5 format specification, superblock).
bool is_hdf5(const std::string& bytes) { return bytes.rfind("\x89HDF", 0) == 0; }

// ---------------------------------------------------------------- the readers

struct Finding {
  std::string what;
};

void require_finite(const std::vector<double>& values, const char* what) {
  for (double v : values)
    if (!std::isfinite(v)) throw Finding{std::string("a non-finite value in ") + what};
}

void read_study_input(const fs::path& file) {
  const StudyFile study = read_study_file(file.string(), 0);
  if (study.ensemble) return;  // an ensemble's realisations are the same runs; reading was the test
  check_work(estimate_run(study), LIMITS, study.file);
  const RunResult result = run_study(study, RunOptions{.show_progress = false, .limits = LIMITS});
  require_finite(result.circuit.voltage_v, "the voltage");
  require_finite(result.circuit.charge_c, "the charge");
}

void read_surface_input(const fs::path& file) {
  auto document = TomlDocument::from_file(file.string());
  TomlTable root = document->root();
  const Surface surface = Surface::from_toml(root, file.parent_path());
  document->reject_unknown_keys();
  if (const RandomSurface* random = surface.random_surface()) check_work(estimate_surface(*random, 2.0), LIMITS, "surface");
  const SurfaceExamination e = examine_surface(surface, 1, 0, 2, Model1Params{}, Model2Params{}, nullptr, ModelScope{});
  for (const Population& p : e.populations)
    for (const Asperity& a : p.asperities)
      if (!std::isfinite(a.stiffness_n_per_m) || !std::isfinite(a.normal_load_n) || !std::isfinite(a.mass_kg))
        throw Finding{"a non-finite asperity parameter"};
}

void read_csv_input(const fs::path& file, std::size_t execution) {
  switch (execution % 3) {
    case 0: {
      const DisplacementInput input = read_displacement_csv(file.string(), StengElement{});
      require_finite(input.times_s, "the times");
      break;
    }
    case 1: {
      const SignalInput input = read_signal_csv(file.string());
      require_finite(input.voltage_v, "the voltages");
      break;
    }
    default:
      for (const auto& bin : Distribution::read_histogram(file))
        if (!std::isfinite(bin.lower) || !std::isfinite(bin.upper) || !std::isfinite(bin.weight))
          throw Finding{"a non-finite histogram bin"};
  }
}

void read_hdf5_input(const fs::path& file, std::size_t execution) {
  if (execution % 2 == 0) {
    const DisplacementInput input = read_displacement_hdf5(file.string());
    require_finite(input.times_s, "the times");
  } else {
    const SignalInput input = read_signal_hdf5(file.string());
    require_finite(input.voltage_v, "the voltages");
  }
}

//! Reads a netlist as a study would (inside the scratch folder, includes and all), checks
//! what the policy let through, and runs every 50th accepted one in ngspice's child: a 1 us
//! transient with the port driven through 1 kOhm.
void read_netlist_input(const fs::path& file, std::size_t& accepted_so_far) {
  const NetlistLoad load = read_netlist_load(file.string(), file.parent_path().string(), "fuzz");
  for (const std::string& card : load.lines) {
    // Independent of the policy's code: what ngspice would run or read never reaches it.
    const std::string head = card.substr(0, card.find_first_of(" \t"));
    std::string lower(head);
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const bool dot_card_allowed = lower == ".model" || lower == ".subckt" || lower == ".ends" || lower == ".param" ||
                                  lower == ".func";
    if (lower.empty() || (lower[0] == '.' && !dot_card_allowed) || lower[0] == 'a' || lower[0] == 'n' ||
        lower[0] == '*' || lower[0] == '+' || (!std::isalpha(static_cast<unsigned char>(lower[0])) && lower[0] != '.'))
      throw Finding{"the policy let through the card '" + card.substr(0, 80) + "'"};
    if (lower == ".model" && (card.find("filesource") != std::string::npos || card.find("d_source") != std::string::npos))
      throw Finding{"the policy let through a file-reading model"};
    for (const char c : card)
      if (static_cast<unsigned char>(c) < 0x20 && c != '\t') throw Finding{"a control character in an accepted card"};
  }
  if (!ngspice_library_available() || accepted_so_far++ % 50 != 0) return;
  NgspiceTransient transient;
  transient.cards = {"* fuzz", "Vfuzz fuzz_drive 0 sin(0 1 1e6)", "Rfuzz fuzz_drive steng 1k"};
  transient.cards.insert(transient.cards.end(), load.lines.begin(), load.lines.end());
  transient.cards.insert(transient.cards.end(), {".tran 1n 1u", ".end"});
  transient.origin = file.string();
  transient.stop_time_s = 1e-6;
  transient.vectors = {"v(steng)"};
  transient.external_voltage = [](std::string_view, double) { return 0.0; };
  transient.budget.cpu_seconds = 10.0;
  transient.budget.wall_seconds = 30.0;
  transient.budget.memory_bytes = 0.5e9;
  const NgspiceVectors result = run_ngspice_transient(transient);
  require_finite(result.time_s, "ngspice's times");
}

//! What `invert` does with a record file before it computes anything: read it, then check
//! each record's grid, values and variation.
void read_record_input(const fs::path& file) {
  for (const NamedRecord& r : read_inverse_records(file.string())) {
    (void)checked_record_grid(r.times_s, r.voltage_v, r.name);
    check_record_varies(r.voltage_v, r.name);
    require_finite(r.times_s, "the times");
    require_finite(r.voltage_v, "the voltages");
  }
}

//! What invert does with a bank (command_invert.cpp) and calibrate --refit: read it, refuse
//! one made for another device, rebuild its atoms; and the refit's reading of its records.
void read_bank_input(const fs::path& file, const InverseSetup& setup, std::size_t execution) {
  if (execution % 4 == 3) {
    for (const CalibrationSample& s : read_calibration_bank_records(file.string(), setup).samples)
      require_finite(s.stiffness, "a record's stiffnesses");
    return;
  }
  const StoredBank bank = read_calibration_bank(file.string());
  if (!bank.identity.differences(setup.identity).empty()) throw InputError(file.string() + ": made for another device");
  const std::unique_ptr<AtomLibrary> atoms = build_atom_library(setup, bank.atoms);
  AtomParameters atom;
  atom.stiffness_n_per_m = std::sqrt(atoms->min_stiffness() * atoms->max_stiffness());
  atom.load_n = setup.device.asperity.normal_load_n;
  AtomValues value;
  atoms->model().evaluate(atom, setup.device.damping_rate_per_s(), value, true);
  require_finite(value.u, "an atom");
  require_finite(value.d_lnk, "an atom's derivative");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: fuzz_readers study|surface|csv|hdf5|record|netlist|bank RUNS [SEED]\n");
    return 2;
  }
  const std::string reader = argv[1];
  const std::size_t runs = std::stoul(argv[2]);
  const std::uint64_t seed = argc > 3 ? std::stoull(argv[3]) : 1;
  const fs::path source = STENGMC_SOURCE_DIR;
  const fs::path scratch = fs::temp_directory_path() / ("stengmc-fuzz-" + reader + "-" + std::to_string(::getpid()));
  const fs::path findings = fs::current_path() / "fuzz-findings";
  fs::create_directories(scratch);
  fs::create_directories(findings);
  H5::Exception::dontPrint();
  ::signal(SIGALRM, on_alarm);

  const Corpus corpus = corpus_for(reader, source, scratch);
  if (corpus.inputs.empty()) {
    std::fprintf(stderr, "unknown reader '%s' (study, surface, csv, hdf5, record, netlist, bank)\n", reader.c_str());
    return 2;
  }
  const std::optional<InverseSetup> setup =
      reader == "bank" ? std::optional(inverse_setup(bank_device(source, scratch))) : std::nullopt;
  const std::string extension = reader == "hdf5" || reader == "bank" ? ".h5"
                                : reader == "csv"                    ? ".csv"
                                : reader == "netlist"                ? ".cir"
                                                                     : ".toml";
  std::size_t accepted = 0, refused = 0, model_errors = 0, found = 0, netlists_accepted = 0;
  for (std::size_t i = 0; i < runs; ++i) {
    std::mt19937_64 rng(seed * 0x9E3779B97F4A7C15ULL + i);
    const std::string& base = corpus.inputs[rng() % corpus.inputs.size()];
    // A record is a CSV or an HDF5 file, told apart by its name as invert tells them apart.
    const bool binary = !corpus.text || is_hdf5(base);
    const std::string bytes = reader == "bank" ? mutate_structure(base, rng) : mutate(base, rng, !binary, corpus.inputs);
    const fs::path input = scratch / ("input" + (reader == "record" ? std::string(binary ? ".h5" : ".csv") : extension));
    write_file(input, bytes);
    write_file(findings / ("current." + reader), bytes);  // what a crash leaves behind
    // A histogram a mutated surface names is this same CSV seed (surfaces/*.toml name none).
    std::snprintf(hang_message, sizeof hang_message,
                  "FINDING %s execution %zu: no result in %u s (input kept as %s)\n", reader.c_str(), i,
                  SECONDS_PER_INPUT, (findings / ("current." + reader)).c_str());
    ::alarm(SECONDS_PER_INPUT);  // a hang is a finding
    std::string problem;
    try {
      if (reader == "study") read_study_input(input);
      else if (reader == "surface") read_surface_input(input);
      else if (reader == "csv") read_csv_input(input, i);
      else if (reader == "netlist") read_netlist_input(input, netlists_accepted);
      else if (reader == "record") read_record_input(input);
      else if (reader == "bank") read_bank_input(input, *setup, i);
      else read_hdf5_input(input, i);
      ++accepted;
    } catch (const InputError&) {
      ++refused;
    } catch (const ModelError&) {
      ++model_errors;
    } catch (const Finding& f) {
      problem = f.what;
    } catch (const std::exception& e) {
      problem = std::string("an exception outside the documented exit codes: ") + e.what();
    } catch (...) {
      problem = "an unknown exception";
    }
    ::alarm(0);
    if (!problem.empty()) {
      ++found;
      const fs::path kept = findings / (reader + "-" + std::to_string(i) + ".bin");
      write_file(kept, bytes);
      std::fprintf(stderr, "FINDING %s execution %zu: %s (input kept as %s)\n", reader.c_str(), i, problem.c_str(),
                   kept.c_str());
    }
  }
  fs::remove(findings / ("current." + reader));
  fs::remove_all(scratch);
  std::printf("fuzz %s: %zu executions (seed %llu): %zu read, %zu refused (input error), %zu model errors, %zu findings\n",
              reader.c_str(), runs, static_cast<unsigned long long>(seed), accepted, refused, model_errors, found);
  return found == 0 ? 0 : 1;
}
